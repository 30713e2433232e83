//! The drawing vocabulary every mechanism figure shares: scales and their texts, the size
//! table, the content layers, and the symbols the graph-analytical method draws — ground
//! pivot, joint, link, named vector with its arrowhead and letter. A figure for a new
//! mechanism is built from these; nothing here knows a mechanism's fields.
//!
//! All sizes are model units. A figure printed on paper chooses its length scale k_l
//! (model units per paper millimetre, a nice value: [`length_scale`]), builds its sizes from
//! paper millimetres ([`Sizes::on_paper`]: letters 3.5 mm high on the printed page whatever
//! the mechanism's size) and draws each physical vector (m/s, m/s², N …) at a scale per
//! printed millimetre ([`Scale::on_paper`]); every panel carries a [`scale_bar`].

use crate::draw::parts::widest_text_width;
use crate::draw::{Aci, Drawing, Entity, ScaleCaption, Shape};
use crate::figure::shared::labels::TextBox;
use crate::geom::{Point, Vector, perp};

/// Length unit of the model, for scale texts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModelUnits {
    /// Symbol of the length unit (`m` or `mm`); velocities are in `<unit>/s`.
    pub length: &'static str,
    /// Drawing millimetres per model unit (1000 for metres, 1 for millimetres).
    pub mm_per_unit: f64,
}

impl ModelUnits {
    /// Metres (SI scenes).
    pub const SI: ModelUnits = ModelUnits { length: "m", mm_per_unit: 1000.0 };
    /// Millimetres.
    pub const MM: ModelUnits = ModelUnits { length: "mm", mm_per_unit: 1.0 };
}

/// A drawing scale: `per_mm` physical units per drawing millimetre.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scale {
    /// Physical units (m/s, m/s², N …) per drawing millimetre.
    pub per_mm: f64,
    /// Model units per drawing millimetre (1/`mm_per_unit`).
    unit_per_mm: f64,
}

impl Scale {
    /// `per_mm` physical units per drawing millimetre, for a model in `units`.
    pub fn new(per_mm: f64, units: ModelUnits) -> Scale {
        Scale { per_mm, unit_per_mm: 1.0 / units.mm_per_unit }
    }
    /// `per_mm` physical units per millimetre of paper, for a drawing printed at
    /// `paper_mm_per_unit` paper millimetres per model unit (its
    /// [`Drawing::paper_mm_per_unit`]; 1 for a sheet drawn in paper millimetres): the scale
    /// a ruler on the printed page measures.
    pub fn on_paper(per_mm: f64, paper_mm_per_unit: f64) -> Scale {
        Scale { per_mm, unit_per_mm: 1.0 / paper_mm_per_unit }
    }
    /// The drawn vector (model units) for a physical vector.
    pub fn draw(&self, v: Vector) -> Vector {
        v * (self.unit_per_mm / self.per_mm)
    }
}

/// A "nice" scale (1, 2, 2.5 or 5 × 10ᵏ) at least `raw`; 1 for a zero or non-finite `raw`.
pub fn nice_scale(raw: f64) -> f64 {
    if !(raw.is_finite() && raw > 0.0) {
        return 1.0;
    }
    let mag = libm::pow(10f64, libm::log10(raw).floor());
    for m in [1.0, 2.0, 2.5, 5.0, 10.0] {
        if m * mag >= raw * (1.0 - 1e-12) {
            return m * mag;
        }
    }
    10.0 * mag
}

/// The next drafting scale coarser than the drafting scale `k` (2.5 after 2, 4 after 2.5).
pub fn coarser_drafting_scale(k: f64) -> f64 {
    drafting_scale(k * (1.0 + 1e-6))
}

/// The mantissas of the drafting scales a mechanism is drawn at (GOST 2.302's reduction
/// scales 1:2, 1:2.5, 1:4, 1:5, 1:10, 1:15, …, and their decades): a sheet's k_l is one of
/// these × 10ᵏ. They are finer than the nice scales of the polygons (no mantissa more than
/// 1.6 from the next), so that a mechanism can fill its panel.
pub const DRAFTING_MANTISSAS: [f64; 6] = [1.0, 1.5, 2.0, 2.5, 4.0, 5.0];

/// The smallest drafting scale ([`DRAFTING_MANTISSAS`] × 10ᵏ) at least `raw`; 1 for a zero
/// or non-finite `raw`.
pub fn drafting_scale(raw: f64) -> f64 {
    if !(raw.is_finite() && raw > 0.0) {
        return 1.0;
    }
    let mag = libm::pow(10f64, libm::log10(raw).floor());
    for m in DRAFTING_MANTISSAS.iter().chain(&[10.0]) {
        if m * mag >= raw * (1.0 - 1e-12) {
            return m * mag;
        }
    }
    10.0 * mag
}

/// The length scale k_l of a figure, model units per paper millimetre: the nice value
/// (1, 2, 2.5, 5 × 10ᵏ) that draws a model extent `extent` (model units) at most
/// `target_mm` paper millimetres long (0.002 m/mm draws a 0.2 m mechanism 100 mm long).
/// Its reciprocal is the drawing's [`Drawing::paper_mm_per_unit`].
pub fn length_scale(extent: f64, target_mm: f64) -> f64 {
    nice_scale(extent / target_mm)
}

/// The text of a length scale as a textbook writes it: `k_l = 0.002 m/mm` (model units per
/// paper millimetre; `k_l = 2 mm/mm` for a scene in millimetres drawn at 1:2).
pub fn length_scale_text(k_l: f64, units: ModelUnits) -> String {
    format!("k_l = {} {}/mm", scale_text(k_l), units.length)
}

/// The caption of a figure's length scale, `before` then `k_l = 0.002 m/mm` (model units
/// per millimetre: on the figure's paper, printed at 1/`k_l` paper millimetres per model
/// unit, in the SVG and PDF; `k_l = 0.001 m/mm` or `1 mm/mm` in the DXF, which draws the
/// mechanism 1:1).
pub fn length_caption(before: &str, k_l: f64, units: ModelUnits) -> ScaleCaption {
    ScaleCaption::new(format!("{before}k_l = "), k_l, format!(" {}/mm", units.length), 1.0 / k_l)
}

/// The width a scale caption takes in the widest reader ([`widest_text_width`]), as the
/// SVG states it (on its paper) or the DXF (in millimetres of the model, `units`), whichever
/// is wider.
pub fn caption_width(caption: &ScaleCaption, units: ModelUnits, height: f64) -> f64 {
    let paper = widest_text_width(&caption.on_paper(), height);
    paper.max(widest_text_width(&caption.text(units.mm_per_unit), height))
}

/// Cap height of letters on paper, millimetres (ISO 3098's 3.5 mm).
pub const PAPER_TEXT_MM: f64 = 3.5;
/// Cap height of small text on paper (scale-bar numbers, tick numbers), millimetres: the
/// 2.5 mm minimum of ISO 3098.
pub const PAPER_SMALL_TEXT_MM: f64 = 2.5;
/// Length wanted for a scale bar on paper, millimetres: [`bar_value`] rounds it up to a
/// nice value, so a bar is 20 to 50 mm long.
pub const BAR_MM: f64 = 20.0;

/// The value a scale bar stands for at `per_mm` units per paper millimetre: the nice value
/// (1, 2, 2.5, 5 × 10ᵏ) at least [`BAR_MM`] paper millimetres long.
pub fn bar_value(per_mm: f64) -> f64 {
    nice_scale(per_mm * BAR_MM)
}

/// Formats a scale value in plain decimals, as a drawing writes numbers (no exponent:
/// `0.01`, `2.5`, `100000`, `0.00002`; [`crate::draw::plain_decimal`]).
pub fn scale_text(v: f64) -> String {
    crate::draw::plain_decimal(v)
}

/// Content layers of a mechanism figure with polygons: name, colour, line type.
pub mod layers {
    use crate::draw::{Aci, LineType};
    /// A layer: name, colour, line type.
    pub type Layer = (&'static str, Aci, LineType);
    /// Links, joints, ground, letters.
    pub const MECHANISM: Layer = ("MECHANISM", Aci::BLACK, LineType::Continuous);
    /// The path of a traced point (the four-bar's coupler curve of M).
    pub const COUPLER_CURVE: Layer = ("COUPLER_CURVE", Aci::CYAN, LineType::Continuous);
    /// Velocity polygon.
    pub const VELOCITY: Layer = ("VELOCITY", Aci::GREEN, LineType::Continuous);
    /// Acceleration polygon.
    pub const ACCELERATION: Layer = ("ACCELERATION", Aci::BLUE, LineType::Continuous);
    /// Force polygons and reactions on the mechanism.
    pub const FORCES: Layer = ("FORCES", Aci::MAGENTA, LineType::Continuous);
    /// Construction lines (components, directions), dashed.
    pub const CONSTRUCTION: Layer = ("CONSTRUCTION", Aci::DARK_GREY, LineType::Dashed);
    /// Titles and scales.
    pub const DIMENSIONS: Layer = ("DIMENSIONS", Aci::BLACK, LineType::Continuous);
    /// Per-position text (the crank angle).
    pub const TEXT: Layer = ("TEXT", Aci::BLACK, LineType::Continuous);
    /// The frames of an animation's panels: thin light grey rectangles.
    pub const PANELS: Layer = ("PANELS", Aci::LIGHT_GREY, LineType::Continuous);
    /// Every content layer, in drawing order (later on top).
    pub const ALL: [Layer; 9] =
        [PANELS, COUPLER_CURVE, CONSTRUCTION, VELOCITY, ACCELERATION, FORCES, MECHANISM, DIMENSIONS, TEXT];
}

/// A drawing with the content layers created in drawing order.
pub fn content_drawing(dim: crate::draw::DimStyle) -> Drawing {
    let mut d = Drawing::new(dim);
    for (name, color, lt) in layers::ALL {
        d.layer(name, color, lt);
    }
    d
}

/// Index of a content layer in a [`content_drawing`] (0 when the drawing lacks it).
pub fn layer_of(d: &Drawing, l: layers::Layer) -> usize {
    d.layers.iter().position(|x| x.name == l.0).unwrap_or(0)
}

/// Sizes of drawn details, model units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sizes {
    /// Cap height of letters.
    pub text: f64,
    /// Arrowhead length.
    pub head: f64,
    /// Width of link polylines.
    pub link: f64,
    /// Radius of joint circles.
    pub joint: f64,
    /// Height of the ground symbol under a pivot; the spacing of ground hatch.
    pub ground: f64,
    /// Length of a slider's block along its guide.
    pub slider_length: f64,
    /// Height of a slider's block across its guide.
    pub slider_height: f64,
}

impl Sizes {
    /// Sizes for a figure printed at `k_l` model units per paper millimetre, from paper
    /// millimetres: letters [`PAPER_TEXT_MM`] (3.5 mm) high, arrowheads 3 mm, links 0.7 mm
    /// wide, joints 1.5 mm in radius, ground symbols 4 mm high, slider blocks 8 mm by 5 mm.
    /// In the model (and so in the DXF's model space) each is its paper size × k_l.
    pub fn on_paper(k_l: f64) -> Sizes {
        Sizes {
            text: PAPER_TEXT_MM * k_l,
            head: 3.0 * k_l,
            link: 0.7 * k_l,
            joint: 1.5 * k_l,
            ground: 4.0 * k_l,
            slider_length: 8.0 * k_l,
            slider_height: 5.0 * k_l,
        }
    }
    /// The length scale k_l (model units per paper millimetre) these sizes were built for
    /// by [`Sizes::on_paper`].
    pub fn k_l(&self) -> f64 {
        self.text / PAPER_TEXT_MM
    }
    /// Cap height of small text (scale-bar and tick numbers): [`PAPER_SMALL_TEXT_MM`] for
    /// [`PAPER_TEXT_MM`] letters.
    pub fn small_text(&self) -> f64 {
        self.text * PAPER_SMALL_TEXT_MM / PAPER_TEXT_MM
    }
    /// Sizes relative to a mechanism, for a drawing with no paper scale (the figures on
    /// paper use [`Sizes::on_paper`]): sizes for a mechanism of characteristic length `size` (model
    /// units: the extent of the four-bar's motion, the linkage's length scale, the triad's
    /// size): letters 3.2 %, arrowheads 3 %, links 0.9 % wide, joints 1.3 % in radius,
    /// ground symbols 3.5 % high, slider blocks 7 % by 4 %.
    pub fn for_length(size: f64) -> Sizes {
        Sizes {
            text: 0.032 * size,
            head: 0.03 * size,
            link: 0.009 * size,
            joint: 0.013 * size,
            ground: 0.035 * size,
            slider_length: 0.07 * size,
            slider_height: 0.04 * size,
        }
    }
}

/// Unit vector of `v`, or `fallback` for a zero or non-finite `v`.
pub fn unit_or(v: Vector, fallback: Vector) -> Vector {
    let n = v.norm();
    if n > 0.0 && n.is_finite() { v / n } else { fallback }
}

/// A vector: an arrow from `from` by `v` (drawn units); nothing for a vector shorter than
/// a hundredth of the arrowhead. Its name, if any, goes through the letter placer
/// ([`crate::figure::shared::labels::Polygon`]) with the other letters of the drawing.
pub fn vector(d: &mut Drawing, layer: usize, from: Point, v: Vector, s: Sizes) {
    if v.norm().is_nan() || v.norm() <= 0.01 * s.head {
        return;
    }
    d.add(layer, Shape::Arrow { from, to: from + v, head: s.head });
}

/// An angular velocity's arrow (ω1 at a crank's pivot): an arc about `centre` of radius
/// `radius`, from the angle `from` sweeping `sweep` radians (positive counter-clockwise),
/// with a filled arrowhead at its end pointing along the turn. Returns the arc's middle
/// point (for its letter).
pub fn turn_arrow(d: &mut Drawing, layer: usize, centre: Point, radius: f64, from: f64, sweep: f64, s: Sizes) -> Point {
    let to = from + sweep;
    let (start, end) = if sweep >= 0.0 { (from, to) } else { (to, from) };
    d.add(layer, Shape::Arc { center: centre, radius, start, end });
    let at = |a: f64| centre + Vector::new(libm::cos(a), libm::sin(a)) * radius;
    let tip = at(to);
    // Tangent at the tip, along the turn.
    let t = Vector::new(-libm::sin(to), libm::cos(to)) * sweep.signum();
    let h = s.head.min(0.5 * radius * sweep.abs());
    let base = tip - t * h;
    let n = perp(t) * (h * crate::draw::parts::ARROW_HALF_WIDTH);
    d.add(layer, Shape::Filled { points: vec![tip, base + n, base - n] });
    at(from + 0.5 * sweep)
}

/// A link: a wide polyline through `points` (closed for a rigid body of three or more
/// points drawn as a plate), in `color` or the layer's.
pub fn link(d: &mut Drawing, layer: usize, points: Vec<Point>, closed: bool, color: Option<Aci>, s: Sizes) {
    d.push(Entity { layer, color, linetype: None, shape: Shape::Polyline { points, closed, width: s.link } });
}

/// The pole of a polygon: a small circle (a quarter of a joint's radius).
pub fn pole(d: &mut Drawing, layer: usize, p: Point, s: Sizes) {
    d.add(layer, Shape::Circle { center: p, radius: 0.25 * s.joint });
}

/// How far, in millimetres of paper, a traced path as drawn may stray from the polyline
/// through every computed position: 0.02 mm. That is a tenth of the thinnest pen of a
/// technical drawing (0.18 mm, ISO 128-20), about a thirteenth of a screen pixel at 100 %
/// zoom (0.26 mm at 96 dpi) and under a printer's dot at 1200 dpi (0.021 mm): nobody can
/// see it, and a path drawn to it keeps a number of vertices set by its shape on paper, not
/// by the number of positions (so frames grow linearly with the positions, not with their
/// square).
pub const PATH_TOLERANCE_MM: f64 = 0.02;

/// The path of a traced point over the motion: a thin open polyline (nothing for fewer
/// than two points). On a drawing with a paper scale ([`Drawing::paper_mm_per_unit`]) the
/// path is simplified to [`PATH_TOLERANCE_MM`] on paper ([`simplify_path`]): every position
/// lies within that distance of the drawn polyline, whose vertices are positions, the first
/// and the last kept. Without a paper scale every position is drawn.
pub fn path(d: &mut Drawing, layer: usize, points: Vec<Point>) {
    if points.len() >= 2 {
        let points = match d.paper_mm_per_unit.filter(|k| k.is_finite() && *k > 0.0) {
            Some(k) => simplify_path(&points, PATH_TOLERANCE_MM / k),
            None => points,
        };
        d.add(layer, Shape::Polyline { points, closed: false, width: 0.0 });
    }
}

/// Distance from `p` to the segment `a`–`b` (to `a` when the segment has no length).
pub fn distance_to_segment(p: Point, a: Point, b: Point) -> f64 {
    let ab = b - a;
    let len2 = ab.norm_squared();
    let t = if len2 > 0.0 { ((p - a).dot(&ab) / len2).clamp(0.0, 1.0) } else { 0.0 };
    (p - (a + ab * t)).norm()
}

/// The polyline `points` with the vertices left out that lie within `tolerance` (model
/// units) of what remains (Ramer–Douglas–Peucker, distances to segments, not to their
/// lines, so a path that runs back along itself keeps its turning points).
///
/// Guarantees: the result is a subsequence of `points` with the first and the last point
/// kept, and every point of `points` lies within `tolerance` of the result (each left-out
/// point is within `tolerance` of the segment that replaces its stretch); conversely the
/// result lies within `tolerance` of the original polyline. A non-positive or non-finite
/// `tolerance` leaves out only points exactly on the segments (repeated or collinear
/// points) or nothing. O(n log n) for a smooth curve, O(n²) at worst.
pub fn simplify_path(points: &[Point], tolerance: f64) -> Vec<Point> {
    let n = points.len();
    if n <= 2 {
        return points.to_vec();
    }
    let tolerance = if tolerance.is_finite() { tolerance.max(0.0) } else { 0.0 };
    let mut keep = vec![false; n];
    keep[0] = true;
    keep[n - 1] = true;
    // Stretches still to check, as (first, last) indices of kept points.
    let mut stack = vec![(0usize, n - 1)];
    while let Some((i, j)) = stack.pop() {
        let (mut far, mut worst) = (i, tolerance);
        for (k, p) in points.iter().enumerate().take(j).skip(i + 1) {
            let dist = distance_to_segment(*p, points[i], points[j]);
            if dist > worst {
                (far, worst) = (k, dist);
            }
        }
        if far != i {
            keep[far] = true;
            stack.push((far, j));
            stack.push((i, far));
        }
    }
    points.iter().zip(&keep).filter(|(_, k)| **k).map(|(p, _)| *p).collect()
}

/// A joint: a circle of the joint radius at `p`.
pub fn joint(d: &mut Drawing, layer: usize, p: Point, s: Sizes) {
    d.add(layer, Shape::Circle { center: p, radius: s.joint });
}

/// The ground pivot at `p`: the joint circle, a support triangle from the circle's foot
/// down to a base line wider than it, and hatch strokes under the base (the symbol is
/// [`Sizes::ground`] high).
pub fn ground(d: &mut Drawing, layer: usize, p: Point, s: Sizes) {
    let (g, r) = (s.ground, s.joint);
    joint(d, layer, p, s);
    let l = p + Vector::new(-0.6 * g, -g - r);
    let rr = p + Vector::new(0.6 * g, -g - r);
    d.add(layer, Shape::Polyline { points: vec![p + Vector::new(0.0, -r), l, rr], closed: true, width: 0.0 });
    let (bl, br) = (l + Vector::new(-0.4 * g, 0.0), rr + Vector::new(0.4 * g, 0.0));
    d.add(layer, Shape::Line { from: bl, to: br });
    hatch(d, layer, bl, br, 0.5 * g);
}

/// The box the ground symbol at `p` ([`ground`]) covers under its joint circle, hatch
/// included: for letters to keep off.
pub fn ground_extent(p: Point, s: Sizes) -> TextBox {
    let (g, r) = (s.ground, s.joint);
    TextBox { min: p + Vector::new(-1.3 * g, -r - 1.3 * g), max: p + Vector::new(g, -r) }
}

/// Hatch strokes along the segment `a → b`, on its right-hand side (opposite to
/// `perp(b − a)`): the ground under a base line or a fixed guide; `size` sets the
/// strokes' spacing (half of it) and length.
pub fn hatch(d: &mut Drawing, layer: usize, a: Point, b: Point, size: f64) {
    let len = (b - a).norm();
    if len <= 0.0 {
        return;
    }
    let u = (b - a) / len;
    let down = -perp(u);
    let step = 0.5 * size;
    let count = (len / step).floor() as usize;
    for k in 0..=count {
        let p = a + u * (k as f64 * step);
        d.add(layer, Shape::Line { from: p, to: p + (down - u) * (0.6 * size) });
    }
}

/// A guide fixed to the ground from `a` to `b`: the line, and hatch on its right-hand side
/// half a slider's height off it (under the slider's block).
pub fn guide(d: &mut Drawing, layer: usize, a: Point, b: Point, s: Sizes) {
    d.add(layer, Shape::Line { from: a, to: b });
    let u = (b - a).normalize();
    let off = -perp(u) * (0.5 * s.slider_height);
    hatch(d, layer, a + off, b + off, s.ground);
}

/// A slider's block at `p` along the unit direction `u` of its guide: a rectangle
/// [`Sizes::slider_length`] by [`Sizes::slider_height`]. Returns its half length and half
/// height along `u` and across it.
pub fn slider(d: &mut Drawing, layer: usize, p: Point, u: Vector, s: Sizes) -> (f64, f64) {
    let n = perp(u);
    let (hl, hh) = (0.5 * s.slider_length, 0.5 * s.slider_height);
    let corners = vec![p - u * hl - n * hh, p + u * hl - n * hh, p + u * hl + n * hh, p - u * hl + n * hh];
    d.add(layer, Shape::Polyline { points: corners, closed: true, width: 0.0 });
    (hl, hh)
}

/// A scale bar: `0 ├──────┤ 0.05 m`: a bar `length` long (model units) from `at` (its left
/// end) to the right, with end ticks, `0` left of it and `label` (value and unit, e.g.
/// `0.05 m`, `0.5 m/s`) right of it, in small text. Measured on the printed page, the bar
/// is the printed scale times the value. Returns the box it covers, for letters to keep off.
pub fn scale_bar(d: &mut Drawing, layer: usize, at: Point, length: f64, label: &str, s: Sizes) -> TextBox {
    let h = s.small_text();
    let tick = 0.5 * h;
    let end = at + Vector::new(length, 0.0);
    d.add(layer, Shape::Line { from: at, to: end });
    for p in [at, end] {
        d.add(layer, Shape::Line { from: p + Vector::new(0.0, -tick), to: p + Vector::new(0.0, tick) });
    }
    let gap = 0.5 * h;
    let text = |value: &str, at: Point, halign| Shape::Text {
        runs: crate::draw::Runs::flat(),
        at,
        height: h,
        value: value.to_string(),
        halign,
        valign: crate::draw::VAlign::Middle,
        rotation: 0.0,
    };
    d.add(layer, text("0", at - Vector::new(gap, 0.0), crate::draw::HAlign::Right));
    d.add(layer, text(label, end + Vector::new(gap, 0.0), crate::draw::HAlign::Left));
    let left = gap + crate::draw::parts::widest_text_width("0", h);
    let right = gap + crate::draw::parts::widest_text_width(label, h);
    TextBox { min: at + Vector::new(-left, -tick.max(0.5 * h)), max: end + Vector::new(right, tick.max(0.5 * h)) }
}

/// The strip a panel keeps for its [`scale_bar`] under its content, model units: two
/// small-text heights (the bar drawn at its middle).
pub fn scale_bar_room(s: Sizes) -> f64 {
    2.0 * s.small_text()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Distance from `p` to the polyline `line` (the nearest of its segments).
    fn to_polyline(p: Point, line: &[Point]) -> f64 {
        line.windows(2).map(|w| distance_to_segment(p, w[0], w[1])).fold(f64::INFINITY, f64::min)
    }

    /// The Chebyshev template's coupler point M at 3600 crank angles (0.1° apart), from the
    /// closed-form dyad.
    fn coupler_curve() -> Vec<Point> {
        let g = crate::solve::fourbar::test_template();
        (0..3600)
            .map(|k| {
                let phi1 = (k as f64 * 0.1).to_radians();
                crate::solve::fourbar::kinematics::position(&g, phi1, g.branch).expect("the template turns fully").m
            })
            .collect()
    }

    #[test]
    fn a_simplified_coupler_curve_stays_within_the_tolerance_of_every_position() {
        let curve = coupler_curve();
        // The template's drawing: k_l = 0.0025 m/mm, so 0.02 mm of paper is 5e-5 m.
        let tol = PATH_TOLERANCE_MM * 0.0025;
        let simple = simplify_path(&curve, tol);
        assert_eq!(simple.first(), curve.first());
        assert_eq!(simple.last(), curve.last());
        // A subsequence of the positions.
        let mut rest = curve.iter();
        assert!(simple.iter().all(|p| rest.any(|q| q == p)), "vertices are positions, in order");
        // Every position within the tolerance of the drawn polyline, and the drawn polyline
        // (10 points on each segment) within the tolerance of the full one.
        let worst = curve.iter().map(|p| to_polyline(*p, &simple)).fold(0.0, f64::max);
        assert!(worst <= tol, "a position is {worst} from the simplified path (tolerance {tol})");
        let back = simple
            .windows(2)
            .flat_map(|w| (0..10).map(move |k| w[0] + (w[1] - w[0]) * (k as f64 / 10.0)))
            .map(|p| to_polyline(p, &curve))
            .fold(0.0, f64::max);
        assert!(back <= tol, "the simplified path strays {back} from the full one (tolerance {tol})");
        // The curve's shape sets the vertices, not the 3600 positions.
        assert!(simple.len() < 300, "{} of {} points kept", simple.len(), curve.len());
        // A coarser sampling (1°) of the same curve needs about as many.
        let coarse: Vec<Point> = curve.iter().step_by(10).copied().collect();
        let n_coarse = simplify_path(&coarse, tol).len();
        assert!(simple.len() < 2 * n_coarse, "{} at 0.1° against {n_coarse} at 1°", simple.len());
    }

    #[test]
    fn a_stroke_that_runs_back_along_itself_keeps_its_turning_points() {
        // A ram going from x = 0 to 10 and back to 1 on one line: the distances to the
        // segment from the first to the last point (not to its line) keep x = 10.
        let pts: Vec<Point> = (0..=10).chain((1..10).rev()).map(|x| Point::new(x as f64, 600.0)).collect();
        let simple = simplify_path(&pts, 0.01);
        assert_eq!(simple, vec![Point::new(0.0, 600.0), Point::new(10.0, 600.0), Point::new(1.0, 600.0)]);
        // A straight run keeps its ends; two points or fewer come back as they are.
        let line: Vec<Point> = (0..5).map(|x| Point::new(x as f64, 2.0 * x as f64)).collect();
        assert_eq!(simplify_path(&line, 0.0), vec![line[0], line[4]]);
        assert_eq!(simplify_path(&line[..2], 1.0), line[..2].to_vec());
        // A corner above the tolerance stays; a bump below it goes.
        let corner = [Point::new(0.0, 0.0), Point::new(1.0, 0.3), Point::new(2.0, 0.0)];
        assert_eq!(simplify_path(&corner, 0.29).len(), 3);
        assert_eq!(simplify_path(&corner, 0.31).len(), 2);
    }

    #[test]
    fn a_path_is_simplified_on_paper_only() {
        let curve = coupler_curve();
        let mut on_paper = Drawing::new(crate::draw::DimStyle { text_height: 1.0, arrow_size: 1.0 });
        on_paper.paper_mm_per_unit = Some(400.0);
        let mut model = on_paper.clone();
        model.paper_mm_per_unit = None;
        let layer = on_paper.layer("P", Aci::CYAN, crate::draw::LineType::Continuous);
        let layer_m = model.layer("P", Aci::CYAN, crate::draw::LineType::Continuous);
        path(&mut on_paper, layer, curve.clone());
        path(&mut model, layer_m, curve.clone());
        let points = |d: &Drawing| match &d.entities[0].shape {
            Shape::Polyline { points, .. } => points.clone(),
            other => panic!("{other:?}"),
        };
        assert_eq!(points(&on_paper), simplify_path(&curve, PATH_TOLERANCE_MM / 400.0));
        assert_eq!(points(&model), curve);
    }

    #[test]
    fn nice_scales_round_up_to_1_2_2_5_5() {
        for (raw, nice) in [(0.7, 1.0), (1.3, 2.0), (2.1, 2.5), (3.0, 5.0), (7.0, 10.0), (0.013, 0.02)] {
            assert!((nice_scale(raw) - nice).abs() < 1e-12 * nice, "{raw} -> {}", nice_scale(raw));
        }
        assert_eq!(nice_scale(0.0), 1.0);
        assert_eq!(nice_scale(f64::NAN), 1.0);
        assert_eq!(scale_text(0.01), "0.01");
        assert_eq!(scale_text(2.5), "2.5");
        assert_eq!(scale_text(2e-5), "0.00002");
        assert_eq!(scale_text(1e5), "100000");
        assert_eq!(scale_text(0.1 + 0.2), "0.3");
        assert_eq!(scale_text(2e5), "200000");
        assert_eq!(scale_text(0.0025), "0.0025");
    }

    #[test]
    fn drafting_scales_round_up_to_the_next_gost_mantissa() {
        for (raw, k) in [(0.0013, 0.0015), (0.0016, 0.002), (3.0, 4.0), (4.4, 5.0), (0.9, 1.0), (150.0, 150.0)] {
            assert!((drafting_scale(raw) - k).abs() < 1e-12 * k, "{raw} -> {}", drafting_scale(raw));
        }
        assert_eq!(drafting_scale(f64::NAN), 1.0);
        for (k, next) in [(2.0, 2.5), (2.5, 4.0), (5.0, 10.0), (0.004, 0.005), (1.5, 2.0)] {
            assert!((coarser_drafting_scale(k) - next).abs() < 1e-12 * next, "{k} -> {}", coarser_drafting_scale(k));
        }
    }

    #[test]
    fn a_length_scale_is_nice_and_prints_as_a_textbook_writes_it() {
        // A 0.23 m motion in 100 mm of paper: 0.0023 m/mm rounds up to 0.0025.
        let k = length_scale(0.23, 100.0);
        assert!((k - 0.0025).abs() < 1e-15, "{k}");
        assert_eq!(length_scale_text(0.002, ModelUnits::SI), "k_l = 0.002 m/mm");
        assert_eq!(length_scale_text(2.0, ModelUnits::MM), "k_l = 2 mm/mm");
        // Letters 3.5 mm on paper are 3.5 × k_l in the model.
        assert!((Sizes::on_paper(0.002).text - 0.007).abs() < 1e-15);
        // A bar at 0.01 (m/s)/mm stands for 0.2 m/s (20 mm); at 0.02, for 0.5 m/s (25 mm).
        assert!((bar_value(0.01) - 0.2).abs() < 1e-12);
        assert!((bar_value(0.02) - 0.5).abs() < 1e-12);
    }

    #[test]
    fn a_scale_bar_is_as_long_as_its_value_at_the_scale() {
        let mut d = Drawing::new(crate::draw::DimStyle { text_height: 1.0, arrow_size: 1.0 });
        let s = Sizes::on_paper(1.0);
        let b = scale_bar(&mut d, 0, Point::new(0.0, 0.0), 25.0, "0.5 m/s", s);
        let bar = d.entities.iter().find_map(|e| match e.shape {
            Shape::Line { from, to } if from.y == to.y => Some((to - from).norm()),
            _ => None,
        });
        assert_eq!(bar, Some(25.0));
        assert!(b.min.x < 0.0 && b.max.x > 25.0 + 2.5 * 5.0 * 0.5, "{b:?}");
    }
}
