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
//! [`modes_sheet`] draws every assembly mode as small multiples: one cell per mode, in
//! the report's order, each with the circles, the mode's triangle and links, the joints'
//! names O1 … A3 (placed by the letter placer clear of every line, joint and symbol), its
//! number, orientation and phi1, phi2, phi3; the mode drawn in Fig. 3 is marked. The
//! sheet is laid out on [`MODES_PAPER`] (A3) either way round ([`modes_layout`]): of every
//! grid, the one holding every sketch at the finest drafting scale, each sketch centred in
//! its cell under the cell's texts. Layers: `PANELS` (cell frames), `CONSTRUCTION`,
//! `MECHANISM`, `TEXT`.
//!
//! Both are drawn on paper: a length scale k_l (model units per paper millimetre) — for
//! Fig. 3 the nice value drawing the three circles at most [`TRIAD_MM`] long (A4), for the
//! sheet the layout's drafting scale — the drawing carries `paper_mm_per_unit = 1/k_l`,
//! sizes are the shared table's from paper millimetres ([`Sizes::on_paper`]: letters
//! 3.5 mm), and k_l is printed (`k_l = 2 mm/mm`) above a scale bar; so a triad in metres
//! looks the same as one in millimetres.

use crate::draw::parts::widest_text_width;
use crate::draw::svg::SvgOptions;
use crate::draw::{Aci, Bounds, DimStyle, Drawing, Entity, LineType, Shape};
use crate::geom::{Point, Vector, angle_of};
use crate::solve::triad::{Configuration, Orientation, Triad};

use crate::figure::shared::construction::{
    arc_segments, caption, dimension_text_box, free_direction, keep_letters_off_dimension, length_scale_block,
    place_dimension,
};
use crate::figure::shared::labels::{self, Label, TextBox};
use crate::figure::shared::sheet::Paper;
use crate::figure::shared::vocab::{self, ModelUnits, PAPER_SMALL_TEXT_MM, PAPER_TEXT_MM, Sizes};

/// Width of the seed's polylines (`Pline A1 "W" "0.5" "0.5" A2 A3 "Close"`), drawing
/// millimetres.
pub const SEED_PLINE_WIDTH_MM: f64 = 0.5;

/// Largest extent of the three circles of Fig. 3 on paper, millimetres.
pub const TRIAD_MM: f64 = 150.0;

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
    name_joints(&mut letters, &t.o, &a, &f.exact.phi, s, true);
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

/// The paper the assembly-mode sheet is laid out on, either way round: A3, the paper the
/// sheet needed before it was laid out on one (317 × 275 mm at k_l = 5 mm/mm).
pub const MODES_PAPER: Paper = Paper::A3;
/// The room on a page of `page` (width, height, paper millimetres) for what the modes sheet
/// draws: its SVG, written with the default margin ([`SvgOptions::margin`], a share of the
/// drawing's larger side on each side), is then no larger than the page.
pub fn modes_area(page: Vector) -> Vector {
    let m = 2.0 * SvgOptions::default().margin;
    if page.y >= page.x {
        let h = page.y / (1.0 + m);
        Vector::new(page.x - m * h, h)
    } else {
        let w = page.x / (1.0 + m);
        Vector::new(w, page.y - m * w)
    }
}
/// Gap between two cells of the modes sheet, and between the cells and the caption block
/// above them, paper millimetres (a letter height).
pub const MODES_GAP_MM: f64 = PAPER_TEXT_MM;
/// Padding inside a cell around its texts and its sketch, paper millimetres.
pub const MODES_PAD_MM: f64 = PAPER_SMALL_TEXT_MM;

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

/// The heading of mode `number` (from 1) in its panel: `Mode 3 · clockwise`, `Mode 1 ·
/// counter-clockwise · in Fig. 3` for the mode Fig. 3 draws.
pub fn mode_heading(number: usize, c: &Configuration, drawn: bool) -> String {
    let mark = if drawn { " · in Fig. 3" } else { "" };
    format!("Mode {number} · {}{mark}", orientation_text(c.orientation))
}

/// The angles of a mode as a panel writes them: `φ1 = 75.77°, φ2 = …, φ3 = …` (commas: SVG
/// collapses runs of spaces), each index a subscript where the writer can (φ_1), flat in the
/// DXF.
pub fn mode_angles(c: &Configuration) -> Label {
    Label::marked(&(0..3).map(|i| phi_markup(i + 1, c.phi[i])).collect::<Vec<_>>().join(", "))
}

/// What a sketch of the sheet covers (the circles and the ground symbols), unshifted, model
/// units.
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

/// How the assembly-mode sheet is laid out on its page: the grid and the one length scale
/// of every sketch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModesLayout {
    /// The page as it is turned (width, height), paper millimetres.
    pub page: Vector,
    /// Cells to a row.
    pub columns: usize,
    /// Rows of cells.
    pub rows: usize,
    /// A cell's width and height, paper millimetres.
    pub cell: Vector,
    /// The length scale of every sketch, model units per paper millimetre (a drafting
    /// scale, [`vocab::drafting_scale`]).
    pub k_l: f64,
}

/// Height of a cell's header (its heading and its angles line, padded), paper millimetres.
pub fn modes_header_mm() -> f64 {
    2.0 * MODES_PAD_MM + PAPER_TEXT_MM + 1.8 * SMALL_TEXT * PAPER_TEXT_MM
}

/// Height of the caption block above the cells (the title's `lines`, the length scale and
/// its bar), paper millimetres: from the title's first cap line down to the cells' top.
pub fn modes_caption_mm(lines: usize) -> f64 {
    let scale_top = MODES_GAP_MM + 3.0 * PAPER_SMALL_TEXT_MM;
    let more = lines.saturating_sub(1) as f64;
    scale_top + MODES_GAP_MM + 0.3 * PAPER_TEXT_MM + 1.8 * PAPER_TEXT_MM * more + PAPER_TEXT_MM
}

/// The layout of `m`'s sheet: of every grid (columns × rows, no row empty) on
/// [`MODES_PAPER`] either way round, the one whose cells hold every sketch (its circles and
/// ground symbols, [`MODES_PAD_MM`] clear of the cell's sides and under its header) at the
/// finest drafting scale, each heading and angles line as the widest reader draws it
/// ([`widest_text_width`]) and the title within the page's width; on a tie the one whose
/// sketch fills more of its cell. When no grid holds the texts, the finest scale whatever
/// they need.
pub fn modes_layout(m: &ModesSheet) -> ModesLayout {
    let t = m.triad;
    let n = m.modes.len().max(1);
    let widest_cell_text = m.modes.iter().enumerate().fold(0.0f64, |w, (k, c)| {
        let heading = widest_text_width(&mode_heading(k + 1, c, k == m.drawn), PAPER_TEXT_MM);
        w.max(heading).max(widest_text_width(&mode_angles(c).text, SMALL_TEXT * PAPER_TEXT_MM))
    });
    let widest_title = m.title.iter().map(|l| widest_text_width(&l.text, PAPER_TEXT_MM)).fold(0.0, f64::max);
    let size = MODES_PAPER.size_mm();
    let (pad, gap) = (MODES_PAD_MM, MODES_GAP_MM);
    // The sketch's size on paper at k (its ground symbols are paper-sized).
    let sketch = |k: f64| {
        let b = panel_extent(t, Sizes::on_paper(k));
        Vector::new(b.width(), b.height()) / k
    };
    // The circles alone (no symbol: sizes 0), model units.
    let circles = panel_extent(t, Sizes::on_paper(0.0));
    let mut best: Option<(bool, f64, f64, ModesLayout)> = None;
    for page in [size, Vector::new(size.y, size.x)] {
        let area = modes_area(page);
        let width = area.x;
        let height = area.y - modes_caption_mm(m.title.len()) - gap;
        for columns in 1..=n {
            let rows = n.div_ceil(columns);
            let cell = Vector::new(
                (width - (columns - 1) as f64 * gap) / columns as f64,
                (height - (rows - 1) as f64 * gap) / rows as f64,
            );
            let room = Vector::new(cell.x - 2.0 * pad, cell.y - modes_header_mm() - pad);
            if room.x <= 0.0 || room.y <= 0.0 {
                continue;
            }
            let texts_fit = widest_cell_text + 2.0 * pad <= cell.x && widest_title <= width;
            // From the circles alone (a lower bound), coarser until the sketch fits.
            let mut k = vocab::drafting_scale((circles.width() / room.x).max(circles.height() / room.y));
            let fits = |k: f64| {
                let s = sketch(k);
                s.x <= room.x && s.y <= room.y
            };
            for _ in 0..64 {
                if fits(k) {
                    break;
                }
                k = vocab::coarser_drafting_scale(k);
            }
            if !fits(k) {
                continue;
            }
            let s = sketch(k);
            let fill = (s.x / room.x).min(s.y / room.y);
            let layout = ModesLayout { page, columns, rows, cell, k_l: k };
            let better = match best {
                None => true,
                Some((f, bk, bfill, _)) => {
                    (texts_fit && !f)
                        || (texts_fit == f && (k < bk * (1.0 - 1e-9) || (k <= bk * (1.0 + 1e-9) && fill > bfill)))
                }
            };
            if better {
                best = Some((texts_fit, k, fill, layout));
            }
        }
    }
    best.map(|b| b.3).unwrap_or(ModesLayout {
        page: size,
        columns: 1,
        rows: n,
        cell: size,
        k_l: vocab::drafting_scale(circles_extent(t) / size.x),
    })
}

/// The names O1 … O3, A1 … A3 of a triad drawn at `a`, each preferably in the widest free
/// direction around its point (at O_i clear of the link, of the ground symbol below and,
/// when `dimensioned`, of the sector of φ_i's angular dimension from +x; at A_i clear of the
/// link back to O_i, the two sides and the circle through A_i), clear of the joint circle.
fn name_joints(
    letters: &mut labels::Polygon,
    o: &[Point; 3],
    a: &[Point; 3],
    phi: &[f64; 3],
    s: Sizes,
    dimensioned: bool,
) {
    let toward = |dir: f64| Vector::new(libm::cos(dir), libm::sin(dir));
    let half_pi = std::f64::consts::FRAC_PI_2;
    for i in 0..3 {
        let mut occupied: Vec<f64> =
            if dimensioned { (0..=8).map(|k| phi[i] * k as f64 / 8.0).collect() } else { vec![phi[i]] };
        occupied.extend([-half_pi - 0.5, -half_pi + 0.5]);
        let dir = free_direction(&occupied);
        letters.letter_clear(o[i], format!("O{}", i + 1), s.text, toward(dir), s.joint);
        let occupied = [
            angle_of(o[i] - a[i]),
            angle_of(a[(i + 1) % 3] - a[i]),
            angle_of(a[(i + 2) % 3] - a[i]),
            phi[i] + half_pi,
            phi[i] - half_pi,
        ];
        let dir = free_direction(&occupied);
        letters.letter_clear(a[i], format!("A{}", i + 1), s.text, toward(dir), s.joint);
    }
}

/// A line `width` wide from `u` to `v` as the letters keep off it: its middle and both edges.
fn wide_segment(letters: &mut labels::Polygon, u: Point, v: Point, width: f64) {
    let n = vocab::unit_or(v - u, Vector::new(1.0, 0.0));
    let side = Vector::new(-n.y, n.x) * (0.5 * width);
    for shift in [Vector::zeros(), side, -side] {
        letters.segment(u + shift, v + shift);
    }
}

/// Draws mode `c` of `t` shifted by `off` on `layers` (construction, mechanism): the
/// circles, the links and the triangle, the ground pivots and the joints; returns the
/// joints' names O1 … A3 ready to place ([`name_joints`]) clear of every line (a link by
/// both its edges), joint circle and ground symbol.
fn sketch(d: &mut Drawing, layers: [usize; 2], t: &Triad, c: &Configuration, off: Vector, s: Sizes) -> labels::Polygon {
    let [construction, mechanism] = layers;
    let o = t.o.map(|p| p + off);
    let a = c.a.map(|p| p + off);
    let mut letters = labels::Polygon::of_names().apart(labels::LABEL_GAP * s.text);
    for (o, r) in o.iter().zip(t.r) {
        d.add(construction, Shape::Circle { center: *o, radius: r });
        let mut chords = Vec::new();
        arc_segments(&mut chords, *o, r, 0.0, std::f64::consts::TAU);
        chords.into_iter().for_each(|(u, v)| letters.segment(u, v));
    }
    for (o, p) in o.iter().zip(a) {
        vocab::link(d, mechanism, vec![*o, p], false, None, s);
        wide_segment(&mut letters, *o, p, s.link);
    }
    vocab::link(d, mechanism, a.to_vec(), true, None, s);
    for i in 0..3 {
        wide_segment(&mut letters, a[i], a[(i + 1) % 3], s.link);
    }
    for p in o {
        vocab::ground(d, mechanism, p, s);
        letters.keep_off(vocab::ground_extent(p, s));
    }
    for p in a {
        vocab::joint(d, mechanism, p, s);
    }
    // Every joint's circle: a name keeps off the others' (its own keeps its clearance).
    for p in o.iter().chain(&a) {
        letters.keep_off(TextBox { min: p - Vector::new(s.joint, s.joint), max: p + Vector::new(s.joint, s.joint) });
    }
    name_joints(&mut letters, &o, &a, &c.phi, s, false);
    letters
}

/// Every assembly mode of `m` as small multiples (see the module docs).
pub fn modes_sheet(m: &ModesSheet) -> Drawing {
    let t = m.triad;
    let layout = modes_layout(m);
    // Every sketch at one length scale, its sizes from paper millimetres; the layout's
    // paper millimetres × k_l are model units.
    let k_l = layout.k_l;
    let s = Sizes::on_paper(k_l);
    let content = panel_extent(t, s);
    let mut d = Drawing::new(DimStyle { text_height: 0.85 * s.text, arrow_size: 0.75 * s.text });
    d.paper_mm_per_unit = Some(1.0 / k_l);
    let panels = d.layer("PANELS", Aci::LIGHT_GREY, LineType::Continuous);
    let construction = d.layer("CONSTRUCTION", Aci::DARK_GREY, LineType::Continuous);
    let mechanism = d.layer("MECHANISM", Aci::BLACK, LineType::Continuous);
    let text = d.layer("TEXT", Aci::BLACK, LineType::Continuous);

    let small_text = SMALL_TEXT * s.text;
    let pad = MODES_PAD_MM * k_l;
    let gap = MODES_GAP_MM * k_l;
    // Header: the heading and the angles, then the sketch, centred in the rest of the cell.
    let heading_base = pad + s.text;
    let angles_base = heading_base + 1.8 * small_text;
    let header = modes_header_mm() * k_l;
    let (cell_w, cell_h) = (layout.cell.x * k_l, layout.cell.y * k_l);
    let columns = layout.columns;

    for (k, c) in m.modes.iter().enumerate() {
        let (col, row) = (k % columns, k / columns);
        let top_left = Point::new(col as f64 * (cell_w + gap), -(row as f64) * (cell_h + gap));
        let area = Bounds {
            min: top_left + Vector::new(pad, -cell_h + pad),
            max: top_left + Vector::new(cell_w - pad, -header),
        };
        let off = Vector::new(
            0.5 * (area.min.x + area.max.x) - 0.5 * (content.min.x + content.max.x),
            0.5 * (area.min.y + area.max.y) - 0.5 * (content.min.y + content.max.y),
        );
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
        let within = TextBox {
            min: top_left + Vector::new(0.5 * pad, -cell_h + 0.5 * pad),
            max: top_left + Vector::new(cell_w - 0.5 * pad, -header + 0.5 * pad),
        };
        let mut letters = sketch(&mut d, [construction, mechanism], t, c, off, s);
        let x = top_left.x + pad;
        d.text(text, Point::new(x, top_left.y - heading_base), s.text, mode_heading(k + 1, c, drawn));
        caption(&mut d, text, Point::new(x, top_left.y - angles_base), &[mode_angles(c)], small_text);
        // The joints' names inside the cell, under its header.
        letters.keep_within(within);
        letters.draw(&mut d, text);
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
        assert_eq!(mode_heading(1, &c, true), "Mode 1 · counter-clockwise · in Fig. 3");
        let angles = mode_angles(&c);
        assert_eq!(angles.text, "φ1 = 75.77°, φ2 = 102.23°, φ3 = 117.04°");
        let subs: Vec<&str> =
            angles.runs.split(&angles.text).filter(|(_, k)| *k == crate::draw::RunKind::Sub).map(|(s, _)| s).collect();
        assert_eq!(subs, ["1", "2", "3"]);
        assert_eq!(phi_text(2, c.phi[1]), "φ2 = 102.23°");
    }
}
