//! Figures of the triad.
//!
//! [`drawing`] is the seed's Fig. 3 alone: the three circles, the approximate triangle at
//! the pattern method's start angle (red, dashed), the exact position (the triangle as the
//! seed's closed polyline `PLine W 0.5`, the links O_iA_i as the same wide polyline),
//! ground pivots, the angular dimensions of phi1, phi2, phi3 measured at O1, O2, O3 from
//! +x, the point letters (clear of each other, of every line and of the dimensions) and a
//! caption. Layers: `CONSTRUCTION` (circles), `APPROXIMATE` (start triangle), `MECHANISM`
//! (exact position, pivots, joints), `DIMENSIONS`, `TEXT`.
//!
//! [`modes_sheet`] draws every assembly mode as small multiples: one panel per mode, in
//! the report's order, [`SHEET_COLUMNS`] to a row, each with the circles, the mode's
//! triangle and links, its number, orientation and phi1, phi2, phi3; the mode drawn in
//! Fig. 3 is marked. Layers: `PANELS` (panel frames), `CONSTRUCTION`, `MECHANISM`, `TEXT`.
//!
//! Both are drawn on paper: a length scale k_l (model units per paper millimetre, a nice
//! value) draws the three circles at most [`TRIAD_MM`] (Fig. 3, on A4) or [`PANEL_MM`]
//! (a panel of the sheet) long, the drawing carries `paper_mm_per_unit = 1/k_l`, sizes are
//! the shared table's from paper millimetres ([`Sizes::on_paper`]: letters 3.5 mm), and
//! k_l is printed (`k_l = 2 mm/mm`) above a scale bar; so a triad in metres looks the same
//! as one in millimetres.

use crate::draw::parts::widest_text_width;
use crate::draw::{Aci, Bounds, DimStyle, Drawing, Entity, LineType, Shape};
use crate::geom::{Point, Vector, angle_of};
use crate::solve::triad::{Configuration, Orientation, Triad};

use crate::figure::shared::construction::{
    arc_segments, caption, dimension_text_box, free_direction, keep_letters_off_dimension, length_scale_block,
    place_dimension,
};
use crate::figure::shared::labels::{self, Label, TextBox};
use crate::figure::shared::vocab::{self, ModelUnits, Sizes};

/// Width of the seed's polylines (`Pline A1 "W" "0.5" "0.5" A2 A3 "Close"`), drawing
/// millimetres.
pub const SEED_PLINE_WIDTH_MM: f64 = 0.5;

/// Largest extent of the three circles of Fig. 3 on paper, millimetres.
pub const TRIAD_MM: f64 = 150.0;
/// Largest extent of the three circles in a panel of the assembly-mode sheet on paper,
/// millimetres.
pub const PANEL_MM: f64 = 80.0;

/// The extent of the three circles (model units), for the length scale.
fn circles_extent(t: &Triad) -> f64 {
    let lo = |k: usize| (0..3).map(|i| t.o[i][k] - t.r[i]).fold(f64::INFINITY, f64::min);
    let hi = |k: usize| (0..3).map(|i| t.o[i][k] + t.r[i]).fold(f64::NEG_INFINITY, f64::max);
    (hi(0) - lo(0)).max(hi(1) - lo(1)).max(f64::MIN_POSITIVE)
}

/// What Fig. 3 draws.
#[derive(Debug, Clone, Copy)]
pub struct TriadFigure<'a> {
    /// The triad's data.
    pub triad: &'a Triad,
    /// The position drawn as the mechanism (the pattern method's, polished).
    pub exact: &'a Configuration,
    /// The approximate triangle at the start angle (A1, A2, A3), if it exists.
    pub approximate: Option<[Point; 3]>,
    /// The model's length unit: the exact position's polylines are
    /// [`SEED_PLINE_WIDTH_MM`] drawing millimetres wide.
    pub units: ModelUnits,
    /// Caption lines under the drawing (may be empty), with their subscripts (φ_1:
    /// [`Label::marked`]).
    pub caption: &'a [Label],
}

/// Height of the small texts (caption, panel values), in letter heights.
const SMALL_TEXT: f64 = 0.8;

/// The text of the angular dimension of phi_i (`i` from 1), radians in, flat as the DXF
/// writes it: `φ1 = 75.77°`.
pub fn phi_text(i: usize, phi: f64) -> String {
    Label::marked(&phi_markup(i, phi)).text
}

/// `φ_i = value` marked up for [`Label::marked`] (`i` from 1, radians in).
fn phi_markup(i: usize, phi: f64) -> String {
    format!("φ_{i} = {:.2}°", phi.to_degrees())
}

/// The seed's Fig. 3 for `f`.
pub fn drawing(f: &TriadFigure) -> Drawing {
    let t = f.triad;
    let k_l = vocab::length_scale(circles_extent(t), TRIAD_MM);
    let s = Sizes::on_paper(k_l);
    let small_text = SMALL_TEXT * s.text;
    let mut d = Drawing::new(DimStyle { text_height: 0.85 * s.text, arrow_size: 0.75 * s.text });
    d.paper_mm_per_unit = Some(1.0 / k_l);
    let construction = d.layer("CONSTRUCTION", Aci::DARK_GREY, LineType::Continuous);
    let approximate = d.layer("APPROXIMATE", Aci::RED, LineType::Dashed);
    let mechanism = d.layer("MECHANISM", Aci::BLACK, LineType::Continuous);
    let dimensions = d.layer("DIMENSIONS", Aci::BLUE, LineType::Continuous);
    let text = d.layer("TEXT", Aci::BLACK, LineType::Continuous);
    // Every line drawn, for the dimension texts and the letters to keep off (the
    // construction circles only for the letters: they are broken under a dimension's text).
    let mut lines: Vec<(Point, Point)> = Vec::new();
    let mut circles: Vec<(Point, Point)> = Vec::new();

    for (o, r) in t.o.iter().zip(t.r) {
        d.add(construction, Shape::Circle { center: *o, radius: r });
        arc_segments(&mut circles, *o, r, 0.0, std::f64::consts::TAU);
    }

    if let Some(a) = f.approximate {
        d.add(approximate, Shape::Polyline { points: a.to_vec(), closed: true, width: 0.0 });
        lines.extend((0..3).map(|i| (a[i], a[(i + 1) % 3])));
    }

    // The exact position: the seed's wide polyline for the triangle and the links.
    let a = f.exact.a;
    let pline = Sizes { link: SEED_PLINE_WIDTH_MM / f.units.mm_per_unit, ..s };
    for (o, p) in t.o.iter().zip(a) {
        vocab::link(&mut d, mechanism, vec![*o, p], false, None, pline);
    }
    vocab::link(&mut d, mechanism, a.to_vec(), true, None, pline);
    for o in t.o {
        vocab::ground(&mut d, mechanism, o, s);
    }
    for p in a {
        vocab::joint(&mut d, mechanism, p, s);
    }
    for i in 0..3 {
        lines.push((t.o[i], a[i]));
        lines.push((a[i], a[(i + 1) % 3]));
    }

    // Angular dimensions phi_i at O_i from +x (`φi = value`, as DIMANGULAR with its text
    // edited), each at the first radius that keeps its text off every line and off the
    // other dimensions' texts.
    let mut letters = labels::Polygon::of_names();
    let mut dimension_texts: Vec<TextBox> = Vec::new();
    for (i, (o, p)) in t.o.iter().zip(a).enumerate() {
        let preferred = 0.42 * t.r[i].min(0.3 * t.scale() + 0.1 * t.r[i]);
        let dim_at = |radius: f64| Shape::AngularDimension {
            vertex: *o,
            first: o + Vector::new(s.joint + 0.3 * s.text, 0.0),
            second: p,
            radius,
            text: phi_text(i + 1, f.exact.phi[i]),
            // Placed flat (the DXF's text, the wider); φ_1 set below.
            runs: Default::default(),
        };
        let dim = place_dimension(dim_at, preferred, &d.dim_style, &dimension_texts, &lines);
        dimension_texts.extend(dimension_text_box(&dim, &d.dim_style));
        keep_letters_off_dimension(&mut letters, &dim, &d.dim_style);
        // φ_1 where the writer can draw a subscript, `φ1` in the DXF.
        d.add(dimensions, labels::with_dimension_runs(dim));
    }

    // The construction circles broken where a dimension's text lies over them.
    labels::break_around(&mut d, construction, &dimension_texts, 0.3 * s.text);
    // Letters: each preferably in the widest free direction around its point, placed by the
    // letter placer clear of the joint, every line (circles, both triangles, links,
    // dimensions), the ground symbols and the dimension texts.
    for (u, v) in lines.iter().chain(&circles) {
        letters.segment(*u, *v);
    }
    for o in t.o {
        letters.keep_off(vocab::ground_extent(o, s));
    }
    let toward = |dir: f64| Vector::new(libm::cos(dir), libm::sin(dir));
    let half_pi = std::f64::consts::FRAC_PI_2;
    for i in 0..3 {
        let phi = f.exact.phi[i];
        // At O_i: the link, the +x reference line, the dimensioned sector between them and
        // the ground symbol below.
        let mut occupied: Vec<f64> = (0..=8).map(|k| phi * k as f64 / 8.0).collect();
        occupied.extend([-half_pi - 0.5, -half_pi + 0.5]);
        let dir = free_direction(&occupied);
        letters.letter_clear(t.o[i], format!("O{}", i + 1), s.text, toward(dir), s.joint);
        // At A_i: the link back to O_i, the two sides and the circle through A_i.
        let occupied = [
            angle_of(t.o[i] - a[i]),
            angle_of(a[(i + 1) % 3] - a[i]),
            angle_of(a[(i + 2) % 3] - a[i]),
            phi + half_pi,
            phi - half_pi,
        ];
        let dir = free_direction(&occupied);
        letters.letter_clear(a[i], format!("A{}", i + 1), s.text, toward(dir), s.joint);
    }
    letters.draw(&mut d, text);

    // Caption under everything drawn so far, then the length scale and its bar.
    if let Some(b) = d.bounds() {
        let top = Point::new(b.min.x, b.min.y - 2.0 * s.text);
        caption(&mut d, text, top, f.caption, small_text);
        let below = top - Vector::new(0.0, 1.8 * small_text * f.caption.len() as f64);
        length_scale_block(&mut d, text, below, k_l, f.units, s);
    }
    d
}

/// Panels per row of the assembly-mode sheet.
pub const SHEET_COLUMNS: usize = 2;

/// What the assembly-mode sheet draws.
#[derive(Debug, Clone, Copy)]
pub struct ModesSheet<'a> {
    /// The triad's data.
    pub triad: &'a Triad,
    /// Every assembly mode, in the report's order (numbered from 1).
    pub modes: &'a [Configuration],
    /// Index in `modes` of the mode drawn in Fig. 3 (its panel is marked).
    pub drawn: usize,
    /// Title lines above the panels (may be empty), with their subscripts.
    pub title: &'a [Label],
    /// The model's units, for the length scale's text.
    pub units: ModelUnits,
}

/// The orientation of a mode as the sheet writes it: `counter-clockwise`, `clockwise`,
/// `collinear`.
pub fn orientation_text(o: Orientation) -> &'static str {
    match o {
        Orientation::Ccw => "counter-clockwise",
        Orientation::Cw => "clockwise",
        Orientation::Collinear => "collinear",
    }
}

/// The heading of mode `number` (from 1) in its panel: `Mode 3 · clockwise`.
pub fn mode_heading(number: usize, c: &Configuration, drawn: bool) -> String {
    let mark = if drawn { " · drawn in Fig. 3" } else { "" };
    format!("Mode {number} · {}{mark}", orientation_text(c.orientation))
}

/// The angles of a mode as a panel writes them: `φ1 = 75.77°, φ2 = …, φ3 = …` (commas: SVG
/// collapses runs of spaces), each index a subscript where the writer can (φ_1), flat in the
/// DXF.
pub fn mode_angles(c: &Configuration) -> Label {
    Label::marked(&(0..3).map(|i| phi_markup(i + 1, c.phi[i])).collect::<Vec<_>>().join(", "))
}

/// What a panel's content covers (the circles and the ground symbols), unshifted.
fn panel_extent(t: &Triad, s: Sizes) -> Bounds {
    let mut min = Point::new(f64::INFINITY, f64::INFINITY);
    let mut max = Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY);
    for (o, r) in t.o.iter().zip(t.r) {
        let g = vocab::ground_extent(*o, s);
        for p in [o - Vector::new(r, r), o + Vector::new(r, r), g.min, g.max] {
            min = Point::new(min.x.min(p.x), min.y.min(p.y));
            max = Point::new(max.x.max(p.x), max.y.max(p.y));
        }
    }
    Bounds { min, max }
}

/// Every assembly mode of `m` as small multiples (see the module docs).
pub fn modes_sheet(m: &ModesSheet) -> Drawing {
    let t = m.triad;
    // Every panel at one length scale, its sizes from paper millimetres.
    let k_l = vocab::length_scale(circles_extent(t), PANEL_MM);
    let s = Sizes::on_paper(k_l);
    let content = panel_extent(t, s);
    let mut d = Drawing::new(DimStyle { text_height: 0.85 * s.text, arrow_size: 0.75 * s.text });
    d.paper_mm_per_unit = Some(1.0 / k_l);
    let panels = d.layer("PANELS", Aci::LIGHT_GREY, LineType::Continuous);
    let construction = d.layer("CONSTRUCTION", Aci::DARK_GREY, LineType::Continuous);
    let mechanism = d.layer("MECHANISM", Aci::BLACK, LineType::Continuous);
    let text = d.layer("TEXT", Aci::BLACK, LineType::Continuous);

    let small_text = SMALL_TEXT * s.text;
    let pad = s.text;
    let gap = s.text;
    // Header: the heading and the angles, then the content.
    let heading_base = pad + s.text;
    let angles_base = heading_base + 1.8 * small_text;
    let header = angles_base + pad;
    // Each cell as wide as its content and as the widest heading or angles line as the
    // widest reader draws it (LibreCAD's stroke font: the SVG's DejaVu widths alone let
    // the first heading run into the next cell in LibreCAD).
    let widest = m.modes.iter().enumerate().fold(0.0f64, |w, (k, c)| {
        let heading = widest_text_width(&mode_heading(k + 1, c, k == m.drawn), s.text);
        w.max(heading).max(widest_text_width(&mode_angles(c).text, small_text))
    });
    let cell_w = content.width().max(widest) + 2.0 * pad;
    let cell_h = header + content.height() + pad;
    let columns = SHEET_COLUMNS.min(m.modes.len()).max(1);

    for (k, c) in m.modes.iter().enumerate() {
        let (col, row) = (k % columns, k / columns);
        let top_left = Point::new(col as f64 * (cell_w + gap), -(row as f64) * (cell_h + gap));
        let off = Vector::new(top_left.x + pad - content.min.x, top_left.y - header - content.max.y);
        let drawn = k == m.drawn;
        let corners = vec![
            top_left,
            top_left + Vector::new(cell_w, 0.0),
            top_left + Vector::new(cell_w, -cell_h),
            top_left + Vector::new(0.0, -cell_h),
        ];
        let (color, width) = if drawn { (Some(Aci::BLACK), 0.5 * s.link) } else { (None, 0.0) };
        d.push(Entity {
            layer: panels,
            color,
            linetype: None,
            shape: Shape::Polyline { points: corners, closed: true, width },
        });
        let o = t.o.map(|p| p + off);
        let a = c.a.map(|p| p + off);
        for (o, r) in o.iter().zip(t.r) {
            d.add(construction, Shape::Circle { center: *o, radius: r });
        }
        for (o, p) in o.iter().zip(a) {
            vocab::link(&mut d, mechanism, vec![*o, p], false, None, s);
        }
        vocab::link(&mut d, mechanism, a.to_vec(), true, None, s);
        for p in o {
            vocab::ground(&mut d, mechanism, p, s);
        }
        for p in a {
            vocab::joint(&mut d, mechanism, p, s);
        }
        let x = top_left.x + pad;
        d.text(text, Point::new(x, top_left.y - heading_base), s.text, mode_heading(k + 1, c, drawn));
        caption(&mut d, text, Point::new(x, top_left.y - angles_base), &[mode_angles(c)], small_text);
    }
    // The length scale and its bar above the first row, the title above them, its last
    // line's descent `gap` clear of the scale.
    let scale_top = Point::new(0.0, gap + 3.0 * s.small_text());
    length_scale_block(&mut d, text, scale_top, k_l, m.units, s);
    let lines = m.title.len().saturating_sub(1) as f64;
    let title_base = scale_top.y + gap + 0.3 * s.text + 1.8 * s.text * lines;
    caption(&mut d, text, Point::new(0.0, title_base), m.title, s.text);
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn texts_of_a_mode() {
        let c = Configuration {
            phi: [75.7692f64.to_radians(), 102.2287f64.to_radians(), 117.0448f64.to_radians()],
            a: [Point::origin(); 3],
            orientation: Orientation::Ccw,
            residual: 0.0,
        };
        assert_eq!(mode_heading(1, &c, true), "Mode 1 · counter-clockwise · drawn in Fig. 3");
        let angles = mode_angles(&c);
        assert_eq!(angles.text, "φ1 = 75.77°, φ2 = 102.23°, φ3 = 117.04°");
        let subs: Vec<&str> =
            angles.runs.split(&angles.text).filter(|(_, k)| *k == crate::draw::RunKind::Sub).map(|(s, _)| s).collect();
        assert_eq!(subs, ["1", "2", "3"]);
        assert_eq!(phi_text(2, c.phi[1]), "φ2 = 102.23°");
    }
}
