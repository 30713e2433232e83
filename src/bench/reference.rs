//! Independent, high-accuracy answers the bench (and the tests) measure methods against:
//! closed forms written without the solvers, and roots polished further than any method
//! is asked to go.

use crate::geom::{Point, Side, angle_of, polar, wrap_pi};
use crate::solve::fourbar::Geometry;
use crate::solve::triad::{Configuration, NewtonOptions, Triad, TriadError, all_modes, newton_to};

/// The shaper of `templates/shaper.toml` (seed 002) in closed form: crank O1A = 125 about
/// O1 = (0, 300) turning at 360°/s from phi1 = 0, rocker O3B = 600 about O3 = (0, 0) through
/// A, link BE = 150, ram point E on the line y = 600 with x_E > x_B. Units mm, s.
pub mod shaper {
    /// Height of the crank pivot O1 above the rocker pivot O3, mm.
    pub const H_PIVOT: f64 = 300.0;
    /// Crank O1A, mm.
    pub const R: f64 = 125.0;
    /// Rocker O3B, mm.
    pub const L: f64 = 600.0;
    /// Link BE, mm.
    pub const LBE: f64 = 150.0;
    /// The ram's line y = Y_RAM, mm.
    pub const Y_RAM: f64 = 600.0;
    /// Crank angular velocity, rad/s (360°/s).
    pub const OMEGA: f64 = std::f64::consts::TAU;

    /// `([x_E, v_E, a_E], [theta, theta', theta''])` at time `t` (s): the ram point's
    /// abscissa, velocity and acceleration (mm, mm/s, mm/s²) and the rocker's angle,
    /// angular velocity and acceleration (rad, rad/s, rad/s²), from the loop closure by
    /// direct differentiation.
    pub fn closed_form(t: f64) -> ([f64; 3], [f64; 3]) {
        let phi = OMEGA * t;
        let (s, c) = libm::sincos(phi);
        let a = [R * c, H_PIVOT + R * s];
        let ad = [-R * OMEGA * s, R * OMEGA * c];
        let add = [-R * OMEGA * OMEGA * c, -R * OMEGA * OMEGA * s];
        let n2 = a[0] * a[0] + a[1] * a[1];
        let cross = |u: [f64; 2], v: [f64; 2]| u[0] * v[1] - u[1] * v[0];
        let dot = |u: [f64; 2], v: [f64; 2]| u[0] * v[0] + u[1] * v[1];
        let th = libm::atan2(a[1], a[0]);
        let thd = cross(a, ad) / n2;
        let thdd = cross(a, add) / n2 - 2.0 * cross(a, ad) * dot(a, ad) / (n2 * n2);
        let (st, ct) = libm::sincos(th);
        let b = [L * ct, L * st];
        let bd = [-L * thd * st, L * thd * ct];
        let bdd = [-L * thdd * st - L * thd * thd * ct, L * thdd * ct - L * thd * thd * st];
        let dy = Y_RAM - b[1];
        let root = (LBE * LBE - dy * dy).sqrt();
        let xe = b[0] + root;
        let ve = bd[0] + dy * bd[1] / root;
        let ae = bdd[0] + (dy * bdd[1] - bd[1] * bd[1]) / root - (dy * bd[1]) * (dy * bd[1]) / (root * root * root);
        ([xe, ve, ae], [th, thd, thdd])
    }
}

/// Every assembly mode of `triad`, each polished by Newton to the step floor (goal 0), so
/// the reference is tighter than any method charted. A mode whose polish fails (a double
/// root) is kept as the enumeration gave it.
pub fn triad_modes(triad: &Triad) -> Result<Vec<Configuration>, TriadError> {
    Ok(all_modes(triad, None)?
        .into_iter()
        .map(|m| {
            newton_to(triad, &NewtonOptions { start: m.phi, max_iterations: 8 }, 0.0)
                .map(|s| s.configuration)
                .unwrap_or(m)
        })
        .collect())
}

/// Index of the reference mode nearest to the vertices `a`, and the distance (largest
/// vertex distance divided by [`Triad::scale`]).
pub fn nearest_mode(triad: &Triad, modes: &[Configuration], a: &[Point; 3]) -> Option<(usize, f64)> {
    modes
        .iter()
        .enumerate()
        .map(|(k, m)| (k, (0..3).map(|i| (m.a[i] - a[i]).norm()).fold(0.0, f64::max) / triad.scale()))
        .min_by(|x, y| x.1.total_cmp(&y.1))
}

/// B of the four-bar at crank angle `phi1` by a second route: the rocker angle from the law
/// of cosines in triangle A C B (angle at C between C→A and C→B), then two Newton
/// corrections of B on the two circle equations. `None` outside the assembly range.
pub fn fourbar_b(g: &Geometry, phi1: f64) -> Option<Point> {
    let a = polar(g.o1, g.l1, phi1);
    let ca = a - g.c;
    let d = ca.norm();
    let cos_gamma = (g.l_bc * g.l_bc + d * d - g.l_ab * g.l_ab) / (2.0 * g.l_bc * d);
    if !(-1.0..=1.0).contains(&cos_gamma) {
        return None;
    }
    let gamma = libm::acos(cos_gamma);
    // B left of A→C means B right of C→A: turn clockwise from C→A.
    let turn = if g.branch == Side::Left { -gamma } else { gamma };
    let mut b = polar(g.c, g.l_bc, angle_of(ca) + turn);
    for _ in 0..2 {
        // f1 = (|B−A|² − l_ab²)/2, f2 = (|B−C|² − l_bc²)/2; J rows (B−A)ᵀ, (B−C)ᵀ.
        let (u, v) = (b - a, b - g.c);
        let f = [(u.norm_squared() - g.l_ab * g.l_ab) / 2.0, (v.norm_squared() - g.l_bc * g.l_bc) / 2.0];
        let det = u.x * v.y - u.y * v.x;
        if det.abs() <= f64::EPSILON * u.norm() * v.norm() {
            break;
        }
        b.x -= (f[0] * v.y - f[1] * u.y) / det;
        b.y -= (u.x * f[1] - v.x * f[0]) / det;
    }
    Some(b)
}

/// Largest relative loop-closure error of a four-bar position: |O1A| − l1, |AB| − l_ab,
/// |CB| − l_bc, divided by the longest link.
pub fn fourbar_residual(g: &Geometry, a: Point, b: Point) -> f64 {
    let scale = g.l1.max(g.l_ab).max(g.l_bc).max(g.ground());
    [(a - g.o1).norm() - g.l1, (b - a).norm() - g.l_ab, (b - g.c).norm() - g.l_bc]
        .iter()
        .fold(0.0_f64, |m, e| m.max(e.abs()))
        / scale
}

/// Smallest angular distance between two angles, radians.
pub fn angle_distance(a: f64, b: f64) -> f64 {
    wrap_pi(a - b).abs()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::rad;

    #[test]
    fn second_route_b_matches_circle_intersection() {
        let g = crate::figure::fourbar::tests::chebyshev();
        for k in 0..36 {
            let phi1 = rad(10.0 * k as f64);
            let b = fourbar_b(&g, phi1).unwrap();
            let pos = crate::solve::fourbar::position(&g, phi1, Side::Left).unwrap();
            assert!((b - pos.b).norm() <= 1e-15, "{k}: {b:?} vs {:?}", pos.b);
            assert!(fourbar_residual(&g, pos.a, b) <= 1e-15);
        }
    }

    #[test]
    fn shaper_closed_form_derivatives_match_differences() {
        let h = 1e-6;
        for t in [0.1, 0.37, 0.8] {
            let (x, th) = shaper::closed_form(t);
            let (xp, thp) = shaper::closed_form(t + h);
            let (xm, thm) = shaper::closed_form(t - h);
            assert!((x[1] - (xp[0] - xm[0]) / (2.0 * h)).abs() <= 1e-5 * x[1].abs().max(1.0));
            assert!((x[2] - (xp[1] - xm[1]) / (2.0 * h)).abs() <= 1e-4 * x[2].abs().max(1.0));
            assert!((th[1] - (thp[0] - thm[0]) / (2.0 * h)).abs() <= 1e-7);
            assert!((th[2] - (thp[1] - thm[1]) / (2.0 * h)).abs() <= 1e-5);
        }
    }
}
