//! Newton–Raphson on the three-angle system of the triad (the seed's analytic reference):
//! unknowns phi1, phi2, phi3 with A_i = O_i + R_i·(cos phi_i, sin phi_i), equations
//!
//! g_ij = (|A_i − A_j|² − l_ij²) / (2·l_ij) = 0   for ij = 12, 23, 13,
//!
//! (each ≈ |A_iA_j| − l_ij near a solution, so the residual is a length), with the
//! analytic Jacobian ∂g_ij/∂phi_i = (A_i − A_j)·R_i·(−sin phi_i, cos phi_i) / l_ij.
//! The system does not fix the triangle's orientation: Newton converges to the mode
//! (of either orientation) whose basin holds the start.

use super::{Configuration, Triad, TriadError};
use crate::geom::{deg, tol};

/// Iteration stops when the largest |g_ij| is below this fraction of [`Triad::scale`]
/// (a few units in the last place of the coordinates).
pub const NEWTON_RESIDUAL_REL: f64 = 1e-15;

/// A Jacobian whose determinant is below this fraction of the product of its row norms
/// counts as singular.
pub const SINGULAR_REL: f64 = 1e-13;

/// A Newton step below this (radians, every angle) ends [`newton`]: convergence is
/// quadratic, so the error after it is ~1e-16 and another evaluation would only confirm it
/// (the final residual is still computed and checked against
/// [`super::RESIDUAL_ACCEPT_REL`]).
pub const CONVERGED_STEP: f64 = 1e-9;

/// Settings of Newton–Raphson.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonOptions {
    /// Start angles phi1, phi2, phi3, radians.
    pub start: [f64; 3],
    /// Iteration cap.
    pub max_iterations: usize,
}

/// Result of Newton–Raphson.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonSolution {
    /// The converged configuration.
    pub configuration: Configuration,
    /// Newton steps taken.
    pub iterations: usize,
}

/// Residuals g and Jacobian J of the three-angle system at `phi`.
#[inline]
pub(crate) fn system(t: &Triad, phi: &[f64; 3]) -> ([f64; 3], [[f64; 3]; 3]) {
    let (s1, c1) = libm::sincos(phi[0]);
    let (s2, c2) = libm::sincos(phi[1]);
    let (s3, c3) = libm::sincos(phi[2]);
    let [o1, o2, o3] = t.o;
    let [r1, r2, r3] = t.r;
    let a1 = (o1.x + r1 * c1, o1.y + r1 * s1);
    let a2 = (o2.x + r2 * c2, o2.y + r2 * s2);
    let a3 = (o3.x + r3 * c3, o3.y + r3 * s3);
    // Tangents dA_i/dphi_i.
    let t1 = (-r1 * s1, r1 * c1);
    let t2 = (-r2 * s2, r2 * c2);
    let t3 = (-r3 * s3, r3 * c3);
    let d12 = (a1.0 - a2.0, a1.1 - a2.1);
    let d23 = (a2.0 - a3.0, a2.1 - a3.1);
    let d13 = (a1.0 - a3.0, a1.1 - a3.1);
    let dot = |a: (f64, f64), b: (f64, f64)| a.0 * b.0 + a.1 * b.1;
    let (k12, k23, k13) = (0.5 / t.l12, 0.5 / t.l23, 0.5 / t.l13);
    let g = [
        (dot(d12, d12) - t.l12 * t.l12) * k12,
        (dot(d23, d23) - t.l23 * t.l23) * k23,
        (dot(d13, d13) - t.l13 * t.l13) * k13,
    ];
    let j = [
        [2.0 * k12 * dot(d12, t1), -2.0 * k12 * dot(d12, t2), 0.0],
        [0.0, 2.0 * k23 * dot(d23, t2), -2.0 * k23 * dot(d23, t3)],
        [2.0 * k13 * dot(d13, t1), 0.0, -2.0 * k13 * dot(d13, t3)],
    ];
    (g, j)
}

/// Solves `j·x = b` with the adjugate (Cramer's rule sharing the cofactors); `None` when
/// `j` is singular (see [`SINGULAR_REL`]).
#[inline]
pub(crate) fn solve3(j: &[[f64; 3]; 3], b: [f64; 3]) -> Option<[f64; 3]> {
    let [[a, bb, c], [d, e, f], [g, h, i]] = *j;
    // Cofactors.
    let c00 = e * i - f * h;
    let c01 = f * g - d * i;
    let c02 = d * h - e * g;
    let det = a * c00 + bb * c01 + c * c02;
    let n2 = |r: &[f64; 3]| r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    let norms2 = n2(&j[0]) * n2(&j[1]) * n2(&j[2]);
    if det.is_nan() || det * det <= SINGULAR_REL * SINGULAR_REL * norms2 {
        return None;
    }
    let c10 = c * h - bb * i;
    let c11 = a * i - c * g;
    let c12 = bb * g - a * h;
    let c20 = bb * f - c * e;
    let c21 = c * d - a * f;
    let c22 = a * e - bb * d;
    let inv = 1.0 / det;
    Some([
        (c00 * b[0] + c10 * b[1] + c20 * b[2]) * inv,
        (c01 * b[0] + c11 * b[1] + c21 * b[2]) * inv,
        (c02 * b[0] + c12 * b[1] + c22 * b[2]) * inv,
    ])
}

/// Newton–Raphson from `opts.start`. Errors name a singular Jacobian (with the angles) or a
/// missed convergence.
pub fn newton(triad: &Triad, opts: &NewtonOptions) -> Result<NewtonSolution, TriadError> {
    newton_to(triad, opts, NEWTON_RESIDUAL_REL)
}

/// [`newton`] with another stopping goal: iteration stops when the largest |g_ij| is below
/// `residual_rel` · [`Triad::scale`] (or the step is below [`CONVERGED_STEP`]); the
/// answer is accepted when its residual is below the larger of `residual_rel` and
/// [`super::RESIDUAL_ACCEPT_REL`]. `mechdraw bench` charts speed against accuracy with it.
pub fn newton_to(triad: &Triad, opts: &NewtonOptions, residual_rel: f64) -> Result<NewtonSolution, TriadError> {
    let accept = super::RESIDUAL_ACCEPT_REL.max(residual_rel);
    let stop = residual_rel * triad.scale();
    let mut phi = opts.start;
    for iteration in 0..=opts.max_iterations {
        let (g, j) = system(triad, &phi);
        let gmax = g[0].abs().max(g[1].abs()).max(g[2].abs());
        if gmax <= stop {
            return finish(triad, phi, iteration, opts.max_iterations, accept);
        }
        if iteration == opts.max_iterations {
            break;
        }
        let dx =
            solve3(&j, [-g[0], -g[1], -g[2]]).ok_or(TriadError::NewtonSingular { phi_deg: phi.map(deg), iteration })?;
        for (p, d) in phi.iter_mut().zip(dx) {
            *p += d;
        }
        if !phi.iter().all(|p| p.is_finite()) {
            break;
        }
        if dx.iter().all(|d| d.abs() <= CONVERGED_STEP) {
            return finish(triad, phi, iteration + 1, opts.max_iterations, accept);
        }
    }
    let residual = if phi.iter().all(|p| p.is_finite()) { triad.residual(&triad.vertices(phi)) } else { f64::INFINITY };
    Err(TriadError::NewtonNotConverged { iterations: opts.max_iterations, residual })
}

fn finish(
    triad: &Triad,
    phi: [f64; 3],
    iterations: usize,
    cap: usize,
    accept: f64,
) -> Result<NewtonSolution, TriadError> {
    let configuration = triad.configuration(phi);
    if configuration.residual > accept {
        return Err(TriadError::NewtonNotConverged { iterations: cap, residual: configuration.residual });
    }
    Ok(NewtonSolution { configuration, iterations })
}

/// Newton polishing of a near-solution (used by the all-modes search): like [`newton`] but
/// a singular Jacobian (a double root) ends the iteration quietly. Returns the last angles.
pub(super) fn polish(triad: &Triad, mut phi: [f64; 3], max_iterations: usize) -> [f64; 3] {
    let stop = NEWTON_RESIDUAL_REL * triad.scale();
    for _ in 0..max_iterations {
        let (g, j) = system(triad, &phi);
        if g[0].abs().max(g[1].abs()).max(g[2].abs()) <= stop {
            break;
        }
        let Some(dx) = solve3(&j, [-g[0], -g[1], -g[2]]) else { break };
        let next = [phi[0] + dx[0], phi[1] + dx[1], phi[2] + dx[2]];
        if !next.iter().all(|p| p.is_finite()) {
            break;
        }
        phi = next;
        if dx.iter().all(|d| d.abs() <= tol::NEWTON_ANGLE) {
            break;
        }
    }
    phi
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::triad::tests::seed;
    use crate::solve::triad::{PatternOptions, pattern};

    #[test]
    fn jacobian_matches_central_differences() {
        let t = seed();
        let phi = [1.1, 1.9, 2.3];
        let (_, j) = system(&t, &phi);
        let h = 1e-6;
        for k in 0..3 {
            let mut p = phi;
            p[k] += h;
            let (gp, _) = system(&t, &p);
            p[k] -= 2.0 * h;
            let (gm, _) = system(&t, &p);
            for i in 0..3 {
                let fd = (gp[i] - gm[i]) / (2.0 * h);
                assert!((fd - j[i][k]).abs() <= 1e-6 * (1.0 + fd.abs()), "J[{i}][{k}] = {} vs {fd}", j[i][k]);
            }
        }
    }

    #[test]
    fn agrees_with_the_pattern_method_from_its_start_triangle() {
        let t = seed();
        let p = pattern(&t, &PatternOptions::default()).unwrap();
        let [a1, a2, a3] = p.start;
        let start = [a1 - t.o[0], a2 - t.o[1], a3 - t.o[2]].map(crate::geom::angle_of);
        let n = newton(&t, &NewtonOptions { start, max_iterations: 50 }).unwrap();
        assert!(n.configuration.residual < 1e-13);
        for k in 0..3 {
            // The pattern method stops at |R3 − d| < 1e-5: about 1e-7 rad from the root.
            let d = crate::geom::wrap_pi(n.configuration.phi[k] - p.configuration.phi[k]);
            assert!(d.abs() < 1e-5, "phi{} differs by {d}", k + 1);
        }
    }

    #[test]
    fn solve3_solves() {
        let j = [[2.0, -1.0, 0.5], [0.3, 4.0, -2.0], [1.0, 0.0, 3.0]];
        let x = [0.7, -1.3, 2.1];
        let b = [0, 1, 2].map(|r| j[r][0] * x[0] + j[r][1] * x[1] + j[r][2] * x[2]);
        let got = solve3(&j, b).unwrap();
        for k in 0..3 {
            assert!((got[k] - x[k]).abs() < 1e-14);
        }
    }

    #[test]
    fn singular_jacobian_is_named() {
        // All three links pointing at one point: the rows of J are dependent only if the
        // lines O_iA_i are concurrent — build that: O_i on rays from P through A_i.
        let a =
            [crate::geom::Point::new(0.0, 0.0), crate::geom::Point::new(4.0, 0.0), crate::geom::Point::new(1.0, 3.0)];
        let p = crate::geom::Point::new(1.5, 1.0);
        let o = a.map(|ai| ai + (ai - p) * 1.5);
        let r = [0, 1, 2].map(|i| (a[i] - o[i]).norm());
        let t = Triad::new(o, r, 4.0, (a[2] - a[1]).norm(), (a[2] - a[0]).norm()).unwrap();
        let phi = [0, 1, 2].map(|i| crate::geom::angle_of(a[i] - o[i]));
        // Exactly at the singular solution Newton stops at once (residual zero), so start
        // slightly off: the Jacobian there is nearly singular but solvable; at the exact
        // point the solver must not produce NaN.
        let (_, j) = system(&t, &phi);
        assert!(solve3(&j, [1.0, 0.0, 0.0]).is_none());
    }
}
