//! A detail view of a linkage's crank (issue 31: crank ≥ 25 mm on every sheet), as a
//! draftsman draws a part too small at the sheet's scale (ISO 128-30 detail views): when the
//! crank would be drawn shorter than [`CRANK_MIN_MM`] at the page's k_l, the neighbourhood of
//! its ground pivot (the crank, its joints, the circle its far point runs on, the first
//! millimetres of the links it carries) is drawn again enlarged, at the coarsest ISO 5455
//! scale (1, 2, 5 × 10ᵏ) that draws the crank at least [`CRANK_MIN_MM`] long, in a panel of
//! its own captioned `Detail B (5:1)` with its k_l and a scale bar; the region is marked on
//! the main view by a thin circle and the detail's letter. What lies outside the region is
//! cut at a thin circle, the region's edge.

use crate::draw::{Bounds, Drawing, HAlign, Runs, Shape, VAlign};
use crate::geom::{Point, Vector};
use crate::solve::linkage::{Anchor, Attach, place};

use crate::figure::linkage::{self as fig, JointSymbol, LinkageFigure};
use crate::figure::shared::labels::{self, TextBox};
use crate::figure::shared::sheet::Panel;
use crate::figure::shared::vocab::{self, Sizes, length_scale_text};

/// The least length of the crank on a sheet, paper mm: below it the crank gets a detail view.
pub const CRANK_MIN_MM: f64 = 25.0;
/// Room around the crank's circle inside the detail's region, in letter heights (the
/// joints' names and the ω arrow's letter).
const REGION_ROOM: f64 = 4.0;

/// A detail view of the crank: where, at which scale, how large.
#[derive(Debug, Clone, PartialEq)]
pub struct Detail {
    /// Its letter: the first capital that no point's name starts with (`B` beside O1, C,
    /// A1, A2, A3), else the first that names no point.
    pub letter: String,
    /// Its scale: model units per paper mm.
    pub k: f64,
    /// The model's millimetres per unit (for the ratio `5:1`).
    mm_per_unit: f64,
    /// The crank's body.
    body: usize,
    /// The crank's ground pivot (the region's centre), on the crank's body.
    pivot: Anchor,
    /// The crank's length (its longest distance between two of its points), model units.
    crank: f64,
    /// The region's radius, paper mm in the detail.
    radius_mm: f64,
}

/// The crank's length of `figure`: the longest distance between two points of its body,
/// model units; with its body and pivot.
fn crank_of(figure: &LinkageFigure) -> Option<(usize, Anchor, f64)> {
    let (body, pivot) = figure.crank?;
    let pts = &figure.bodies.get(body)?.points;
    let len = pts.iter().flat_map(|(_, a)| pts.iter().map(move |(_, c)| (a - c).norm())).fold(0.0, f64::max);
    (len > 0.0 && len.is_finite()).then_some((body, pivot, len))
}

/// The coarsest scale of ISO 5455's series (1, 2, 5 × 10ᵏ: 1:1, 1:2, 1:5, 2:1, 5:1, 10:1 …)
/// at most `raw` (paper-independent, mm per mm).
pub fn iso_scale(raw: f64) -> f64 {
    if !(raw.is_finite() && raw > 0.0) {
        return 1.0;
    }
    let mag = libm::pow(10f64, libm::log10(raw).floor());
    [5.0, 2.0, 1.0].iter().map(|m| m * mag).find(|k| *k <= raw * (1.0 + 1e-12)).unwrap_or(mag)
}

/// The ratio of a scale of `k_mm` model mm per paper mm as ISO 5455 writes it: `5:1`, `1:2`.
pub fn ratio_text(k_mm: f64) -> String {
    if k_mm < 1.0 {
        format!("{}:1", vocab::scale_text(libm::round(1.0 / k_mm)))
    } else {
        format!("1:{}", vocab::scale_text(k_mm))
    }
}

impl Detail {
    /// The detail `figure` (model units) needs at the page's scale `k_l` (model units per
    /// paper mm), for letters of `s`: `None` when its crank is drawn at least
    /// [`CRANK_MIN_MM`] long, or it has no crank.
    pub fn needed(figure: &LinkageFigure, k_l: f64, s: Sizes) -> Option<Detail> {
        let (body, pivot, crank) = crank_of(figure)?;
        if crank / k_l >= CRANK_MIN_MM * (1.0 - 1e-12) {
            return None;
        }
        let mm_per_unit = figure.units.mm_per_unit;
        let k = iso_scale(crank * mm_per_unit / CRANK_MIN_MM) / mm_per_unit;
        let names: Vec<&str> = figure
            .bodies
            .iter()
            .flat_map(|b| b.points.iter().map(|(n, _)| n.as_str()))
            .chain(figure.joints.iter().filter_map(|j| match j {
                JointSymbol::Pin { name, .. } => Some(name.as_str()),
                JointSymbol::Slider { name, .. } => name.as_deref(),
            }))
            .collect();
        // A letter that no point's name starts with (not A beside A1, A2, A3), else one that
        // names no point.
        let initial = |c: char| names.iter().any(|n| n.starts_with(c));
        let letter = ('A'..='Z')
            .find(|&c| !initial(c))
            .or_else(|| ('A'..='Z').find(|c| !names.contains(&c.to_string().as_str())))
            .map(String::from)
            .unwrap_or_default();
        let radius_mm = crank / k + REGION_ROOM * s.text;
        Some(Detail { letter, k, mm_per_unit, body, pivot, crank, radius_mm })
    }

    /// The outline of the detail's panel, paper mm, as a draftsman sizes a detail view to
    /// its content: the region's circle with the panel's margins ([`Panel::of_outline`]:
    /// the caption's band over it, the scale bar's strip under it), at least as wide as its
    /// caption ([`Detail::caption`] in `units`).
    pub fn panel_size(&self, s: Sizes, units: vocab::ModelUnits) -> Vector {
        let probe = Panel::of_outline(Bounds { min: Point::origin(), max: Point::new(100.0, 100.0) }, s);
        let margins = Vector::new(100.0 - probe.area.width(), 100.0 - probe.area.height());
        let region = Vector::new(2.0 * self.radius_mm, 2.0 * self.radius_mm) + margins;
        let caption = crate::draw::parts::widest_text_width(&self.caption(units), s.text) + 1.2 * s.text;
        Vector::new(region.x.max(caption), region.y)
    }

    /// The crank as drawn in the detail, paper mm.
    pub fn crank_mm(&self) -> f64 {
        self.crank / self.k
    }

    /// The panel's caption: `Detail B (5:1)   k_l = 0.2 mm/mm`.
    pub fn caption(&self, units: vocab::ModelUnits) -> String {
        format!(
            "Detail {} ({})   {}",
            self.letter,
            ratio_text(self.k * self.mm_per_unit),
            length_scale_text(self.k, units)
        )
    }

    /// Marks the region on the main view: a thin circle about the crank's pivot at `q` (the
    /// main view's figure `main` and coordinates, drawn at `k_l`), on `layer`. Returns the
    /// circle (centre, radius) for [`Detail::letter_on`].
    pub fn mark(&self, d: &mut Drawing, layer: usize, q: &[f64], k_l: f64) -> (Point, f64) {
        let pivot = Anchor { body: self.pivot.body, local: self.pivot.local / k_l };
        let c = fig::anchor_at(q, pivot);
        let r = self.radius_mm * self.k / k_l;
        d.add(layer, Shape::Circle { center: c, radius: r });
        (c, r)
    }

    /// The detail's letter beside its circle on the main view (after everything else on it
    /// is drawn, in the first free place around the circle, inside `within`).
    pub fn letter_on(&self, d: &mut Drawing, layer: usize, (c, r): (Point, f64), within: TextBox, s: Sizes) {
        let h = 1.2 * s.text;
        let text = |at: Point, value: String| Shape::Text {
            runs: Runs::flat(),
            at,
            height: h,
            value,
            halign: HAlign::Center,
            valign: VAlign::Middle,
            rotation: 0.0,
        };
        let candidates = [45.0, 135.0, -45.0, -135.0, 90.0, 0.0, 180.0, -90.0, 22.5, 67.5, 112.5, 157.5]
            .iter()
            .flat_map(|deg: &f64| {
                [0.7, 1.5, 2.5].map(|gap| {
                    let a = deg.to_radians();
                    let u = Vector::new(libm::cos(a), libm::sin(a));
                    // The text's centre beyond the circle, its box clear of it.
                    let at = c + u * (r + gap * h + 0.5 * h);
                    text(at, format!("  {}  ", self.letter))
                })
            })
            .collect();
        // Tried with a space either side, so that the letter stands apart from the names
        // beside it (`O1 A`, not `O1A`); drawn without.
        if let Some(Shape::Text { at, .. }) = labels::first_free(d, candidates, Some(within), &[]) {
            d.add(layer, text(at, self.letter.clone()));
        }
    }

    /// Draws the detail in `panel` of `d` on `layer` (the crank's circle on `path_layer`):
    /// `figure` in model units at `q` (model coordinates), `spans` the ground guides over
    /// the motion (model), `omega` the crank's angular velocity (rad/s) for its ω arrow.
    #[allow(clippy::too_many_arguments)]
    pub fn draw(
        &self,
        d: &mut Drawing,
        (layer, path_layer): (usize, usize),
        figure: &LinkageFigure,
        q: &[f64],
        spans: &[Option<(Point, Point)>],
        panel: &Panel,
        omega: Option<f64>,
        s: Sizes,
    ) {
        let area = panel.area;
        let centre = Point::from((area.min.coords + area.max.coords) / 2.0);
        let pivot_model = place(q, self.pivot.body, self.pivot.local);
        let origin = centre - pivot_model.coords / self.k;
        let pf = figure.on_paper(origin, self.k);
        let qd = fig::on_paper(q, origin, self.k);
        let to_paper = |p: Point| origin + p.coords / self.k;
        let r = self.radius_mm;
        // The region's edge and the crank's circle.
        d.add(layer, Shape::Circle { center: centre, radius: r });
        d.add(path_layer, Shape::Circle { center: centre, radius: self.crank_mm() });
        let mut letters = labels::Polygon::of_names();
        let view = View { layer, pf: &pf, q: &qd, centre, s };
        self.draw_bodies(d, &view, &mut letters);
        for (a, b) in spans.iter().flatten() {
            if let Some((a, b)) = clip_to_circle(to_paper(*a), to_paper(*b), centre, r) {
                vocab::guide(d, layer, a, b, s);
                letters.segment(a, b);
            }
        }
        self.draw_joints(d, &view, &mut letters);
        if let Some(w) = omega.filter(|w| *w != 0.0 && w.is_finite()) {
            let crank = (self.body, Anchor { body: self.pivot.body, local: self.pivot.local / self.k });
            fig::crank_turn(d, layer, (&pf, &qd), crank, &[], w, s, &mut letters);
        }
        letters.keep_off_drawing(d);
        letters.keep_within(TextBox { min: panel.outline.min, max: panel.outline.max });
        letters.draw(d, layer);
    }

    /// The bodies' outlines cut at the region's edge (a body wholly inside drawn whole).
    fn draw_bodies(&self, d: &mut Drawing, view: &View, letters: &mut labels::Polygon) {
        let View { layer, pf, q, centre, s } = *view;
        let r = self.radius_mm;
        for (i, b) in pf.bodies.iter().enumerate() {
            let pts: Vec<Point> = b.points.iter().map(|(_, v)| place(q, Attach::Body(i), *v)).collect();
            let n = pts.len();
            let sides = if n >= 3 { n } else { n.saturating_sub(1) };
            let edges: Vec<(Point, Point)> = (0..sides).map(|k| (pts[k], pts[(k + 1) % n])).collect();
            if n >= 2 && pts.iter().all(|p| (p - centre).norm() <= r) {
                vocab::link(d, layer, pts.clone(), n >= 3, None, s);
                edges.iter().for_each(|(a, b)| letters.segment(*a, *b));
                continue;
            }
            for (a, b) in edges.iter().filter_map(|(a, b)| clip_to_circle(*a, *b, centre, r)) {
                vocab::link(d, layer, vec![a, b], false, None, s);
                letters.segment(a, b);
            }
        }
    }

    /// The joints inside the region, with their names, and the names of the bodies' other
    /// points inside it.
    fn draw_joints(&self, d: &mut Drawing, view: &View, letters: &mut labels::Polygon) {
        let View { layer, pf, q, centre, s } = *view;
        let inside = |p: Point, margin: f64| (p - centre).norm() + margin <= self.radius_mm;
        let mut labelled: Vec<Point> = Vec::new();
        let mut name_at = |letters: &mut labels::Polygon, p: Point, name: &str, dir: Vector| {
            if !labelled.iter().any(|x| (x - p).norm() <= s.joint) {
                labelled.push(p);
                letters.letter_clear(p, name, s.text, dir, s.joint);
            }
        };
        let up_right = Vector::new(1.8, 1.2);
        for j in &pf.joints {
            match j {
                JointSymbol::Pin { at, grounded, name } => {
                    let p = fig::anchor_at(q, *at);
                    if !inside(p, s.joint) {
                        continue;
                    }
                    if *grounded {
                        vocab::ground(d, layer, p, s);
                        letters.keep_off(vocab::ground_extent(p, s));
                    } else {
                        vocab::joint(d, layer, p, s);
                    }
                    name_at(letters, p, name, up_right);
                }
                JointSymbol::Slider { point, q1, q2, name } => {
                    let p = fig::anchor_at(q, *point);
                    let dir = fig::anchor_at(q, *q2) - fig::anchor_at(q, *q1);
                    if !inside(p, 0.5 * libm::hypot(s.slider_length, s.slider_height)) || dir.norm() == 0.0 {
                        continue;
                    }
                    let u = dir.normalize();
                    let (hl, hh) = vocab::slider(d, layer, p, u, s);
                    let n = crate::geom::perp(u);
                    let half = Vector::new(hl * u.x.abs() + hh * n.x.abs(), hl * u.y.abs() + hh * n.y.abs());
                    letters.keep_off(TextBox { min: p - half, max: p + half });
                    if let Some(name) = name {
                        name_at(letters, p, name, n);
                    }
                }
            }
        }
        for (i, b) in pf.bodies.iter().enumerate() {
            for (name, v) in &b.points {
                let p = place(q, Attach::Body(i), *v);
                if inside(p, s.joint) {
                    name_at(letters, p, name, up_right);
                }
            }
        }
    }
}

/// The detail's drawing on paper: its layer, the figure and coordinates placed at its scale
/// (paper mm), the region's centre and the letter sizes.
#[derive(Clone, Copy)]
struct View<'a> {
    layer: usize,
    pf: &'a LinkageFigure,
    q: &'a [f64],
    centre: Point,
    s: Sizes,
}

/// The part of the segment `a`–`b` inside the circle about `c` of radius `r`, `None` when it
/// misses it.
pub fn clip_to_circle(a: Point, b: Point, c: Point, r: f64) -> Option<(Point, Point)> {
    let (d, f) = (b - a, a - c);
    let (qa, qb, qc) = (d.dot(&d), 2.0 * f.dot(&d), f.dot(&f) - r * r);
    if qa == 0.0 {
        return None;
    }
    let disc = qb * qb - 4.0 * qa * qc;
    if disc <= 0.0 {
        return None;
    }
    let root = libm::sqrt(disc);
    let (t0, t1) = (((-qb - root) / (2.0 * qa)).max(0.0), ((-qb + root) / (2.0 * qa)).min(1.0));
    (t1 > t0).then(|| (a + d * t0, a + d * t1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn iso_scales_are_the_coarsest_of_1_2_5_at_most_the_raw_value() {
        assert_eq!(iso_scale(0.2), 0.2);
        assert_eq!(iso_scale(0.3), 0.2);
        assert_eq!(iso_scale(0.19), 0.1);
        assert_eq!(iso_scale(0.06), 0.05);
        assert_eq!(iso_scale(3.0), 2.0);
        assert_eq!(ratio_text(0.2), "5:1");
        assert_eq!(ratio_text(0.05), "20:1");
        assert_eq!(ratio_text(2.0), "1:2");
    }

    #[test]
    fn a_segment_is_cut_at_the_circle() {
        let c = Point::new(0.0, 0.0);
        let (a, b) = clip_to_circle(Point::new(0.0, 0.0), Point::new(10.0, 0.0), c, 4.0).unwrap();
        assert!((a - Point::new(0.0, 0.0)).norm() < 1e-12 && (b - Point::new(4.0, 0.0)).norm() < 1e-12);
        assert!(clip_to_circle(Point::new(-10.0, 5.0), Point::new(10.0, 5.0), c, 4.0).is_none());
        let (a, b) = clip_to_circle(Point::new(-10.0, 0.0), Point::new(10.0, 0.0), c, 4.0).unwrap();
        assert!((a.x + 4.0).abs() < 1e-12 && (b.x - 4.0).abs() < 1e-12);
    }
}
