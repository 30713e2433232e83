//! Figure: a general linkage at one instant, as the engineer draws a kinematic diagram:
//! bodies as polylines between their points (closed for three or more), revolute joints
//! as small circles, sliders as small rectangles along their guide, guides fixed to the
//! ground as lines with hatching, ground pivots with the ground symbol (triangle, base
//! line, hatch), point names, and the paths of the traced points.
//!
//! What it draws is a [`LinkageFigure`], built from the solver's [`Mechanism`] and the
//! names of its points (the run builds it from the scene), so that the figure knows no
//! scene file.
//!
//! The figure is drawn on paper: [`paper_style`] chooses the length scale k_l (a nice
//! value that draws the motion at most [`LINKAGE_MM`] long) and the sizes from paper
//! millimetres; the drawings carry `paper_mm_per_unit = 1/k_l` and the base prints
//! `k_l = 5 mm/mm` with a scale bar under the motion.

pub mod detail;
pub mod forces;
pub mod frame;
pub mod polygon;
pub mod sheet;

use crate::draw::{Aci, DimStyle, Drawing, LineType};
use crate::geom::{Point, Vector, perp};
use crate::solve::linkage::{Anchor, Attach, JointKind, Mechanism, place};

use crate::figure::shared::forces::ForceArrow;
use crate::figure::shared::labels::{self, Label, TextBox};
use crate::figure::shared::vocab::{self, ModelUnits, Sizes};

/// Largest extent of the motion (every body point over every position) on paper,
/// millimetres.
pub const LINKAGE_MM: f64 = 150.0;

/// A body as drawn: its named points in body coordinates, in the order its outline joins
/// them (closed for three or more).
#[derive(Debug, Clone, PartialEq)]
pub struct BodyOutline {
    /// Named points, body coordinates.
    pub points: Vec<(String, Vector)>,
}

/// A joint as drawn.
#[derive(Debug, Clone, PartialEq)]
pub enum JointSymbol {
    /// A revolute joint: a circle at `at`, with the ground symbol when `grounded`.
    Pin {
        /// Where it is (a point of either body).
        at: Anchor,
        /// Whether one of its bodies is the ground.
        grounded: bool,
        /// The name written beside it.
        name: String,
    },
    /// A prismatic joint: a block at `point` along the guide line `q1 → q2`; a guide fixed
    /// to the ground (`q1` on the ground) is drawn as a hatched line over the motion.
    Slider {
        /// The sliding point.
        point: Anchor,
        /// First point of the guide line.
        q1: Anchor,
        /// Second point of the guide line.
        q2: Anchor,
        /// The name written beside the block, when the point has one.
        name: Option<String>,
    },
}

/// What the linkage figure draws: bodies (by index, as the solver's
/// [`Attach::Body`]), joints, and the points whose paths are drawn.
#[derive(Debug, Clone, PartialEq)]
pub struct LinkageFigure {
    /// The moving bodies, in the solver's order.
    pub bodies: Vec<BodyOutline>,
    /// The joints, in the solver's order.
    pub joints: Vec<JointSymbol>,
    /// Points whose paths over the motion are drawn (points on the ground are skipped).
    pub traced: Vec<Anchor>,
    /// The model's units, for the length scale's text (millimetres unless set).
    pub units: ModelUnits,
    /// The driven crank, when the mechanism has one angular driver: its body and its point
    /// pinned to the ground (where the ω arrow is drawn).
    pub crank: Option<(usize, Anchor)>,
}

impl LinkageFigure {
    /// The figure of `mechanism`: `name_of` gives a point's name (`None` for an unnamed
    /// point; a revolute joint without named points is called by the joint's own name);
    /// `traced` are the points whose paths are drawn.
    pub fn new<'a>(mechanism: &Mechanism, name_of: impl Fn(Anchor) -> Option<&'a str>, traced: Vec<Anchor>) -> Self {
        let bodies = mechanism.bodies.iter().map(|b| BodyOutline { points: b.points.clone() }).collect();
        let joints = mechanism
            .joints
            .iter()
            .map(|j| match j.kind {
                JointKind::Revolute { a, b } => JointSymbol::Pin {
                    at: a,
                    grounded: a.body == Attach::Ground || b.body == Attach::Ground,
                    name: name_of(b).or_else(|| name_of(a)).unwrap_or(&j.name).to_string(),
                },
                JointKind::Prismatic { point, q1, q2, .. } => {
                    JointSymbol::Slider { point, q1, q2, name: name_of(point).map(str::to_string) }
                }
            })
            .collect();
        // The crank: the angular driver's body and its ground pivot.
        let crank = mechanism.angular_driver().and_then(|(_, body)| {
            let Attach::Body(b) = body else { return None };
            mechanism.joints.iter().find_map(|j| match j.kind {
                JointKind::Revolute { a, b: other } if a.body == Attach::Ground && other.body == body => {
                    Some((b, other))
                }
                JointKind::Revolute { a, b: other } if other.body == Attach::Ground && a.body == body => Some((b, a)),
                _ => None,
            })
        });
        LinkageFigure { bodies, joints, traced, units: ModelUnits::MM, crank }
    }

    /// The figure with its model's units (for the printed length scale).
    pub fn with_units(self, units: ModelUnits) -> Self {
        LinkageFigure { units, ..self }
    }
}

impl LinkageFigure {
    /// The figure drawn on paper: body points scaled by 1/`k_l` (model units per paper mm)
    /// and ground points placed at `origin + p/k_l`; draw it at the coordinates of
    /// [`on_paper`].
    pub fn on_paper(&self, origin: Point, k_l: f64) -> LinkageFigure {
        let anchor = |a: Anchor| match a.body {
            Attach::Ground => Anchor { body: Attach::Ground, local: origin.coords + a.local / k_l },
            Attach::Body(_) => Anchor { body: a.body, local: a.local / k_l },
        };
        let bodies = self
            .bodies
            .iter()
            .map(|b| BodyOutline { points: b.points.iter().map(|(n, v)| (n.clone(), v / k_l)).collect() })
            .collect();
        let joints = self
            .joints
            .iter()
            .map(|j| match j {
                JointSymbol::Pin { at, grounded, name } => {
                    JointSymbol::Pin { at: anchor(*at), grounded: *grounded, name: name.clone() }
                }
                JointSymbol::Slider { point, q1, q2, name } => {
                    JointSymbol::Slider { point: anchor(*point), q1: anchor(*q1), q2: anchor(*q2), name: name.clone() }
                }
            })
            .collect();
        let traced = self.traced.iter().map(|a| anchor(*a)).collect();
        let crank = self.crank.map(|(b, a)| (b, anchor(a)));
        LinkageFigure { bodies, joints, traced, units: self.units, crank }
    }
}

/// Body coordinates `q` (x, y, φ per body) on paper: positions at `origin + r/k_l`.
pub fn on_paper(q: &[f64], origin: Point, k_l: f64) -> Vec<f64> {
    q.chunks(3).flat_map(|c| [origin.x + c[0] / k_l, origin.y + c[1] / k_l, c[2]]).collect()
}

/// Where every body point goes over `motion` (lower-left, upper-right), `None` for no point.
fn motion_bounds(fig: &LinkageFigure, motion: &[&[f64]]) -> Option<(Point, Point)> {
    let mut b: Option<(Point, Point)> = None;
    for q in motion {
        for (i, body) in fig.bodies.iter().enumerate() {
            for (_, v) in &body.points {
                let p = place(q, Attach::Body(i), *v);
                if !(p.x.is_finite() && p.y.is_finite()) {
                    continue;
                }
                b = Some(match b {
                    None => (p, p),
                    Some((lo, hi)) => (Point::from(lo.coords.inf(&p.coords)), Point::from(hi.coords.sup(&p.coords))),
                });
            }
        }
    }
    b
}

/// Sizes for drawing `fig` over `motion` on paper: from paper millimetres at the length
/// scale k_l that draws every body point's motion at most [`LINKAGE_MM`] long
/// ([`Sizes::k_l`] gives it back).
pub fn paper_style(fig: &LinkageFigure, motion: &[&[f64]]) -> Style {
    let extent = motion_bounds(fig, motion).map_or(1.0, |(lo, hi)| (hi - lo).amax());
    Sizes::on_paper(vocab::length_scale(extent.max(f64::MIN_POSITIVE), LINKAGE_MM))
}

/// Sizes of the symbols: the shared table from paper millimetres ([`paper_style`]).
pub type Style = Sizes;

pub(crate) fn anchor_at(q: &[f64], a: Anchor) -> Point {
    place(q, a.body, a.local)
}

/// Extent of each ground-fixed guide over a motion: for each prismatic joint whose line
/// is on the ground, the segment of the guide line the slider covers over the motion, plus
/// the slider's length either side. `None` for guides on moving bodies.
pub fn guide_spans(fig: &LinkageFigure, motion: &[&[f64]], style: &Style) -> Vec<Option<(Point, Point)>> {
    fig.joints
        .iter()
        .map(|j| match *j {
            JointSymbol::Slider { point, q1, q2, .. } if q1.body == Attach::Ground => {
                let (a, b) = (Point::from(q1.local), Point::from(q2.local));
                let u = (b - a).normalize();
                let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
                for q in motion {
                    let s = u.dot(&(anchor_at(q, point) - a));
                    lo = lo.min(s);
                    hi = hi.max(s);
                }
                if !(lo.is_finite() && hi.is_finite()) {
                    // No motion: the line's own points.
                    (lo, hi) = (0.0, (b - a).norm());
                }
                let ext = style.slider_length;
                Some((a + u * (lo - ext), a + u * (hi + ext)))
            }
            _ => None,
        })
        .collect()
}

/// Draws the mechanism at coordinates `q` on layer `layer` of `d`.
pub fn mechanism(
    d: &mut Drawing,
    layer: usize,
    fig: &LinkageFigure,
    q: &[f64],
    spans: &[Option<(Point, Point)>],
    style: &Style,
) {
    mechanism_with_forces(d, layer, fig, q, spans, &[], None, style, labels::Around::default());
}

/// [`mechanism`] with the names of the force arrows `arrows` (drawn on the mechanism by
/// [`crate::figure::shared::forces::draw_on_mechanism`]) placed with the points' names, clear of them, on
/// the `FORCES` layer; every name clear of what `d` already holds and of `around`. With the
/// crank's angular velocity `omega` (rad/s, CCW positive), its ω arrow at its pivot. The
/// links in black, each with its number in a circle.
#[allow(clippy::too_many_arguments)]
pub fn mechanism_with_forces(
    d: &mut Drawing,
    layer: usize,
    fig: &LinkageFigure,
    q: &[f64],
    spans: &[Option<(Point, Point)>],
    arrows: &[ForceArrow],
    omega: Option<f64>,
    style: &Style,
    around: labels::Around<'_>,
) {
    let s = *style;
    // The names go through the letter placer, clear of the joints, the bodies' outlines,
    // the guides, the ground symbols and the sliders' blocks; one name a place.
    let mut letters = labels::Polygon::of_names();
    for a in arrows {
        letters.segment(a.arrow.0, a.arrow.1);
        if a.arrow.0 != a.at {
            letters.segment(a.at, a.arrow.0);
        }
    }
    draw_links(d, layer, (fig, q), spans, s, &mut letters);
    draw_joints(d, layer, (fig, q), s, &mut letters);
    number_links((fig, q), s, &mut letters);
    if let (Some(crank), Some(w)) = (fig.crank, omega.filter(|w| *w != 0.0 && w.is_finite())) {
        crank_turn(d, layer, (fig, q), crank, arrows, w, s, &mut letters);
    }
    for a in arrows {
        letters.letter(a.arrow.1, a.force.label(), s.text, a.arrow.1 - a.arrow.0, None);
    }
    letters.keep_off_drawing(d);
    letters.around(around);
    if arrows.is_empty() {
        letters.draw(d, layer);
        return;
    }
    // Points' names on the mechanism's layer, the forces' names on the forces' layer.
    let frc = vocab::layer_of(d, vocab::layers::FORCES);
    let placed = letters.place();
    let on_mechanism = placed.len() - arrows.len();
    for (i, p) in placed.iter().enumerate() {
        let l = if i < on_mechanism { layer } else { frc };
        labels::draw_placed(d, l, p, Some(LineType::Continuous));
    }
}

/// Draws the guides fixed to the ground (`spans`) and the bodies of `fig` at `q` in black,
/// as a kinematic diagram is drawn (the vectors are coloured), on `layer`; `letters` keep
/// off every guide and every side of a body.
fn draw_links(
    d: &mut Drawing,
    layer: usize,
    (fig, q): (&LinkageFigure, &[f64]),
    spans: &[Option<(Point, Point)>],
    s: Style,
    letters: &mut labels::Polygon,
) {
    for span in spans.iter().flatten() {
        vocab::guide(d, layer, span.0, span.1, s);
        letters.segment(span.0, span.1);
    }
    for (i, b) in fig.bodies.iter().enumerate() {
        let pts: Vec<Point> = b.points.iter().map(|(_, v)| place(q, Attach::Body(i), *v)).collect();
        let n = pts.len();
        let sides = if n >= 3 { n } else { n.saturating_sub(1) };
        for k in 0..sides {
            letters.segment(pts[k], pts[(k + 1) % n]);
        }
        if pts.len() >= 2 {
            vocab::link(d, layer, pts, b.points.len() >= 3, None, s);
        }
    }
}

/// Draws the joints of `fig` at `q` on `layer` (pins, ground symbols, sliders' blocks,
/// `letters` keeping off the symbols) and gives `letters` the points' names: the sliders'
/// first, so that they sit beside the block rather than on it, then the pins', then the
/// body points not at a joint (coupler points, tips); one name a place.
fn draw_joints(
    d: &mut Drawing,
    layer: usize,
    (fig, q): (&LinkageFigure, &[f64]),
    s: Style,
    letters: &mut labels::Polygon,
) {
    let mut labelled: Vec<Point> = Vec::new();
    let mut name_at = |letters: &mut labels::Polygon, p: Point, name: &str, dir: Vector, clear: f64| {
        if !labelled.iter().any(|x| (x - p).norm() <= s.joint) {
            labelled.push(p);
            letters.letter_clear(p, name, s.text, dir, clear);
        }
    };
    let order = fig
        .joints
        .iter()
        .filter(|j| matches!(j, JointSymbol::Slider { .. }))
        .chain(fig.joints.iter().filter(|j| matches!(j, JointSymbol::Pin { .. })));
    let up_right = Vector::new(1.8, 1.2);
    for j in order {
        match j {
            JointSymbol::Pin { at, grounded, name } => {
                let p = anchor_at(q, *at);
                if *grounded {
                    vocab::ground(d, layer, p, s);
                    letters.keep_off(vocab::ground_extent(p, s));
                } else {
                    vocab::joint(d, layer, p, s);
                }
                name_at(letters, p, name, up_right, s.joint);
            }
            JointSymbol::Slider { point, q1, q2, name } => {
                let (point, q1, q2) = (*point, *q1, *q2);
                let p = anchor_at(q, point);
                let dir = anchor_at(q, q2) - anchor_at(q, q1);
                let u = dir.normalize();
                let n = perp(u);
                let (hl, hh) = vocab::slider(d, layer, p, u, s);
                // The block's box, axis-aligned.
                let half = Vector::new(hl * u.x.abs() + hh * n.x.abs(), hl * u.y.abs() + hh * n.y.abs());
                letters.keep_off(TextBox { min: p - half, max: p + half });
                if let Some(name) = name {
                    // Beside the block, preferably across the guide from its middle.
                    name_at(letters, p, name, n, hh);
                }
            }
        }
    }
    for (i, b) in fig.bodies.iter().enumerate() {
        for (name, v) in &b.points {
            let p = place(q, Attach::Body(i), *v);
            name_at(letters, p, name, up_right, s.joint);
        }
    }
}

/// Gives `letters` each link's number in a circle, beside the link's middle where it is
/// clearest of the joints (another link passing near a pivot leaves its middle crowded),
/// away from the mechanism's middle; a block's beside it.
fn number_links((fig, q): (&LinkageFigure, &[f64]), s: Style, letters: &mut labels::Polygon) {
    let centre = {
        let pts: Vec<Point> = (0..fig.bodies.len())
            .flat_map(|i| fig.bodies[i].points.iter().map(move |(_, v)| place(q, Attach::Body(i), *v)))
            .collect();
        Point::from(pts.iter().map(|p| p.coords).sum::<Vector>() / pts.len().max(1) as f64)
    };
    let joints: Vec<Point> = fig
        .joints
        .iter()
        .map(|j| match j {
            JointSymbol::Pin { at, .. } => anchor_at(q, *at),
            JointSymbol::Slider { point, .. } => anchor_at(q, *point),
        })
        .collect();
    let clearance = |x: Point| joints.iter().map(|j| (j - x).norm()).fold(f64::INFINITY, f64::min);
    for (i, b) in fig.bodies.iter().enumerate() {
        let pts: Vec<Point> = b.points.iter().map(|(_, v)| place(q, Attach::Body(i), *v)).collect();
        let (mid, dir, clear) = match pts.as_slice() {
            [] => continue,
            [p] => (*p, Vector::new(-1.0, 1.0), 0.5 * s.slider_height),
            [p, r, ..] => {
                let along = [0.5, 0.38, 0.62, 0.28, 0.72].map(|t| p + (r - p) * t);
                let mid = along.iter().copied().find(|x| clearance(*x) >= 4.0 * s.text).unwrap_or_else(|| {
                    along.iter().copied().fold(along[0], |a, x| if clearance(x) > clearance(a) { x } else { a })
                });
                let mut n = perp(vocab::unit_or(r - p, Vector::new(1.0, 0.0)));
                if n.dot(&(mid - centre)) < 0.0 {
                    n = -n;
                }
                (mid, n, 0.5 * s.link)
            }
        };
        letters.circled(mid, &(i + 1).to_string(), s.text, dir, clear);
    }
}

/// The crank's ω arrow: an arc of 120° about its pivot in the widest sector free of the
/// links and forces (`arrows`) that leave the pivot and of its ground symbol, its head in
/// the sense of rotation of `w` (rad/s, CCW positive); its letter with a leader where
/// crowded, into `letters`. `crank` is the crank's body and its pivot ([`LinkageFigure::crank`]).
#[allow(clippy::too_many_arguments)]
pub(crate) fn crank_turn(
    d: &mut Drawing,
    layer: usize,
    (fig, q): (&LinkageFigure, &[f64]),
    (body, pivot): (usize, Anchor),
    arrows: &[ForceArrow],
    w: f64,
    s: Sizes,
    letters: &mut labels::Polygon,
) {
    let p = anchor_at(q, pivot);
    let near =
        |x: Point| (x - p).norm() <= 1e-9 * (1.0 + x.coords.norm() + p.coords.norm()) || (x - p).norm() < s.joint;
    let mut taken: Vec<f64> = Vec::new();
    for (i, b) in fig.bodies.iter().enumerate() {
        let pts: Vec<Point> = b.points.iter().map(|(_, v)| place(q, Attach::Body(i), *v)).collect();
        for w2 in pts.windows(2) {
            for (x, y) in [(w2[0], w2[1]), (w2[1], w2[0])] {
                if near(x) {
                    taken.push(crate::geom::angle_of(y - x));
                }
            }
        }
    }
    // The forces from the pivot: from its centre, or from its symbol's edge along their
    // line of action (a sheet's [`crate::figure::shared::clear_forces`]).
    let from_pivot = |a: &&ForceArrow| {
        let (t, v) = (a.arrow.0 - p, a.arrow.1 - a.arrow.0);
        near(a.arrow.0)
            || (t.norm() <= s.joint + s.head
                && v.norm() > 0.0
                && crate::geom::cross(v, t).abs() <= 1e-9 * v.norm() * (1.0 + t.norm()))
    };
    taken.extend(arrows.iter().filter(from_pivot).map(|a| crate::geom::angle_of(a.arrow.1 - a.arrow.0)));
    // The ground symbol under the pivot.
    taken.extend([-0.5 * std::f64::consts::PI - 0.6, -0.5 * std::f64::consts::PI + 0.6]);
    let mid_angle = widest_gap(&mut taken);
    let half = 60f64.to_radians();
    let (a0, a1) = (mid_angle - half, mid_angle + half);
    let (from, sweep) = if w > 0.0 { (a0, a1 - a0) } else { (a1, a0 - a1) };
    let mid = vocab::turn_arrow(d, layer, p, 3.5 * s.joint, from, sweep, s);
    letters.name_with_leader(mid, Label::quantity(&format!("ω{}", body + 1)), s.text, mid - p, None);
}

/// The middle of the widest gap between the directions `taken` (radians, any range; sorted
/// here), the upper half of the turn when nothing is taken.
fn widest_gap(taken: &mut [f64]) -> f64 {
    let tau = std::f64::consts::TAU;
    for a in taken.iter_mut() {
        *a = a.rem_euclid(tau);
    }
    taken.sort_by(f64::total_cmp);
    let mut best = (0.0, 0.5 * std::f64::consts::PI);
    for (i, a) in taken.iter().enumerate() {
        let next = if i + 1 < taken.len() { taken[i + 1] } else { taken[0] + tau };
        if next - a > best.0 {
            best = (next - a, a + 0.5 * (next - a));
        }
    }
    best.1
}

/// Paths of the traced points over the motion, on layer `layer` (dashed grey).
pub fn trajectories(d: &mut Drawing, layer: usize, fig: &LinkageFigure, motion: &[&[f64]]) {
    for &a in &fig.traced {
        if a.body == Attach::Ground {
            continue;
        }
        vocab::path(d, layer, motion.iter().map(|q| anchor_at(q, a)).collect());
    }
}

/// A new drawing with the dimension style of the sizes, on their paper
/// (`paper_mm_per_unit = 1/k_l`).
pub fn new_drawing(style: &Style) -> Drawing {
    let mut d = Drawing::new(DimStyle { text_height: style.text, arrow_size: style.head });
    d.paper_mm_per_unit = Some(1.0 / style.k_l());
    d
}

/// Layer of the paths of measured points.
pub fn trajectory_layer(d: &mut Drawing) -> usize {
    d.layer("TRAJECTORY", Aci::DARK_GREY, LineType::Dashed)
}

/// One frame of the animation: the mechanism at `q` on layer `MECHANISM`, with the paths
/// of the measured points over `motion` on `TRAJECTORY` ([`frame_base`], then
/// [`frame_moving`]).
pub fn frame(
    fig: &LinkageFigure,
    motion: &[&[f64]],
    q: &[f64],
    spans: &[Option<(Point, Point)>],
    style: &Style,
) -> Drawing {
    let mut d = frame_base(fig, motion, style);
    moving_part(&mut d, fig, q, spans, style);
    d
}

/// What every frame shares: the paths of the measured points over `motion`, and the length
/// scale `k_l = …` with its scale bar under the motion (on layer `SCALE`).
pub fn frame_base(fig: &LinkageFigure, motion: &[&[f64]], style: &Style) -> Drawing {
    let mut d = new_drawing(style);
    let tl = trajectory_layer(&mut d);
    trajectories(&mut d, tl, fig, motion);
    if let Some((lo, _)) = motion_bounds(fig, motion) {
        let scale = d.layer("SCALE", Aci::BLACK, LineType::Continuous);
        let k_l = style.k_l();
        let h = style.small_text();
        let at = Point::new(lo.x, lo.y - 3.0 * style.ground - 2.0 * style.text);
        d.scale_text(scale, at, h, vocab::length_caption("", k_l, fig.units));
        let value = vocab::bar_value(k_l);
        let label = format!("{} {}", vocab::scale_text(value), fig.units.length);
        vocab::scale_bar(&mut d, scale, at + Vector::new(2.0 * h, -2.0 * h), value, &label, *style);
    }
    d
}

/// What changes from frame to frame: the mechanism at `q` on layer `MECHANISM` (to be
/// written after [`frame_base`], see `draw::svg::splice`).
pub fn frame_moving(fig: &LinkageFigure, q: &[f64], spans: &[Option<(Point, Point)>], style: &Style) -> Drawing {
    let mut d = new_drawing(style);
    moving_part(&mut d, fig, q, spans, style);
    d
}

fn moving_part(d: &mut Drawing, fig: &LinkageFigure, q: &[f64], spans: &[Option<(Point, Point)>], style: &Style) {
    let layer = d.layer("MECHANISM", Aci::BLACK, LineType::Continuous);
    mechanism(d, layer, fig, q, spans, style);
}
