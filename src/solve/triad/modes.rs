//! Every assembly mode of the triad.
//!
//! For a fixed orientation the triangle is rigid: A3 = A1 + m·(A2 − A1) with the complex
//! factor m = (l13/l12)·e^{±iα} (α the angle at A1, + for counter-clockwise). Writing
//! A1 = O1 + R1·e1, A2 = O2 + R2·e2 (e_i unit vectors, here complex numbers), the two
//! closure equations |A2 − A1| = l12 and |A3 − O3| = R3 are both linear in
//! e2 = (cos phi2, sin phi2):
//!
//! A_k(phi1)·cos phi2 + B_k(phi1)·sin phi2 + C_k(phi1) = 0,   k = 1, 2,
//!
//! with A_k, B_k, C_k first-degree trigonometric polynomials in phi1. Eliminating phi2
//! (Cramer's rule and cos² + sin² = 1) gives one equation in phi1,
//!
//! F(phi1) = (B1C2 − B2C1)² + (C1A2 − C2A1)² − (A1B2 − A2B1)² = 0,
//!
//! a trigonometric polynomial whose 4th harmonic vanishes identically (the circular points
//! cancel), so F has at most 6 real roots: a class-III triad has at most 6 configurations per
//! orientation. F is turned into two degree-6 polynomials, in tan(phi1/2) for
//! |phi1| ≤ 100° and in tan((phi1 − π)/2) for the rest (with overlap, so every root is
//! interior to one chart and no coefficient blows up near phi1 = π), and their real roots
//! are isolated exactly by the derivative sequence (the private module `poly`); critical points
//! where F vanishes to rounding are kept, so double roots (two modes merging) and very
//! close pairs are not lost. Each root is completed geometrically (both intersections for
//! A2, the one that closes the triangle kept), polished by Newton–Raphson on the
//! three-angle system, checked (residual ≤ [`super::RESIDUAL_ACCEPT_REL`], orientation)
//! and de-duplicated.

use nalgebra::Complex;

use super::newton::polish;
use super::poly::{Trig, real_roots};
use super::{Configuration, Orientation, RESIDUAL_ACCEPT_REL, Triad, TriadError};
use crate::geom::{Point, Vector, angle_of, deg, polar};

type C = Complex<f64>;

/// Each chart covers |ψ| ≤ 2·atan(CHART_HALF_WIDTH) = 100° (ψ = phi1 or phi1 − π): the
/// charts overlap by 10° on each side, so a root at a chart's edge is interior to the other.
pub const CHART_HALF_WIDTH: f64 = 1.191_753_592_594_209_8; // tan(50°)

/// A critical point of the chart polynomial where |P| ≤ this × Σ|a_i||t|^i counts as a
/// (double) root candidate. Candidates are verified, so this errs on the generous side.
pub const NEAR_ZERO_REL: f64 = 1e-9;

/// A root's geometric completion is polished only when ||O3A3| − R3| ≤ this × scale
/// (wrong A2 branches are far off; double roots, found to ~1e-8 rad, are well inside).
pub const CANDIDATE_REL: f64 = 1e-5;

/// Two modes whose vertices all lie within this × scale of each other are one mode (a
/// double root seen from two candidates).
pub const DEDUPE_REL: f64 = 1e-7;

/// A closure polynomial whose coefficients are all below this fraction of their
/// pre-cancellation size vanishes identically: the triad is movable.
pub const MOVABLE_REL: f64 = 1e-12;

/// Roots phi1 closer than this (radians) are one root seen from both charts.
const SAME_ROOT_RAD: f64 = 1e-12;

/// Newton steps allowed when polishing a root.
const POLISH_ITERATIONS: usize = 60;

/// Complex factor m with A3 − A1 = m·(A2 − A1).
fn rigid_factor(triad: &Triad, orientation: Orientation) -> C {
    let (c, s) = triad.angle_at_a1();
    let s = match orientation {
        Orientation::Ccw => s,
        Orientation::Cw => -s,
        Orientation::Collinear => 0.0,
    };
    C::new(c, s) * (triad.l13 / triad.l12)
}

fn cx(v: Vector) -> C {
    C::new(v.x, v.y)
}

/// The closure polynomial F(phi1) for one orientation, in units of the triad's scale, and
/// the size of its terms before cancellation.
fn closure(triad: &Triad, m: C) -> (Trig, f64) {
    let l = triad.scale();
    let o1 = C::new(0.0, 0.0);
    let o2 = cx(triad.o[1] - triad.o[0]) / l;
    let o3 = cx(triad.o[2] - triad.o[0]) / l;
    let [r1, r2, r3] = triad.r.map(|r| r / l);
    let (l12, _) = (triad.l12 / l, triad.l23 / l);
    let n = C::new(1.0, 0.0) - m;
    let d = o2 - o1;
    let p = n * o1 + m * o2 - o3;
    // |A2 − A1|² = l12²:  (d − R1 e1)·(2R2 e2) + |d − R1 e1|² + R2² − l12² = 0
    let a1 = Trig::first(2.0 * r2 * d.re, -2.0 * r2 * r1, 0.0);
    let b1 = Trig::first(2.0 * r2 * d.im, 0.0, -2.0 * r2 * r1);
    let c1 = Trig::first(d.norm_sqr() + r1 * r1 + r2 * r2 - l12 * l12, -2.0 * r1 * d.re, -2.0 * r1 * d.im);
    // |p + R1 n e1 + R2 m e2|² = R3²:  w·(2R2 e2) + |p + R1 n e1|² + R2²|m|² − R3² = 0,
    // w = conj(m)(p + R1 n e1) = w0 + w1 e1.
    let w0 = m.conj() * p;
    let w1 = m.conj() * n * r1;
    let a2 = Trig::first(2.0 * r2 * w0.re, 2.0 * r2 * w1.re, -2.0 * r2 * w1.im);
    let b2 = Trig::first(2.0 * r2 * w0.im, 2.0 * r2 * w1.im, 2.0 * r2 * w1.re);
    let q = p.conj() * n;
    let c2 = Trig::first(
        p.norm_sqr() + r1 * r1 * n.norm_sqr() + r2 * r2 * m.norm_sqr() - r3 * r3,
        2.0 * r1 * q.re,
        -2.0 * r1 * q.im,
    );
    let x = b1.mul(&c2).sub(&b2.mul(&c1));
    let y = c1.mul(&a2).sub(&c2.mul(&a1));
    let dd = a1.mul(&b2).sub(&a2.mul(&b1));
    let f = x.mul(&x).add(&y.mul(&y)).sub(&dd.mul(&dd));
    let (mx, my, md) = (x.magnitude(), y.magnitude(), dd.magnitude());
    let size = mx * mx + my * my + md * md;
    (f, size)
}

/// The configurations of one orientation (possibly none). Fails only for a movable triad.
pub fn modes_with(triad: &Triad, orientation: Orientation) -> Result<Vec<Configuration>, TriadError> {
    let orientation = if triad.is_flat() { Orientation::Collinear } else { orientation };
    let m = rigid_factor(triad, orientation);
    let (f, size) = closure(triad, m);
    if f.magnitude() <= MOVABLE_REL * size {
        return Err(TriadError::Movable);
    }
    let mut found: Vec<Configuration> = Vec::with_capacity(6);
    for (chart, offset) in [(f, 0.0), (f.shifted_by_pi(), std::f64::consts::PI)] {
        let p = chart.tan_half_poly();
        let roots = real_roots(&p, -CHART_HALF_WIDTH, CHART_HALF_WIDTH, NEAR_ZERO_REL);
        for &t in roots.as_slice() {
            complete(triad, m, orientation, offset + 2.0 * libm::atan(t), &mut found);
        }
    }
    found.sort_by(|a, b| a.phi[0].total_cmp(&b.phi[0]));
    Ok(found)
}

/// Completes a root phi1 into configurations (both A2 branches tried), polishes, checks and
/// adds the new ones to `found`.
fn complete(triad: &Triad, m: C, orientation: Orientation, phi1: f64, found: &mut Vec<Configuration>) {
    // A root in the overlap of the two charts is seen twice; both of its A2 branches were
    // tried the first time.
    if found.iter().any(|c| crate::geom::wrap_pi(c.phi[0] - phi1).abs() <= SAME_ROOT_RAD) {
        return;
    }
    let scale = triad.scale();
    let a1 = polar(triad.o[0], triad.r[0], phi1);
    for a2 in a2_candidates(a1, triad.l12, triad.o[1], triad.r[1], scale).into_iter().flatten() {
        let a3 = Point::from(
            a1.coords + {
                let v = m * cx(a2 - a1);
                Vector::new(v.re, v.im)
            },
        );
        if ((a3 - triad.o[2]).norm() - triad.r[2]).abs() > CANDIDATE_REL * scale {
            continue;
        }
        let start = [phi1, angle_of(a2 - triad.o[1]), angle_of(a3 - triad.o[2])];
        let c = triad.configuration(polish(triad, start, POLISH_ITERATIONS));
        if c.residual.is_nan() || c.residual > RESIDUAL_ACCEPT_REL || c.orientation != orientation {
            continue;
        }
        let same = |o: &Configuration| (0..3).all(|i| (o.a[i] - c.a[i]).norm() <= DEDUPE_REL * scale);
        if !found.iter().any(same) {
            found.push(c);
        }
    }
}

/// The points at distance `l` from `a1` on circle (`o2`, `r2`); a discriminant that is
/// negative only by rounding gives the tangent point.
fn a2_candidates(a1: Point, l: f64, o2: Point, r2: f64, scale: f64) -> [Option<Point>; 2] {
    let dv = o2 - a1;
    let d2 = dv.norm_squared();
    if d2 == 0.0 {
        return [None, None];
    }
    let d = d2.sqrt();
    let a = (d2 + l * l - r2 * r2) / (2.0 * d);
    let h2 = l * l - a * a;
    if h2 < -CANDIDATE_REL * scale * scale {
        return [None, None];
    }
    let u = dv / d;
    let foot = a1 + u * a;
    let h = h2.max(0.0).sqrt();
    let nrm = crate::geom::perp(u) * h;
    if h == 0.0 { [Some(foot), None] } else { [Some(foot + nrm), Some(foot - nrm)] }
}

/// Every configuration of the triad: of `orientation` only, or of both orientations when
/// `None` (counter-clockwise first, each sorted by phi1). Flat triangles have one
/// orientation, [`Orientation::Collinear`].
///
/// Errors: [`TriadError::CannotJoin`] when two vertices can never be their side apart,
/// [`TriadError::NoConfiguration`] (with the closest miss) when no configuration exists,
/// [`TriadError::Movable`] for a triad with infinitely many.
pub fn all_modes(triad: &Triad, orientation: Option<Orientation>) -> Result<Vec<Configuration>, TriadError> {
    triad.check_pairs()?;
    let wanted: &[Orientation] = if triad.is_flat() {
        &[Orientation::Collinear]
    } else {
        match orientation {
            None => &[Orientation::Ccw, Orientation::Cw],
            Some(Orientation::Ccw) => &[Orientation::Ccw],
            Some(Orientation::Cw) => &[Orientation::Cw],
            Some(Orientation::Collinear) => &[Orientation::Ccw, Orientation::Cw],
        }
    };
    let mut all = Vec::with_capacity(12);
    for &o in wanted {
        all.extend(modes_with(triad, o)?);
    }
    if all.is_empty() {
        let single = if wanted.len() == 1 && !triad.is_flat() { Some(wanted[0]) } else { None };
        let mirror_modes = match single {
            Some(o) => modes_with(triad, o.mirror())?.len(),
            None => 0,
        };
        let (closest_miss, at) = closest_miss(triad, wanted);
        return Err(TriadError::NoConfiguration {
            orientation: single,
            closest_miss,
            at_phi1_deg: deg(at),
            mirror_modes,
        });
    }
    Ok(all)
}

/// Signed |O3A3| − R3 closest to zero over a scan of phi1 (both A2 branches): how far the
/// data is from having a configuration. Only used for the error message.
fn closest_miss(triad: &Triad, orientations: &[Orientation]) -> (f64, f64) {
    let mut best = (f64::INFINITY, 0.0);
    const STEPS: usize = 3600;
    for &o in orientations {
        let m = rigid_factor(triad, o);
        for i in 0..STEPS {
            let phi1 = std::f64::consts::TAU * i as f64 / STEPS as f64;
            let a1 = polar(triad.o[0], triad.r[0], phi1);
            for a2 in a2_candidates(a1, triad.l12, triad.o[1], triad.r[1], 0.0).into_iter().flatten() {
                let v = m * cx(a2 - a1);
                let a3 = a1 + Vector::new(v.re, v.im);
                let miss = (a3 - triad.o[2]).norm() - triad.r[2];
                if miss.abs() < best.0.abs() {
                    best = (miss, phi1);
                }
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::triad::tests::seed;

    #[test]
    fn fourth_harmonic_cancels() {
        let t = seed();
        for o in [Orientation::Ccw, Orientation::Cw] {
            let (f, size) = closure(&t, rigid_factor(&t, o));
            assert!(f.coeff(4).norm() <= 1e-14 * size, "{} vs {size}", f.coeff(4).norm());
            assert!(f.coeff(3).norm() > 1e-6 * size);
        }
    }

    #[test]
    fn closure_vanishes_at_the_pattern_solution() {
        let t = seed();
        let p = crate::solve::triad::pattern(&t, &Default::default()).unwrap();
        let (f, size) = closure(&t, rigid_factor(&t, Orientation::Ccw));
        // F has a simple root there; the pattern result is ~1e-7 rad off.
        let v = f.eval(p.configuration.phi[0]).abs();
        let v_far = f.eval(p.configuration.phi[0] + 0.3).abs();
        assert!(v < 1e-5 * size && v_far > 1e3 * v, "{v} {v_far} {size}");
    }

    #[test]
    fn seed_has_four_plus_four_modes_including_the_pattern_result() {
        let t = seed();
        let modes = all_modes(&t, None).unwrap();
        let ccw = modes.iter().filter(|c| c.orientation == Orientation::Ccw).count();
        assert_eq!((ccw, modes.len() - ccw), (4, 4), "{modes:#?}");
        assert!(modes.iter().any(|c| (c.phi_deg()[0] - 75.77).abs() < 0.005));
        for c in &modes {
            assert!(c.residual < 1e-13, "{c:?}");
        }
    }
}
