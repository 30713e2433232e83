//! Positions, velocities and accelerations of the four-bar at one crank angle: the
//! closed-form RRR dyad (with a hot path for sweeps, [`Prepared`]) and the analytic
//! velocity and acceleration equations (see the parent module for the methods).

use super::{FourbarError, Geometry, Reach, SINGULAR_SIN};
use crate::geom::{self, CircleIntersection, Point, Side, Vector, cross, perp};

/// Velocities and accelerations at one crank angle (units/s, units/s²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kinematics {
    /// Angular velocity of the crank (link 1), rad/s, CCW positive: the scene's omega1.
    pub omega1: f64,
    /// Angular acceleration of the crank, rad/s², CCW positive: the scene's epsilon1.
    pub eps1: f64,
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
        let (sin_alpha, cos_alpha) = libm::sincos(geom.alpha);
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

/// Velocities and accelerations at `pos` for the crank turning at `omega1` (rad/s, CCW
/// positive) with no angular acceleration: [`kinematics_eps`] with `eps1 = 0`.
#[inline]
pub fn kinematics(geom: &Geometry, pos: &Position, omega1: f64) -> Result<Kinematics, FourbarError> {
    kinematics_eps(geom, pos, omega1, 0.0)
}

/// Velocities and accelerations at `pos` for the crank's state `omega1` (rad/s) and `eps1`
/// (rad/s²), both counter-clockwise positive: A has the tangential acceleration
/// eps1 × (A − O1) besides the normal −omega1²·(A − O1). Errors with
/// [`FourbarError::Singular`] when A, B, C are collinear.
#[inline]
pub fn kinematics_eps(geom: &Geometry, pos: &Position, omega1: f64, eps1: f64) -> Result<Kinematics, FourbarError> {
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
    // The tangential term only when eps1 ≠ 0: adding a ±0 would turn a −0 component into
    // +0 and change the printed constant-speed results.
    let a_a = if eps1 == 0.0 { -r1 * (omega1 * omega1) } else { -r1 * (omega1 * omega1) + perp(r1) * eps1 };
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
        omega1,
        eps1,
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
