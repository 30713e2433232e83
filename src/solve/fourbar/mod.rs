//! The four-bar of seed 003 and its reference \[8\]: crank O1A, coupler A–B–M (one rigid
//! ternary link), rocker BC. Closed-form RRR dyad for positions, analytic velocities and
//! accelerations, kineto-statics, and the motion over a sweep of crank angles.
//!
//! Sign conventions: angles from +x, counter-clockwise positive; phi2 = direction A→B,
//! phi3 = direction C→B; omega and eps counter-clockwise positive (rad/s, rad/s²).
//! The crank turns at a constant omega1 (eps1 = 0).
//!
//! Methods (docs/fourbar-solver.md has the derivations):
//! - [`kinematics`](mod@kinematics): position: B = circle(A, l_ab) ∩ circle(C, l_bc) on the side
//!   of the directed line A→C named by the assembly mode ([`Geometry::branch`]);
//!   velocity: v_B = v_A + ω2 × (B−A) = ω3 × (B−C), two scalar equations solved by
//!   Cramer's rule with the determinant D = (B−A) × (B−C) = l_ab·l_bc·sin(transmission);
//!   acceleration: a_A + a_BA^n + a_BA^t = a_BC^n + a_BC^t, same determinant;
//!   D = 0 (A, B, C collinear: a dead point) is the named error [`FourbarError::Singular`];
//! - [`kinetostatics`](mod@kinetostatics): inertia torsors, reactions and balancing moment (the seed's route,
//!   and a Newton–Euler check);
//! - [`motion`](mod@motion): [`solve_motion`], the sweep of crank angles: gaps, dead points, branch
//!   continuity.
//!
//! This file holds what all three share (the geometry, its limits, the error); each
//! submodule imports from here and from the ones before it (kinematics ← kinetostatics ←
//! motion), never back. Everything public is re-exported here.

pub mod centres;
pub mod joukowski;
pub mod kinematics;
pub mod kinetostatics;
pub mod motion;
pub mod transmission;

pub use kinematics::{Kinematics, Position, Prepared, kinematics, kinematics_eps, position};
pub use kinetostatics::{
    CrankRange, Dynamics, ExternalForce, ForcePoint, Forces, Link, LinkLoad, LinkMass, Loads, Reactions, forces,
    forces_newton_euler, loads,
};
pub use motion::{
    DeadPoint, DeadPointKind, Gap, GapReason, MAX_POSITIONS, Motion, MotionSpec, Outputs, Sweep, dead_points,
    solve_motion,
};

use crate::geom::{self, Point, Side};

/// `|sin(transmission angle)|` at or below which the dyad counts as singular (A, B, C
/// collinear): velocities would exceed ~10¹⁰ times their usual size.
pub const SINGULAR_SIN: f64 = 1e-10;
/// Tolerance on the cosine of the law of cosines (triangle O1AC) under which a limit
/// angle counts as a touch (the crank only grazes the assembly limit, no gap opens).
pub const TOUCH_COS: f64 = 1e-12;
/// Tolerance (degrees) of the sweep grid: `to_deg` is included when the grid lands within
/// this of it; a limit or dead-point angle within this of a range end counts as inside.
pub const ANGLE_EPS_DEG: f64 = 1e-9;

/// Why a four-bar cannot be solved.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FourbarError {
    /// The circles (A, l_ab) and (C, l_bc) do not meet: |AC| > l_ab + l_bc
    /// ([`Reach::TooFar`]) or |AC| < |l_ab − l_bc| ([`Reach::TooClose`]).
    #[error(
        "the four-bar cannot be assembled at phi1 = {phi1_deg}°: |AC| = {ac} is {} (the coupler AB and rocker BC reach {reach_min}..{reach_max})",
        reach.describe()
    )]
    Unassemblable {
        /// Crank angle, degrees.
        phi1_deg: f64,
        /// Distance A–C.
        ac: f64,
        /// Which limit is exceeded.
        reach: Reach,
        /// |l_ab − l_bc|.
        reach_min: f64,
        /// l_ab + l_bc.
        reach_max: f64,
    },
    /// A coincides with C and l_ab = l_bc: B can be anywhere on a circle.
    #[error("the four-bar is undetermined at phi1 = {phi1_deg}°: A coincides with C and l_ab = l_bc")]
    Coincident {
        /// Crank angle, degrees.
        phi1_deg: f64,
    },
    /// A, B, C collinear (transmission angle 0° or 180°): the dyad's velocity equations
    /// are singular, velocities and reactions unbounded.
    #[error(
        "the dyad ABC is singular at phi1 = {phi1_deg}° (transmission angle {transmission_deg}°, A, B, C collinear): velocities and reactions are unbounded"
    )]
    Singular {
        /// Crank angle, degrees.
        phi1_deg: f64,
        /// Transmission angle, degrees (≈ 0 or 180).
        transmission_deg: f64,
    },
    /// A computed quantity overflowed or is not a number: the scene's magnitudes are beyond
    /// what double precision carries through the equations (e.g. a length of 1e200, whose
    /// square overflows, or omega1 = 1e200).
    #[error(
        "the {quantity} at phi1 = {phi1_deg}° are not finite numbers: the scene's lengths, omega1, masses or forces are too large (or too small) for double precision"
    )]
    NonFinite {
        /// Crank angle, degrees.
        phi1_deg: f64,
        /// What overflowed: "positions", "velocities and accelerations" or "reactions".
        quantity: &'static str,
    },
    /// Not one crank angle of the sweep gives an assembled linkage.
    #[error("the four-bar cannot be assembled at any crank angle of phi1_deg = {from_deg}..{to_deg}")]
    NeverAssembled {
        /// Sweep start, degrees.
        from_deg: f64,
        /// Sweep end, degrees.
        to_deg: f64,
    },
}

/// Which assembly limit a crank angle violates.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Reach {
    /// |AC| > l_ab + l_bc: the dyad cannot stretch that far (transmission 180° at the limit).
    TooFar,
    /// |AC| < |l_ab − l_bc|: the dyad cannot fold that short (transmission 0° at the limit).
    TooClose,
}

impl Reach {
    fn describe(self) -> &'static str {
        match self {
            Reach::TooFar => "longer than l_ab + l_bc",
            Reach::TooClose => "shorter than |l_ab − l_bc|",
        }
    }

    /// Transmission angle at this limit, degrees.
    pub fn transmission_deg(self) -> f64 {
        match self {
            Reach::TooFar => 180.0,
            Reach::TooClose => 0.0,
        }
    }
}

/// Checked geometry of the four-bar (lengths > 0, scene units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Geometry {
    /// Crank pivot O1 (ground).
    pub o1: Point,
    /// Rocker pivot C (ground).
    pub c: Point,
    /// Crank length O1A.
    pub l1: f64,
    /// Coupler side AB.
    pub l_ab: f64,
    /// Coupler side BM.
    pub l_bm: f64,
    /// Angle from ray B→A to ray B→M, counter-clockwise, radians (π: M on AB beyond B).
    pub alpha: f64,
    /// Rocker length BC.
    pub l_bc: f64,
    /// Assembly mode: side of B relative to the directed line A→C, at the first crank angle
    /// of every assemblable run of the sweep (see [`solve_motion`] for how it is kept).
    pub branch: Side,
}

/// Grashof classification of the four links (ground O1C, crank, coupler AB, rocker BC).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Grashof {
    /// s + l < p + q: some link turns fully.
    Grashof,
    /// s + l = p + q (within [`geom::tol::LENGTH_REL`]): change point, the links can fold flat.
    ChangePoint,
    /// s + l > p + q: no link turns fully relative to another.
    NonGrashof,
}

impl Geometry {
    /// Ground length |O1C|.
    pub fn ground(&self) -> f64 {
        (self.c - self.o1).norm()
    }

    /// Grashof class of the linkage (the coupler's side AB counts as the coupler).
    pub fn grashof(&self) -> Grashof {
        let mut l = [self.ground(), self.l1, self.l_ab, self.l_bc];
        l.sort_by(f64::total_cmp);
        let lhs = l[0] + l[3];
        let rhs = l[1] + l[2];
        if (lhs - rhs).abs() <= geom::tol::LENGTH_REL * l[3] {
            Grashof::ChangePoint
        } else if lhs < rhs {
            Grashof::Grashof
        } else {
            Grashof::NonGrashof
        }
    }

    /// Crank angles (radians, in (−π, π] plus the ground direction) where |AC| equals
    /// `l_ab + l_bc` ([`Reach::TooFar`]) or `|l_ab − l_bc|` ([`Reach::TooClose`]): the
    /// dead points of the dyad, by the law of cosines in the triangle O1AC:
    /// `|AC|² = l1² + d² − 2·l1·d·cos(phi1 − θ)`, d = |O1C|, θ = direction of O1→C.
    pub fn limit_angles(&self) -> Vec<LimitAngle> {
        let d_vec = self.c - self.o1;
        let d = d_vec.norm();
        let theta = geom::angle_of(d_vec);
        let mut out = Vec::new();
        if self.l1 * d == 0.0 {
            return out;
        }
        for (reach, len) in [(Reach::TooFar, self.l_ab + self.l_bc), (Reach::TooClose, (self.l_ab - self.l_bc).abs())] {
            let cos = (self.l1 * self.l1 + d * d - len * len) / (2.0 * self.l1 * d);
            if cos.abs() > 1.0 + TOUCH_COS {
                continue;
            }
            if cos >= 1.0 - TOUCH_COS {
                out.push(LimitAngle { phi1: theta, reach, touch: true });
            } else if cos <= -1.0 + TOUCH_COS {
                out.push(LimitAngle { phi1: theta + std::f64::consts::PI, reach, touch: true });
            } else {
                let half = libm::acos(cos);
                out.push(LimitAngle { phi1: theta - half, reach, touch: false });
                out.push(LimitAngle { phi1: theta + half, reach, touch: false });
            }
        }
        out
    }
}

/// A crank angle where A, B, C are collinear, from [`Geometry::limit_angles`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LimitAngle {
    /// Crank angle, radians (any representative; compare modulo 2π).
    pub phi1: f64,
    /// Which assembly limit: [`Reach::TooFar`] (transmission 180°) or
    /// [`Reach::TooClose`] (transmission 0°).
    pub reach: Reach,
    /// The crank only grazes the limit here (|AC| touches it and turns back): no gap.
    pub touch: bool,
}

/// The template's Chebyshev geometry (design.md §3), for the unit tests of this folder.
#[cfg(test)]
pub(crate) fn test_template() -> Geometry {
    Geometry {
        o1: Point::origin(),
        c: Point::new(0.08, 0.0),
        l1: 0.04,
        l_ab: 0.10,
        l_bm: 0.10,
        alpha: std::f64::consts::PI,
        l_bc: 0.10,
        branch: Side::Left,
    }
}
