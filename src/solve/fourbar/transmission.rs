//! The transmission angle γ of the four-bar: the angle between the coupler AB and the
//! rocker BC at B, folded to 0…90° (the acute angle between the two lines), as a teacher
//! plots it against φ1 to judge how well the coupler drives the rocker. Below about 40°
//! (the usual design limit, [`GAMMA_LIMIT_DEG`]) friction and play in the joints make the
//! rocker stick; at 0° (A, B, C collinear) the dyad is at a dead point.
//!
//! [`Position::transmission`] is the unfolded angle between the directions B→A and B→C
//! (0…180°); γ = min(θ, 180° − θ).

use super::kinematics::Position;
use crate::geom::deg;

/// The usual lower limit of the transmission angle in design practice, degrees.
pub const GAMMA_LIMIT_DEG: f64 = 40.0;

/// Transmission angle γ at `pos`, radians in [0, π/2]: the acute angle between the lines
/// AB and BC.
pub fn gamma(pos: &Position) -> f64 {
    let theta = pos.transmission();
    theta.min(std::f64::consts::PI - theta)
}

/// The smallest transmission angle over a motion and where it occurs.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct GammaMin {
    /// γ_min, degrees (0…90).
    pub gamma_deg: f64,
    /// Crank angle where it occurs (the first such position of the sweep), degrees.
    pub phi1_deg: f64,
}

impl GammaMin {
    /// Whether γ_min is below the usual 40° limit ([`GAMMA_LIMIT_DEG`]).
    pub fn below_limit(&self) -> bool {
        self.gamma_deg < GAMMA_LIMIT_DEG
    }
}

/// γ_min over `positions` (`None` for no position). Ties keep the first position.
pub fn gamma_min(positions: &[Position]) -> Option<GammaMin> {
    let mut best: Option<GammaMin> = None;
    for p in positions {
        let g = deg(gamma(p));
        if best.is_none_or(|b| g < b.gamma_deg) {
            best = Some(GammaMin { gamma_deg: g, phi1_deg: deg(p.phi1) });
        }
    }
    best
}

#[cfg(test)]
#[allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the code under test calls"
)]
mod tests {
    use super::*;
    use crate::geom::Side;
    use crate::solve::fourbar::{Geometry, position};

    fn template() -> Geometry {
        super::super::test_template()
    }

    /// γ by the law of cosines in the triangle ABC, from |AC| alone (no solver): |AC|² =
    /// l_ab² + l_bc² − 2·l_ab·l_bc·cos θ, and |AC|² = l1² + d² − 2·l1·d·cos φ1 in O1AC.
    fn gamma_closed_form(g: &Geometry, phi1: f64) -> f64 {
        let d = (g.c - g.o1).norm();
        let ac2 = g.l1 * g.l1 + d * d - 2.0 * g.l1 * d * phi1.cos();
        let theta = ((g.l_ab * g.l_ab + g.l_bc * g.l_bc - ac2) / (2.0 * g.l_ab * g.l_bc)).acos();
        theta.min(std::f64::consts::PI - theta)
    }

    #[test]
    fn gamma_agrees_with_the_law_of_cosines_over_a_turn() {
        let g = template();
        for k in 0..360 {
            let phi1 = f64::from(k).to_radians();
            let p = position(&g, phi1, Side::Left).unwrap();
            assert!((gamma(&p) - gamma_closed_form(&g, phi1)).abs() < 1e-12, "{k}°");
        }
    }

    #[test]
    fn the_template_has_gamma_min_23_07_deg_at_phi1_0() {
        let g = template();
        let ps: Vec<Position> =
            (0..360).map(|k| position(&g, f64::from(k).to_radians(), Side::Left).unwrap()).collect();
        let m = gamma_min(&ps).unwrap();
        // cos θ = (0.1² + 0.1² − 0.04²) / (2·0.1·0.1) = 0.92 at φ1 = 0 (|AC| = 0.04).
        let expected = 0.92f64.acos().to_degrees();
        assert!((m.gamma_deg - expected).abs() < 1e-9, "{m:?}");
        assert_eq!(format!("{:.2}", m.gamma_deg), "23.07");
        assert_eq!(m.phi1_deg, 0.0);
        assert!(m.below_limit());
    }
}
