//! Assur-group solving of a linkage (issue 16 §1): the mechanism split into its driven
//! bodies and its Assur groups in solving order, each group solved in closed form where
//! its kind is known (the dyads RRR, RRP, RPR, PRP, RPP; the 6R triad through the triad's
//! degree-6 closed form) and by Newton–Raphson on its own few coordinates otherwise;
//! velocities and accelerations per group from its differentiated closures (directly for
//! a driven body, a 2×2 solve for every dyad; the group's block of Φq, with the known
//! bodies' motion on the right-hand side, for the triad and general groups).
//!
//! A group is a set of bodies whose joints and drivers, once the bodies solved before it
//! are known, give exactly three equations per body. Kinds:
//! - a *driven body*: one body, one joint to a known body and the driver that sets it (a
//!   crank turned by an angle, a slider pushed along its guide by a distance);
//! - a *dyad*: two bodies b1, b2 with a joint from a known body to b1, one between b1 and
//!   b2 and one from b2 to a known body, named by those joints in that order (R revolute,
//!   P prismatic: a point of one body on a line of the other with their relative rotation
//!   locked); PRR and PPR are the same dyads as RRP and RPP read from the other end and are
//!   stored that way;
//! - the *triad*: a ternary body joined by three revolutes to three binary links, each
//!   pinned to a known body (class III, seed 000);
//! - *general*: any other group (solved by Newton).
//!
//! Branch continuity: a dyad has two assembly modes; at every step the solver takes the
//! root nearest the predicted position (the last position extrapolated with its velocity
//! and acceleration, or linearly when only positions are solved) when it is clearly the
//! nearer, else the branch it took at the last step. Nearest is judged on one point or
//! direction per dyad, and only the chosen root's poses are built: RRR the joint between
//! its links where b1's predicted angle puts it, RRP the slider's predicted origin, RPR the
//! guide's normal at its predicted angle (PRP and RPP have one root); it assembles the first position in
//! the mode the general solver finds from the scene's initial placement, so that both
//! routes follow the same branch. Body angles are kept continuous (not wrapped), as the
//! general solver keeps them, so both give the same coordinates q.

use super::kinematics::{Con, NearSingular, Solver, State, con_gamma, con_jacobian, con_rate, con_residual, whole_law};
use super::lu::Lu;
use super::{
    Anchor, Attach, DriverTarget, GROUND_POSE, JointKind, LinkageError, MAX_NEWTON_ITERATIONS, Mechanism,
    NEAR_SINGULAR_PIVOT_REL, Pose, Poses, pz,
};
use crate::geom::{Vector, cross, perp, wrap_pi};

mod forms;
mod rates;
mod sweep;
use super::lanes;
use forms::{LineOf, PoseOf, RprForm, RrrForm};
use sweep::Sweep;

/// A joint's or a body's length below which (relative to the mechanism's size) a closed
/// form would divide by zero: such a group is left to Newton.
const DEGENERATE_REL: f64 = 1e-12;
/// Largest group the decomposition searches for before it gives everything left to Newton
/// as one group.
const MAX_SEARCHED_GROUP: usize = 5;

/// The joints of a dyad, in the order known body → b1 → b2 → known body.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DyadKind {
    /// Three revolutes: two links pinned to known bodies and to each other.
    Rrr,
    /// Revolute, revolute, prismatic: a link pinned to a known body and to a slider on a
    /// known guide (the slider-crank's connecting rod and piston).
    Rrp,
    /// Revolute, prismatic, revolute: two bodies pinned to known bodies, one sliding on the
    /// other (the shaper's block and rocker: an inverted slider).
    Rpr,
    /// Prismatic, revolute, prismatic: two sliders on known guides pinned to each other.
    Prp,
    /// Revolute, prismatic, prismatic: a body pinned to a known body sliding on a slider on
    /// a known guide.
    Rpp,
}

impl DyadKind {
    /// The usual name, e.g. `RRP`.
    pub fn name(self) -> &'static str {
        match self {
            DyadKind::Rrr => "RRR",
            DyadKind::Rrp => "RRP",
            DyadKind::Rpr => "RPR",
            DyadKind::Prp => "PRP",
            DyadKind::Rpp => "RPP",
        }
    }
}

/// How a driven body is set.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DrivenKind {
    /// Its angle (absolute or across its revolute joint) is the driver's law: a crank.
    Angle,
    /// Its distance along its prismatic joint is the driver's law: a driven slider.
    Distance,
}

/// What kind of group.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GroupKind {
    /// One body set by a driver and its joint to a known body.
    Driven(DrivenKind),
    /// Two bodies, three joints.
    Dyad(DyadKind),
    /// The 6R triad: bodies `[ternary, link1, link2, link3]`.
    Triad,
    /// Anything else.
    General,
}

/// How a group is solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Route {
    /// Explicit formulas (circle and line intersections, a 2×2 solve).
    ClosedForm,
    /// Newton–Raphson on the group's own coordinates.
    Newton,
}

impl Route {
    /// As the run reports it: `closed form` or `Newton`.
    pub fn name(self) -> &'static str {
        match self {
            Route::ClosedForm => "closed form",
            Route::Newton => "Newton",
        }
    }
}

/// One group of the decomposition: its kind, its bodies (indices into
/// [`Mechanism::bodies`], in the order its kind names them), and the joints and drivers it
/// solves (indices into [`Mechanism::joints`] and [`Mechanism::drivers`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Group {
    /// The kind.
    pub kind: GroupKind,
    /// Its bodies: a driven body `[b]`; a dyad `[b1, b2]`; a triad `[ternary, l1, l2, l3]`.
    pub bodies: Vec<usize>,
    /// Its joints: a driven body `[j]`; a dyad `[j1, j2, j3]` (known–b1, b1–b2, b2–known);
    /// a triad the three links' pivots, then their pins on the ternary body.
    pub joints: Vec<usize>,
    /// Its drivers (a driven body's one; none for the others unless general).
    pub drivers: Vec<usize>,
}

impl Group {
    /// How it is solved.
    pub fn route(&self) -> Route {
        match self.kind {
            GroupKind::Driven(_) | GroupKind::Dyad(_) | GroupKind::Triad => Route::ClosedForm,
            GroupKind::General => Route::Newton,
        }
    }

    /// The kind's short name: `driven (angle)`, `RRR`, `triad`, `general`.
    pub fn kind_name(&self) -> &'static str {
        match self.kind {
            GroupKind::Driven(DrivenKind::Angle) => "driven (angle)",
            GroupKind::Driven(DrivenKind::Distance) => "driven (distance)",
            GroupKind::Dyad(k) => k.name(),
            GroupKind::Triad => "triad",
            GroupKind::General => "general",
        }
    }

    /// A description for reports and messages, e.g. `dyad RPR (block, rocker)`.
    pub fn describe(&self, mech: &Mechanism) -> String {
        let names: Vec<&str> = self.bodies.iter().map(|&b| mech.bodies[b].name.as_str()).collect();
        let what = match self.kind {
            GroupKind::Driven(DrivenKind::Angle) => "driven body (angle)".to_string(),
            GroupKind::Driven(DrivenKind::Distance) => "driven body (distance)".to_string(),
            GroupKind::Dyad(k) => format!("dyad {}", k.name()),
            GroupKind::Triad => "triad".to_string(),
            GroupKind::General => "general group".to_string(),
        };
        format!("{what} ({})", names.join(", "))
    }
}

fn joint_bodies(mech: &Mechanism, j: usize) -> (Attach, Attach) {
    match mech.joints[j].kind {
        JointKind::Revolute { a, b } => (a.body, b.body),
        JointKind::Prismatic { point, q1, .. } => (point.body, q1.body),
    }
}

fn driver_bodies(mech: &Mechanism, d: usize) -> (Attach, Attach) {
    match mech.drivers[d].target {
        DriverTarget::BodyAngle(b) => (Attach::Body(b), Attach::Ground),
        DriverTarget::JointAngle(j) | DriverTarget::JointDistance(j) => {
            joint_bodies(mech, j.min(mech.joints.len().saturating_sub(1)))
        }
    }
}

/// The constraints that close on a set of bodies: unused joints and drivers that touch
/// `set` and whose other body is known or in `set`.
struct Closed {
    joints: Vec<usize>,
    drivers: Vec<usize>,
}

impl Closed {
    fn equations(&self) -> usize {
        2 * self.joints.len() + self.drivers.len()
    }
}

struct Decomposer<'a> {
    mech: &'a Mechanism,
    known: Vec<bool>,
    joint_used: Vec<bool>,
    driver_used: Vec<bool>,
}

impl Decomposer<'_> {
    fn is_known(&self, a: Attach) -> bool {
        match a {
            Attach::Ground => true,
            Attach::Body(b) => self.known[b],
        }
    }

    fn closed(&self, set: &[usize]) -> Closed {
        let inside = |a: Attach| matches!(a, Attach::Body(b) if set.contains(&b));
        let fits = |(x, y): (Attach, Attach)| {
            (inside(x) || inside(y)) && (inside(x) || self.is_known(x)) && (inside(y) || self.is_known(y))
        };
        let joints =
            (0..self.mech.joints.len()).filter(|&j| !self.joint_used[j] && fits(joint_bodies(self.mech, j))).collect();
        let drivers = (0..self.mech.drivers.len())
            .filter(|&d| !self.driver_used[d] && fits(driver_bodies(self.mech, d)))
            .collect();
        Closed { joints, drivers }
    }

    fn take(&mut self, g: Group) -> Group {
        for &b in &g.bodies {
            self.known[b] = true;
        }
        for &j in &g.joints {
            self.joint_used[j] = true;
        }
        for &d in &g.drivers {
            self.driver_used[d] = true;
        }
        g
    }

    fn unknown(&self) -> Vec<usize> {
        (0..self.known.len()).filter(|&b| !self.known[b]).collect()
    }

    /// A driven body: `b` with one joint to a known body and one driver on it.
    fn driven(&self, b: usize) -> Option<Group> {
        let c = self.closed(&[b]);
        let ([j], [d]) = (c.joints.as_slice(), c.drivers.as_slice()) else { return None };
        let (j, d) = (*j, *d);
        let kind = match (&self.mech.joints[j].kind, self.mech.drivers[d].target) {
            (JointKind::Revolute { .. }, DriverTarget::BodyAngle(_)) => DrivenKind::Angle,
            (JointKind::Revolute { .. }, DriverTarget::JointAngle(dj)) if dj == j => DrivenKind::Angle,
            (JointKind::Prismatic { .. }, DriverTarget::JointDistance(dj)) if dj == j => DrivenKind::Distance,
            _ => return None,
        };
        if kind == DrivenKind::Angle && pin_of(self.mech, j, b).is_none() {
            return None;
        }
        Some(Group { kind: GroupKind::Driven(kind), bodies: vec![b], joints: vec![j], drivers: vec![d] })
    }

    /// A dyad on `b1`, `b2`, with its bodies and joints in canonical order.
    fn dyad(&self, b1: usize, b2: usize) -> Option<Group> {
        let c = self.closed(&[b1, b2]);
        if !c.drivers.is_empty() || c.joints.len() != 3 {
            return None;
        }
        let touches = |j: usize, b: usize| {
            let (x, y) = joint_bodies(self.mech, j);
            x == Attach::Body(b) || y == Attach::Body(b)
        };
        let mid = c.joints.iter().copied().find(|&j| touches(j, b1) && touches(j, b2))?;
        let j1 = c.joints.iter().copied().find(|&j| j != mid && touches(j, b1) && !touches(j, b2))?;
        let j3 = c.joints.iter().copied().find(|&j| j != mid && touches(j, b2) && !touches(j, b1))?;
        let letter = |j: usize| matches!(self.mech.joints[j].kind, JointKind::Prismatic { .. });
        // (prismatic?) per joint; PRR and PPR are read from the other end.
        let (b1, b2, j1, j3) = match (letter(j1), letter(mid), letter(j3)) {
            (true, false, false) | (true, true, false) => (b2, b1, j3, j1),
            _ => (b1, b2, j1, j3),
        };
        let kind = match (letter(j1), letter(mid), letter(j3)) {
            (false, false, false) => DyadKind::Rrr,
            (false, false, true) => DyadKind::Rrp,
            (false, true, false) => DyadKind::Rpr,
            (true, false, true) => DyadKind::Prp,
            (false, true, true) => DyadKind::Rpp,
            _ => return None,
        };
        let g = Group { kind: GroupKind::Dyad(kind), bodies: vec![b1, b2], joints: vec![j1, mid, j3], drivers: vec![] };
        // Closed forms that would divide by zero (a link whose two joints coincide).
        Plan::dyad(self.mech, &g).map(|_| g)
    }

    /// The 6R triad pattern on a set of four bodies that closes.
    fn triad(&self, set: &[usize], c: &Closed) -> Option<Group> {
        if set.len() != 4 || !c.drivers.is_empty() || c.joints.len() != 6 {
            return None;
        }
        let revolute = |j: usize| matches!(self.mech.joints[j].kind, JointKind::Revolute { .. });
        if !c.joints.iter().all(|&j| revolute(j)) {
            return None;
        }
        let touching = |b: usize| -> Vec<usize> {
            c.joints
                .iter()
                .copied()
                .filter(|&j| {
                    let (x, y) = joint_bodies(self.mech, j);
                    x == Attach::Body(b) || y == Attach::Body(b)
                })
                .collect()
        };
        let centre = set.iter().copied().find(|&b| {
            touching(b).iter().all(|&j| {
                let (x, y) = joint_bodies(self.mech, j);
                matches!(x, Attach::Body(o) if set.contains(&o)) && matches!(y, Attach::Body(o) if set.contains(&o))
            }) && touching(b).len() == 3
        })?;
        let mut bodies = vec![centre];
        let (mut pivots, mut pins) = (Vec::new(), Vec::new());
        for &pin in &touching(centre) {
            let (x, y) = joint_bodies(self.mech, pin);
            let link = if x == Attach::Body(centre) { y } else { x };
            let Attach::Body(link) = link else { return None };
            let js = touching(link);
            let [a, b] = js.as_slice() else { return None };
            let pivot = if *a == pin { *b } else { *a };
            bodies.push(link);
            pivots.push(pivot);
            pins.push(pin);
        }
        pivots.extend(pins);
        Some(Group { kind: GroupKind::Triad, bodies, joints: pivots, drivers: vec![] })
    }

    /// The smallest set of unknown bodies (up to [`MAX_SEARCHED_GROUP`]) that closes.
    fn smallest(&self, unknown: &[usize]) -> Option<Group> {
        for size in 1..=MAX_SEARCHED_GROUP.min(unknown.len()) {
            let mut idx: Vec<usize> = (0..size).collect();
            loop {
                let set: Vec<usize> = idx.iter().map(|&i| unknown[i]).collect();
                let c = self.closed(&set);
                if c.equations() == 3 * size {
                    if let Some(g) = self.triad(&set, &c) {
                        return Some(g);
                    }
                    return Some(Group { kind: GroupKind::General, bodies: set, joints: c.joints, drivers: c.drivers });
                }
                // Next combination.
                let mut k = size;
                loop {
                    if k == 0 {
                        break;
                    }
                    k -= 1;
                    if idx[k] < unknown.len() - size + k {
                        idx[k] += 1;
                        for m in k + 1..size {
                            idx[m] = idx[m - 1] + 1;
                        }
                        k = usize::MAX;
                        break;
                    }
                }
                if k != usize::MAX {
                    break;
                }
            }
        }
        None
    }
}

/// The driven bodies and Assur groups of `mech`, in solving order: at each stage a driven
/// body, else a dyad, else the smallest set of bodies that closes (a triad or a general
/// group), else everything left as one general group. Every body, joint and driver is in
/// exactly one group.
pub fn decompose(mech: &Mechanism) -> Vec<Group> {
    let mut d = Decomposer {
        mech,
        known: vec![false; mech.bodies.len()],
        joint_used: vec![false; mech.joints.len()],
        driver_used: vec![false; mech.drivers.len()],
    };
    let mut out = Vec::new();
    loop {
        let unknown = d.unknown();
        if unknown.is_empty() {
            break;
        }
        let found = unknown.iter().find_map(|&b| d.driven(b)).or_else(|| {
            unknown.iter().enumerate().find_map(|(k, &b1)| unknown[k + 1..].iter().find_map(|&b2| d.dyad(b1, b2)))
        });
        let found = found.or_else(|| d.smallest(&unknown)).unwrap_or_else(|| {
            let c = d.closed(&unknown);
            Group { kind: GroupKind::General, bodies: unknown.clone(), joints: c.joints, drivers: c.drivers }
        });
        out.push(d.take(found));
    }
    out
}

/// A revolute joint seen from its unknown body `u`: the point of `u` (body coordinates)
/// and the known anchor it is pinned to.
#[derive(Debug, Clone, Copy)]
struct Pin {
    local: Vector,
    known: Anchor,
}

fn pin_of(mech: &Mechanism, j: usize, u: usize) -> Option<Pin> {
    match mech.joints[j].kind {
        JointKind::Revolute { a, b } if a.body == Attach::Body(u) => Some(Pin { local: a.local, known: b }),
        JointKind::Revolute { a, b } if b.body == Attach::Body(u) => Some(Pin { local: b.local, known: a }),
        _ => None,
    }
}

/// A prismatic joint between an unknown body `u` and a known body: `u`'s angle is locked
/// to the known body's, and `u`'s origin runs on a line c + s·w.
#[derive(Debug, Clone, Copy)]
struct Slide {
    /// `u` carries the sliding point (else it carries the line).
    u_is_slider: bool,
    /// The sliding point.
    point: Anchor,
    /// The line's first point.
    q1: Anchor,
    /// The line's unit direction in its body's coordinates.
    dir: Vector,
    /// φ_slider − φ_guide.
    angle: f64,
    /// Its cosine and sine.
    turn: (f64, f64),
}

/// The rotation by a then b: (cos, sin) of the sum of their angles.
#[inline]
fn compose(a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    (a.0 * b.0 - a.1 * b.1, a.1 * b.0 + a.0 * b.1)
}

fn slide_of(mech: &Mechanism, j: usize, u: usize) -> Option<Slide> {
    let JointKind::Prismatic { point, q1, q2, angle } = mech.joints[j].kind else { return None };
    let dir = q2.local - q1.local;
    let n = dir.norm();
    if n == 0.0 {
        return None;
    }
    let turn = (libm::cos(angle), libm::sin(angle));
    Some(Slide { u_is_slider: point.body == Attach::Body(u), point, q1, dir: dir / n, angle, turn })
}

/// Global position of an anchor at the cached poses. A ground anchor is its own
/// coordinates plus 0 — exactly what R + A(φ)·s gives at R = 0, φ = 0 (a −0 becomes +0,
/// as there), without the rotation.
#[inline(always)]
fn glob<P: Poses + ?Sized>(poses: &P, a: Anchor) -> Vector {
    match a.body {
        Attach::Ground => Vector::new(a.local.x + 0.0, a.local.y + 0.0),
        Attach::Body(i) => {
            let p = poses.pose(i);
            p.r + p.rot(a.local)
        }
    }
}

/// A rotation (cos, sin) applied to a vector.
#[inline]
fn rot(cs: (f64, f64), v: Vector) -> Vector {
    Vector::new(cs.0 * v.x - cs.1 * v.y, cs.1 * v.x + cs.0 * v.y)
}

impl Slide {
    /// (φ_u, (cos, sin) of φ_u, c, w): `u`'s angle and the line its origin runs on.
    #[inline(always)]
    fn line<P: Poses + ?Sized>(&self, poses: &P) -> (f64, (f64, f64), Vector, Vector) {
        let l = self.line_of(poses);
        (l.phi, l.cs, l.c.into(), l.w.into())
    }

    /// The line `u`'s origin runs on, at the cached poses.
    #[inline(always)]
    fn line_of<P: Poses + ?Sized>(&self, poses: &P) -> LineOf<f64> {
        let known = if self.u_is_slider { self.q1.body } else { self.point.body };
        let pose = match known {
            Attach::Ground => None,
            Attach::Body(i) => Some(PoseOf::from(poses.pose(i))),
        };
        self.line_at(pose)
    }

    /// The line `u`'s origin runs on when the known body is at `known` (`None`: the ground).
    #[inline(always)]
    fn line_at<T: lanes::Real>(&self, known: Option<PoseOf<T>>) -> LineOf<T> {
        let g = known.unwrap_or_else(PoseOf::ground);
        if self.u_is_slider {
            let phi = g.phi + T::splat(self.angle);
            let cs = lanes::compose(g.cs(), (T::splat(self.turn.0), T::splat(self.turn.1)));
            let w = lanes::V2::splat(self.dir).rot(g.cs());
            LineOf { phi, cs, c: forms::placed(known, self.q1.local) - lanes::V2::splat(self.point.local).rot(cs), w }
        } else {
            let phi = g.phi - T::splat(self.angle);
            let cs = lanes::compose(g.cs(), (T::splat(self.turn.0), T::splat(-self.turn.1)));
            let w = lanes::V2::splat(self.dir).rot(cs);
            LineOf { phi, cs, c: forms::placed(known, self.point.local) - lanes::V2::splat(self.q1.local).rot(cs), w }
        }
    }
}

/// The middle prismatic joint of an RPR or RPP dyad: which of b1, b2 slides, its point and
/// the line in their bodies' coordinates.
#[derive(Debug, Clone, Copy)]
struct Mid {
    b1_is_slider: bool,
    /// The sliding point, slider body coordinates.
    p: Vector,
    /// The line's first point, guide body coordinates.
    q1: Vector,
    /// The line's unit normal (perp of its direction), guide body coordinates.
    n0: Vector,
    /// φ_slider − φ_guide.
    angle: f64,
    /// Its cosine and sine.
    turn: (f64, f64),
}

fn mid_of(mech: &Mechanism, j: usize, b1: usize) -> Option<Mid> {
    let JointKind::Prismatic { point, q1, q2, angle } = mech.joints[j].kind else { return None };
    let dir = q2.local - q1.local;
    let n = dir.norm();
    (n > 0.0).then(|| Mid {
        b1_is_slider: point.body == Attach::Body(b1),
        p: point.local,
        q1: q1.local,
        n0: perp(dir / n),
        angle,
        turn: (libm::cos(angle), libm::sin(angle)),
    })
}

/// The 6R triad: three links pinned to known bodies (pivots) and to a ternary body.
#[derive(Debug, Clone)]
struct TriadPlan {
    centre: usize,
    links: [usize; 3],
    /// Each link's pivot (its point and the known anchor).
    pivots: [Pin; 3],
    /// Each link's pin on the ternary body, link coordinates.
    pins: [Vector; 3],
    /// The pins in the ternary body's coordinates.
    corners: [Vector; 3],
    /// R_i = |pin − pivot| on link i.
    r: [f64; 3],
    /// The triangle's sides l12, l23, l13.
    sides: [f64; 3],
    orientation: crate::solve::triad::Orientation,
}

fn triad_plan(mech: &Mechanism, g: &Group) -> Option<TriadPlan> {
    let ([centre, l1, l2, l3], [p1, p2, p3, c1, c2, c3]) = (g.bodies.as_slice(), g.joints.as_slice()) else {
        return None;
    };
    let links = [*l1, *l2, *l3];
    let pivots = [pin_of(mech, *p1, *l1)?, pin_of(mech, *p2, *l2)?, pin_of(mech, *p3, *l3)?];
    let pins = [pin_of(mech, *c1, *l1)?.local, pin_of(mech, *c2, *l2)?.local, pin_of(mech, *c3, *l3)?.local];
    let corners =
        [pin_of(mech, *c1, *centre)?.local, pin_of(mech, *c2, *centre)?.local, pin_of(mech, *c3, *centre)?.local];
    let r = [0, 1, 2].map(|i| (pins[i] - pivots[i].local).norm());
    let sides = [(corners[1] - corners[0]).norm(), (corners[2] - corners[1]).norm(), (corners[2] - corners[0]).norm()];
    let tiny = DEGENERATE_REL * mech.length_scale;
    if r.iter().chain(&sides).any(|&v| v <= tiny) {
        return None;
    }
    let turn = cross(corners[1] - corners[0], corners[2] - corners[0]);
    let orientation =
        if turn > 0.0 { crate::solve::triad::Orientation::Ccw } else { crate::solve::triad::Orientation::Cw };
    Some(TriadPlan { centre: *centre, links, pivots, pins, corners, r, sides, orientation })
}

/// The triad's position: every assembly mode by the degree-6 closed form of
/// [`crate::solve::triad::modes_with`] (in the ternary body's own orientation), the one
/// whose pins are nearest the predicted pins taken.
fn solve_triad(s: &mut Solver, tp: &TriadPlan) -> Result<(), String> {
    use crate::solve::triad::{Configuration, Triad, modes_with};
    let o = tp.pivots.map(|p| crate::geom::Point::from(glob(&s.poses, p.known)));
    let triad = Triad::new(o, tp.r, tp.sides[0], tp.sides[1], tp.sides[2]).map_err(|e| e.to_string())?;
    let modes = modes_with(&triad, tp.orientation).map_err(|e| e.to_string())?;
    let c = tp.centre;
    let (sn, cs) = libm::sincos(s.q[3 * c + 2]);
    let at = Vector::new(s.q[3 * c], s.q[3 * c + 1]);
    let predicted = tp.corners.map(|k| at + rot((cs, sn), k));
    let d = |m: &Configuration| (0..3).map(|i| (m.a[i].coords - predicted[i]).norm_squared()).sum::<f64>();
    let best = modes
        .iter()
        .min_by(|a, b| d(a).total_cmp(&d(b)))
        .ok_or_else(|| "the triangle fits none of the three circles' positions".to_string())?;
    let a = best.a.map(|p| p.coords);
    for i in 0..3 {
        let b = tp.links[i];
        let ko = o[i].coords;
        let rc = rotation_between(tp.pins[i] - tp.pivots[i].local, a[i] - ko);
        let phi = unwrap_near(rc, s.q[3 * b + 2]);
        set_body(&mut s.q, &mut s.poses, b, ko - rot(rc, tp.pivots[i].local), phi, rc);
    }
    let rc = rotation_between(tp.corners[1] - tp.corners[0], a[1] - a[0]);
    let phi = unwrap_near(rc, s.q[3 * c + 2]);
    set_body(&mut s.q, &mut s.poses, c, a[0] - rot(rc, tp.corners[0]), phi, rc);
    Ok(())
}

/// A crank's position: φ_u = φ_ref + sign·f; u pinned.
#[derive(Debug, Clone, Copy)]
struct DrivenAngle {
    u: usize,
    pin: Pin,
    reference: Attach,
    sign: f64,
    law: usize,
}

/// An RRR dyad's position (see [`rrr`]).
#[derive(Debug, Clone, Copy)]
struct Rrr {
    b1: usize,
    b2: usize,
    k1: Pin,
    a1: Vector,
    k3: Pin,
    /// The links' lengths (d2 for messages), d1², d2², 1/d1², 1/d2².
    form: RrrForm,
    d2: f64,
    /// a1 − k1 and a2 − k3 (b1's and b2's arms).
    arm1: Vector,
    arm3: Vector,
}

/// An RRP dyad's position (see [`rrp`]).
#[derive(Debug, Clone, Copy)]
struct Rrp {
    b1: usize,
    b2: usize,
    k1: Pin,
    a1: Vector,
    a2: Vector,
    s3: Slide,
    d1: f64,
    /// a1 − k1 (b1's arm), d1², 1/d1².
    arm1: Vector,
    d1sq: f64,
    inv_d1sq: f64,
}

/// An RPR dyad's position (see [`rpr`]).
#[derive(Debug, Clone, Copy)]
struct Rpr {
    b1: usize,
    b2: usize,
    k1: Pin,
    mid: Mid,
    k3: Pin,
    /// The guide's normal, the slider's turn and the guide's offset c0.
    form: RprForm,
}

/// How one group's position is found.
#[derive(Debug, Clone)]
enum Position {
    DrivenAngle(DrivenAngle),
    /// u on its slide at s = sign·f.
    DrivenDistance {
        u: usize,
        slide: Slide,
        sign: f64,
        law: usize,
    },
    Rrr(Rrr),
    Rrp(Rrp),
    Rpr(Rpr),
    Prp {
        b1: usize,
        b2: usize,
        s1: Slide,
        a1: Vector,
        a2: Vector,
        s3: Slide,
    },
    Rpp {
        b1: usize,
        b2: usize,
        k1: Pin,
        mid: Mid,
        s3: Slide,
    },
    Triad(Box<TriadPlan>),
    Newton,
}

/// One group compiled for solving.
#[derive(Debug, Clone)]
struct Plan {
    group: Group,
    description: String,
    /// Indices into the solver's constraints, and the first row of each in the group block.
    cons: Vec<(usize, usize)>,
    /// Global rows (for scales and names).
    rows: Vec<usize>,
    /// 3 × bodies.
    k: usize,
    lu: Lu,
    /// Right-hand sides and the known bodies' share Φq,known·q̈known.
    rhs: Vec<f64>,
    known_a: Vec<f64>,
    gamma: Vec<f64>,
    /// Smallest relative pivot of the last velocity factorisation.
    pivot: f64,
    /// Newton iterations of the last step (0 for a closed form).
    iterations: usize,
}

/// The hot part of a group's plan, what a step reads: how its position is found, with
/// every index, local vector and constant resolved at construction, and its branch.
#[derive(Debug, Clone)]
struct Op {
    position: Position,
    /// The branch of a two-root dyad taken at the last step (+1, −1; 0 before the first).
    side: f64,
}

impl Plan {
    fn dyad(mech: &Mechanism, g: &Group) -> Option<Position> {
        let GroupKind::Dyad(kind) = g.kind else { return None };
        let ([b1, b2], [j1, j2, j3]) = (g.bodies.as_slice(), g.joints.as_slice()) else { return None };
        let (b1, b2, j1, j2, j3) = (*b1, *b2, *j1, *j2, *j3);
        let tiny = DEGENERATE_REL * mech.length_scale;
        let inner = || -> Option<(Vector, Vector)> {
            let a = pin_of(mech, j2, b1)?;
            let b = pin_of(mech, j2, b2)?;
            Some((a.local, b.local))
        };
        Some(match kind {
            DyadKind::Rrr => {
                let (k1, k3) = (pin_of(mech, j1, b1)?, pin_of(mech, j3, b2)?);
                let (a1, a2) = inner()?;
                let (d1, d2) = ((a1 - k1.local).norm(), (a2 - k3.local).norm());
                if d1 <= tiny || d2 <= tiny {
                    return None;
                }
                Position::Rrr(Rrr {
                    b1,
                    b2,
                    k1,
                    a1,
                    k3,
                    form: RrrForm {
                        d1,
                        d1sq: d1 * d1,
                        d2sq: d2 * d2,
                        inv_d1sq: 1.0 / (d1 * d1),
                        inv_d2sq: 1.0 / (d2 * d2),
                    },
                    d2,
                    arm1: a1 - k1.local,
                    arm3: a2 - k3.local,
                })
            }
            DyadKind::Rrp => {
                let k1 = pin_of(mech, j1, b1)?;
                let (a1, a2) = inner()?;
                let d1 = (a1 - k1.local).norm();
                if d1 <= tiny {
                    return None;
                }
                Position::Rrp(Rrp {
                    b1,
                    b2,
                    k1,
                    a1,
                    a2,
                    s3: slide_of(mech, j3, b2)?,
                    d1,
                    arm1: a1 - k1.local,
                    d1sq: d1 * d1,
                    inv_d1sq: 1.0 / (d1 * d1),
                })
            }
            DyadKind::Rpr => {
                let (k1, mid, k3) = (pin_of(mech, j1, b1)?, mid_of(mech, j2, b1)?, pin_of(mech, j3, b2)?);
                // Slider S, guide G: rot(φ_G)·n0 · (K_S − K_G) = −n0 · (rot(α)(p − k_S) − (q1 − k_G)).
                let (pks, qkg) = if mid.b1_is_slider {
                    (mid.p - k1.local, mid.q1 - k3.local)
                } else {
                    (mid.p - k3.local, mid.q1 - k1.local)
                };
                let c0 = mid.n0.dot(&(rot(mid.turn, pks) - qkg));
                let form = RprForm { n0: mid.n0, turn: mid.turn, c0, b1_is_slider: mid.b1_is_slider };
                Position::Rpr(Rpr { b1, b2, k1, mid, k3, form })
            }
            DyadKind::Prp => {
                let (a1, a2) = inner()?;
                Position::Prp { b1, b2, s1: slide_of(mech, j1, b1)?, a1, a2, s3: slide_of(mech, j3, b2)? }
            }
            DyadKind::Rpp => Position::Rpp {
                b1,
                b2,
                k1: pin_of(mech, j1, b1)?,
                mid: mid_of(mech, j2, b1)?,
                s3: slide_of(mech, j3, b2)?,
            },
        })
    }

    fn new(mech: &Mechanism, g: Group, con_of_joint: &[usize], con_of_driver: &[usize], solver: &Solver) -> (Plan, Op) {
        let position = Plan::position_of(mech, &g);
        Plan::compiled(mech, g, con_of_joint, con_of_driver, solver, position)
    }

    /// How group `g` of `mech` is positioned: its closed form with every number resolved,
    /// or Newton.
    fn position_of(mech: &Mechanism, g: &Group) -> Position {
        match g.kind {
            GroupKind::Driven(DrivenKind::Angle) => {
                let (u, j, d) = (g.bodies[0], g.joints[0], g.drivers[0]);
                let pin = pin_of(mech, j, u);
                let (reference, sign) = match mech.drivers[d].target {
                    DriverTarget::JointAngle(_) => {
                        // Φ = φ_b − φ_a − f across the joint ["a", "b"].
                        let (a, b) = joint_bodies(mech, j);
                        if b == Attach::Body(u) { (a, 1.0) } else { (b, -1.0) }
                    }
                    _ => (Attach::Ground, 1.0),
                };
                match pin {
                    Some(pin) => Position::DrivenAngle(DrivenAngle { u, pin, reference, sign, law: d }),
                    None => Position::Newton,
                }
            }
            GroupKind::Driven(DrivenKind::Distance) => {
                let (u, j, d) = (g.bodies[0], g.joints[0], g.drivers[0]);
                match slide_of(mech, j, u) {
                    Some(slide) => {
                        Position::DrivenDistance { u, slide, sign: if slide.u_is_slider { 1.0 } else { -1.0 }, law: d }
                    }
                    None => Position::Newton,
                }
            }
            GroupKind::Dyad(_) => Plan::dyad(mech, g).unwrap_or(Position::Newton),
            GroupKind::Triad => triad_plan(mech, g).map_or(Position::Newton, |t| Position::Triad(Box::new(t))),
            GroupKind::General => Position::Newton,
        }
    }

    /// The plan of group `g` positioned by `position`: its constraints' rows and buffers.
    fn compiled(
        mech: &Mechanism,
        g: Group,
        con_of_joint: &[usize],
        con_of_driver: &[usize],
        solver: &Solver,
        position: Position,
    ) -> (Plan, Op) {
        let mut cons = Vec::new();
        let mut row = 0;
        let mut rows = Vec::new();
        let mut ci: Vec<usize> = Vec::new();
        for &j in &g.joints {
            ci.push(con_of_joint[j]);
            if matches!(mech.joints[j].kind, JointKind::Prismatic { .. }) {
                ci.push(con_of_joint[j] + 1);
            }
        }
        ci.extend(g.drivers.iter().map(|&d| con_of_driver[d]));
        let first_row = |c: usize| solver.cons[..c].iter().map(Con::rows).sum::<usize>();
        for c in ci {
            cons.push((c, row));
            let r0 = first_row(c);
            for k in 0..solver.cons[c].rows() {
                rows.push(r0 + k);
            }
            row += solver.cons[c].rows();
        }
        let k = 3 * g.bodies.len();
        let description = g.describe(mech);
        let plan = Plan {
            group: g,
            description,
            cons,
            rows,
            k,
            lu: Lu::new(k),
            rhs: vec![0.0; k],
            known_a: vec![0.0; k],
            gamma: vec![0.0; 2],
            pivot: f64::INFINITY,
            iterations: 0,
        };
        (plan, Op { position, side: 0.0 })
    }

    /// The group's constraint names, for messages.
    fn constraint_names(&self, solver: &Solver) -> String {
        let mut names: Vec<&str> = Vec::new();
        for &r in &self.rows {
            let n = solver.row_names[r].as_str();
            if !names.contains(&n) {
                names.push(n);
            }
        }
        format!("{}: {}", self.description, names.join(", "))
    }
}

/// Writes body `b`'s pose into q and the cached poses.
#[inline]
fn set_body(q: &mut [f64], poses: &mut [Pose], b: usize, r: Vector, phi: f64, cs: (f64, f64)) {
    // One bounds check for the three coordinates.
    let w = &mut q[3 * b..3 * b + 3];
    w[0] = r.x;
    w[1] = r.y;
    w[2] = phi;
    poses[b] = Pose { r, phi, c: cs.0, s: cs.1 };
}

/// The angle nearest `pred` with the rotation `cs`.
#[inline]
fn unwrap_near(cs: (f64, f64), pred: f64) -> f64 {
    pred + wrap_pi(libm::atan2(cs.1, cs.0) - pred)
}

/// The rotation taking unit-length direction `from` to `to` (both nonzero).
#[inline]
fn rotation_between(from: Vector, to: Vector) -> (f64, f64) {
    let (f, t) = (from / from.norm(), to / to.norm());
    (f.dot(&t), cross(f, t))
}

/// The angle in (−π, π] from rotation `from` to rotation `to` (unit (cos, sin) pairs): a
/// short series for the small turn of one time step, `atan2` for a larger one.
#[inline(always)]
fn turn_between(from: (f64, f64), to: (f64, f64)) -> f64 {
    let (c, s) = forms::rotation_turn(from, to);
    forms::turn_angle(c, s)
}

/// Body `b`'s rotation (cos, sin) at the angle predicted for this step (its pose still
/// holds the last step's): see [`forms::predicted_turn`].
#[inline(always)]
fn predicted_rotation<F: Frame>(f: &F, b: usize) -> (f64, f64) {
    let last = f.last(b);
    forms::predicted_turn((last.c, last.s), f.predicted_phi(b) - last.phi)
}

/// What a group's closed form reads and writes at one time step: the known bodies' poses
/// at this step ([`Poses`]), the group's own bodies' at the last step, the laws' values,
/// the prediction of its own coordinates. Implemented by the live solver (a step at a
/// time, [`Live`]) and by a sweep over many steps ([`Lane`]): the same closed forms, the
/// same operations in the same order, so the same bits.
trait Frame: Poses {
    /// Body `b`'s pose at the last step (one of the group's own bodies, before it puts it).
    fn last(&self, b: usize) -> Pose;
    /// Driver `d`'s law value at this step.
    fn law(&self, d: usize) -> f64;
    /// Body `b`'s predicted angle.
    fn predicted_phi(&self, b: usize) -> f64;
    /// Body `b`'s predicted origin.
    fn predicted_r(&self, b: usize) -> Vector;
    /// Writes body `b`'s pose: origin `r`, angle `phi`, rotation `cs`.
    fn put(&mut self, b: usize, r: Vector, phi: f64, cs: (f64, f64));
}

/// A body's q̇ and q̈ entries: (ẋ, ẏ, ω) and (ẍ, ÿ, ε).
#[derive(Debug, Clone, Copy, Default)]
struct Rates {
    qd: [f64; 3],
    qdd: [f64; 3],
}

/// What a group's closed-form rates read and write at one time step: the bodies' poses
/// ([`Poses`]), the known bodies' rates, the laws' values and rates, the group's own
/// bodies' rates. Implemented by the solver at its step and by a sweep's [`Lane`]: the
/// same formulas, the same operations in the same order, so the same bits.
trait RateFrame: Poses {
    /// Body `b`'s q̇ and q̈ at this step.
    fn rates(&self, b: usize) -> Rates;
    /// Driver `d`'s law at this step: its value, first and second time derivatives.
    fn jet(&self, d: usize) -> (f64, f64, f64);
    /// Writes body `b`'s q̇ and q̈.
    fn put_rates(&mut self, b: usize, r: Rates);
}

impl Poses for Solver {
    #[inline(always)]
    fn pose(&self, b: usize) -> Pose {
        self.poses[b]
    }
}

impl RateFrame for Solver {
    #[inline(always)]
    fn rates(&self, b: usize) -> Rates {
        Rates { qd: coords(&self.qd, b), qdd: coords(&self.qdd, b) }
    }
    #[inline(always)]
    fn jet(&self, d: usize) -> (f64, f64, f64) {
        self.laws[d]
    }
    #[inline(always)]
    fn put_rates(&mut self, b: usize, r: Rates) {
        self.qd[3 * b..3 * b + 3].copy_from_slice(&r.qd);
        self.qdd[3 * b..3 * b + 3].copy_from_slice(&r.qdd);
    }
}

/// The live solver at the step being solved.
struct Live<'a, 'p> {
    s: &'a mut Solver,
    pred: &'a Predictor<'p>,
}

impl Poses for Live<'_, '_> {
    #[inline(always)]
    fn pose(&self, b: usize) -> Pose {
        self.s.poses[b]
    }
}

impl Frame for Live<'_, '_> {
    #[inline(always)]
    fn last(&self, b: usize) -> Pose {
        self.s.poses[b]
    }
    #[inline(always)]
    fn law(&self, d: usize) -> f64 {
        self.s.laws[d].0
    }
    #[inline(always)]
    fn predicted_phi(&self, b: usize) -> f64 {
        self.pred.at(&self.s.q, 3 * b + 2)
    }
    #[inline(always)]
    fn predicted_r(&self, b: usize) -> Vector {
        Vector::new(self.pred.at(&self.s.q, 3 * b), self.pred.at(&self.s.q, 3 * b + 1))
    }
    #[inline(always)]
    fn put(&mut self, b: usize, r: Vector, phi: f64, cs: (f64, f64)) {
        set_body(&mut self.s.q, &mut self.s.poses, b, r, phi, cs);
    }
}

/// How this step's q is predicted from the last (which `q_prev` holds; the solver's own q
/// holds the step before it until a group overwrites its bodies' coordinates).
#[derive(Debug, Clone, Copy)]
enum Extrapolation {
    /// The last q as it is (the first position, or no earlier one).
    Hold,
    /// Linearly from the last two positions, Δt over the last Δt as given.
    Linear(f64),
    /// q + q̇·Δt + ½·q̈·Δt² with the last step's rates (in `qd_prev`, `qdd_prev`).
    Taylor(f64),
}

impl Extrapolation {
    /// The prediction of a coordinate now at `now`, from the step before's value `before`
    /// (linearly) or its rate and acceleration `rates` (Taylor).
    #[inline(always)]
    fn apply(self, now: f64, before: impl FnOnce() -> f64, rates: impl FnOnce() -> (f64, f64)) -> f64 {
        match self {
            Extrapolation::Hold => now,
            Extrapolation::Linear(f) => now + (now - before()) * f,
            Extrapolation::Taylor(dt) => {
                let (v, a) = rates();
                now + v * dt + 0.5 * a * dt * dt
            }
        }
    }

    /// How a step `dt` after the last predicts: with the last rates when they belong to the
    /// last q (`rates_valid`), else linearly from the last two positions (`dt_prev` apart),
    /// else the last q as it is.
    fn of(rates_valid: bool, dt_prev: Option<f64>, dt: f64) -> Extrapolation {
        if rates_valid {
            Extrapolation::Taylor(dt)
        } else {
            match dt_prev.filter(|d| *d != 0.0) {
                Some(d) => Extrapolation::Linear(dt / d),
                None => Extrapolation::Hold,
            }
        }
    }
}

/// This step's prediction of q, computed per coordinate where a group asks for it (a dyad
/// one angle or point, Newton and the triad their bodies' coordinates): the same numbers,
/// in the same order of operations, as extrapolating the whole q first.
struct Predictor<'a> {
    how: Extrapolation,
    last: &'a [f64],
    qd: &'a [f64],
    qdd: &'a [f64],
}

impl Predictor<'_> {
    /// The predicted coordinate `i`, from the last step and `before`, the step before it
    /// (the solver's own q, read before the group that owns coordinate `i` writes it).
    #[inline(always)]
    fn at(&self, before: &[f64], i: usize) -> f64 {
        self.how.apply(self.last[i], || before[i], || (self.qd[i], self.qdd[i]))
    }

    /// Writes the prediction of `bodies`' coordinates into `s.q` (for the groups that start
    /// from it: the triad's choice of mode, Newton's first iterate).
    fn write(&self, s: &mut Solver, bodies: &[usize]) {
        for &b in bodies {
            for i in 3 * b..3 * b + 3 {
                s.q[i] = self.at(&s.q, i);
            }
        }
    }
}

/// Positions, velocities and accelerations over a motion ([`AssurSolver::motion_into`]):
/// each step's q, q̇, q̈ (n values a step, laid out as [`State::q`]) and the Newton
/// iterations it took (0: closed forms only), and the reports of the steps solved close to
/// a dead point.
#[derive(Debug, Clone, Default)]
pub struct Motion {
    /// q of every step, one after another.
    pub q: Vec<f64>,
    /// q̇ of every step.
    pub qd: Vec<f64>,
    /// q̈ of every step.
    pub qdd: Vec<f64>,
    /// Newton iterations per step.
    pub iterations: Vec<usize>,
    /// The steps solved close to a singular position: (the step's index in the motion, its
    /// report), in order.
    pub near: Vec<(usize, NearSingular)>,
}

impl Motion {
    /// Empties every list (keeping their memory, for the next motion).
    pub fn clear(&mut self) {
        self.q.clear();
        self.qd.clear();
        self.qdd.clear();
        self.iterations.clear();
        self.near.clear();
    }
}

/// The Assur-group solver: the same outputs as [`Solver`] (a [`State`] per step, the same
/// q layout), each group solved in closed form or by its own Newton iterations.
#[derive(Debug, Clone)]
pub struct AssurSolver {
    /// The general solver: its compiled constraints, laws and buffers are shared, it
    /// assembles the first position (the assembly mode) and factors Φq for the forces.
    inner: Solver,
    plans: Vec<Plan>,
    /// The groups' ops, in solving order (one per plan).
    ops: Vec<Op>,
    /// The general solver's iterations when it solved the last step (at a dead point),
    /// else `None` (the groups' own: Newton groups count theirs, closed forms none).
    fallback: Option<usize>,
    /// q, q̇, q̈ of the last step while a step is solved (the prediction; the fallback at
    /// an exact dead point): swapped with the solver's own at the start of a step, so the
    /// solver's hold the step before until overwritten (q the linear predictor's second
    /// point).
    q_prev: Vec<f64>,
    qd_prev: Vec<f64>,
    qdd_prev: Vec<f64>,
    /// Whether q̇ and q̈ belong to the last step (the Taylor predictor may use them).
    rates_valid: bool,
    dt_prev: Option<f64>,
    /// How the step being solved predicts q.
    how: Extrapolation,
    /// Newton group block and residual buffers.
    work: Vec<f64>,
    /// The sweep's buffers.
    sweep: Sweep,
}

impl AssurSolver {
    /// Decomposes and compiles the mechanism (degrees of freedom counted first, as
    /// [`Solver::new`] does).
    pub fn new(mech: Mechanism) -> Result<AssurSolver, LinkageError> {
        let groups = decompose(&mech);
        let inner = Solver::new(mech)?;
        let mech = &inner.mech;
        let (mut con_of_joint, mut con_of_driver) = (Vec::new(), Vec::new());
        let mut c = 0;
        for j in &mech.joints {
            con_of_joint.push(c);
            c += match j.kind {
                JointKind::Revolute { .. } => 1,
                JointKind::Prismatic { .. } => 2,
            };
        }
        for _ in &mech.drivers {
            con_of_driver.push(c);
            c += 1;
        }
        let (plans, ops) =
            groups.into_iter().map(|g| Plan::new(mech, g, &con_of_joint, &con_of_driver, &inner)).unzip();
        let n = inner.n;
        let most = 3 * mech.bodies.len();
        Ok(AssurSolver {
            inner,
            plans,
            ops,
            fallback: None,
            q_prev: vec![0.0; n],
            qd_prev: vec![0.0; n],
            qdd_prev: vec![0.0; n],
            rates_valid: false,
            dt_prev: None,
            how: Extrapolation::Hold,
            work: vec![0.0; most * most + 2 * most],
            sweep: Sweep::default(),
        })
    }

    /// Changes the mechanism's numbers in place by `change` (body points, joint anchors,
    /// locked angles: a tolerance study's sample) and recompiles the constraints and the
    /// groups' closed forms, keeping the decomposition, the groups and every buffer (no
    /// allocation but a triad's plan). `change` must keep the bodies, joints and drivers
    /// (their number and kinds); the branches are forgotten, so the next step takes each
    /// group's root nearest its prediction: [`AssurSolver::resume`] from a state of the
    /// mechanism before the change, then step, and each group stays in that state's
    /// assembly mode. Errors as [`Solver::new`] for a driver that no longer fits its joint.
    pub fn refit(&mut self, change: impl FnOnce(&mut Mechanism)) -> Result<(), LinkageError> {
        let counts = |m: &Mechanism| (m.bodies.len(), m.joints.len(), m.drivers.len());
        let before = counts(&self.inner.mech);
        change(&mut self.inner.mech);
        if counts(&self.inner.mech) != before {
            return Err(LinkageError::InvalidModel {
                what: "a refit changed the number of bodies, joints or drivers".to_string(),
            });
        }
        self.inner.recompile()?;
        for (plan, op) in self.plans.iter().zip(self.ops.iter_mut()) {
            op.position = Plan::position_of(&self.inner.mech, &plan.group);
            op.side = 0.0;
        }
        self.fallback = None;
        self.rates_valid = false;
        self.dt_prev = None;
        Ok(())
    }

    /// The groups in solving order.
    pub fn groups(&self) -> impl Iterator<Item = &Group> {
        self.plans.iter().map(|p| &p.group)
    }

    /// Whether every group is solved in closed form.
    pub fn all_closed_form(&self) -> bool {
        self.ops.iter().all(|o| !matches!(o.position, Position::Newton))
    }

    /// How each group is solved (a dyad whose closed form would divide by zero is left to
    /// Newton, whatever its kind).
    pub fn routes(&self) -> Vec<(&Group, Route)> {
        self.plans
            .iter()
            .zip(&self.ops)
            .map(|(p, o)| {
                (&p.group, if matches!(o.position, Position::Newton) { Route::Newton } else { Route::ClosedForm })
            })
            .collect()
    }

    /// The mechanism.
    pub fn mechanism(&self) -> &Mechanism {
        &self.inner.mech
    }

    /// The general solver this one shares its model with (for the strokes' refinement and
    /// the drag, which stay on Newton).
    pub fn general(&self) -> &Solver {
        &self.inner
    }

    /// Current coordinates.
    pub fn q(&self) -> &[f64] {
        &self.inner.q
    }

    /// The state after the last step.
    pub fn state(&mut self) -> State {
        self.inner.residual();
        State {
            t: self.inner.t.unwrap_or(0.0),
            q: self.inner.q.clone(),
            qd: self.inner.qd.clone(),
            qdd: self.inner.qdd.clone(),
            iterations: self.fallback.unwrap_or_else(|| self.plans.iter().map(|p| p.iterations).max().unwrap_or(0)),
            residual: self.inner.residual_norm().0,
            near_singular: self.inner.near.clone(),
        }
    }

    /// Resumes from `state` (a state this route or the general one computed at this
    /// mechanism): the next step starts from it, extrapolated with its rates, in its
    /// assembly mode.
    pub fn resume(&mut self, state: &State) {
        let n = self.inner.n;
        if state.q.len() != n || state.qd.len() != n || state.qdd.len() != n {
            return;
        }
        self.inner.q.copy_from_slice(&state.q);
        self.inner.qd.copy_from_slice(&state.qd);
        self.inner.qdd.copy_from_slice(&state.qdd);
        self.q_prev.copy_from_slice(&state.q);
        super::fill_poses(&self.inner.q, &mut self.inner.poses);
        self.inner.t = Some(state.t);
        self.inner.near = state.near_singular.clone();
        self.rates_valid = true;
        self.dt_prev = None;
    }

    /// Solves at every time in `times` (positions, velocities, accelerations); the first
    /// time is assembled in the general solver's assembly mode. Swept
    /// ([`AssurSolver::motion_into`]) when every group has a closed form, else a step and
    /// its state at a time.
    pub fn run(&mut self, times: &[f64]) -> Result<Vec<State>, LinkageError> {
        if !self.sweeps() {
            let mut out = Vec::with_capacity(times.len());
            for &t in times {
                self.step(t)?;
                out.push(self.state());
            }
            return Ok(out);
        }
        let mut m = Motion::default();
        self.motion_into(times, &mut m)?;
        self.states(times, m)
    }

    /// The states of a motion solved at `times` (`m.qd`, `m.qdd` and `m.iterations` empty
    /// for positions alone: q̇, q̈ zero, no iterations), each with its residual as
    /// [`AssurSolver::state`] gives it.
    fn states(&mut self, times: &[f64], m: Motion) -> Result<Vec<State>, LinkageError> {
        let n = self.inner.n;
        let mut near = m.near.into_iter().peekable();
        let mut out = Vec::with_capacity(times.len());
        for (k, &t) in times.iter().enumerate() {
            let at = k * n..(k + 1) * n;
            let q = &m.q[at.clone()];
            // The laws at t (the drivers' rows of the residual) and q's poses, as a step
            // leaves them.
            self.inner.eval_law_values(t)?;
            self.inner.q.copy_from_slice(q);
            self.inner.residual();
            let rates = |v: &[f64]| if v.is_empty() { vec![0.0; n] } else { v[at.clone()].to_vec() };
            out.push(State {
                t,
                q: q.to_vec(),
                qd: rates(&m.qd),
                qdd: rates(&m.qdd),
                iterations: m.iterations.get(k).copied().unwrap_or(0),
                residual: self.inner.residual_norm().0,
                near_singular: near.next_if(|(step, _)| *step == k).map(|(_, report)| report),
            });
        }
        Ok(out)
    }

    /// Positions only at every time in `times` (q per step; velocities and accelerations
    /// are not computed): [`AssurSolver::positions_into`], one q per step.
    pub fn run_positions(&mut self, times: &[f64]) -> Result<Vec<Vec<f64>>, LinkageError> {
        let n = self.inner.n;
        let mut flat = Vec::with_capacity(times.len() * n);
        self.positions_into(times, &mut flat)?;
        if n == 0 {
            return Ok(vec![Vec::new(); times.len()]);
        }
        Ok(flat.chunks_exact(n).map(<[f64]>::to_vec).collect())
    }

    /// Positions only at every time in `times`, as states: each step's q with its residual
    /// (relative, as [`AssurSolver::state`] gives it); q̇ and q̈ zero, not computed. Swept
    /// ([`AssurSolver::positions_into`]) when every group has a closed form, else a step
    /// and its state at a time (each step's Newton iterations).
    pub fn run_positions_states(&mut self, times: &[f64]) -> Result<Vec<State>, LinkageError> {
        if !self.sweeps() {
            let mut states = Vec::with_capacity(times.len());
            for &t in times {
                self.step_positions(t)?;
                let mut st = self.state();
                st.qd.iter_mut().chain(st.qdd.iter_mut()).for_each(|v| *v = 0.0);
                states.push(st);
            }
            return Ok(states);
        }
        let mut m = Motion::default();
        self.sweep_or_step(times, &mut m, false)?;
        self.states(times, m)
    }

    /// Positions only at every time in `times`, each step's q appended to `out` (n values a
    /// step; on an error, the steps before it). The same numbers, bit for bit, as
    /// [`AssurSolver::step_positions`] at each time in turn, found group by group: when
    /// every group has a closed form, each group is solved over all the steps before the
    /// next group is (a sweep: one loop per group, its constants held across the steps),
    /// after the first step, which assembles. A step a sweep cannot solve (a law not
    /// finite, a group that cannot be assembled) is then stepped alone, which reports it
    /// as [`AssurSolver::step_positions`] does.
    pub fn positions_into(&mut self, times: &[f64], out: &mut Vec<f64>) -> Result<(), LinkageError> {
        let mut m = Motion { q: std::mem::take(out), ..Motion::default() };
        let done = self.sweep_or_step(times, &mut m, false);
        *out = m.q;
        done
    }

    /// Positions, velocities and accelerations at every time in `times`, each step's
    /// appended to `out` (on an error, the steps before it). The same numbers, bit for bit,
    /// as [`AssurSolver::step`] at each time in turn, found group by group as
    /// [`AssurSolver::positions_into`] finds positions: each group's positions and rates
    /// over all the steps before the next group's (a group's rates need only its own
    /// positions and the earlier groups' rates at the same time; its prediction, its last
    /// step's rates). A step a sweep cannot solve (a law not finite, a group that cannot be
    /// assembled, rates at a dead point) is then stepped alone, as [`AssurSolver::step`]
    /// solves or reports it.
    pub fn motion_into(&mut self, times: &[f64], out: &mut Motion) -> Result<(), LinkageError> {
        self.sweep_or_step(times, out, true)
    }

    /// Sweeps (when every group has a closed form, after the first step) or steps, with or
    /// without the rates, appending each step to `out`.
    fn sweep_or_step(&mut self, times: &[f64], out: &mut Motion, rates: bool) -> Result<(), LinkageError> {
        let sweeps = self.sweeps();
        let mut i = 0;
        while i < times.len() {
            if sweeps && self.inner.t.is_some() {
                let m = self.sweep(&times[i..], out, rates);
                i += m;
                if i == times.len() {
                    break;
                }
            }
            self.advance(times[i], rates)?;
            out.q.extend_from_slice(&self.inner.q);
            if rates {
                out.qd.extend_from_slice(&self.inner.qd);
                out.qdd.extend_from_slice(&self.inner.qdd);
                let iterations =
                    self.fallback.unwrap_or_else(|| self.plans.iter().map(|p| p.iterations).max().unwrap_or(0));
                out.iterations.push(iterations);
                if let Some(near) = &self.inner.near {
                    out.near.push((out.iterations.len() - 1, near.clone()));
                }
            }
            i += 1;
        }
        Ok(())
    }

    /// Whether positions are swept: every group has a closed form the sweep knows (the
    /// triad's and Newton's are stepped).
    fn sweeps(&self) -> bool {
        self.ops.iter().all(|o| !matches!(o.position, Position::Triad(_) | Position::Newton))
    }

    /// Solves at every time, with the forces at each: the groups' positions, then Φq of the
    /// whole mechanism factored there for q̇, q̈ and the multipliers, as
    /// [`Solver::run_kinetostatics`] does.
    pub fn run_kinetostatics(
        &mut self,
        times: &[f64],
        dynamics: &super::Dynamics,
    ) -> Result<(Vec<State>, Vec<super::Forces>), LinkageError> {
        let mut states = Vec::with_capacity(times.len());
        let mut forces = Vec::with_capacity(times.len());
        for &t in times {
            self.step(t)?;
            // The forces take q̇ and q̈ from the same factorisation as the multipliers (as
            // the general solver does), so that the virtual-power balance closes to
            // rounding even where every power is itself at rounding level.
            self.inner.residual();
            if !self.inner.factor() {
                return Err(LinkageError::Singular {
                    t,
                    drivers: self.inner.driver_values(),
                    constraints: self.plans.iter().map(|p| p.description.clone()).collect::<Vec<_>>().join("; "),
                });
            }
            self.inner.kinematics();
            forces.push(self.inner.forces(dynamics)?);
            states.push(self.state());
        }
        Ok((states, forces))
    }

    /// The first position: the general solver assembles from the scene's placement (its
    /// assembly mode is the prediction every group's root is chosen by).
    fn first(&mut self, t: f64) -> Result<(), LinkageError> {
        self.how = Extrapolation::Hold;
        let assembled = self.inner.assemble(t);
        self.q_prev.copy_from_slice(&self.inner.q);
        match assembled {
            Ok(_) => Ok(()),
            Err(e) => {
                // Name the group that cannot be assembled, when a closed form can tell.
                let mech = self.inner.mech.clone();
                for (i, b) in mech.bodies.iter().enumerate() {
                    self.inner.q[3 * i] = b.at.x;
                    self.inner.q[3 * i + 1] = b.at.y;
                    self.inner.q[3 * i + 2] = b.angle;
                }
                super::fill_poses(&self.inner.q, &mut self.inner.poses);
                self.q_prev.copy_from_slice(&self.inner.q);
                self.inner.eval_laws(t)?;
                self.positions(t)?;
                Err(e)
            }
        }
    }

    /// Positions, velocities and accelerations at `t`.
    pub fn step(&mut self, t: f64) -> Result<(), LinkageError> {
        self.advance(t, true)
    }

    /// Positions only at `t` (q̇ and q̈ are left as they were, and not used to predict).
    pub fn step_positions(&mut self, t: f64) -> Result<(), LinkageError> {
        self.advance(t, false)
    }

    fn advance(&mut self, t: f64, rates: bool) -> Result<(), LinkageError> {
        self.fallback = None;
        let Some(t0) = self.inner.t else {
            self.first(t)?;
            return self.finish(t, None, rates);
        };
        if rates {
            self.inner.eval_laws(t)?;
        } else {
            // Positions read the laws' values alone.
            self.inner.eval_law_values(t)?;
        }
        let dt = t - t0;
        let had_rates = self.rates_valid;
        self.predict(dt, rates);
        match self.finish(t, Some(dt), rates) {
            Err(singular @ LinkageError::Singular { .. }) if rates && had_rates => self.dead_point(t, t0, dt, singular),
            other => other,
        }
    }

    /// A step exactly on a dead point (out of the step's hot path): the closed forms land
    /// on it, where a group's rates do not exist. The general solver's step from the last
    /// position lands within its tolerance of it and reports it as it always has
    /// (near-singular, solved; or singular).
    #[cold]
    #[inline(never)]
    fn dead_point(&mut self, t: f64, t0: f64, dt: f64, singular: LinkageError) -> Result<(), LinkageError> {
        let s = &mut self.inner;
        s.q.copy_from_slice(&self.q_prev);
        s.qd.copy_from_slice(&self.qd_prev);
        s.qdd.copy_from_slice(&self.qdd_prev);
        s.dt_prev = None;
        s.t = Some(t0);
        let iterations = match s.step(t) {
            Ok(it) => it,
            // Singular there too: the group names the dead point.
            Err(LinkageError::Singular { .. }) => return Err(singular),
            Err(e) => return Err(e),
        };
        self.fallback = Some(iterations);
        self.rates_valid = true;
        self.dt_prev = Some(dt);
        Ok(())
    }

    /// Starts a step: the last q, q̇, q̈ into `q_prev`, `qd_prev`, `qdd_prev` and how q is
    /// predicted from them — with q̇·Δt + ½·q̈·Δt² when the rates belong to the last q,
    /// else linearly from the last two positions. The last q and (on a step with rates)
    /// q̇, q̈ are swapped in, not copied: every group writes all its bodies' coordinates
    /// and rates. A positions-only step leaves q̇ and q̈ as they are (copied once for the
    /// prediction when they belong to the last q).
    fn predict(&mut self, dt: f64, rates: bool) {
        let s = &mut self.inner;
        std::mem::swap(&mut s.q, &mut self.q_prev);
        if rates {
            std::mem::swap(&mut s.qd, &mut self.qd_prev);
            std::mem::swap(&mut s.qdd, &mut self.qdd_prev);
        } else if self.rates_valid {
            self.qd_prev.copy_from_slice(&s.qd);
            self.qdd_prev.copy_from_slice(&s.qdd);
        }
        self.how = Extrapolation::of(self.rates_valid, self.dt_prev, dt);
    }

    /// Solves every group at `t` from the predicted q (laws evaluated), then the rates.
    fn finish(&mut self, t: f64, dt: Option<f64>, rates: bool) -> Result<(), LinkageError> {
        self.positions(t)?;
        if rates {
            self.rates(t)?;
        }
        self.rates_valid = rates;
        if dt.is_some() {
            self.dt_prev = dt;
        }
        self.inner.t = Some(t);
        Ok(())
    }

    /// Every group's position, in order: a straight run through the compiled ops, each
    /// closed form its own small function (a group's failure message is built out of the
    /// run, by [`cannot_assemble`]).
    fn positions(&mut self, t: f64) -> Result<(), LinkageError> {
        let l = self.inner.mech.length_scale;
        // How far a closure may miss and still count as met: the residual every answer
        // must meet (the general solver accepts the same).
        let slack = crate::geom::tol::RESIDUAL_REL * l;
        let pred = Predictor { how: self.how, last: &self.q_prev, qd: &self.qd_prev, qdd: &self.qdd_prev };
        let s = &mut self.inner;
        for (gi, op) in self.ops.iter_mut().enumerate() {
            let live = &mut Live { s: &mut *s, pred: &pred };
            let done = match op.position {
                Position::DrivenAngle(_) => driven_angle(live, &op.position, &mut op.side, slack),
                Position::DrivenDistance { .. } => driven_distance(live, &op.position, &mut op.side, slack),
                Position::Rrr(_) => rrr(live, &op.position, &mut op.side, slack),
                Position::Rrp(_) => rrp(live, &op.position, &mut op.side, slack),
                Position::Rpr(_) => rpr(live, &op.position, &mut op.side, slack),
                Position::Prp { .. } => prp(live, &op.position, &mut op.side, slack),
                Position::Rpp { .. } => rpp(live, &op.position, &mut op.side, slack),
                Position::Triad(ref tp) => {
                    pred.write(s, &self.plans[gi].group.bodies);
                    solve_triad(s, tp).map_err(Why::Triad)
                }
                Position::Newton => {
                    let plan = &mut self.plans[gi];
                    pred.write(s, &plan.group.bodies);
                    newton(s, plan, &mut self.work, t)?;
                    Ok(())
                }
            };
            if let Err(why) = done {
                return Err(cannot_assemble(s, &self.plans[gi], t, why));
            }
        }
        Ok(())
    }

    /// Every group's velocities and accelerations, in order (positions solved).
    fn rates(&mut self, t: f64) -> Result<(), LinkageError> {
        let mut worst: Option<(f64, usize)> = None;
        for gi in 0..self.plans.len() {
            let s = &mut self.inner;
            let plan = &mut self.plans[gi];
            if let Some(rho) = closed_rates(&mut *s, &self.ops[gi].position) {
                if rho.is_nan() || rho <= super::SINGULAR_PIVOT_REL {
                    return Err(singular_group(s, plan, t));
                }
                plan.pivot = rho;
                if worst.is_none_or(|(p, _)| rho < p) {
                    worst = Some((rho, gi));
                }
                continue;
            }
            let k = plan.k;
            // Block Φq,group (equilibrated) and the known bodies' shares.
            let bodies = &plan.group.bodies;
            let a = &mut plan.lu.a;
            a.iter_mut().for_each(|v| *v = 0.0);
            plan.rhs.iter_mut().for_each(|v| *v = 0.0);
            plan.known_a.iter_mut().for_each(|v| *v = 0.0);
            for &(c, r0) in &plan.cons {
                let con = &s.cons[c];
                plan.rhs[r0] = con_rate(con, &s.laws);
                let (qd, qdd) = (&s.qd, &s.qdd);
                let (rhs, known_a) = (&mut plan.rhs, &mut plan.known_a);
                con_jacobian(con, &s.poses, |row, at, dx, dy, dphi| {
                    let Attach::Body(b) = at else { return };
                    let r = r0 + row;
                    match bodies.iter().position(|&x| x == b) {
                        Some(gb) => {
                            a[r * k + 3 * gb] += dx;
                            a[r * k + 3 * gb + 1] += dy;
                            a[r * k + 3 * gb + 2] += dphi;
                        }
                        None => {
                            rhs[r] -= dx * qd[3 * b] + dy * qd[3 * b + 1] + dphi * qd[3 * b + 2];
                            known_a[r] += dx * qdd[3 * b] + dy * qdd[3 * b + 1] + dphi * qdd[3 * b + 2];
                        }
                    }
                });
            }
            let l = s.mech.length_scale;
            let norm = equilibrate(a, k, &plan.rows, &s.row_scale, l);
            if !plan.lu.factor(norm) {
                return Err(LinkageError::Singular {
                    t,
                    drivers: s.driver_values(),
                    constraints: plan.constraint_names(s),
                });
            }
            plan.pivot = plan.lu.min_pivot_rel;
            if worst.is_none_or(|(p, _)| plan.pivot < p) {
                worst = Some((plan.pivot, gi));
            }
            // Velocities.
            for (r, &gr) in plan.rows.iter().enumerate() {
                plan.rhs[r] /= s.row_scale[gr];
            }
            plan.lu.solve(&mut plan.rhs);
            for (gb, &b) in bodies.iter().enumerate() {
                s.qd[3 * b] = plan.rhs[3 * gb] * l;
                s.qd[3 * b + 1] = plan.rhs[3 * gb + 1] * l;
                s.qd[3 * b + 2] = plan.rhs[3 * gb + 2];
            }
            // Accelerations: Φq,group·q̈group = γ − Φq,known·q̈known.
            for &(c, r0) in &plan.cons {
                let con = &s.cons[c];
                let rows = con.rows();
                con_gamma(con, &s.poses, &s.qd, &s.laws, &mut plan.gamma[..rows]);
                for m in 0..rows {
                    plan.rhs[r0 + m] = plan.gamma[m] - plan.known_a[r0 + m];
                }
            }
            for (r, &gr) in plan.rows.iter().enumerate() {
                plan.rhs[r] /= s.row_scale[gr];
            }
            plan.lu.solve(&mut plan.rhs);
            for (gb, &b) in bodies.iter().enumerate() {
                s.qdd[3 * b] = plan.rhs[3 * gb] * l;
                s.qdd[3 * b + 1] = plan.rhs[3 * gb + 1] * l;
                s.qdd[3 * b + 2] = plan.rhs[3 * gb + 2];
            }
        }
        self.inner.near = match worst {
            Some((pivot, gi)) if pivot < NEAR_SINGULAR_PIVOT_REL => Some(NearSingular {
                t,
                pivot,
                drivers: self.inner.driver_values(),
                constraints: self.plans[gi].constraint_names(&self.inner),
            }),
            _ => None,
        };
        Ok(())
    }
}

/// A crank's position: its angle from the law, its pin on the known body. Every kind's step has the same
/// signature (the prediction, the branch in `op`, the closure's slack); a failure returns
/// why, for [`cannot_assemble`].
#[inline(always)]
fn driven_angle<F: Frame>(f: &mut F, position: &Position, side: &mut f64, slack: f64) -> Result<(), Why> {
    let Position::DrivenAngle(DrivenAngle { u, pin, reference, sign, law, .. }) = *position else { return Ok(()) };
    let _ = (slack, &side); // not every kind reads both
    let phi = pz(f, reference).phi + sign * f.law(law);
    // One argument reduction for both (the same bits as libm's sin and cos).
    let (sn, cn) = libm::sincos(phi);
    let cs = (cn, sn);
    let r = glob(f, pin.known) - rot(cs, pin.local);
    f.put(u, r, phi, cs);
    Ok(())
}

/// A driven slider's position: along its guide by the law. Every kind's step has the same
/// signature (the prediction, the branch in `op`, the closure's slack); a failure returns
/// why, for [`cannot_assemble`].
#[inline(always)]
fn driven_distance<F: Frame>(f: &mut F, position: &Position, side: &mut f64, slack: f64) -> Result<(), Why> {
    let Position::DrivenDistance { u, slide, sign, law } = *position else { return Ok(()) };
    let _ = (slack, &side); // not every kind reads both
    let (phi, cs, c, w) = slide.line(f);
    f.put(u, c + w * (sign * f.law(law)), phi, cs);
    Ok(())
}

/// An RRR dyad's position: the circles about its two known pivots, the root nearer the
/// joint where b1's predicted angle puts it. Every kind's step has the same
/// signature (the prediction, the branch in `op`, the closure's slack); a failure returns
/// why, for [`cannot_assemble`].
#[inline(always)]
fn rrr<F: Frame>(f: &mut F, position: &Position, side: &mut f64, slack: f64) -> Result<(), Why> {
    let Position::Rrr(Rrr { b1, b2, k1, k3, arm1, arm3, ref form, d2, .. }) = *position else {
        return Ok(());
    };
    let (p1, p3) = (glob(f, k1.known).into(), glob(f, k3.known).into());
    let ch = forms::rrr_chord(form, p1, p3, slack);
    if !ch.ok {
        return Err(Why::Apart { d: (p3 - p1).norm_squared().sqrt(), d1: form.d1, d2 });
    }
    let (d0, d1) = forms::rrr_distances((ch.m, ch.off, ch.h2), p1, predicted_rotation(f, b1), arm1);
    let root = if choose(d0, d1, side) == 0 { 1.0 } else { -1.0 };
    let at = forms::rrr_poses(form, &ch, root, p1, p3, (arm1, arm3), (k1.local, k3.local));
    turn_arm_to(f, b1, at.r1.into(), at.c1, arm1, at.v1);
    turn_arm_to(f, b2, at.r2.into(), at.c2, arm3, at.v3);
    Ok(())
}

/// An RRP dyad's position: the circle about its known pivot and the slider's line, the
/// root nearer b2's predicted origin. Every kind's step has the same
/// signature (the prediction, the branch in `op`, the closure's slack); a failure returns
/// why, for [`cannot_assemble`].
#[inline(always)]
fn rrp<F: Frame>(f: &mut F, position: &Position, side: &mut f64, slack: f64) -> Result<(), Why> {
    let Position::Rrp(Rrp { b1, b2, k1, a2, s3, arm1, d1, d1sq, inv_d1sq, .. }) = *position else { return Ok(()) };
    let p1 = glob(f, k1.known).into();
    let line = s3.line_of(f);
    let reach = forms::rrp_reach(p1, &line, a2, (d1, d1sq), slack);
    if !reach.ok {
        return Err(Why::Reach { d1 });
    }
    // b2's origin is c + s·w and the joint rides with it (b2's rotation is known): the
    // root nearer b2's predicted origin.
    let ((sv0, sv1), (e0, e1)) =
        forms::rrp_distances((reach.b, reach.root), (line.c, line.w), f.predicted_r(b2).into());
    let sv = if choose(e0, e1, side) == 0 { sv0 } else { sv1 };
    let (c1, r1, v1, r2) = forms::rrp_poses(&reach, &line, sv, p1, (arm1, inv_d1sq, k1.local));
    turn_arm_to(f, b1, r1.into(), c1, arm1, v1);
    f.put(b2, r2.into(), line.phi, line.cs);
    Ok(())
}

/// An RPR dyad's position: the guide's normal from the pivots' distance, the root nearer
/// the normal at the guide's predicted angle. Every kind's step has the same
/// signature (the prediction, the branch in `op`, the closure's slack); a failure returns
/// why, for [`cannot_assemble`].
#[inline(always)]
fn rpr<F: Frame>(f: &mut F, position: &Position, side: &mut f64, slack: f64) -> Result<(), Why> {
    let Position::Rpr(Rpr { b1, b2, k1, k3, ref form, .. }) = *position else { return Ok(()) };
    let (p1, p3) = (glob(f, k1.known).into(), glob(f, k3.known).into());
    let (ks, kg) = if form.b1_is_slider { (p1, p3) } else { (p3, p1) };
    let normal = forms::rpr_normal(form, ks, kg, slack);
    if !normal.ok {
        return Err(Why::Passes { c0: form.c0, d: (ks - kg).norm_squared().sqrt() });
    }
    // The two bodies turn together: the root whose guide normal is nearer the normal at
    // the guide's predicted angle.
    let guide = if form.b1_is_slider { b2 } else { b1 };
    let (d0, d1) = forms::rpr_distances(form, (normal.along, normal.across), predicted_rotation(f, guide));
    let root = if choose(d0, d1, side) == 0 { 1.0 } else { -1.0 };
    let (c1, c2) = forms::rpr_rotations(form, &normal, root);
    // Slider and guide turn together: one turn, b1's, continues both angles.
    let (last1, last2) = (f.last(b1), f.last(b2));
    let turn = turn_between((last1.c, last1.s), c1);
    f.put(b1, Vector::from(p1 - lanes::V2::splat(k1.local).rot(c1)), last1.phi + turn, c1);
    f.put(b2, Vector::from(p3 - lanes::V2::splat(k3.local).rot(c2)), last2.phi + turn, c2);
    Ok(())
}

/// A PRP dyad's position: the two sliders' lines intersected (one root). Every kind's step has the same
/// signature (the prediction, the branch in `op`, the closure's slack); a failure returns
/// why, for [`cannot_assemble`].
#[inline(always)]
fn prp<F: Frame>(f: &mut F, position: &Position, side: &mut f64, slack: f64) -> Result<(), Why> {
    let Position::Prp { b1, b2, s1, a1, a2, s3 } = *position else { return Ok(()) };
    let _ = (slack, &side); // not every kind reads both
    let (phi1, cs1, c1, w1) = s1.line(f);
    let (phi2, cs2, c3, w3) = s3.line(f);
    let e = (c3 + rot(cs2, a2)) - (c1 + rot(cs1, a1));
    // s1·w1 − s3·w3 = e.
    let det = cross(w1, -w3);
    if det.abs() <= DEGENERATE_REL {
        return Err(Why::Parallel);
    }
    let sv1 = cross(e, -w3) / det;
    let sv3 = cross(w1, e) / det;
    f.put(b1, c1 + w1 * sv1, phi1, cs1);
    f.put(b2, c3 + w3 * sv3, phi2, cs2);
    Ok(())
}

/// An RPP dyad's position: both bodies turn with the guide's body (one root). Every kind's step has the same
/// signature (the prediction, the branch in `op`, the closure's slack); a failure returns
/// why, for [`cannot_assemble`].
#[inline(always)]
fn rpp<F: Frame>(f: &mut F, position: &Position, side: &mut f64, slack: f64) -> Result<(), Why> {
    let Position::Rpp { b1, b2, k1, mid, s3 } = *position else { return Ok(()) };
    let _ = (slack, &side); // not every kind reads both
    let (phi2, cs2, c, w) = s3.line(f);
    let (phi1, cs1) = if mid.b1_is_slider {
        (phi2 + mid.angle, compose(cs2, mid.turn))
    } else {
        (phi2 - mid.angle, compose(cs2, (mid.turn.0, -mid.turn.1)))
    };
    let p1 = glob(f, k1.known);
    let r1 = p1 - rot(cs1, k1.local);
    f.put(b1, r1, phi1, cs1);
    // n_G·(P − Q1) = 0 with b2's origin c + s·w.
    let (num, den) = if mid.b1_is_slider {
        let n = rot(cs2, mid.n0);
        let p = r1 + rot(cs1, mid.p);
        (n.dot(&(p - c - rot(cs2, mid.q1))), n.dot(&w))
    } else {
        let n = rot(cs1, mid.n0);
        let q1 = r1 + rot(cs1, mid.q1);
        (-n.dot(&(c + rot(cs2, mid.p) - q1)), n.dot(&w))
    };
    if den.abs() <= DEGENERATE_REL {
        return Err(Why::Along);
    }
    f.put(b2, c + w * (num / den), phi2, cs2);
    Ok(())
}

/// The error of a group whose rates do not exist at `t` (a dead point; built out of the
/// step's hot path).
#[cold]
#[inline(never)]
fn singular_group(s: &Solver, plan: &Plan, t: f64) -> LinkageError {
    LinkageError::Singular { t, drivers: s.driver_values(), constraints: plan.constraint_names(s) }
}

/// Why a group's closed form finds no position (the numbers its message shows).
enum Why {
    /// RRR: the circles' centres are `d` apart.
    Apart { d: f64, d1: f64, d2: f64 },
    /// RRP: the circle of radius `d1` misses the line.
    Reach { d1: f64 },
    /// RPR: the line passes `|c0|` from the other pivot, `d` away.
    Passes { c0: f64, d: f64 },
    /// PRP: parallel guides.
    Parallel,
    /// RPP: the line runs along the guide.
    Along,
    /// The triad's own message.
    Triad(String),
}

/// The error of a group that cannot be assembled at `t`: the group, its joint and why
/// (built here, out of the step's hot path).
#[cold]
#[inline(never)]
fn cannot_assemble(s: &Solver, plan: &Plan, t: f64, why: Why) -> LinkageError {
    let joints = &plan.group.joints;
    let name = |slot: usize| s.mech.joints[joints[slot]].name.as_str();
    let (joint, why) = match why {
        Why::Apart { d, d1, d2 } => (
            1,
            format!(
                "the circles about `{}` and `{}` do not meet: centres {:.6} apart, radii {:.6} and {:.6}",
                name(0),
                name(2),
                d,
                d1,
                d2
            ),
        ),
        Why::Reach { d1 } => {
            (1, format!("the circle of radius {:.6} about `{}` does not reach the line of `{}`", d1, name(0), name(2)))
        }
        Why::Passes { c0, d } => (
            1,
            format!(
                "the line of `{}` passes {:.6} from the pivot of the other body, which is {:.6} away",
                name(1),
                c0.abs(),
                d
            ),
        ),
        Why::Parallel => (1, format!("the guides of `{}` and `{}` are parallel", name(0), name(2))),
        Why::Along => (1, format!("the line of `{}` runs along the guide of `{}`", name(1), name(2))),
        Why::Triad(why) => (3, why),
    };
    LinkageError::GroupCannotAssemble {
        group: plan.description.clone(),
        joint: name(joint).to_string(),
        t,
        why: format!("{}: {why}", s.driver_values()),
    }
}

/// Body `b`'s entries (x, y, φ or their rates) in a vector laid out as q: one bounds check
/// for the three.
#[inline(always)]
fn coords(v: &[f64], b: usize) -> [f64; 3] {
    let w = &v[3 * b..3 * b + 3];
    [w[0], w[1], w[2]]
}

/// A [`RateFrame`] read as [`rates::Motions`] on `f64` (a step's bodies).
struct Step<'a, F>(&'a F);

impl<F: RateFrame> rates::Motions<f64> for Step<'_, F> {
    #[inline(always)]
    fn pose(&self, b: usize) -> PoseOf<f64> {
        PoseOf::from(self.0.pose(b))
    }
    #[inline(always)]
    fn rates(&self, b: usize) -> rates::RatesOf<f64> {
        let Rates { qd: [vx, vy, w], qdd: [ax, ay, e] } = self.0.rates(b);
        rates::RatesOf { v: lanes::V2::new(vx, vy), w, a: lanes::V2::new(ax, ay), e }
    }
}

/// Writes body `b`'s rates.
#[inline(always)]
fn put_rates<F: RateFrame>(fr: &mut F, b: usize, r: rates::RatesOf<f64>) {
    fr.put_rates(b, Rates { qd: [r.v.x, r.v.y, r.w], qdd: [r.a.x, r.a.y, r.e] });
}

/// Writes a dyad's bodies' rates; its conditioning ρ.
#[inline(always)]
fn put_dyad<F: RateFrame>(
    fr: &mut F,
    (b1, b2): (usize, usize),
    ([r1, r2], rho): ([rates::RatesOf<f64>; 2], f64),
) -> f64 {
    put_rates(fr, b1, r1);
    put_rates(fr, b2, r2);
    rho
}

/// Velocities and accelerations of a group from its differentiated closures (a 2×2 solve
/// for a dyad), for the kinds that have them; `None` for the others (the group's block
/// of Φq is solved instead). Returns ρ, the conditioning of the 2×2 (1 for a driven body).
#[inline(always)]
fn closed_rates<F: RateFrame>(fr: &mut F, position: &Position) -> Option<f64> {
    match *position {
        Position::DrivenAngle(_) => driven_angle_rates(fr, position),
        Position::Rrr(_) => rrr_rates(fr, position),
        Position::DrivenDistance { .. } => driven_distance_rates(fr, position),
        Position::Rrp(_) => rrp_rates(fr, position),
        Position::Prp { .. } => prp_rates(fr, position),
        Position::Rpp { .. } => rpp_rates(fr, position),
        Position::Rpr(_) => rpr_rates(fr, position),
        _ => None,
    }
}

/// A crank's rates: its ω, ε from the law's, its pin's velocity and acceleration. Returns 1
/// (no 2×2 to condition); `None` for another kind.
#[inline(always)]
fn driven_angle_rates<F: RateFrame>(fr: &mut F, position: &Position) -> Option<f64> {
    let Position::DrivenAngle(c) = position else { return None };
    let (_, d1, d2) = fr.jet(c.law);
    let r = rates::crank(c, &Step(&*fr), (d1, d2));
    put_rates(fr, c.u, r);
    Some(1.0)
}

/// An RRR dyad's rates (see [`rates::rrr`]): ρ, the 2×2's conditioning; `None` for another
/// kind.
#[inline(always)]
fn rrr_rates<F: RateFrame>(fr: &mut F, position: &Position) -> Option<f64> {
    let Position::Rrr(c) = position else { return None };
    let r = rates::rrr(c, &Step(&*fr));
    Some(put_dyad(fr, (c.b1, c.b2), r))
}

/// A driven slider's rates: its sliding speed and acceleration from the law's. Returns 1 (no
/// 2×2 to condition); `None` for another kind.
#[inline(always)]
fn driven_distance_rates<F: RateFrame>(fr: &mut F, position: &Position) -> Option<f64> {
    let Position::DrivenDistance { u, slide, law, .. } = *position else { return None };
    let (_, d1, d2) = fr.jet(law);
    let r = rates::slider(&Step(&*fr), &slide, u, (d1, d2));
    put_rates(fr, u, r);
    Some(1.0)
}

/// An RRP dyad's rates (see [`rates::rrp`]): ρ, the 2×2's conditioning; `None` for another
/// kind.
#[inline(always)]
fn rrp_rates<F: RateFrame>(fr: &mut F, position: &Position) -> Option<f64> {
    let Position::Rrp(c) = position else { return None };
    let r = rates::rrp(c, &Step(&*fr));
    Some(put_dyad(fr, (c.b1, c.b2), r))
}

/// A PRP dyad's rates (see [`rates::prp`]): ρ, the 2×2's conditioning; `None` for another
/// kind.
#[inline(always)]
fn prp_rates<F: RateFrame>(fr: &mut F, position: &Position) -> Option<f64> {
    let Position::Prp { b1, b2, a1, s1, s3, .. } = *position else { return None };
    let r = rates::prp(&Step(&*fr), (b1, b2), a1, (&s1, &s3));
    Some(put_dyad(fr, (b1, b2), r))
}

/// An RPP dyad's rates (see [`rates::rpp`]): ρ, the 2×2's conditioning; `None` for another
/// kind.
#[inline(always)]
fn rpp_rates<F: RateFrame>(fr: &mut F, position: &Position) -> Option<f64> {
    let Position::Rpp { b1, b2, k1, mid, s3 } = *position else { return None };
    let r = rates::rpp(&Step(&*fr), (b1, b2), k1, &mid, &s3);
    Some(put_dyad(fr, (b1, b2), r))
}

/// An RPR dyad's rates (see [`rates::rpr`]): ρ, the 2×2's conditioning; `None` for another
/// kind.
#[inline(always)]
fn rpr_rates<F: RateFrame>(fr: &mut F, position: &Position) -> Option<f64> {
    let Position::Rpr(c) = position else { return None };
    let r = rates::rpr(c, &Step(&*fr));
    Some(put_dyad(fr, (c.b1, c.b2), r))
}

/// Which of a dyad's two roots (first: the `+` branch of its formula, second: the `−`)
/// continues the motion, from their squared distances `d0`, `d1` to the prediction: the
/// nearer when it is clearly the nearer (under 1/16 of the other), else the branch taken at
/// the last step (`side`: +1 or −1, 0 before the first), which a continuous motion keeps
/// between dead points — so that a time step too coarse for the prediction keeps the mode.
#[inline(always)]
fn choose(d0: f64, d1: f64, side: &mut f64) -> usize {
    let k = if d0 <= d1 / 16.0 {
        0
    } else if d1 <= d0 / 16.0 {
        1
    } else if *side > 0.0 {
        0
    } else if *side < 0.0 {
        1
    } else {
        usize::from(d1 < d0)
    };
    *side = if k == 0 { 1.0 } else { -1.0 };
    k
}

/// Writes body `b` at origin `r` and rotation `cs`, its angle continued from the last step
/// (still in its cached pose) by this step's turn: the turn from where its `arm` (body
/// coordinates) pointed to the global direction `v` it points now (`cs` takes `arm` along
/// `v`). Read off `v` itself, the angle waits on fewer dependent operations than through `cs`.
#[inline(always)]
fn turn_arm_to<F: Frame>(f: &mut F, b: usize, r: Vector, cs: (f64, f64), arm: Vector, v: lanes::V2<f64>) {
    let last = f.last(b);
    let (c, s) = forms::arm_turn((last.c, last.s), arm, v);
    f.put(b, r, last.phi + forms::turn_angle(c, s), cs);
}

/// Newton–Raphson on one group's coordinates from the predicted q (the known bodies fixed).
fn newton(s: &mut Solver, plan: &mut Plan, work: &mut [f64], t: f64) -> Result<(), LinkageError> {
    let k = plan.k;
    let l = s.mech.length_scale;
    let (a, rest) = work.split_at_mut(k * k);
    let (phi, _) = rest.split_at_mut(k);
    let refresh = |s: &mut Solver, bodies: &[usize]| {
        for &b in bodies {
            let (sn, cs) = libm::sincos(s.q[3 * b + 2]);
            s.poses[b] = Pose { r: Vector::new(s.q[3 * b], s.q[3 * b + 1]), phi: s.q[3 * b + 2], c: cs, s: sn };
        }
    };
    refresh(s, &plan.group.bodies);
    let mut iterations = 0;
    loop {
        let mut res: f64 = 0.0;
        let mut worst = 0;
        for &(c, r0) in &plan.cons {
            let con = &s.cons[c];
            con_residual(con, &s.poses, &s.laws, &mut phi[r0..r0 + con.rows()]);
        }
        for (r, &gr) in plan.rows.iter().enumerate() {
            let v = (phi[r] / s.row_scale[gr]).abs();
            if v > res || v.is_nan() {
                res = v;
                worst = gr;
            }
        }
        if res <= s.newton_tol {
            break;
        }
        if iterations >= MAX_NEWTON_ITERATIONS || !res.is_finite() {
            if res <= crate::geom::tol::RESIDUAL_REL {
                break;
            }
            return Err(LinkageError::NoConvergence {
                t,
                iterations,
                residual: res,
                worst: s.row_names[worst].clone(),
            });
        }
        a.iter_mut().for_each(|v| *v = 0.0);
        let bodies = &plan.group.bodies;
        for &(c, r0) in &plan.cons {
            con_jacobian(&s.cons[c], &s.poses, |row, at, dx, dy, dphi| {
                let Attach::Body(b) = at else { return };
                if let Some(gb) = bodies.iter().position(|&x| x == b) {
                    let r = r0 + row;
                    a[r * k + 3 * gb] += dx;
                    a[r * k + 3 * gb + 1] += dy;
                    a[r * k + 3 * gb + 2] += dphi;
                }
            });
        }
        let norm = equilibrate(a, k, &plan.rows, &s.row_scale, l);
        for (r, &gr) in plan.rows.iter().enumerate() {
            plan.rhs[r] = -phi[r] * (1.0 / s.row_scale[gr]);
        }
        plan.lu.a.copy_from_slice(a);
        if !plan.lu.factor(norm) {
            return Err(LinkageError::Singular {
                t,
                drivers: s.driver_values(),
                constraints: plan.constraint_names(s),
            });
        }
        plan.lu.solve(&mut plan.rhs);
        for (gb, &b) in bodies.iter().enumerate() {
            s.q[3 * b] += plan.rhs[3 * gb] * l;
            s.q[3 * b + 1] += plan.rhs[3 * gb + 1] * l;
            s.q[3 * b + 2] += plan.rhs[3 * gb + 2];
        }
        refresh(s, &plan.group.bodies);
        iterations += 1;
    }
    plan.iterations = iterations;
    Ok(())
}

/// Equilibrates a group's Jacobian block `a` (`k` columns, one row per entry of `rows`) in
/// place as the general solver does — each row divided by its constraint's scale, the x, y
/// columns times the mechanism's length `l` — and returns its ∞-norm.
fn equilibrate(a: &mut [f64], k: usize, rows: &[usize], row_scale: &[f64], l: f64) -> f64 {
    let mut norm: f64 = 0.0;
    for (r, &gr) in rows.iter().enumerate() {
        let ir = 1.0 / row_scale[gr];
        let mut sum = 0.0;
        for c in 0..k {
            let cs = if c % 3 == 2 { 1.0 } else { l };
            a[r * k + c] *= cs * ir;
            sum += a[r * k + c].abs();
        }
        norm = norm.max(sum);
    }
    norm
}

#[cfg(test)]
#[allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the code under test calls"
)]
mod tests {
    use super::super::{Body, Driver, GROUND_POSE, Joint};
    use super::*;
    use crate::geom::Point;
    use crate::solve::expr::Expr;

    fn body(name: &str, at: Point, angle: f64) -> Body {
        Body { name: name.into(), points: vec![], at, angle }
    }

    fn pin(name: &str, a: Attach, la: Vector, b: Attach, lb: Vector) -> Joint {
        Joint {
            name: name.into(),
            kind: JointKind::Revolute { a: Anchor { body: a, local: la }, b: Anchor { body: b, local: lb } },
        }
    }

    /// A slider-crank (crank 1, rod 3, slider on the x axis), its bodies listed slider
    /// first so that the dyad is found as P–R–R and must be read from the other end.
    fn slider_crank() -> Mechanism {
        let (r, l, phi0) = (1.0, 3.0, 0.3_f64);
        let a = Vector::new(r * phi0.cos(), r * phi0.sin());
        let beta = (-(a.y / l)).asin();
        let bx = a.x + l * beta.cos();
        let (g, s, c, rod) = (Attach::Ground, Attach::Body(0), Attach::Body(1), Attach::Body(2));
        Mechanism {
            bodies: vec![
                body("slider", Point::new(bx, 0.0), 0.0),
                body("crank", Point::origin(), phi0),
                body("rod", Point::from(a), beta),
            ],
            joints: vec![
                Joint {
                    name: "guide".into(),
                    kind: JointKind::Prismatic {
                        point: Anchor { body: s, local: Vector::zeros() },
                        q1: Anchor { body: g, local: Vector::new(-1.0, 0.0) },
                        q2: Anchor { body: g, local: Vector::new(1.0, 0.0) },
                        angle: 0.0,
                    },
                },
                pin("B", s, Vector::zeros(), rod, Vector::new(l, 0.0)),
                pin("A", c, Vector::new(r, 0.0), rod, Vector::zeros()),
                pin("O", g, Vector::zeros(), c, Vector::zeros()),
            ],
            drivers: vec![Driver {
                name: "crank".into(),
                target: DriverTarget::JointAngle(3),
                law: Expr::parse("0.3 + 2*t").unwrap(),
            }],
            length_scale: 4.0,
        }
    }

    #[test]
    fn a_ground_anchor_is_placed_as_the_general_formula_places_it() {
        let values = [0.0, -0.0, 1.5, -2.25, 1e-300, -1e300, f64::MIN_POSITIVE, 0.1];
        for x in values {
            for y in values {
                let local = Vector::new(x, y);
                let p = GROUND_POSE;
                let general = p.r + p.rot(local);
                let fast = glob::<[Pose]>(&[], Anchor { body: Attach::Ground, local });
                assert_eq!(
                    (fast.x.to_bits(), fast.y.to_bits()),
                    (general.x.to_bits(), general.y.to_bits()),
                    "{x}, {y}"
                );
            }
        }
    }

    #[test]
    fn a_cranks_sincos_is_libms_sin_and_cos_bit_for_bit() {
        // The driven crank takes both from one argument reduction; results stay the bits of
        // the two separate calls (over many turns, both signs, near the reduction's edges).
        for k in -200_000..=200_000 {
            let x = k as f64 * 1.7e-4 + if k % 7 == 0 { std::f64::consts::FRAC_PI_4 } else { 0.0 };
            let (sn, cs) = libm::sincos(x);
            assert_eq!((sn.to_bits(), cs.to_bits()), (libm::sin(x).to_bits(), libm::cos(x).to_bits()), "{x}");
        }
    }

    #[test]
    fn a_predicted_rotation_is_the_rotation_at_the_predicted_angle() {
        let mut s = Solver::new(slider_crank()).unwrap();
        let q = s.q.clone();
        super::super::fill_poses(&q, &mut s.poses);
        for (last, turn) in [(0.3, 0.0), (0.3, 0.01), (-2.0, -0.4), (3.0, 0.5), (1.0, 0.5000001), (1.0, -3.0)] {
            let (sn, cs) = libm::sincos(last);
            s.poses[1] = Pose { r: Vector::zeros(), phi: last, c: cs, s: sn };
            let mut q = s.q.clone();
            q[5] = last + turn;
            let pred = Predictor { how: Extrapolation::Hold, last: &q, qd: &q, qdd: &q };
            let (c, sv) = predicted_rotation(&Live { s: &mut s, pred: &pred }, 1);
            // A turn over 0.5 rad is not trusted: the last rotation.
            let expect = if turn.abs() <= 0.5 { last + turn } else { last };
            assert!((c - libm::cos(expect)).abs() < 2e-6 && (sv - libm::sin(expect)).abs() < 2e-6, "{last} {turn}");
        }
    }

    #[test]
    fn a_steps_turn_is_atan2_of_the_two_rotations_to_an_ulp() {
        for k in 0..20_000 {
            let a = -7.0 + k as f64 * 7e-4;
            for turn in [0.0, 1e-9, -3e-4, 0.01, -0.0455, 0.0624, -0.0626, 0.3, -2.9] {
                let (sa, ca) = libm::sincos(a);
                let (sb, cb) = libm::sincos(a + turn);
                let got = turn_between((ca, sa), (cb, sb));
                let c = cb * ca + sb * sa;
                let s = sb * ca - cb * sa;
                let exact = libm::atan2(s, c);
                assert!((got - exact).abs() <= 2.3e-16 * exact.abs(), "{a} {turn}: {got} vs {exact}");
                // Off vectors of any length (an arm against the arm found): the same angle
                // (to two ulps: scaling rounds c and s once more).
                for len in [1e-3, 0.37, 600.0] {
                    let got = forms::turn_angle(c * len, s * len);
                    assert!((got - exact).abs() <= 4.5e-16 * exact.abs(), "{a} {turn} ×{len}: {got} vs {exact}");
                }
            }
        }
    }

    #[test]
    fn a_prr_dyad_is_read_as_rrp_from_its_other_end() {
        let m = slider_crank();
        let groups = decompose(&m);
        assert_eq!(groups.len(), 2);
        assert_eq!(groups[0].kind, GroupKind::Driven(DrivenKind::Angle));
        assert_eq!(groups[0].bodies, vec![1]);
        assert_eq!(groups[0].joints, vec![3]);
        assert_eq!(groups[1].kind, GroupKind::Dyad(DyadKind::Rrp));
        // b1 = rod (pinned to the crank at A), b2 = slider; joints A, B, guide.
        assert_eq!(groups[1].bodies, vec![2, 0]);
        assert_eq!(groups[1].joints, vec![2, 1, 0]);
        assert_eq!(groups[1].describe(&m), "dyad RRP (rod, slider)");
        assert_eq!(groups[1].route(), Route::ClosedForm);
    }

    #[test]
    fn slider_crank_matches_its_closed_form_and_the_general_solver() {
        let m = slider_crank();
        let times: Vec<f64> = (0..50).map(|k| k as f64 * 0.07).collect();
        let ours = AssurSolver::new(m.clone()).unwrap().run(&times).unwrap();
        let newton = Solver::new(m).unwrap().run(&times).unwrap();
        let slider = Anchor { body: Attach::Body(0), local: Vector::zeros() };
        for (st, nw) in ours.iter().zip(&newton) {
            let phi = 0.3 + 2.0 * st.t;
            let (r, l, w) = (1.0_f64, 3.0_f64, 2.0_f64);
            let root = (l * l - (r * phi.sin()).powi(2)).sqrt();
            let x = r * phi.cos() + root;
            let v = -r * w * phi.sin() - r * r * w * phi.sin() * phi.cos() / root;
            assert!((st.point(slider).x - x).abs() < 1e-13, "t = {}", st.t);
            assert!((st.velocity(slider).x - v).abs() < 1e-12, "t = {}", st.t);
            assert_eq!(st.iterations, 0);
            for k in 0..9 {
                assert!((st.q[k] - nw.q[k]).abs() < 1e-12);
                assert!((st.qd[k] - nw.qd[k]).abs() < 1e-11);
                assert!((st.qdd[k] - nw.qdd[k]).abs() < 1e-10);
            }
        }
    }

    #[test]
    fn a_step_close_to_a_dead_point_is_reported_by_the_sweep_as_by_steps() {
        // r = l (as below), the last time 1e-9 s short of the fold: solved, near-singular
        // (the sweep stops there and steps, as the steps do).
        let mut m = slider_crank();
        if let JointKind::Revolute { b, .. } = &mut m.joints[1].kind {
            b.local = Vector::new(1.0, 0.0);
        }
        m.bodies[2].angle = -0.3;
        m.bodies[0].at = Point::new(2.0 * 0.3_f64.cos(), 0.0);
        let end = (std::f64::consts::FRAC_PI_2 - 0.3) / 2.0 - 1e-9;
        let times: Vec<f64> = (0..=100).map(|k| k as f64 * end / 100.0).collect();
        let swept = AssurSolver::new(m.clone()).unwrap().run(&times).unwrap();
        let mut stepping = AssurSolver::new(m).unwrap();
        for (k, &t) in times.iter().enumerate() {
            stepping.step(t).unwrap();
            let st = stepping.clone().state();
            let near = |s: &State| s.near_singular.as_ref().map(|n| (n.pivot.to_bits(), n.constraints.clone()));
            assert_eq!(near(&swept[k]), near(&st), "step {k}");
            assert!(swept[k].qd.iter().zip(&st.qd).all(|(a, b)| a.to_bits() == b.to_bits()), "step {k}");
        }
        // There the dyad's rates are singular to the closed form: the general solver's step
        // solves it (as a step falls back to it), near-singular.
        assert!(swept[100].near_singular.is_some() && swept[99].near_singular.is_none());
    }

    #[test]
    fn a_dead_point_is_reported_as_singular_by_group() {
        // r = l: the rod folds onto the crank at φ = 90°.
        let mut m = slider_crank();
        if let JointKind::Revolute { b, .. } = &mut m.joints[1].kind {
            b.local = Vector::new(1.0, 0.0);
        }
        m.bodies[2].angle = -0.3;
        m.bodies[0].at = Point::new(2.0 * 0.3_f64.cos(), 0.0);
        let end = std::f64::consts::FRAC_PI_2 - 0.3;
        let times: Vec<f64> = (0..=100).map(|k| k as f64 * end / 2.0 / 100.0).collect();
        let e = AssurSolver::new(m).unwrap().run(&times).unwrap_err();
        match &e {
            LinkageError::Singular { t, constraints, .. } => {
                assert!((t - times[100]).abs() < 1e-12, "{e}");
                assert!(constraints.starts_with("dyad RRP (rod, slider)"), "{e}");
            }
            other => panic!("expected a singularity, got {other}"),
        }
    }
}
