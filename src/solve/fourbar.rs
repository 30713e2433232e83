//! Four-bar kinematics (seed 003 and its reference [8]): crank O1A, coupler A–B–M (one
//! rigid ternary link), rocker BC; closed-form RRR dyad for positions, analytic
//! velocities and accelerations.
//!
//! Sign conventions: angles from +x, counter-clockwise positive; phi2 = direction A→B,
//! phi3 = direction C→B; omega and eps counter-clockwise positive (rad/s, rad/s²).
//! The crank turns at a constant omega1 (eps1 = 0).
//!
//! Methods (docs/fourbar-solver.md has the derivations):
//! - position: B = circle(A, l_ab) ∩ circle(C, l_bc) on the side of the directed line A→C
//!   named by the assembly mode ([`Geometry::branch`]);
//! - velocity: v_B = v_A + ω2 × (B−A) = ω3 × (B−C), two scalar equations solved by
//!   Cramer's rule with the determinant D = (B−A) × (B−C) = l_ab·l_bc·sin(transmission);
//! - acceleration: a_A + a_BA^n + a_BA^t = a_BC^n + a_BC^t, same determinant;
//! - D = 0 (A, B, C collinear: a dead point) is the named error [`FourbarError::Singular`].

use crate::geom::{self, CircleIntersection, Point, Side, Vector, cross, perp};

use super::kinetostatics::{self, Dynamics, Forces};

/// `|sin(transmission angle)|` at or below which the dyad counts as singular (A, B, C
/// collinear): velocities would exceed ~10¹⁰ times their usual size.
pub const SINGULAR_SIN: f64 = 1e-10;
/// Tolerance on the cosine of the law of cosines (triangle O1AC) under which a limit
/// angle counts as a touch (the crank only grazes the assembly limit, no gap opens).
pub const TOUCH_COS: f64 = 1e-12;
/// Tolerance (degrees) of the sweep grid: `to_deg` is included when the grid lands within
/// this of it; a limit or dead-point angle within this of a range end counts as inside.
pub const ANGLE_EPS_DEG: f64 = 1e-9;
/// Largest number of crank angles a sweep may have (keeps a typo like `step = 1e-9` from
/// exhausting memory).
pub const MAX_POSITIONS: usize = 1_000_000;

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
                let half = cos.acos();
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

/// The crank angles of a motion: `from_deg, from_deg + step_deg, …` up to and including
/// `to_deg` (within [`ANGLE_EPS_DEG`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sweep {
    /// First crank angle, degrees.
    pub from_deg: f64,
    /// Last crank angle (included when the grid lands on it), degrees; ≥ `from_deg`.
    pub to_deg: f64,
    /// Step, degrees, > 0.
    pub step_deg: f64,
}

impl Sweep {
    /// Number of crank angles.
    pub fn count(&self) -> usize {
        let n = ((self.to_deg - self.from_deg) / self.step_deg + ANGLE_EPS_DEG / self.step_deg).floor();
        if n.is_finite() && n >= 0.0 { n as usize + 1 } else { 0 }
    }

    /// The `k`-th crank angle, degrees.
    pub fn angle_deg(&self, k: usize) -> f64 {
        self.from_deg + k as f64 * self.step_deg
    }
}

/// What a scene asks to compute (its `outputs`). Positions are always computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Outputs {
    /// Velocities (poles, velocity polygons).
    pub velocity: bool,
    /// Accelerations (acceleration polygons).
    pub acceleration: bool,
    /// Kineto-statics (needs accelerations; needs `[dynamics]`).
    pub forces: bool,
}

impl Outputs {
    /// Positions, velocities, accelerations and forces.
    pub const ALL: Outputs = Outputs { velocity: true, acceleration: true, forces: true };
    /// Positions only.
    pub const POSITIONS: Outputs = Outputs { velocity: false, acceleration: false, forces: false };

    /// Whether [`Kinematics`] are evaluated: any of velocity, acceleration, forces. (The
    /// velocities and accelerations are evaluated together: a few flops more.)
    pub fn kinematics(&self) -> bool {
        self.velocity || self.acceleration || self.forces
    }
}

/// Everything the motion solver needs: the checked content of a `fourbar` scene.
#[derive(Debug, Clone, PartialEq)]
pub struct MotionSpec {
    /// Link geometry and assembly mode.
    pub geometry: Geometry,
    /// Crank angular velocity, rad/s, counter-clockwise positive, constant.
    pub omega1: f64,
    /// Crank angles.
    pub sweep: Sweep,
    /// What to compute.
    pub outputs: Outputs,
    /// Masses, gravity and external forces (present when `outputs.forces`).
    pub dynamics: Option<Dynamics>,
}

/// Velocities and accelerations at one crank angle (units/s, units/s²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kinematics {
    /// Angular velocity of the coupler (link 2), rad/s, CCW positive.
    pub omega2: f64,
    /// Angular velocity of the rocker (link 3).
    pub omega3: f64,
    /// Angular acceleration of the coupler, rad/s².
    pub eps2: f64,
    /// Angular acceleration of the rocker.
    pub eps3: f64,
    /// Velocity of A.
    pub v_a: Vector,
    /// Velocity of B.
    pub v_b: Vector,
    /// Velocity of M.
    pub v_m: Vector,
    /// Velocity of B relative to A (v_B = v_A + v_BA).
    pub v_ba: Vector,
    /// Acceleration of A.
    pub a_a: Vector,
    /// Acceleration of B.
    pub a_b: Vector,
    /// Acceleration of M.
    pub a_m: Vector,
    /// Normal (centripetal) part of a_BA: −omega2²·(B−A).
    pub a_ba_n: Vector,
    /// Tangential part of a_BA: eps2 × (B−A).
    pub a_ba_t: Vector,
    /// Normal part of a_B about C: −omega3²·(B−C).
    pub a_bc_n: Vector,
    /// Tangential part of a_B about C: eps3 × (B−C).
    pub a_bc_t: Vector,
    /// Acceleration of the crank's centroid G1 (middle of O1A).
    pub a_g1: Vector,
    /// Acceleration of the centroid G21 of bar AB (its middle).
    pub a_g21: Vector,
    /// Acceleration of the centroid G22 of bar BM (its middle).
    pub a_g22: Vector,
    /// Acceleration of the rocker's centroid G3 (middle of BC).
    pub a_g3: Vector,
}

impl Kinematics {
    /// Whether every component is a finite number (one sum: NaN and infinities propagate).
    pub fn is_finite(&self) -> bool {
        let vectors = [
            self.v_a,
            self.v_b,
            self.v_m,
            self.v_ba,
            self.a_a,
            self.a_b,
            self.a_m,
            self.a_ba_n,
            self.a_ba_t,
            self.a_bc_n,
            self.a_bc_t,
            self.a_g1,
            self.a_g21,
            self.a_g22,
            self.a_g3,
        ];
        let sum: f64 =
            vectors.iter().map(|v| v.x + v.y).sum::<f64>() + self.omega2 + self.omega3 + self.eps2 + self.eps3;
        sum.is_finite()
    }
}

/// The four-bar at one crank angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Position {
    /// Crank angle, radians.
    pub phi1: f64,
    /// Crank pin A.
    pub a: Point,
    /// Coupler–rocker joint B.
    pub b: Point,
    /// Coupler point M.
    pub m: Point,
    /// Fixed pivot C (the rocker's ground joint), kept so that the link angles can be
    /// derived from the position alone.
    pub c: Point,
    /// Velocities and accelerations, when the scene asks for them.
    pub kin: Option<Kinematics>,
}

impl Position {
    /// Coupler angle (direction A→B), radians in (−π, π], CCW from +x.
    ///
    /// Link angles are derived on demand rather than stored: the solver's hot path needs
    /// only the joint positions, and two `atan2` calls are most of a position's cost.
    #[inline]
    pub fn phi2(&self) -> f64 {
        let ab = self.b - self.a;
        libm::atan2(ab.y, ab.x)
    }

    /// Rocker angle (direction C→B), radians in (−π, π], CCW from +x.
    #[inline]
    pub fn phi3(&self) -> f64 {
        let cb = self.b - self.c;
        libm::atan2(cb.y, cb.x)
    }

    /// Transmission angle (between BA and BC), radians in [0, π]: the angle between the
    /// directions A→B and C→B, |φ2 − φ3| wrapped into [0, π].
    pub fn transmission(&self) -> f64 {
        // Both angles lie in [−π, π], so one correction by 2π wraps the difference.
        let diff = (self.phi2() - self.phi3()).abs();
        if diff > std::f64::consts::PI { std::f64::consts::TAU - diff } else { diff }
    }

    /// Side of B relative to the directed line A→C (the assembly mode at this position);
    /// `None` when A, B, C are collinear.
    pub fn side(&self, geom: &Geometry) -> Option<Side> {
        let s = cross(geom.c - self.a, self.b - self.a);
        if s > 0.0 {
            Some(Side::Left)
        } else if s < 0.0 {
            Some(Side::Right)
        } else {
            None
        }
    }
}

/// Geometry with the per-mechanism constants precomputed, for the per-angle hot path.
#[derive(Debug, Clone, Copy)]
pub struct Prepared {
    /// The geometry.
    pub geom: Geometry,
    /// −(l_bm/l_ab)·(cos alpha, sin alpha): maps A→B onto B→M.
    bm: (f64, f64),
    /// l_ab² − l_bc².
    r_diff: f64,
    /// l_ab².
    r1_sq: f64,
    /// max(l_ab, l_bc)²: the tangent tolerance's scale (with |AC|², as in `geom::circle_circle`).
    r_max_sq: f64,
}

impl Prepared {
    /// Precomputes `geom`'s constants.
    pub fn new(geom: &Geometry) -> Prepared {
        let (sin_alpha, cos_alpha) = geom.alpha.sin_cos();
        let r1_sq = geom.l_ab * geom.l_ab;
        let r2_sq = geom.l_bc * geom.l_bc;
        let ratio = -geom.l_bm / geom.l_ab;
        Prepared {
            geom: *geom,
            bm: (ratio * cos_alpha, ratio * sin_alpha),
            r_diff: r1_sq - r2_sq,
            r1_sq,
            r_max_sq: r1_sq.max(r2_sq),
        }
    }

    /// Crank pin A and the intersection of the circles (A, l_ab), (C, l_bc): the same
    /// points and the same tangent tolerance as [`geom::circle_circle`], written with one
    /// division and one square root for the hot path.
    #[inline]
    pub fn dyad(&self, phi1: f64) -> Result<(Point, CircleIntersection), FourbarError> {
        let g = &self.geom;
        // libm (the musl/fdlibm port, < 1 ulp) is about twice as fast as the platform's
        // sin/cos/atan2 here; the hot path makes one sincos call per angle (the link angles are
        // derived on demand: [`Position::phi2`]).
        let (s, c) = libm::sincos(phi1);
        let a = Point::new(g.o1.x + g.l1 * c, g.o1.y + g.l1 * s);
        let ac = g.c - a;
        let d2 = ac.norm_squared();
        if d2 == 0.0 || !d2.is_finite() {
            return Err(self.why_not(phi1, a));
        }
        let inv_d2 = 1.0 / d2;
        // Foot of the chord at k·AC from A, k = a/d; half-chord h = √h2, h2 = l_ab² − a².
        let k = 0.5 * (1.0 + self.r_diff * inv_d2);
        let h2 = self.r1_sq - k * k * d2;
        let foot = a + ac * k;
        if h2.abs() <= geom::tol::TANGENT_REL * self.r_max_sq.max(d2) {
            return Ok((a, CircleIntersection::Tangent(foot)));
        }
        if h2 < 0.0 {
            return Err(self.why_not(phi1, a));
        }
        // perp(AC)·h/d: on the left of A→C.
        let off = perp(ac) * (h2 * inv_d2).sqrt();
        Ok((a, CircleIntersection::Two { left: foot + off, right: foot - off }))
    }

    #[cold]
    fn why_not(&self, phi1: f64, a: Point) -> FourbarError {
        let g = &self.geom;
        let ac = (g.c - a).norm();
        if !(a.x.is_finite() && a.y.is_finite() && (ac * ac).is_finite()) {
            // |AC|² overflows: no assembly question can be answered in double precision.
            return FourbarError::NonFinite { phi1_deg: geom::deg(phi1), quantity: "positions" };
        }
        let reach_max = g.l_ab + g.l_bc;
        let reach_min = (g.l_ab - g.l_bc).abs();
        let phi1_deg = geom::deg(phi1);
        if ac > reach_max {
            FourbarError::Unassemblable { phi1_deg, ac, reach: Reach::TooFar, reach_min, reach_max }
        } else if ac < reach_min {
            FourbarError::Unassemblable { phi1_deg, ac, reach: Reach::TooClose, reach_min, reach_max }
        } else {
            // circle_circle refuses only concentric circles inside the reach.
            FourbarError::Coincident { phi1_deg }
        }
    }

    /// The position with A and B known (kinematics not evaluated).
    #[inline]
    pub fn complete(&self, phi1: f64, a: Point, b: Point) -> Position {
        let ab = b - a;
        // B→M is B→A rotated by alpha and scaled by l_bm/l_ab (precomputed in `bm`).
        let m = b + Vector::new(self.bm.0 * ab.x - self.bm.1 * ab.y, self.bm.1 * ab.x + self.bm.0 * ab.y);
        Position { phi1, a, b, m, c: self.geom.c, kin: None }
    }

    /// The position at crank angle `phi1` (radians) with B on `side` of A→C.
    #[inline]
    pub fn position(&self, phi1: f64, side: Side) -> Result<Position, FourbarError> {
        let (a, ix) = self.dyad(phi1)?;
        // `dyad` has refused `None`, so `on` gives a point.
        let b = ix.on(side).unwrap_or(a);
        Ok(self.complete(phi1, a, b))
    }
}

/// The position at crank angle `phi1` (radians) with B on `side` of the directed line A→C
/// (kinematics not evaluated: `kin = None`). Errors when the linkage cannot be assembled.
pub fn position(geom: &Geometry, phi1: f64, side: Side) -> Result<Position, FourbarError> {
    Prepared::new(geom).position(phi1, side)
}

/// Velocities and accelerations at `pos` for the crank turning at the constant `omega1`
/// (rad/s, CCW positive). Errors with [`FourbarError::Singular`] when A, B, C are collinear.
#[inline]
pub fn kinematics(geom: &Geometry, pos: &Position, omega1: f64) -> Result<Kinematics, FourbarError> {
    let r1 = pos.a - geom.o1;
    let r2 = pos.b - pos.a; // A→B
    let r3 = pos.b - geom.c; // C→B
    let det = cross(r2, r3);
    if det.abs() <= SINGULAR_SIN * geom.l_ab * geom.l_bc {
        return Err(singular(pos));
    }
    // v_A + ω2·perp(r2) = ω3·perp(r3)  ⇒  ω2·perp(r2) − ω3·perp(r3) = w, w = −v_A;
    // dot with r3 and r2: ω2·D = w·r3, ω3·D = w·r2 (perp(x)·y = x × y).
    let v_a = perp(r1) * omega1;
    let w = -v_a;
    let omega2 = w.dot(&r3) / det;
    let omega3 = w.dot(&r2) / det;
    let v_ba = perp(r2) * omega2;
    let v_b = v_a + v_ba;
    // a_A + a_BA^n + ε2·perp(r2) = a_BC^n + ε3·perp(r3); same system, right side w.
    let a_a = -r1 * (omega1 * omega1);
    let a_ba_n = -r2 * (omega2 * omega2);
    let a_bc_n = -r3 * (omega3 * omega3);
    let w = a_bc_n - a_a - a_ba_n;
    let eps2 = w.dot(&r3) / det;
    let eps3 = w.dot(&r2) / det;
    let a_ba_t = perp(r2) * eps2;
    let a_bc_t = perp(r3) * eps3;
    let a_b = a_a + a_ba_n + a_ba_t;
    let rm = pos.m - pos.b;
    let v_m = v_b + perp(rm) * omega2;
    let a_m = a_b - rm * (omega2 * omega2) + perp(rm) * eps2;
    Ok(Kinematics {
        omega2,
        omega3,
        eps2,
        eps3,
        v_a,
        v_b,
        v_m,
        v_ba,
        a_a,
        a_b,
        a_m,
        a_ba_n,
        a_ba_t,
        a_bc_n,
        a_bc_t,
        // Rigid bodies: the acceleration field is affine, so a midpoint's acceleration is
        // the mean of the ends' (O1 fixed).
        a_g1: a_a * 0.5,
        a_g21: (a_a + a_b) * 0.5,
        a_g22: (a_b + a_m) * 0.5,
        a_g3: a_b * 0.5,
    })
}

#[cold]
pub(crate) fn singular(pos: &Position) -> FourbarError {
    FourbarError::Singular { phi1_deg: geom::deg(pos.phi1), transmission_deg: geom::deg(pos.transmission()) }
}

/// Why crank angles of the sweep were skipped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum GapReason {
    /// The linkage cannot be assembled (|AC| outside the dyad's reach).
    Unassemblable(Reach),
    /// A, B, C collinear at a grid angle: velocities (and reactions) unbounded.
    Singular,
    /// A coincides with C and l_ab = l_bc: position undetermined.
    Coincident,
}

/// A run of consecutive crank angles of the sweep that were skipped (never drawn).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Gap {
    /// Where the gap begins, degrees: the exact limit angle (law of cosines, see
    /// [`Geometry::limit_angles`]) between the last solved grid angle and the first
    /// skipped one; the first skipped grid angle when the gap starts the sweep or for
    /// [`GapReason::Singular`] and [`GapReason::Coincident`].
    pub from_deg: f64,
    /// Where the gap ends, degrees: the exact limit angle between the last skipped grid
    /// angle and the next solved one (the last skipped grid angle when the gap ends the
    /// sweep). For an unassemblable gap the linkage cannot be assembled on the open
    /// interval (from_deg, to_deg).
    pub to_deg: f64,
    /// First skipped grid angle, degrees.
    pub first_skipped_deg: f64,
    /// Last skipped grid angle, degrees.
    pub last_skipped_deg: f64,
    /// Number of skipped grid angles.
    pub skipped: usize,
    /// Why.
    pub reason: GapReason,
}

impl Gap {
    /// One line for the terminal, naming the angles.
    pub fn describe(&self) -> String {
        let why = match self.reason {
            GapReason::Unassemblable(Reach::TooFar) => "cannot be assembled (|AC| > l_ab + l_bc)",
            GapReason::Unassemblable(Reach::TooClose) => "cannot be assembled (|AC| < |l_ab − l_bc|)",
            GapReason::Singular => "singular dyad (A, B, C collinear: dead point)",
            GapReason::Coincident => "undetermined (A coincides with C, l_ab = l_bc)",
        };
        if self.skipped == 1 && self.from_deg == self.to_deg {
            format!("phi1 = {}°: {why}; position skipped", fmt_deg(self.from_deg))
        } else {
            format!(
                "phi1 in ({}°, {}°): {why}; {} positions skipped ({}° … {}°)",
                fmt_deg(self.from_deg),
                fmt_deg(self.to_deg),
                self.skipped,
                fmt_deg(self.first_skipped_deg),
                fmt_deg(self.last_skipped_deg)
            )
        }
    }
}

fn fmt_deg(d: f64) -> String {
    let r = (d * 1e4).round() / 1e4;
    format!("{r}")
}

/// Kind of dead point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum DeadPointKind {
    /// The end of a range where the linkage cannot be assembled (the crank cannot pass).
    Limit,
    /// |AC| only touches the limit and turns back: the linkage passes through a
    /// flat (change-point) position, where the branch may switch.
    Touch,
}

/// A crank angle of the sweep where the transmission angle is 0° or 180° (A, B, C
/// collinear), solved exactly (law of cosines), not just the nearest grid angle.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct DeadPoint {
    /// Crank angle, degrees, within the sweep.
    pub phi1_deg: f64,
    /// Transmission angle there: 180 (|AC| = l_ab + l_bc) or 0 (|AC| = |l_ab − l_bc|).
    pub transmission_deg: f64,
    /// Limit of an unassemblable range, or a touch.
    pub kind: DeadPointKind,
}

impl DeadPoint {
    /// One line for the terminal.
    pub fn describe(&self) -> String {
        let kind = match self.kind {
            DeadPointKind::Limit => "limit of assembly",
            DeadPointKind::Touch => "flat position (branch may switch)",
        };
        format!(
            "dead point at phi1 = {}°: transmission angle {}° ({kind})",
            fmt_deg(self.phi1_deg),
            self.transmission_deg
        )
    }
}

/// The solved motion over the sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct Motion {
    /// Solved positions in sweep order (skipped angles left out; see `gaps`).
    pub positions: Vec<Position>,
    /// Kineto-statics, one per position (same index) when the scene asks for forces;
    /// empty otherwise.
    pub forces: Vec<Forces>,
    /// Skipped crank angles, in sweep order.
    pub gaps: Vec<Gap>,
    /// Dead points within the sweep, in increasing crank angle.
    pub dead_points: Vec<DeadPoint>,
    /// Grashof class of the linkage.
    pub grashof: Grashof,
}

impl Motion {
    /// Warning lines for the terminal: every gap and every dead point.
    pub fn warnings(&self) -> Vec<String> {
        self.gaps.iter().map(Gap::describe).chain(self.dead_points.iter().map(DeadPoint::describe)).collect()
    }
}

/// Dead points of `geom` within `sweep`, exact, in increasing crank angle.
pub fn dead_points(geom: &Geometry, sweep: &Sweep) -> Vec<DeadPoint> {
    let mut out = Vec::new();
    for l in geom.limit_angles() {
        // Every representative l.phi1 + 2πk within [from, to] (within ANGLE_EPS_DEG).
        let base = geom::deg(l.phi1);
        let first = base + 360.0 * ((sweep.from_deg - ANGLE_EPS_DEG - base) / 360.0).ceil();
        let mut d = first;
        while d <= sweep.to_deg + ANGLE_EPS_DEG {
            out.push(DeadPoint {
                phi1_deg: d,
                transmission_deg: l.reach.transmission_deg(),
                kind: if l.touch { DeadPointKind::Touch } else { DeadPointKind::Limit },
            });
            d += 360.0;
        }
    }
    out.sort_by(|a, b| a.phi1_deg.total_cmp(&b.phi1_deg));
    out
}

/// The representative of `angle_deg` (mod 360) in (lo, hi] (within [`ANGLE_EPS_DEG`]), if any.
fn in_bracket(angle_deg: f64, lo: f64, hi: f64) -> Option<f64> {
    let x = lo + (angle_deg - lo).rem_euclid(360.0);
    if x <= hi + ANGLE_EPS_DEG {
        Some(x)
    } else if x >= lo + 360.0 - ANGLE_EPS_DEG {
        Some(x - 360.0) // equal to lo within the tolerance
    } else {
        None
    }
}

/// The exact limit angle of kind `reach` in (lo, hi], degrees, if any.
fn limit_between(limits: &[LimitAngle], reach: Reach, lo: f64, hi: f64) -> Option<f64> {
    limits.iter().filter(|l| l.reach == reach).find_map(|l| in_bracket(geom::deg(l.phi1), lo, hi))
}

/// Builds gaps from consecutive skipped grid angles.
struct GapBuilder {
    open: Option<Gap>,
    prev_ok_deg: Option<f64>,
    gaps: Vec<Gap>,
}

impl GapBuilder {
    fn skip(&mut self, deg: f64, reason: GapReason, limits: &[LimitAngle]) {
        if let Some(g) = &mut self.open {
            if g.reason == reason && !matches!(reason, GapReason::Singular | GapReason::Coincident) {
                g.last_skipped_deg = deg;
                g.to_deg = deg;
                g.skipped += 1;
                return;
            }
        }
        self.close(None, limits);
        let from_deg = match (reason, self.prev_ok_deg) {
            (GapReason::Unassemblable(r), Some(lo)) => limit_between(limits, r, lo, deg).unwrap_or(deg),
            _ => deg,
        };
        self.open =
            Some(Gap { from_deg, to_deg: deg, first_skipped_deg: deg, last_skipped_deg: deg, skipped: 1, reason });
    }

    fn ok(&mut self, deg: f64, limits: &[LimitAngle]) {
        self.close(Some(deg), limits);
        self.prev_ok_deg = Some(deg);
    }

    /// Closes the open gap; `next_ok` is the solved grid angle after it, if any.
    fn close(&mut self, next_ok: Option<f64>, limits: &[LimitAngle]) {
        if let Some(mut g) = self.open.take() {
            if let (GapReason::Unassemblable(r), Some(hi)) = (g.reason, next_ok) {
                // The end limit lies in [last skipped, next ok): search (last, hi] and
                // accept hi only as a tolerance artefact.
                if let Some(x) = limit_between(limits, r, g.last_skipped_deg, hi) {
                    g.to_deg = x;
                }
            }
            self.gaps.push(g);
        }
    }
}

/// Whether the joints of `p` are finite numbers.
fn position_finite(p: &Position) -> bool {
    [p.a, p.b, p.m].iter().all(|q| q.x.is_finite() && q.y.is_finite())
}

/// Solves the motion over the sweep of `spec`.
///
/// Assembly mode along the motion: at the first angle of each assemblable run (the sweep
/// start, or the first angle after an unassemblable gap) B is put on the side
/// `spec.geometry.branch` of the directed line A→C. Within a run the side is kept: it can
/// only change where A, B, C are collinear. Where a [`DeadPointKind::Touch`] dead point lies
/// between the angle before the previous one and the current one, the solution nearest to
/// the linear extrapolation of B from the two previous positions is taken instead (the
/// smooth continuation through the flat position), and its side is kept from then on.
///
/// Skipped angles (unassemblable, singular when kinematics are asked for, undetermined)
/// are reported in [`Motion::gaps`]; a positions-only scene keeps a singular (flat)
/// position. Kinematics are evaluated only when `spec.outputs.kinematics()`, forces only
/// when `spec.outputs.forces` and `spec.dynamics` is present.
pub fn solve_motion(spec: &MotionSpec) -> Result<Motion, FourbarError> {
    let geom = &spec.geometry;
    let prepared = Prepared::new(geom);
    let n = spec.sweep.count().min(MAX_POSITIONS);
    let limits = geom.limit_angles();
    let touches: Vec<f64> = limits.iter().filter(|l| l.touch).map(|l| geom::deg(l.phi1)).collect();
    let want_kin = spec.outputs.kinematics();
    let dynamics = if spec.outputs.forces { spec.dynamics.as_ref() } else { None };
    let mut positions = Vec::with_capacity(n);
    let mut forces = Vec::with_capacity(if dynamics.is_some() { n } else { 0 });
    let mut gaps = GapBuilder { open: None, prev_ok_deg: None, gaps: Vec::new() };
    // The last two solved (degree, B) of the current run, newest last.
    let mut track: [Option<(f64, Point)>; 2] = [None, None];
    let mut side = geom.branch;
    let mut position_sum = 0.0;
    for k in 0..n {
        let deg = spec.sweep.angle_deg(k);
        let phi1 = geom::rad(deg);
        let (a, ix) = match prepared.dyad(phi1) {
            Ok(x) => x,
            Err(e @ FourbarError::NonFinite { .. }) => return Err(e),
            Err(e) => {
                let reason = match e {
                    FourbarError::Unassemblable { reach, .. } => GapReason::Unassemblable(reach),
                    _ => GapReason::Coincident,
                };
                gaps.skip(deg, reason, &limits);
                if matches!(reason, GapReason::Unassemblable(_)) {
                    track = [None, None];
                    side = geom.branch;
                }
                continue;
            }
        };
        let b = match ix {
            CircleIntersection::Two { left, right } => {
                let (l, r) = (left, right);
                match (track, touches.is_empty()) {
                    (_, true) | ([None, _], false) | ([_, None], false) => ix.on(side).unwrap_or(l),
                    ([Some((d0, b0)), Some((d1, b1))], false) => {
                        if touches.iter().any(|&t| in_bracket(t, d0 - ANGLE_EPS_DEG, deg).is_some()) {
                            let pred = b1 + (b1 - b0) * ((deg - d1) / (d1 - d0));
                            side = if (l - pred).norm() <= (r - pred).norm() { Side::Left } else { Side::Right };
                        }
                        ix.on(side).unwrap_or(l)
                    }
                }
            }
            CircleIntersection::Tangent(p) => p,
            CircleIntersection::None => a, // refused by `dyad`
        };
        track = [track[1], Some((deg, b))];
        let mut pos = prepared.complete(phi1, a, b);
        // Checked once after the loop (a branch here costs the positions-only loop ~20 %).
        position_sum += pos.a.x + pos.a.y + pos.b.x + pos.b.y + pos.m.x + pos.m.y;
        if want_kin {
            match kinematics(geom, &pos, spec.omega1) {
                Ok(kin) if !kin.is_finite() => {
                    let quantity = if position_finite(&pos) { "velocities and accelerations" } else { "positions" };
                    return Err(FourbarError::NonFinite { phi1_deg: deg, quantity });
                }
                Ok(kin) => pos.kin = Some(kin),
                Err(_) => {
                    gaps.skip(deg, GapReason::Singular, &limits);
                    continue;
                }
            }
            if let (Some(dynamics), Some(kin)) = (dynamics, pos.kin.as_ref()) {
                match kinetostatics::forces(geom, &pos, kin, dynamics) {
                    Ok(f) if !f.is_finite() => {
                        return Err(FourbarError::NonFinite { phi1_deg: deg, quantity: "reactions" });
                    }
                    Ok(f) => forces.push(f),
                    Err(_) => {
                        gaps.skip(deg, GapReason::Singular, &limits);
                        continue;
                    }
                }
            }
        }
        gaps.ok(deg, &limits);
        positions.push(pos);
    }
    if !position_sum.is_finite()
        && let Some(p) = positions.iter().find(|p| !position_finite(p))
    {
        return Err(FourbarError::NonFinite { phi1_deg: geom::deg(p.phi1), quantity: "positions" });
    }
    gaps.close(None, &limits);
    if positions.is_empty() {
        return Err(FourbarError::NeverAssembled { from_deg: spec.sweep.from_deg, to_deg: spec.sweep.to_deg });
    }
    Ok(Motion {
        positions,
        forces,
        gaps: gaps.gaps,
        dead_points: dead_points(geom, &spec.sweep),
        grashof: geom.grashof(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hot_path_dyad_agrees_with_circle_circle() {
        let g = Geometry {
            o1: Point::new(0.3, -0.2),
            c: Point::new(1.1, 0.4),
            l1: 0.35,
            l_ab: 0.9,
            l_bm: 0.5,
            alpha: 2.0,
            l_bc: 0.6,
            branch: Side::Left,
        };
        let p = Prepared::new(&g);
        for k in 0..720 {
            let phi1 = f64::from(k).to_radians() * 0.5;
            let (a, ix) = p.dyad(phi1).unwrap();
            let reference = geom::circle_circle(a, g.l_ab, g.c, g.l_bc);
            match (ix, reference) {
                (CircleIntersection::Two { left, right }, CircleIntersection::Two { left: l, right: r }) => {
                    assert!((left - l).norm() < 1e-15 && (right - r).norm() < 1e-15, "phi1 = {phi1}");
                }
                other => panic!("phi1 = {phi1}: {other:?}"),
            }
        }
        // Tangent and disjoint cases: |AC| = l_ab + l_bc at phi1 = π for this geometry.
        let t = Geometry { o1: Point::origin(), c: Point::new(0.08, 0.0), l1: 0.04, l_ab: 0.07, l_bc: 0.05, ..g };
        let p = Prepared::new(&t);
        assert!(matches!(p.dyad(std::f64::consts::PI), Ok((_, CircleIntersection::Tangent(_)))));
        let far = Geometry { l_ab: 0.06, ..t };
        assert!(matches!(
            Prepared::new(&far).dyad(std::f64::consts::PI),
            Err(FourbarError::Unassemblable { reach: Reach::TooFar, .. })
        ));
    }
}
