//! Joukowski's lever drawn: the velocity polygon turned 90° clockwise about its pole p,
//! every load applied at the image of its point with its own direction, named, and the
//! balancing force F_b at a (dashed, red) that the lever's moments about p give: a sheet
//! `<name>-joukowski` with one panel per chosen position and, under each, the sum of the
//! moments and Me1 = −Σ M_p(F_i)/ω1 beside the reactions route's Me1 (the numbers from
//! [`crate::solve::fourbar::joukowski`]).
//!
//! The velocity scale is shared by the panels and nice (1, 2, 2.5, 5 × 10ᵏ), the turned
//! polygon's largest image at most 0.55 of the panel width. The loads' arrows all have one length
//! (they differ by two orders of magnitude): they show direction and point of application;
//! a table under the panel gives each load's magnitude and moment about p.

use crate::draw::{Aci, DimStyle, Drawing, Entity, HAlign, LineType, ScaleCaption, Shape, VAlign};
use crate::geom::{Point, Vector, perp};
use crate::solve::fourbar::joukowski::{Lever, LeverForce, image_point};

use crate::figure::fourbar::angle_text;
use crate::figure::shared::labels::{self, Label};
use crate::figure::shared::vocab::{
    ModelUnits, Scale, Sizes, content_drawing, layer_of, layers, length_scale, nice_scale, pole, unit_or, vector,
};

/// One panel of the sheet: a lever and what to print under it.
#[derive(Debug, Clone)]
pub struct LeverPanel<'a> {
    /// Crank angle, degrees.
    pub phi1_deg: f64,
    /// The lever at that angle.
    pub lever: &'a Lever,
    /// Me1 by the reactions route, for comparison (same unit as the lever's).
    pub me1_reactions: f64,
    /// ω1, rad/s.
    pub omega1: f64,
}

/// Units for the sheet's texts.
#[derive(Debug, Clone, Copy)]
pub struct LeverUnits {
    /// The model's length unit (m or mm) and drawing millimetres per unit.
    pub model: ModelUnits,
    /// The moment unit (`N·m`, `N·mm`).
    pub moment: &'static str,
}

/// `v` to four significant digits, never with an exponent ([`crate::figure::shared::sheet::number`]).
pub fn sig4(v: f64) -> String {
    crate::figure::shared::sheet::number(v)
}

/// Length of a load's arrow on the lever, in panel sizes: the loads differ by two orders
/// of magnitude (F = 50 N beside weights of 1.2 N in the template), so the arrows show
/// directions and points of application and the table under the panel their magnitudes
/// and moments.
const ARROW: f64 = 0.12;

/// Width of a lever panel on paper, millimetres (k_l is the nice value that draws it so).
const LEVER_PANEL_MM: f64 = 110.0;

/// Height of a panel's lever area, in panel widths.
const LEVER_HEIGHT: f64 = 0.85;

/// A text line of a panel, marked up with `_` before each subscript (`M_e1 = −Σ M_p(F_i)`:
/// [`crate::draw::Runs::underscored`], the `_` written only in the DXF).
fn line(d: &mut Drawing, layer: usize, at: Point, height: f64, value: String, halign: HAlign) {
    let runs = crate::draw::Runs::underscored(&value);
    labelled(d, layer, at, height, Label { text: value, runs }, halign);
}

/// A text of a panel drawn as `label` states it (a load's name: F_i21).
fn labelled(d: &mut Drawing, layer: usize, at: Point, height: f64, label: Label, halign: HAlign) {
    let Label { text: value, runs } = label;
    let shape = Shape::Text { runs, at, height, value, halign, valign: VAlign::Top, rotation: 0.0 };
    d.push(Entity { layer, color: None, linetype: None, shape });
}

/// The sheet: panels side by side, each `size` model units square for the lever, with
/// the table of loads and the balance under it.
pub fn joukowski_sheet(panels: &[LeverPanel], units: LeverUnits, size: f64) -> Drawing {
    // On paper: each lever panel about LEVER_PANEL_MM wide at a nice k_l.
    let k_l = length_scale(size, LEVER_PANEL_MM);
    let s = Sizes::on_paper(k_l);
    let mut d = content_drawing(DimStyle { text_height: s.text, arrow_size: s.head });
    d.paper_mm_per_unit = Some(1.0 / k_l);
    let frame = d.layer("PANELS", Aci::LIGHT_GREY, LineType::Continuous);
    let size_mm = size / k_l;
    let max_image = panels.iter().flat_map(|p| p.lever.points.iter().map(|(_, v)| v.norm())).fold(0.0, f64::max);
    let small = 0.8 * s.text;
    // One table row per load (and F_b), under a header.
    let rows = panels.iter().map(|p| p.lever.forces.len() + 1).max().unwrap_or(0) + 1;
    let sheet = LeverSheet {
        k_l,
        s,
        k_v: Scale::on_paper(nice_scale(max_image / (0.55 * size_mm)), 1.0 / k_l),
        size,
        small,
        row: 1.6 * small,
        rows,
        units,
        speed: format!("{}/s", units.model.length),
        layers: (frame, layer_of(&d, layers::VELOCITY), layer_of(&d, layers::FORCES), layer_of(&d, layers::TEXT)),
    };
    let gap = 2.0 * s.text;
    for (k, panel) in panels.iter().enumerate() {
        sheet.panel(&mut d, panel, k as f64 * (size + gap));
    }
    d
}

/// The measures and layers a Joukowski sheet's panels share.
struct LeverSheet {
    k_l: f64,
    s: Sizes,
    /// The velocity polygon's scale, the same in every panel.
    k_v: Scale,
    /// A lever's square, model units.
    size: f64,
    /// The table's and the notes' letter height and row.
    small: f64,
    row: f64,
    /// The table's rows (the most loads of a panel, F_b, the header).
    rows: usize,
    units: LeverUnits,
    /// The velocities' unit (`m/s`).
    speed: String,
    /// The panels', the polygon's, the forces' and the texts' layers.
    layers: (usize, usize, usize, usize),
}

impl LeverSheet {
    /// Room under a lever for its table and the balance's lines.
    fn notes_room(&self) -> f64 {
        (self.rows as f64 + 6.0 + 1.0) * self.row
    }

    /// A panel from `x0`: its frame and title, the lever, the table and the balance.
    fn panel(&self, d: &mut Drawing, panel: &LeverPanel, x0: f64) {
        let s = self.s;
        let (lo, hi) = (Point::new(x0, 0.0), Point::new(x0 + self.size, LEVER_HEIGHT * self.size));
        let title_room = 2.2 * s.text;
        let corners = vec![
            Point::new(lo.x, lo.y - self.notes_room()),
            Point::new(hi.x, lo.y - self.notes_room()),
            Point::new(hi.x, hi.y + title_room),
            Point::new(lo.x, hi.y + title_room),
        ];
        let frame_box = labels::TextBox { min: corners[0], max: corners[2] };
        d.add(self.layers.0, Shape::Polyline { points: corners, closed: true, width: 0.0 });
        // φ_1 and ω_1 where the writer can draw a subscript, `φ1` in the DXF.
        let title = if panel.lever.crank_speed != panel.omega1 {
            format!("Joukowski's lever   φ_1 = {}°, ω_1 = 0", angle_text(panel.phi1_deg))
        } else {
            format!("Joukowski's lever   φ_1 = {}°", angle_text(panel.phi1_deg))
        };
        let Label { text: value, runs } = Label::marked(&title);
        let at = Point::new(lo.x + 0.5 * s.text, hi.y + 0.7 * s.text);
        let shape = Shape::Text {
            runs,
            at,
            height: s.text,
            value,
            halign: HAlign::Left,
            valign: VAlign::Baseline,
            rotation: 0.0,
        };
        d.push(Entity { layer: self.layers.3, color: None, linetype: None, shape });
        self.lever(d, panel.lever, (lo, hi), frame_box);
        let left = lo.x + 0.5 * s.text;
        let top = lo.y - 0.3 * self.row;
        self.table(d, panel.lever, left, top);
        self.balance(d, panel, left, top - (self.rows as f64 + 0.5) * self.row);
    }

    /// The lever in the square `lo`–`hi`: the velocity polygon turned 90°, each load at its
    /// image point (the balancing force dashed), the points' letters and the loads' names
    /// inside `frame_box`.
    fn lever(&self, d: &mut Drawing, lever: &Lever, (lo, hi): (Point, Point), frame_box: labels::TextBox) {
        let (s, k_v) = (self.s, self.k_v);
        let (_, vel, frc, _) = self.layers;
        let arrows: Vec<(&LeverForce, bool)> =
            lever.forces.iter().map(|f| (f, false)).chain(lever.balancing.iter().map(|f| (f, true))).collect();
        let arrow = ARROW * self.size;
        let dir = |f: &LeverForce| unit_or(f.force, Vector::zeros()) * arrow;
        // Every drawn point relative to the pole, to centre the lever in its panel.
        let mut ext_min = Vector::zeros();
        let mut ext_max = Vector::zeros();
        let mut grow = |v: Vector| {
            ext_min = ext_min.inf(&v);
            ext_max = ext_max.sup(&v);
        };
        for (_, v) in &lever.points {
            grow(k_v.draw(*v));
        }
        for (f, _) in &arrows {
            grow(k_v.draw(f.image) + dir(f));
        }
        let centre = Point::from((lo.coords + hi.coords) / 2.0);
        let p0 = centre - (ext_min + ext_max) / 2.0;
        let at = |v: Vector| p0 + k_v.draw(v);
        let mut letters = labels::Polygon::of_points();
        let mut names = labels::Polygon::of_names();
        // The turned polygon: pa, pb, pm and the coupler's image a b m.
        let img = |n: &str| image_point(lever, n).unwrap_or_else(Vector::zeros);
        for (a, b) in [("p", "a"), ("p", "b"), ("p", "m"), ("a", "b"), ("b", "m")] {
            let (pa, pb) = (at(img(a)), at(img(b)));
            d.add(vel, Shape::Line { from: pa, to: pb });
            letters.segment(pa, pb);
            names.segment(pa, pb);
        }
        pole(d, vel, p0, s);
        let mid = at((img("a") + img("b") + img("m")) / 3.0);
        for (n, v) in &lever.points {
            let q = at(*v);
            if n.starts_with('c') {
                d.add(vel, Shape::Circle { center: q, radius: 0.25 * s.joint });
            }
            letters.letter(q, *n, s.text, q - mid, None);
        }
        for (f, balancing) in &arrows {
            let from = at(f.image);
            let v = dir(f);
            if *balancing {
                d.push(Entity {
                    layer: frc,
                    color: Some(Aci::RED),
                    linetype: Some(LineType::Dashed),
                    shape: Shape::Arrow { from, to: from + v, head: s.head },
                });
            } else {
                vector(d, frc, from, v, s);
            }
            names.segment(from, from + v);
        }
        // Clear of everything drawn (the polygon, the arrows, the title) and inside the panel.
        letters.keep_off_drawing(d);
        letters.keep_within(frame_box);
        let boxes = letters.draw(d, vel);
        for b in boxes {
            names.keep_off(b);
        }
        for (f, balancing) in &arrows {
            let from = at(f.image);
            let v = dir(f);
            let color = balancing.then_some(Aci::RED);
            names.name_with_leader(from + v * 0.6, Label::quantity(&f.name), self.small, perp(v), color);
        }
        names.keep_off_drawing(d);
        names.keep_within(frame_box);
        names.draw(d, frc);
    }

    /// The table under a lever from (`left`, `top`): load, its image point, |F| [N],
    /// M_p [N·(unit)/s].
    fn table(&self, d: &mut Drawing, lever: &Lever, left: f64, top: f64) {
        let (small, row, text) = (self.small, self.row, self.layers.3);
        let loads: Vec<&LeverForce> = lever.forces.iter().chain(lever.balancing.iter()).collect();
        let largest = loads.iter().map(|f| f.moment.abs()).fold(0.0, f64::max);
        let (at_x, f_x, m_x) = (left + 0.16 * self.size, left + 0.5 * self.size, left + 0.85 * self.size);
        line(d, text, Point::new(left, top), small, "load".into(), HAlign::Left);
        line(d, text, Point::new(at_x, top), small, "at".into(), HAlign::Left);
        line(d, text, Point::new(f_x, top), small, "|F| [N]".into(), HAlign::Right);
        line(d, text, Point::new(m_x, top), small, format!("M_p [N·{}]", self.speed), HAlign::Right);
        for (i, f) in loads.iter().enumerate() {
            let y = top - (i + 1) as f64 * row;
            labelled(d, text, Point::new(left, y), small, Label::quantity(&f.name), HAlign::Left);
            line(d, text, Point::new(at_x, y), small, f.at.to_string(), HAlign::Left);
            line(d, text, Point::new(f_x, y), small, sig4(f.force.norm()), HAlign::Right);
            // Rounding noise (a moment 1e-17 where an image point lies on the force's line).
            let m = if f.moment.abs() < 1e-12 * largest { 0.0 } else { f.moment };
            line(d, text, Point::new(m_x, y), small, sig4(m), HAlign::Right);
        }
    }

    /// The balance's lines from (`left`, `y0`): what the polygon is, its k_v, Σ M_p, M_e1
    /// by the lever and by the reactions.
    fn balance(&self, d: &mut Drawing, panel: &LeverPanel, left: f64, y0: f64) {
        let (lever, speed, units) = (panel.lever, &self.speed, self.units);
        let me1 = lever.me1.map_or("—".to_string(), sig4);
        // A standing crank: the polygon of virtual velocities, the crank at 1 rad/s.
        let standing = lever.crank_speed != panel.omega1;
        let (polygon, divisor) = if standing {
            ("polygon at ω_1 = 1 rad/s (virtual), 90° cw", "(1 rad/s)")
        } else {
            ("velocity polygon turned 90° clockwise", "ω_1")
        };
        let lines = [
            polygon.to_string(),
            String::new(),
            "Σ M_p(F_i) = Σ F_i·v_i (without F_b)".to_string(),
            format!("  = {} N·{speed}", sig4(lever.moment)),
            format!("M_e1 = −Σ M_p(F_i) / {divisor} = {me1} {}", units.moment),
            format!("by the reactions: M_e1 = {} {}", sig4(panel.me1_reactions), units.moment),
        ];
        for (i, l) in lines.into_iter().enumerate() {
            let at = Point::new(left, y0 - i as f64 * self.row);
            if i == 1 {
                // The velocity scale as the medium states it (on paper, or in the DXF's
                // millimetres).
                let caption = ScaleCaption::new("k_v = ", self.k_v.per_mm, format!(" ({speed})/mm"), 1.0 / self.k_l);
                let (height, halign, valign) = (self.small, HAlign::Left, VAlign::Top);
                d.add(self.layers.3, Shape::ScaleText { at, height, caption, halign, valign, rotation: 0.0 });
            } else {
                line(d, self.layers.3, at, self.small, l, HAlign::Left);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn four_significant_digits() {
        assert_eq!(sig4(-1.49012), "−1.490");
        assert_eq!(sig4(1490.12), "1490");
        assert_eq!(sig4(0.0123456), "0.01235");
        assert_eq!(sig4(0.0), "0");
        assert_eq!(sig4(1.5e7), "15000000");
        assert_eq!(sig4(-2.5e-6), "−0.000002500");
    }
}
