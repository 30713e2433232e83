//! General planar linkage solver (seed 002): bodies with Cartesian coordinates
//! q = (x, y, φ) per body, revolute joints (coincidence constraints), prismatic joints
//! (collinear constraints: a point of one body on a line of another, relative rotation
//! locked) and drivers (a body angle, a relative angle across a revolute joint, or a
//! relative distance along a prismatic joint, each a law f(t) from [`super::expr`]).
//!
//! Method: Newton–Raphson on Φ(q, t) = 0 with the analytic Jacobian Φq of each constraint
//! type and an in-place LU factorisation with partial pivoting; the start of each time
//! step is the previous solution extrapolated with q̇·Δt + ½·q̈·Δt², which keeps the
//! assembly mode and usually converges in one or two iterations. Velocities from
//! Φq·q̇ = −Φt, accelerations from Φq·q̈ = γ, with γ analytic per constraint type and the
//! drivers' f′, f″ exact (second-order jets). The hot loop allocates nothing: matrices and
//! vectors are sized once in [`Solver::new`]. A Jacobian singular at a step (smallest
//! relative pivot ≤ [`SINGULAR_PIVOT_REL`]) is an error; one nearly so (≤
//! [`NEAR_SINGULAR_PIVOT_REL`]) is solved and flagged in [`State::near_singular`].
//!
//! Conventions: lengths in the scene's units, angles in radians from +x,
//! counter-clockwise positive; a body's point with body coordinates s is at
//! r = R + A(φ)·s. The ground has R = 0, φ = 0: its points are global.

pub mod assur;
mod kinematics;
mod kinetostatics;
mod lanes;
mod lu;
pub mod structure;
mod variations;

pub use assur::{AssurSolver, DrivenKind, DyadKind, Group, GroupKind, Motion, Route, decompose};
pub use kinematics::{NearSingular, Sliding, Solver, State};
pub use kinetostatics::{
    Applied, AppliedKind, Dynamics, Forces, Load, LoadAction, LoadValue, MassProperties, Reaction, TIME_WINDOW_EPS_REL,
    TimeWindow, applied_forces,
};
pub use structure::{GroupStructure, Mobility, Structure};

use crate::geom::{Point, Vector, rotate};
use crate::solve::expr::Expr;

/// Relative pivot size under which the Jacobian counts as singular: a pivot `|u_kk|`
/// below `SINGULAR_PIVOT_REL · ‖Φq‖∞` (with the φ columns scaled by the mechanism's size).
pub const SINGULAR_PIVOT_REL: f64 = 1e-10;
/// Newton–Raphson iterations allowed per time step.
pub const MAX_NEWTON_ITERATIONS: usize = 30;
/// Relative residual at which the position iterations stop: well below
/// `geom::tol::RESIDUAL_REL`, which every answer must meet.
pub const NEWTON_TOL: f64 = 1e-14;
/// Iterations allowed to assemble the mechanism from the scene's initial placement.
pub const MAX_ASSEMBLY_ITERATIONS: usize = 200;
/// Relative pivot size under which a solved step counts as near-singular (see
/// [`NearSingular`]): the smallest pivot ρ = `|u_kk|` / ‖J̃‖∞ of the equilibrated Jacobian
/// at the answer, between [`SINGULAR_PIVOT_REL`] and this, ρ standing for 1/κ(J̃).
///
/// Why 1e-5: the velocity and acceleration solves lose about log10(1/ρ) digits each, and
/// near a dead point (a fold: the position moves as the square root of a disturbance,
/// velocities grow as 1/ρ, accelerations as 1/ρ³) a relative disturbance η of the data —
/// at best [`NEWTON_TOL`] = 1e-14, the accuracy of the position itself — changes them by
/// about η/ρ² relative. At ρ = 1e-5 that is 1e-4: fewer digits than the outputs print,
/// and values set by where the roundoff of t put the step rather than by the mechanism.
/// Measured on the rocker-driven Chebyshev four-bar (tests/stability_linkage.rs):
/// ρ ≈ 0.36·√δθ at a rocker angle δθ rad before its extreme, 1.2e-7 on the extreme
/// itself; the bundled templates stay above 2e-2.
pub const NEAR_SINGULAR_PIVOT_REL: f64 = 1e-5;

/// Which body a point or line belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Attach {
    /// The fixed frame.
    Ground,
    /// A moving body, by index into [`Mechanism::bodies`].
    Body(usize),
}

/// A moving body.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    /// Name (unique, not `ground`).
    pub name: String,
    /// Named points in body coordinates, in the order the body's outline joins them.
    pub points: Vec<(String, Vector)>,
    /// Initial placement (a guess the solver assembles from): origin of the body frame.
    pub at: Point,
    /// Initial placement: angle of the body frame, radians.
    pub angle: f64,
}

/// A point fixed in a body (or in the ground).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Anchor {
    /// The body.
    pub body: Attach,
    /// Body coordinates (global for the ground).
    pub local: Vector,
}

/// A joint between two bodies.
#[derive(Debug, Clone, PartialEq)]
pub enum JointKind {
    /// The points coincide (2 equations).
    Revolute {
        /// Point of the first body.
        a: Anchor,
        /// Point of the second body.
        b: Anchor,
    },
    /// `point` (on the slider body) stays on the line `q1 → q2` of the guide body, and
    /// φ_slider − φ_guide = `angle` (2 equations: the seed's collinear constraint).
    Prismatic {
        /// The sliding point.
        point: Anchor,
        /// First point of the guide line (its origin for distance drivers).
        q1: Anchor,
        /// Second point of the guide line (q1 → q2 is the positive direction), same body as q1.
        q2: Anchor,
        /// Locked relative rotation φ_slider − φ_guide, radians.
        angle: f64,
    },
}

/// A named joint.
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    /// Name for messages and drivers.
    pub name: String,
    /// The constraint.
    pub kind: JointKind,
}

/// What a driver prescribes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DriverTarget {
    /// φ of a body = f(t), radians.
    BodyAngle(usize),
    /// φ_b − φ_a across a revolute joint (index into [`Mechanism::joints`]) = f(t), radians.
    JointAngle(usize),
    /// Distance of the slider point from q1 along q1 → q2 of a prismatic joint = f(t).
    JointDistance(usize),
}

/// A driver: a coordinate prescribed as a function of time.
#[derive(Debug, Clone, PartialEq)]
pub struct Driver {
    /// Name for messages.
    pub name: String,
    /// What it drives.
    pub target: DriverTarget,
    /// The law f(t) (radians or length units).
    pub law: Expr,
}

/// The mechanism as the solver sees it (built from a checked scene).
#[derive(Debug, Clone, PartialEq)]
pub struct Mechanism {
    /// Moving bodies.
    pub bodies: Vec<Body>,
    /// Joints.
    pub joints: Vec<Joint>,
    /// Drivers.
    pub drivers: Vec<Driver>,
    /// Characteristic length (the mechanism's size): residuals of length equations are
    /// divided by it.
    pub length_scale: f64,
}

impl Mechanism {
    /// The direction (unit, global) along which `body` translates when a prismatic joint
    /// ties it to the ground (either side: its point on a ground line, or its line over a
    /// ground point), with the joint's index; `None` for any other body. The direction is
    /// the guide line's q1 → q2 as placed in the ground (for a line carried by the body,
    /// turned by the body's locked angle −`angle`).
    pub fn ground_guide(&self, body: usize) -> Option<(usize, Vector)> {
        self.joints.iter().enumerate().find_map(|(k, j)| match j.kind {
            JointKind::Prismatic { point, q1, q2, angle } => {
                let line = q2.local - q1.local;
                let dir = if point.body == Attach::Body(body) && q1.body == Attach::Ground {
                    line
                } else if q1.body == Attach::Body(body) && point.body == Attach::Ground {
                    rotate(line, -angle)
                } else {
                    return None;
                };
                let n = dir.norm();
                (n > 0.0).then(|| (k, dir / n))
            }
            JointKind::Revolute { .. } => None,
        })
    }

    /// The single angular driver (a body angle or a revolute joint's relative angle) and
    /// the body it turns (the body, or the joint's second body; its first when the second
    /// is the ground); `None` unless the mechanism has exactly one driver and it is angular.
    pub fn angular_driver(&self) -> Option<(&Driver, Attach)> {
        let [d] = self.drivers.as_slice() else { return None };
        match d.target {
            DriverTarget::BodyAngle(i) => Some((d, Attach::Body(i))),
            DriverTarget::JointAngle(j) => match self.joints.get(j)?.kind {
                JointKind::Revolute { a, b } => Some((d, if b.body == Attach::Ground { a.body } else { b.body })),
                JointKind::Prismatic { .. } => None,
            },
            DriverTarget::JointDistance(_) => None,
        }
    }
}

/// Why a linkage cannot be solved.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LinkageError {
    /// Degrees of freedom and drivers don't match (counted before solving).
    /// Example: a crank-rocker with no driver.
    #[error(
        "the mechanism has {} (3 × {bodies} moving bodies − {equations} joint equations) but {}: {hint}",
        crate::text::counted(*dof, "degree of freedom", "degrees of freedom"),
        crate::text::counted(*drivers as i64, "driver", "drivers")
    )]
    DofMismatch {
        /// Moving bodies.
        bodies: usize,
        /// Joint equations (2 per revolute or prismatic joint).
        equations: usize,
        /// 3·bodies − equations.
        dof: i64,
        /// Drivers given.
        drivers: usize,
        /// What to do.
        hint: String,
    },
    /// The start cannot be assembled. Example: a coupler too short to reach the rocker.
    #[error(
        "cannot assemble the mechanism at t = {t} s from the initial placement: the constraints cannot all be met \
         (smallest residual {residual:.3e} relative, largest in {worst}); check the lengths and the initial placement"
    )]
    CannotAssemble {
        /// Time.
        t: f64,
        /// Relative residual reached.
        residual: f64,
        /// The constraint with the largest residual.
        worst: String,
    },
    /// The Jacobian turned singular (a dead point, a change of assembly mode, redundant
    /// constraints). Example: a crank-rocker whose crank is driven through a dead point.
    #[error(
        "the constraint Jacobian is singular at t = {t} s ({drivers}): a dead point or redundant constraints; \
         involved: {constraints}"
    )]
    Singular {
        /// Time.
        t: f64,
        /// The drivers' values there (the position), e.g. "driver `O1` = 90°".
        drivers: String,
        /// The constraints that take part (from the left singular vector), comma-separated.
        constraints: String,
    },
    /// Newton–Raphson did not converge.
    #[error(
        "Newton–Raphson did not converge at t = {t} s after {iterations} iterations (residual {residual:.3e} relative, largest in {worst}): the mechanism cannot be assembled there (a dead point just passed), or the time step is too large for the motion (try more time steps)"
    )]
    NoConvergence {
        /// Time.
        t: f64,
        /// Iterations done.
        iterations: usize,
        /// Relative residual reached.
        residual: f64,
        /// The constraint with the largest residual.
        worst: String,
    },
    /// A driver law is not finite (outside a function's domain).
    #[error("driver `{driver}`: its law `{law}` is not finite at t = {t} s (value {value}, f' {d1}, f'' {d2})")]
    DriverNotFinite {
        /// Driver name.
        driver: String,
        /// The law's text.
        law: String,
        /// Time.
        t: f64,
        /// f(t).
        value: f64,
        /// f'(t).
        d1: f64,
        /// f''(t).
        d2: f64,
    },
    /// The model given to the solver is inconsistent (a bug in the caller: checked scenes
    /// never produce it). Example: an angle driver on a prismatic joint.
    #[error("invalid linkage model: {what}")]
    InvalidModel {
        /// What is inconsistent.
        what: String,
    },
    /// A load's expression is not finite at a sample (outside a function's domain).
    /// Example: `force = ["50/(t - 0.5)", 0]` at t = 0.5 s.
    #[error("load `{load}`: its {what} `{expr}` is not finite at t = {t} s (value {value})")]
    LoadNotFinite {
        /// Load name.
        load: String,
        /// Which value: `force x`, `force y` or `torque`.
        what: &'static str,
        /// The expression's text.
        expr: String,
        /// Time.
        t: f64,
        /// Its value there.
        value: f64,
    },
    /// The reactions came out non-finite (loads or speeds beyond f64 range, or a position
    /// too close to a dead point for the multipliers).
    #[error("the reactions are not finite at t = {t} s: {what}")]
    ForcesNotFinite {
        /// Time.
        t: f64,
        /// Which reaction or driver force.
        what: String,
    },
    /// A group of the Assur decomposition (see [`assur`]) cannot be assembled at a
    /// position: its closed form has no real root there. Example: a crank-rocker whose
    /// crank is driven past the angle where the coupler and the rocker can still meet.
    #[error("the {group} cannot be assembled at t = {t} s: joint `{joint}` cannot close ({why})")]
    GroupCannotAssemble {
        /// The group, e.g. "dyad RRR (coupler, rocker)".
        group: String,
        /// The joint whose closure fails, e.g. `B`.
        joint: String,
        /// Time, s.
        t: f64,
        /// The drivers' values and what does not meet, e.g. "driver `crank` = 117.6000°: the
        /// circles about `A` and `C` do not meet: centres 0.21 apart, radii 0.1 and 0.1".
        why: String,
    },
    /// A drag request does not converge.
    #[error("drag {what}")]
    Drag {
        /// What went wrong.
        what: String,
    },
}

/// Coordinates of one body (ground: zeros), read from q.
#[derive(Debug, Clone, Copy)]
pub(super) struct Pose {
    pub(super) r: Vector,
    pub(super) phi: f64,
    pub(super) c: f64,
    pub(super) s: f64,
}

pub(super) fn col(a: Attach) -> Option<usize> {
    match a {
        Attach::Ground => None,
        Attach::Body(i) => Some(3 * i),
    }
}

pub(super) fn pose(q: &[f64], a: Attach) -> Pose {
    match col(a) {
        None => Pose { r: Vector::zeros(), phi: 0.0, c: 1.0, s: 0.0 },
        Some(k) => {
            let (s, c) = libm::sincos(q[k + 2]);
            Pose { r: Vector::new(q[k], q[k + 1]), phi: q[k + 2], c, s }
        }
    }
}

/// Poses of every moving body at `q` (one sin/cos each), into `out`.
pub(super) fn fill_poses(q: &[f64], out: &mut Vec<Pose>) {
    out.clear();
    for k in (0..q.len()).step_by(3) {
        out.push(pose(q, Attach::Body(k / 3)));
    }
}

pub(super) const GROUND_POSE: Pose = Pose { r: Vector::new(0.0, 0.0), phi: 0.0, c: 1.0, s: 0.0 };

/// The cached pose of `a`.
#[inline(always)]
pub(super) fn pz<P: Poses + ?Sized>(poses: &P, a: Attach) -> Pose {
    match a {
        Attach::Ground => GROUND_POSE,
        Attach::Body(i) => poses.pose(i),
    }
}

/// Where the bodies' cached poses are read from: a slice of them, or one step of the
/// Assur route's sweep over many steps.
pub(super) trait Poses {
    /// Body `b`'s pose.
    fn pose(&self, b: usize) -> Pose;
}

impl Poses for [Pose] {
    #[inline(always)]
    fn pose(&self, b: usize) -> Pose {
        self[b]
    }
}

impl Poses for Vec<Pose> {
    #[inline(always)]
    fn pose(&self, b: usize) -> Pose {
        self[b]
    }
}

impl Pose {
    /// A(φ)·v.
    pub(super) fn rot(&self, v: Vector) -> Vector {
        Vector::new(self.c * v.x - self.s * v.y, self.s * v.x + self.c * v.y)
    }
}

/// Velocity triple of a body (zeros for the ground).
pub(super) fn rate(qd: &[f64], a: Attach) -> (Vector, f64) {
    match col(a) {
        None => (Vector::zeros(), 0.0),
        Some(k) => (Vector::new(qd[k], qd[k + 1]), qd[k + 2]),
    }
}

/// The global position of a body point from coordinates `q` (helper for figures).
pub fn place(q: &[f64], body: Attach, local: Vector) -> Point {
    let p = pose(q, body);
    Point::from(p.r + rotate(local, p.phi))
}
