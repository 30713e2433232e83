//! The seed's "pattern method" (metoda șablonului): move a cardboard triangle with A1 on
//! circle 1 and A2 on circle 2 until A3 lands on circle 3.
//!
//! For a trial phi1 (the seed's function `Calcul`):
//! I. A1 = O1 + R1·(cos phi1, sin phi1) (eq. 1);
//! II. A2 = intersection of circle (O2, R2) with circle (A1, l12) (eqs. 6–9);
//! III. A3 = intersection of circle (A2, l23) with circle (A1, l13);
//! IV. d = |O3A3| is compared with R3.
//!
//! The angle is corrected by the secant of eq. (2), phi1 ← phi1 + Δφ·(R3 − d1)/(d2 − d1),
//! with d1 = d(phi1), d2 = d(phi1 + Δφ), and the step refined Δφ ← Δφ/10 each time, until
//! |R3 − d1| < ε (eq. 3). The seed's AutoLisp performs only one refinement (its `IF` is not
//! a loop) and evaluates the secant from phi1 + Δφ instead of phi1; this follows the text.

use super::{Configuration, Orientation, Triad, TriadError};
use crate::geom::{CircleIntersection, Point, Side, circle_circle, deg, polar, rad, rotate};

/// Settings of the pattern method. The defaults are the seed's: start phi1 = 90°,
/// Δφ = 0.01°, ε = 1e-5, and the branches that give its result 75.77°.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatternOptions {
    /// Start angle phi1, radians.
    pub phi1_start: f64,
    /// First step Δφ, radians (non-zero; its sign sets the side of the first secant point).
    pub step: f64,
    /// ε: the iteration stops when |R3 − |O3A3|| < ε (model units).
    pub tol: f64,
    /// Iteration cap (secant updates).
    pub max_iterations: usize,
    /// Which intersection is A2: its side of the directed line O2 → A1 (the seed intersects
    /// circle (O2, R2) first; its second root, `P2`, is the right-hand one on its data).
    pub a2: Side,
    /// Which intersection is A3: the sense of A1 → A2 → A3 (the seed's `P2` gives
    /// counter-clockwise on its data).
    pub orientation: Orientation,
}

impl Default for PatternOptions {
    fn default() -> Self {
        PatternOptions {
            phi1_start: rad(90.0),
            step: rad(0.01),
            tol: 1e-5,
            max_iterations: 50,
            a2: Side::Right,
            orientation: Orientation::Ccw,
        }
    }
}

/// Result of the pattern method.
#[derive(Debug, Clone, PartialEq)]
pub struct PatternSolution {
    /// The converged position: phi1 from the iteration, phi2 and phi3 the directions
    /// O2→A2 and O3→A3 of its construction (A3 is within ε of circle 3).
    pub configuration: Configuration,
    /// Secant updates performed (eq. 2).
    pub iterations: usize,
    /// Final |R3 − d1| (model units), below ε.
    pub residual: f64,
    /// Evaluations of the construction I–IV.
    pub evaluations: usize,
    /// The approximate triangle at the start angle (A1, A2, A3; A3 off circle 3).
    pub start: [Point; 3],
    /// phi1 (radians) and |R3 − d1| after the start and after each update.
    pub history: Vec<(f64, f64)>,
}

/// Steps I–III for a trial `phi1`: the vertices A1, A2, A3 (A3 in general not on circle 3),
/// or `None` when circle (A1, l12) misses circle (O2, R2). A tangent meeting gives its
/// single point.
pub fn construct(triad: &Triad, phi1: f64, a2: Side, orientation: Orientation) -> Option<[Point; 3]> {
    let a1 = polar(triad.o[0], triad.r[0], phi1);
    let a2 = circle_circle(triad.o[1], triad.r[1], a1, triad.l12).on(a2)?;
    let side = match orientation {
        Orientation::Ccw | Orientation::Collinear => Side::Left,
        Orientation::Cw => Side::Right,
    };
    // Left of A1 → A2 is counter-clockwise A1A2A3.
    let a3 = match circle_circle(a1, triad.l13, a2, triad.l23) {
        CircleIntersection::None => {
            // Only rounding can get here (the triangle closes): place A3 rigidly.
            let (c, s) = triad.angle_at_a1();
            let s = if side == Side::Left { s } else { -s };
            let u = (a2 - a1) / (a2 - a1).norm();
            a1 + rotate(u, libm::atan2(s, c)) * triad.l13
        }
        other => other.on(side)?,
    };
    Some([a1, a2, a3])
}

/// Runs the pattern method on `triad`.
pub fn pattern(triad: &Triad, opts: &PatternOptions) -> Result<PatternSolution, TriadError> {
    let r3 = triad.r[2];
    let mut evaluations = 0;
    let mut eval = |phi1: f64, iteration: usize| -> Result<[Point; 3], TriadError> {
        evaluations += 1;
        construct(triad, phi1, opts.a2, opts.orientation)
            .ok_or(TriadError::PatternNoIntersection { phi1_deg: deg(phi1), iteration })
    };
    let mut phi = opts.phi1_start;
    let mut step = opts.step;
    let start = eval(phi, 0)?;
    let mut a = start;
    let mut d1 = (a[2] - triad.o[2]).norm();
    let mut history = vec![(phi, (r3 - d1).abs())];
    for iteration in 0..=opts.max_iterations {
        if (r3 - d1).abs() < opts.tol {
            let [a1, a2, a3] = a;
            let phi_all = [phi, crate::geom::angle_of(a2 - triad.o[1]), crate::geom::angle_of(a3 - triad.o[2])]
                .map(crate::geom::normalize_angle);
            let configuration = Configuration {
                phi: phi_all,
                a: [a1, a2, a3],
                orientation: triad.orientation_of(&a),
                residual: triad.residual(&a),
            };
            return Ok(PatternSolution {
                configuration,
                iterations: iteration,
                residual: (r3 - d1).abs(),
                evaluations,
                start,
                history,
            });
        }
        if iteration == opts.max_iterations {
            break;
        }
        let d2 = (eval(phi + step, iteration + 1)?[2] - triad.o[2]).norm();
        // d2 = d1 to within rounding: the secant is undefined (or pure noise).
        if (d2 - d1).abs() <= 4.0 * f64::EPSILON * d1.max(d2) {
            return Err(TriadError::PatternStalled {
                phi1_deg: deg(phi),
                iteration: iteration + 1,
                step_deg: deg(step),
                residual: (r3 - d1).abs(),
            });
        }
        phi += step * (r3 - d1) / (d2 - d1);
        a = eval(phi, iteration + 1)?;
        d1 = (a[2] - triad.o[2]).norm();
        history.push((phi, (r3 - d1).abs()));
        step /= 10.0;
    }
    Err(TriadError::PatternNotConverged {
        iterations: opts.max_iterations,
        residual: (r3 - d1).abs(),
        phi1_deg: deg(phi),
    })
}

#[cfg(test)]
#[allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the code under test calls"
)]
mod tests {
    use super::*;
    use crate::solve::triad::tests::seed;

    /// The seed's `Int_2C` (eqs. 6–9) written out literally: the intersections of circle
    /// (a1, b1, r1) with circle (a2, b2, r2) by the tangent of the half angle.
    fn int_2c(c1: Point, r1: f64, c2: Point, r2: f64) -> Option<(Point, Point)> {
        let (a1, b1, a2, b2) = (c1.x, c1.y, c2.x, c2.y);
        let a = 2.0 * r1 * (a1 - a2);
        let b = 2.0 * r1 * (b1 - b2);
        let c = (a1 - a2).powi(2) + (b1 - b2).powi(2) + r1 * r1 - r2 * r2;
        let aa = a * a + b * b - c * c;
        if aa < 0.0 {
            return None;
        }
        let fi = |bb: f64| if bb > 0.0 { 2.0 * bb.atan() } else { std::f64::consts::TAU + 2.0 * bb.atan() };
        let fil1 = fi((-b + aa.sqrt()) / (c - a));
        let fil2 = fi((-b - aa.sqrt()) / (c - a));
        Some((polar(c1, r1, fil1), polar(c1, r1, fil2)))
    }

    #[test]
    fn reproduces_the_seed_75_77_degrees() {
        let t = seed();
        let s = pattern(&t, &PatternOptions::default()).unwrap();
        let phi1 = s.configuration.phi_deg()[0];
        assert!((phi1 - 75.77).abs() <= 0.005, "phi1 = {phi1}");
        assert!(s.residual < 1e-5);
        assert!(s.iterations >= 2 && s.iterations <= 10, "{}", s.iterations);
        // Each accepted step lowers |R3 − d| (secant steps converge on this smooth function).
        assert!(s.history.windows(2).all(|w| w[1].1 < w[0].1), "{:?}", s.history);
    }

    #[test]
    fn default_branches_are_the_seeds_p2_roots() {
        // The seed's Calcul takes P2 of Int_2C twice; our named sides must pick the same
        // points, at the start and at the solution.
        let t = seed();
        let o = PatternOptions::default();
        let s = pattern(&t, &o).unwrap();
        for phi1 in [o.phi1_start, s.configuration.phi[0]] {
            let [a1, a2, a3] = construct(&t, phi1, o.a2, o.orientation).unwrap();
            let (_, p2) = int_2c(t.o[1], t.r[1], a1, t.l12).unwrap();
            assert!((p2 - a2).norm() < 1e-9, "A2 {a2:?} vs seed {p2:?}");
            let (_, p2) = int_2c(a2, t.l23, a1, t.l13).unwrap();
            assert!((p2 - a3).norm() < 1e-9, "A3 {a3:?} vs seed {p2:?}");
        }
    }

    #[test]
    fn a_start_where_a2_does_not_exist_is_named() {
        let t = seed();
        // phi1 = 180°: A1 = (−35, 30), 125.4 from O2 > l12 + R2 = 110.
        let o = PatternOptions { phi1_start: rad(180.0), ..Default::default() };
        assert!(matches!(pattern(&t, &o), Err(TriadError::PatternNoIntersection { iteration: 0, .. })));
    }

    #[test]
    fn a_zero_tolerance_stalls_or_hits_the_cap_by_name() {
        let t = seed();
        let o = PatternOptions { tol: 0.0, ..Default::default() };
        match pattern(&t, &o) {
            Err(TriadError::PatternStalled { .. }) | Err(TriadError::PatternNotConverged { .. }) => {}
            other => panic!("expected a named failure, got {other:?}"),
        }
    }
}
