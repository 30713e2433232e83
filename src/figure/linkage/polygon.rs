//! Velocity and acceleration polygons of any linkage, as [`PointPolygon`] values for the
//! shared [`crate::figure::shared::polygon::draw`] (the four-bar's polygons are drawn by the same code).
//!
//! The points are the named points of the moving bodies (one point per name: `crank.A` and
//! `block.A` pinned together are one point `a`); a point pinned to the ground is the pole.
//! In the velocity polygon (pole `p`) every point is reached from the pole by its absolute
//! velocity, and each body's image joins its points with its relative velocities (arrows
//! from each point to the next: ab is v_BA). By the image principle a body's image is
//! similar to the body, so one point per body is constructed from the body's reference
//! point R (its ground pivot when it has one, else its first point) and its other points
//! are the image's vertices: the point constructed is the guide body's point under a
//! sliding block (the Coriolis construction meets it there), else the body's first other
//! point X (none for a floating body whose every point another body constructs: a
//! triad's ternary link). In the velocity polygon its direction ⊥RX is drawn dashed through r (with the
//! four-bar: ⊥AB through a and ⊥BC through p meet at b). In the acceleration polygon (pole
//! `π`, primed letters) every point is reached from the pole by its absolute acceleration,
//! and X is constructed from R as the four-bar's `nBA`: the normal part a_XR^n = −ω²·RX
//! (towards R) to the point `nXR`, then the tangential part a_XR^t = ε × RX (dashed, along
//! its dashed direction ⊥RX) to x′ — unless either part vanishes ([`NEGLIGIBLE_REL`]: a
//! crank at constant speed, a body that only translates), when x′ is reached by the image
//! side alone.
//!
//! At a prismatic joint whose guide moves (the shaper's block A2 on the rocker 3), the
//! guide body's point under the sliding point gets its own letter (`a3`, the letter and the
//! guide body's number, bodies counted from 1): in the velocity polygon the sliding velocity
//! v_rel runs from a3 to a (dashed direction: the guide); in the acceleration polygon the
//! Coriolis component a_cor = 2·ω_guide × v_rel runs from a3′ to `k`, and the relative
//! acceleration a_rel along the guide (dashed) from k to a′: a_A2 = a_A3 + a_cor + a_rel.
//! A guide fixed to the ground adds nothing (its point is still: v_rel is the velocity).
//!
//! Units: the solver's, per second (mm/s, mm/s² for a scene in mm).

use crate::geom::{Vector, perp};
use crate::solve::linkage::{Anchor, Attach, JointKind, Mechanism, State};

use crate::figure::shared::polygon::{Direction, NamedPoint, POLE, PointPolygon, Side, SideKind};

/// Relative tolerance (of the body's largest point offset) under which two body points
/// are taken as the same point (a body point at a ground pivot).
const SAME_POINT: f64 = 1e-9;

/// A normal or tangential part of a relative acceleration below this fraction of the
/// largest acceleration in the polygon is not constructed (its point would coincide).
pub const NEGLIGIBLE_REL: f64 = 1e-9;

/// The velocity and acceleration polygons of a linkage at one instant.
#[derive(Debug, Clone, PartialEq)]
pub struct LinkagePolygons {
    /// Pole `p`: lower-case letters, each body's image, sliding velocities.
    pub velocity: PointPolygon,
    /// Pole `π`: primed letters, normal and tangential parts per body, Coriolis and
    /// relative accelerations at the moving guides.
    pub acceleration: PointPolygon,
}

/// A point of the polygons: its name (as in the scene) and where it is on its body.
#[derive(Debug, Clone)]
struct PolyPoint {
    name: String,
    anchor: Anchor,
}

/// The points of the polygons and each body's points in outline order (indices into the
/// polygons' numbering: [`POLE`] for a point pinned to the ground).
struct Layout {
    points: Vec<PolyPoint>,
    members: Vec<Vec<usize>>,
    /// Whether a body's image is closed (three or more named points).
    closed: Vec<bool>,
    /// Moving guides: (guide's point, sliding point, the joint's kind).
    guides: Vec<(usize, usize, JointKind)>,
}

fn same_local(a: Vector, b: Vector) -> bool {
    (a - b).norm() <= SAME_POINT * a.norm().max(b.norm()).max(1.0)
}

/// Whether `anchor` is pinned to the ground by a revolute joint.
fn pinned_to_ground(mech: &Mechanism, anchor: Anchor) -> bool {
    mech.joints.iter().any(|j| match j.kind {
        JointKind::Revolute { a, b } => {
            let at = |x: Anchor| x.body == anchor.body && same_local(x.local, anchor.local);
            (a.body == Attach::Ground && at(b)) || (b.body == Attach::Ground && at(a))
        }
        JointKind::Prismatic { .. } => false,
    })
}

/// The polygons' points: every body point, or only those named in `only` (and the
/// points pinned to the ground, which are the pole).
fn layout(mech: &Mechanism, only: Option<&[String]>) -> Layout {
    let mut points: Vec<PolyPoint> = Vec::new();
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); mech.bodies.len()];
    let mut closed = Vec::with_capacity(mech.bodies.len());
    let chosen = |name: &String| only.is_none_or(|o| o.contains(name));
    for (i, body) in mech.bodies.iter().enumerate() {
        for (name, local) in &body.points {
            let anchor = Anchor { body: Attach::Body(i), local: *local };
            let pinned = pinned_to_ground(mech, anchor);
            if !pinned && !chosen(name) {
                continue;
            }
            let index = if pinned {
                POLE
            } else if let Some(k) = points.iter().position(|p| &p.name == name) {
                k + 1
            } else {
                points.push(PolyPoint { name: name.clone(), anchor });
                points.len()
            };
            if !members[i].contains(&index) {
                members[i].push(index);
            }
        }
        closed.push(members[i].len() >= 3);
    }
    let mut guides = Vec::new();
    for j in &mech.joints {
        let JointKind::Prismatic { point, q1, .. } = j.kind else { continue };
        let Attach::Body(g) = q1.body else { continue };
        // The sliding point: a named point of its body at that place, else the joint's name.
        let named = match point.body {
            Attach::Body(b) => {
                mech.bodies[b].points.iter().find(|(_, l)| same_local(*l, point.local)).map(|(n, _)| n.clone())
            }
            Attach::Ground => None,
        };
        if only.is_some() && !named.as_ref().is_some_and(&chosen) {
            continue;
        }
        let sliding = points
            .iter()
            .position(|p| {
                named.as_ref() == Some(&p.name)
                    || (p.anchor.body == point.body && same_local(p.anchor.local, point.local))
            })
            .map(|k| k + 1)
            .unwrap_or_else(|| {
                points.push(PolyPoint { name: j.name.clone(), anchor: point });
                points.len()
            });
        let name = format!("{}{}", points[sliding - 1].name, g + 1);
        // The guide's point is placed from the sliding point's state (see `guide_point`).
        points.push(PolyPoint { name, anchor: point });
        let guide = points.len();
        members[g].push(guide);
        guides.push((guide, sliding, j.kind.clone()));
    }
    Layout { points, members, closed, guides }
}

/// Velocity and acceleration of polygon point `k` (1-based) at `state`: a body point's own,
/// or for a guide's point the guide body's point under the sliding point.
fn motion_of(lay: &Layout, state: &State, k: usize) -> (Vector, Vector) {
    if let Some((_, _, kind)) = lay.guides.iter().find(|(g, _, _)| *g == k) {
        let p = lay.points[k - 1].anchor;
        if let Some(s) = state.sliding(kind) {
            return (state.velocity(p) - s.v_rel, state.acceleration(p) - s.a_cor - s.a_rel);
        }
    }
    let a = lay.points[k - 1].anchor;
    (state.velocity(a), state.acceleration(a))
}

/// Where polygon point `k` is (any of its anchors: they coincide); the pole's points are
/// found from the body's own pivot.
fn position_of(lay: &Layout, state: &State, body: usize, k: usize, mech: &Mechanism) -> Vector {
    if k == POLE {
        // The body's point pinned to the ground.
        let b = &mech.bodies[body];
        for (_, local) in &b.points {
            let anchor = Anchor { body: Attach::Body(body), local: *local };
            if pinned_to_ground(mech, anchor) {
                return state.point(anchor).coords;
            }
        }
        return Vector::zeros();
    }
    state.point(lay.points[k - 1].anchor).coords
}

/// The velocity and acceleration polygons of `mech` at `state`, every body point shown.
pub fn polygons(mech: &Mechanism, state: &State) -> LinkagePolygons {
    polygons_of(mech, state, None)
}

/// The velocity and acceleration polygons of `mech` at `state`, showing the points named
/// in `only` (`None`: every body point; a sliding point left out takes its guide's
/// Coriolis construction with it).
pub fn polygons_of(mech: &Mechanism, state: &State, only: Option<&[String]>) -> LinkagePolygons {
    let lay = layout(mech, only);
    let n = lay.points.len();
    let motions: Vec<(Vector, Vector)> = (1..=n).map(|k| motion_of(&lay, state, k)).collect();
    let images = image_sides(&lay);
    let targets = constructed_points(&lay);
    let on = Construction { mech, state, lay: &lay, motions: &motions, images: &images, targets: &targets };
    LinkagePolygons { velocity: on.velocity(), acceleration: on.acceleration() }
}

/// The images of the bodies: sides between consecutive points, closed for a plate; sides
/// at the pole are the pole's own vectors and left out.
fn image_sides(lay: &Layout) -> Vec<Side> {
    let mut images = Vec::new();
    for (members, &closed) in lay.members.iter().zip(&lay.closed) {
        let m = members.len();
        let count = if closed && m >= 3 { m } else { m.saturating_sub(1) };
        for i in 0..count {
            let (a, b) = (members[i], members[(i + 1) % m]);
            if a != POLE && b != POLE {
                images.push(Side { from: a, to: b, kind: SideKind::Image });
            }
        }
    }
    images
}

/// The image principle: each body's polygon image is similar to the body, so one of its
/// points is constructed from its reference point R (its ground pivot, else its first
/// point) and the others follow as the image's vertices. Per body, (R, the point
/// constructed): the rocker's point under a sliding block when the body is a moving guide
/// (the Coriolis construction meets it), else the body's first other point; none for a
/// floating body (no ground pivot) whose every point another body constructs (a triad's
/// ternary link): its image is already drawn.
fn constructed_points(lay: &Layout) -> Vec<Option<(usize, usize)>> {
    let targets: Vec<Option<(usize, usize)>> = lay
        .members
        .iter()
        .map(|members| {
            if members.len() < 2 {
                return None;
            }
            let reference = if members.contains(&POLE) { POLE } else { members[0] };
            let guide = lay.guides.iter().map(|(g, _, _)| *g).find(|g| members.contains(g) && *g != reference);
            let target = guide.or_else(|| members.iter().copied().find(|&x| x != reference))?;
            Some((reference, target))
        })
        .collect();
    targets
        .iter()
        .enumerate()
        .map(|(body, t)| {
            let members = &lay.members[body];
            let elsewhere =
                |x: usize| targets.iter().enumerate().any(|(b, t)| b != body && t.is_some_and(|t| t.1 == x));
            let covered = !members.contains(&POLE) && members.iter().all(|&x| elsewhere(x));
            t.filter(|_| !covered)
        })
        .collect()
}

/// What both polygons are constructed from: the mechanism at `state`, the points' layout,
/// their (velocity, acceleration), the bodies' image sides and constructed points.
struct Construction<'a> {
    mech: &'a Mechanism,
    state: &'a State,
    lay: &'a Layout,
    motions: &'a [(Vector, Vector)],
    images: &'a [Side],
    targets: &'a [Option<(usize, usize)>],
}

impl Construction<'_> {
    /// The velocity polygon: the points' vectors from the pole, each body's image sides as
    /// its relative velocities (ab is v_BA, as the four-bar draws it), the directions that
    /// locate each constructed point (v_XR ⊥ RX through r) and the guides' sliding.
    fn velocity(&self) -> PointPolygon {
        let (lay, state, mech) = (self.lay, self.state, self.mech);
        let n = lay.points.len();
        let points: Vec<NamedPoint> = lay
            .points
            .iter()
            .zip(self.motions)
            .map(|(p, (v, _))| NamedPoint { name: p.name.to_lowercase(), from: POLE, v: *v })
            .collect();
        let mut sides: Vec<Side> = (1..=n).map(|k| Side { from: POLE, to: k, kind: SideKind::Vector }).collect();
        sides.extend(self.images.iter().map(|s| Side { kind: SideKind::Vector, ..*s }));
        let mut directions = Vec::new();
        let fastest = self.motions.iter().map(|(v, _)| v.norm()).fold(0.0, f64::max);
        for (body, t) in self.targets.iter().enumerate() {
            let Some((reference, x)) = *t else { continue };
            let rx = position_of(lay, state, body, x, mech) - position_of(lay, state, body, reference, mech);
            let (_, omega, _) = state.angular(Attach::Body(body));
            // None for a body that only translates: x is r.
            if (rx * omega).norm() <= NEGLIGIBLE_REL * fastest {
                continue;
            }
            directions.push(Direction { through: reference, dir: perp(rx), reaches: x });
        }
        for (guide, sliding, kind) in &lay.guides {
            sides.push(Side { from: *guide, to: *sliding, kind: SideKind::Vector });
            directions.push(Direction { through: *guide, dir: guide_dir(state, kind), reaches: *sliding });
        }
        // The pole p, named p₀ when a point's letter is p (a piston P).
        let pole = if points.iter().any(|p| p.name == "p") { "p₀" } else { "p" };
        PointPolygon {
            pole: pole.into(),
            pole_away: (1..=n.min(2)).collect(),
            points,
            directions,
            sides,
            marks: vec![],
        }
    }

    /// The acceleration polygon: the points' vectors from the pole π, each constructed
    /// point's normal part n_XR from r′ and its tangential direction, each guide's
    /// Coriolis k and the sliding's direction, then the bodies' image sides.
    fn acceleration(&self) -> PointPolygon {
        let (lay, state, mech) = (self.lay, self.state, self.mech);
        let n = lay.points.len();
        let mut points: Vec<NamedPoint> = lay
            .points
            .iter()
            .zip(self.motions)
            .map(|(p, (_, a))| NamedPoint { name: format!("{}′", p.name.to_lowercase()), from: POLE, v: *a })
            .collect();
        let mut sides: Vec<Side> = (1..=n).map(|k| Side { from: POLE, to: k, kind: SideKind::Vector }).collect();
        let mut directions = Vec::new();
        let largest = self.motions.iter().map(|(_, a)| a.norm()).fold(0.0, f64::max);
        let upper = |k: usize| if k == POLE { String::new() } else { lay.points[k - 1].name.clone() };
        for (body, t) in self.targets.iter().enumerate() {
            let Some((reference, x)) = *t else { continue };
            let (_, omega, epsilon) = state.angular(Attach::Body(body));
            let rx = position_of(lay, state, body, x, mech) - position_of(lay, state, body, reference, mech);
            // No construction where a part vanishes (a crank at constant speed, a body
            // that only translates): the point would coincide with its image.
            let (normal, tangential) = ((rx * (omega * omega)).norm(), (perp(rx) * epsilon).norm());
            if normal <= NEGLIGIBLE_REL * largest || tangential <= NEGLIGIBLE_REL * largest {
                continue;
            }
            let ref_name = if reference == POLE { pivot_name(mech, body) } else { upper(reference) };
            points.push(NamedPoint {
                name: format!("n{}{}", upper(x), ref_name),
                from: reference,
                v: -rx * (omega * omega),
            });
            let nx = points.len();
            sides.push(Side { from: reference, to: nx, kind: SideKind::Vector });
            sides.push(Side { from: nx, to: x, kind: SideKind::Component });
            directions.push(Direction { through: nx, dir: perp(rx), reaches: x });
        }
        let guides = &lay.guides;
        for (i, (guide, sliding, kind)) in guides.iter().enumerate() {
            let Some(s) = state.sliding(kind) else { continue };
            let name = if guides.len() == 1 { "k".to_string() } else { format!("k{}", i + 1) };
            points.push(NamedPoint { name, from: *guide, v: s.a_cor });
            let k = points.len();
            sides.push(Side { from: *guide, to: k, kind: SideKind::Vector });
            sides.push(Side { from: k, to: *sliding, kind: SideKind::Component });
            directions.push(Direction { through: k, dir: guide_dir(state, kind), reaches: *sliding });
        }
        sides.extend(self.images.iter().copied());
        PointPolygon {
            pole: "π".into(), pole_away: (1..=n.min(2)).collect(), points, directions, sides, marks: vec![]
        }
    }
}

/// Name of a body's ground pivot (the name of its point pinned to the ground).
fn pivot_name(mech: &Mechanism, body: usize) -> String {
    mech.bodies[body]
        .points
        .iter()
        .find(|(_, local)| pinned_to_ground(mech, Anchor { body: Attach::Body(body), local: *local }))
        .map_or_else(String::new, |(name, _)| name.clone())
}

/// Direction of a prismatic joint's guide at `state` (q1 → q2).
fn guide_dir(state: &State, kind: &JointKind) -> Vector {
    match *kind {
        JointKind::Prismatic { q1, q2, .. } => state.point(q2) - state.point(q1),
        JointKind::Revolute { .. } => Vector::new(1.0, 0.0),
    }
}
