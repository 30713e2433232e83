//! Kinematic synthesis: the mechanism that does a job, found in closed form or by the
//! textbook's construction (numbers only: the construction's points are returned for the
//! figure to draw, nothing here knows a scene or a drawing).
//!
//! One task per module:
//! - [`crank_rocker`]: a crank-rocker four-bar for a rocker swing ψ and a time ratio K;
//! - [`slider_crank`]: an offset slider-crank for a stroke H and a time ratio K;
//! - [`quick_return`]: the shaper's quick-return six-bar (crank, slotted rocker, link, ram)
//!   for a stroke H and a time ratio K;
//! - [`motion`]: a four-bar whose coupler line passes two or three given positions;
//! - [`function`]: a four-bar whose output angle generates y = f(x) through three
//!   precision points (Freudenstein's equation).
//!
//! The time-ratio tasks share the construction of the textbooks: the crank turns through
//! 180° + θ on the working stroke and 180° − θ on the return, θ = 180°·(K − 1)/(K + 1)
//! (the *excess angle*, [`excess_angle`]), and the crank pivot sees the two extreme
//! positions of the output under θ: it lies on a circle through them ([`seeing_circle`]).
//!
//! Angles are radians, counter-clockwise from +x; lengths in the caller's unit. Every
//! requirement that cannot be met is a named [`SynthesisError`]; the quality of a design
//! (its Grashof class, the smallest transmission angle, the defects a synthesis can hide)
//! is reported beside it, not refused.

pub mod crank_rocker;
pub mod function;
pub mod motion;
pub mod quick_return;
pub mod slider_crank;

use std::f64::consts::PI;

use crate::geom::{Point, Side, Vector, cross, perp};

/// Why a requirement cannot be met. Each variant names the requirement and says what
/// would be valid.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SynthesisError {
    /// The time ratio K is not above 1 (or not finite). Example: `time_ratio = 1.0`.
    #[error(
        "the time ratio K = {k} must be greater than 1: θ = 180°·(K − 1)/(K + 1) = {theta_deg}° leaves no quick return (K = 1 puts the crank pivot on the line of the two extremes; use K > 1)"
    )]
    TimeRatio {
        /// The K given.
        k: f64,
        /// The excess angle it gives, degrees.
        theta_deg: f64,
    },
    /// The rocker swing ψ is not between 0° and 180°. Example: `psi_deg = 180.0`.
    #[error(
        "the rocker swing ψ = {psi_deg}° must be between 0° and 180° (exclusive): a rocker cannot swing through 180° or more"
    )]
    Swing {
        /// The ψ given, degrees.
        psi_deg: f64,
    },
    /// A length that must be positive is not. Example: `stroke = 0`.
    #[error("{what} = {value} must be a positive length")]
    Length {
        /// Which length (`the stroke H`).
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// A free choice lies outside the family of designs that meet the requirement.
    /// Example: a crank-rocker's ground length longer than any crank pivot on the circle.
    #[error("{what} = {value} gives no design: {why}; valid: {valid}")]
    OutOfFamily {
        /// The free choice (`the ground length d`).
        what: &'static str,
        /// Its value.
        value: f64,
        /// Why it gives none.
        why: String,
        /// What would be valid.
        valid: String,
    },
    /// Two required positions of a moving pivot coincide, so the bisector between them is
    /// undefined. Example: two positions that differ only by a turn about that pivot.
    #[error(
        "the moving pivot {pivot} is at the same place in positions {first} and {second} ({x}, {y}): the perpendicular bisector of {pivot}{first}{pivot}{second} is undefined; choose another moving pivot"
    )]
    CoincidentPositions {
        /// The pivot's name (`A`, `B`).
        pivot: &'static str,
        /// First position (from 1).
        first: usize,
        /// Second position (from 1).
        second: usize,
        /// Where it is.
        x: f64,
        /// Where it is.
        y: f64,
    },
    /// The three positions of a moving pivot are collinear: the perpendicular bisectors
    /// are parallel and meet at no fixed pivot (a slider would be needed).
    #[error(
        "the three positions of the moving pivot {pivot} are collinear: the perpendicular bisectors of {pivot}1{pivot}2 and {pivot}2{pivot}3 are parallel and give no fixed pivot (the pivot would move on a straight line: a slider, not a crank); choose another moving pivot"
    )]
    ParallelBisectors {
        /// The pivot's name (`A`, `B`).
        pivot: &'static str,
    },
    /// A precision point lies outside the function's range.
    #[error(
        "the precision point x{index} = {x} lies outside the range [{from}, {to}] of x: precision points must lie in the range"
    )]
    PrecisionPointOutside {
        /// Which (from 1).
        index: usize,
        /// Its value.
        x: f64,
        /// The range's start.
        from: f64,
        /// The range's end.
        to: f64,
    },
    /// Two precision points coincide, or their equations are dependent: Freudenstein's
    /// 3×3 system is singular.
    #[error(
        "Freudenstein's equations at the precision points are singular ({why}): choose distinct precision points or other angle ranges"
    )]
    SingularPrecision {
        /// What makes them singular.
        why: String,
    },
    /// The function is not finite at a point where it is needed, or takes the same value at
    /// both ends of the range (no output range to map onto).
    #[error("the function {what}")]
    Function {
        /// What is wrong, with where.
        what: String,
    },
    /// The link lengths solved for have no real coupler (b² ≤ 0): no four-bar passes these
    /// precision points with these angle ranges.
    #[error(
        "no real four-bar: the coupler's square length comes out {b2} (≤ 0) for these precision points and angle ranges; change the ranges or the starting angles"
    )]
    NoCoupler {
        /// b², length units squared.
        b2: f64,
    },
    /// Two points that must differ coincide (a fixed pivot on the other, a moving pivot on
    /// the coupler's point).
    #[error("{what}")]
    Degenerate {
        /// What coincides.
        what: String,
    },
}

/// The excess angle θ = π·(K − 1)/(K + 1) of a time ratio K > 1, radians in (0, π): the
/// crank turns through π + θ on the working stroke and π − θ on the return.
pub fn excess_angle(k: f64) -> Result<f64, SynthesisError> {
    let theta = PI * (k - 1.0) / (k + 1.0);
    if k.is_finite() && k > 1.0 && theta > 0.0 {
        Ok(theta)
    } else {
        Err(SynthesisError::TimeRatio { k, theta_deg: theta.to_degrees() })
    }
}

/// The time ratio K = (π + θ)/(π − θ) of an excess angle θ (radians).
pub fn time_ratio(theta: f64) -> f64 {
    (PI + theta) / (PI - theta)
}

/// Checks a rocker swing ψ (radians): in (0, π).
pub fn swing(psi: f64) -> Result<f64, SynthesisError> {
    if psi.is_finite() && psi > 0.0 && psi < PI {
        Ok(psi)
    } else {
        Err(SynthesisError::Swing { psi_deg: psi.to_degrees() })
    }
}

/// Checks a length that must be positive.
pub fn positive(what: &'static str, value: f64) -> Result<f64, SynthesisError> {
    if value.is_finite() && value > 0.0 { Ok(value) } else { Err(SynthesisError::Length { what, value }) }
}

/// The circle whose arc on `side` of the directed chord `p → q` sees the chord under the
/// angle `theta` (0 < θ < π): every point X of that arc has ∠pXq = θ (inscribed angle).
/// Returns its centre and radius: R = |pq|/(2·sin θ), the centre on the chord's
/// perpendicular bisector at R·cos θ from the chord, on `side` (on the other side when
/// θ > 90°). The textbook draws it through the right triangle p q P: q P ⊥ pq and
/// ∠qpP = 90° − θ, so pP is a diameter and P = 2·centre − p.
pub fn seeing_circle(p: Point, q: Point, theta: f64, side: Side) -> (Point, f64) {
    let chord = q - p;
    let half = 0.5 * chord.norm();
    let radius = half / libm::sin(theta);
    let n = perp(chord / chord.norm());
    let n = match side {
        Side::Left => n,
        Side::Right => -n,
    };
    let mid = p + 0.5 * chord;
    (mid + n * (radius * libm::cos(theta)), radius)
}

/// Whether `x` lies on the arc of [`seeing_circle`]`(p, q, θ, side)` (strictly on `side`
/// of the chord), i.e. sees the chord under θ rather than π − θ.
pub fn on_seeing_arc(p: Point, q: Point, x: Point, side: Side) -> bool {
    let s = cross(q - p, x - p);
    match side {
        Side::Left => s > 0.0,
        Side::Right => s < 0.0,
    }
}

/// The kind of four-bar by Grashof's rule, from the input link's point of view.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum FourbarClass {
    /// Grashof, the input link shortest: the input turns fully, the output rocks.
    CrankRocker,
    /// Grashof, the ground shortest: both input and output turn fully (drag link).
    DoubleCrank,
    /// Grashof, the coupler shortest, or the output shortest: the input only rocks.
    GrashofRocker,
    /// Non-Grashof (s + l > p + q): no link turns fully (triple rocker).
    TripleRocker,
    /// s + l = p + q: the linkage can fold flat (change point).
    ChangePoint,
}

impl FourbarClass {
    /// Whether the input link turns fully.
    pub fn input_turns(self) -> bool {
        matches!(self, FourbarClass::CrankRocker | FourbarClass::DoubleCrank)
    }

    /// The class in words, for reports.
    pub fn describe(self) -> &'static str {
        match self {
            FourbarClass::CrankRocker => "Grashof crank-rocker (the input turns fully)",
            FourbarClass::DoubleCrank => "Grashof double crank (drag link: the input turns fully)",
            FourbarClass::GrashofRocker => "Grashof, the input rocks (not a crank)",
            FourbarClass::TripleRocker => "non-Grashof triple rocker (no link turns fully)",
            FourbarClass::ChangePoint => "change point (s + l = p + q: it can fold flat)",
        }
    }
}

/// Relative tolerance of Grashof's equality s + l = p + q (of the longest link).
pub const GRASHOF_TOL_REL: f64 = 1e-12;

/// The class of the four-bar with input link `a`, coupler `b`, output `c` and ground `d`.
pub fn fourbar_class(a: f64, b: f64, c: f64, d: f64) -> FourbarClass {
    let mut l = [a, b, c, d];
    l.sort_by(f64::total_cmp);
    let (s, long) = (l[0], l[3]);
    let excess = s + long - (l[1] + l[2]);
    if excess.abs() <= GRASHOF_TOL_REL * long {
        FourbarClass::ChangePoint
    } else if excess > 0.0 {
        FourbarClass::TripleRocker
    } else if a == s {
        FourbarClass::CrankRocker
    } else if d == s {
        FourbarClass::DoubleCrank
    } else {
        FourbarClass::GrashofRocker
    }
}

/// The smallest transmission angle of a four-bar whose input `a` turns fully (ground
/// `d`, coupler `b`, output `c`), radians in [0, π/2]: the acute angle between coupler and
/// output is extreme where the input lies along the ground line (|AC| = d ∓ a), by the law
/// of cosines cos γ = (b² + c² − |AC|²)/(2bc).
pub fn gamma_min_crank(a: f64, b: f64, c: f64, d: f64) -> f64 {
    [d - a, d + a]
        .iter()
        .map(|ac| {
            let cos = ((b * b + c * c - ac * ac) / (2.0 * b * c)).clamp(-1.0, 1.0);
            let g = libm::acos(cos);
            g.min(PI - g)
        })
        .fold(f64::INFINITY, f64::min)
}

/// Maps points of a construction drawn in a local frame to the design's frame, where the
/// crank pivot is the origin and the ground line runs along +x (as the `fourbar` scene
/// and the templates place them).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// The local point that becomes the origin.
    pub origin: Point,
    /// The local direction that becomes +x, radians.
    pub angle: f64,
}

impl Frame {
    /// The frame with `origin` at the origin and the direction `towards − origin` along +x.
    pub fn along(origin: Point, towards: Point) -> Frame {
        Frame { origin, angle: crate::geom::angle_of(towards - origin) }
    }

    /// A local point in the design's frame.
    pub fn point(&self, p: Point) -> Point {
        Point::origin() + self.vector(p - self.origin)
    }

    /// A local vector in the design's frame.
    pub fn vector(&self, v: Vector) -> Vector {
        crate::geom::rotate(v, -self.angle)
    }

    /// A local direction (radians) in the design's frame.
    pub fn angle(&self, a: f64) -> f64 {
        a - self.angle
    }
}

/// The unit vector at `angle` (radians).
pub(crate) fn unit(angle: f64) -> Vector {
    Vector::new(libm::cos(angle), libm::sin(angle))
}

/// Golden-section search for the largest value of `f` on [lo, hi] (a unimodal stretch), to
/// `tol` in the argument.
pub(crate) fn maximise(f: &impl Fn(f64) -> f64, mut lo: f64, mut hi: f64, tol: f64) -> f64 {
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut x1, mut x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
    let (mut f1, mut f2) = (f(x1), f(x2));
    for _ in 0..200 {
        if hi - lo <= tol {
            break;
        }
        if f1 < f2 {
            lo = x1;
            (x1, f1) = (x2, f2);
            x2 = lo + g * (hi - lo);
            f2 = f(x2);
        } else {
            hi = x2;
            (x2, f2) = (x1, f1);
            x1 = hi - g * (hi - lo);
            f1 = f(x1);
        }
    }
    0.5 * (lo + hi)
}

/// The largest value of `f` over [lo, hi]: the best of `samples` equally spaced samples,
/// refined by golden section between its neighbours. Returns (argument, value).
pub(crate) fn best_of(f: &impl Fn(f64) -> f64, lo: f64, hi: f64, samples: usize) -> (f64, f64) {
    let n = samples.max(3);
    let at = |k: usize| lo + (hi - lo) * k as f64 / (n - 1) as f64;
    let (mut k_best, mut v_best) = (0, f64::NEG_INFINITY);
    for k in 0..n {
        let v = f(at(k));
        if v > v_best {
            (k_best, v_best) = (k, v);
        }
    }
    let (a, b) = (at(k_best.saturating_sub(1)), at((k_best + 1).min(n - 1)));
    let x = maximise(f, a, b, 1e-13 * (hi - lo).abs().max(f64::MIN_POSITIVE));
    let v = f(x);
    if v >= v_best { (x, v) } else { (at(k_best), v_best) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_excess_angle_and_the_time_ratio_are_inverse() {
        let theta = excess_angle(1.5).unwrap();
        assert!((theta.to_degrees() - 36.0).abs() < 1e-12);
        assert!((time_ratio(theta) - 1.5).abs() < 1e-15);
        assert!(matches!(excess_angle(1.0), Err(SynthesisError::TimeRatio { .. })));
        assert!(matches!(excess_angle(0.8), Err(SynthesisError::TimeRatio { .. })));
        assert!(matches!(excess_angle(f64::NAN), Err(SynthesisError::TimeRatio { .. })));
    }

    #[test]
    fn every_point_of_the_seeing_arc_sees_the_chord_under_theta() {
        let (p, q) = (Point::new(-3.0, 1.0), Point::new(5.0, 2.0));
        for theta_deg in [10.0, 36.0, 89.0, 120.0, 170.0] {
            let theta = f64::to_radians(theta_deg);
            for side in [Side::Left, Side::Right] {
                let (m, r) = seeing_circle(p, q, theta, side);
                assert!(((p - m).norm() - r).abs() < 1e-12 * r && ((q - m).norm() - r).abs() < 1e-12 * r);
                for k in 0..72 {
                    let x = m + unit(f64::from(k) * 5f64.to_radians()) * r;
                    if (x - p).norm() < 1e-6 || (x - q).norm() < 1e-6 {
                        continue;
                    }
                    let seen = libm::acos((p - x).normalize().dot(&(q - x).normalize()));
                    let expect = if on_seeing_arc(p, q, x, side) { theta } else { PI - theta };
                    assert!((seen - expect).abs() < 1e-9, "θ = {theta_deg}°, {side:?}, {k}: {seen}");
                }
            }
        }
    }

    #[test]
    fn grashof_classes_by_the_shortest_link() {
        assert_eq!(fourbar_class(1.0, 3.0, 2.5, 3.2), FourbarClass::CrankRocker);
        assert_eq!(fourbar_class(3.0, 3.0, 2.5, 1.0), FourbarClass::DoubleCrank);
        assert_eq!(fourbar_class(3.0, 1.0, 2.5, 3.2), FourbarClass::GrashofRocker);
        assert_eq!(fourbar_class(3.0, 3.0, 3.0, 4.0), FourbarClass::TripleRocker);
        assert_eq!(fourbar_class(1.0, 2.0, 2.0, 1.0), FourbarClass::ChangePoint);
    }

    #[test]
    fn the_smallest_transmission_angle_of_the_chebyshev_four_bar() {
        // Seed 003's template: γ_min = acos(0.92) at φ1 = 0 (|AC| = d − a = 0.04).
        let g = gamma_min_crank(0.04, 0.10, 0.10, 0.08);
        assert!((g - libm::acos(0.92)).abs() < 1e-15);
    }
}
