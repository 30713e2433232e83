//! Figure: a general linkage at one instant, as the engineer draws a kinematic diagram:
//! bodies as polylines between their points (closed for three or more), revolute joints
//! as small circles, sliders as small rectangles along their guide, guides fixed to the
//! ground as lines with hatching, ground pivots with the ground symbol (triangle, base
//! line, hatch), point names, and the paths of the traced points.
//!
//! What it draws is a [`LinkageFigure`], built from the solver's [`Mechanism`] and the
//! names of its points (the run builds it from the scene), so that the figure knows no
//! scene file.

use crate::draw::{Aci, DimStyle, Drawing, LineType};
use crate::geom::{Point, Vector, perp};
use crate::solve::linkage::{Anchor, Attach, JointKind, Mechanism, place};

use super::labels::{self, TextBox};
use super::vocab::{self, Sizes};

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
        LinkageFigure { bodies, joints, traced }
    }
}

/// Sizes of the symbols: the shared table, [`Sizes::for_length`] of the mechanism's
/// characteristic length.
pub type Style = Sizes;

/// Colour of the i-th body's outline.
fn body_color(i: usize) -> Aci {
    const COLORS: [Aci; 6] = [Aci::BLUE, Aci::GREEN, Aci::MAGENTA, Aci::ORANGE, Aci::CYAN, Aci::RED];
    COLORS[i % COLORS.len()]
}

fn anchor_at(q: &[f64], a: Anchor) -> Point {
    place(q, a.body, a.local)
}

/// Extent of each ground-fixed guide over a motion: for each prismatic joint whose line
/// is on the ground, the segment of the guide line the slider covers (plus the slider's
/// length and the line's own points). `None` for guides on moving bodies.
pub fn guide_spans(fig: &LinkageFigure, motion: &[&[f64]], style: &Style) -> Vec<Option<(Point, Point)>> {
    fig.joints
        .iter()
        .map(|j| match *j {
            JointSymbol::Slider { point, q1, q2, .. } if q1.body == Attach::Ground => {
                let (a, b) = (Point::from(q1.local), Point::from(q2.local));
                let u = (b - a).normalize();
                let mut lo: f64 = 0.0;
                let mut hi: f64 = (b - a).norm();
                for q in motion {
                    let s = u.dot(&(anchor_at(q, point) - a));
                    lo = lo.min(s);
                    hi = hi.max(s);
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
    let s = *style;
    // The names go through the letter placer, clear of the joints, the bodies' outlines,
    // the guides, the ground symbols and the sliders' blocks; one name a place.
    let mut letters = labels::Polygon::of_names();
    // Guides fixed to the ground.
    for span in spans.iter().flatten() {
        vocab::guide(d, layer, span.0, span.1, s);
        letters.segment(span.0, span.1);
    }
    // Bodies.
    for (i, b) in fig.bodies.iter().enumerate() {
        let pts: Vec<Point> = b.points.iter().map(|(_, v)| place(q, Attach::Body(i), *v)).collect();
        let n = pts.len();
        let sides = if n >= 3 { n } else { n.saturating_sub(1) };
        for k in 0..sides {
            letters.segment(pts[k], pts[(k + 1) % n]);
        }
        if pts.len() >= 2 {
            vocab::link(d, layer, pts, b.points.len() >= 3, Some(body_color(i)), s);
        }
    }
    // Joints.
    let mut labelled: Vec<Point> = Vec::new();
    let mut name_at = |letters: &mut labels::Polygon, p: Point, name: &str, dir: Vector, clear: f64| {
        if !labelled.iter().any(|x| (x - p).norm() <= s.joint) {
            labelled.push(p);
            letters.letter_clear(p, name, s.text, dir, clear);
        }
    };
    // Sliders first, so that their names sit beside the block rather than on it.
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
                name_at(&mut letters, p, name, up_right, s.joint);
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
                    name_at(&mut letters, p, name, n, hh);
                }
            }
        }
    }
    // Names of body points not at a joint (coupler points, tips).
    for (i, b) in fig.bodies.iter().enumerate() {
        for (name, v) in &b.points {
            let p = place(q, Attach::Body(i), *v);
            name_at(&mut letters, p, name, up_right, s.joint);
        }
    }
    letters.draw(d, layer);
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

/// A new drawing with the dimension style of the mechanism's size.
pub fn new_drawing(style: &Style) -> Drawing {
    Drawing::new(DimStyle { text_height: style.text, arrow_size: style.head })
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

/// What every frame shares: the paths of the measured points over `motion`.
pub fn frame_base(fig: &LinkageFigure, motion: &[&[f64]], style: &Style) -> Drawing {
    let mut d = new_drawing(style);
    let tl = trajectory_layer(&mut d);
    trajectories(&mut d, tl, fig, motion);
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
