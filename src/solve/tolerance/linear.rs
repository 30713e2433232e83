//! The linear stack-up of one output component at one position from its sensitivities
//! s_i = ∂output/∂dimension_i (seed 001's methods with the mechanism's coefficients):
//!
//! - mean shift Σ s_i·m_i (m_i the middle of dimension i's band),
//! - worst case ±Σ |s_i|·t_i about it (t_i the half band),
//! - σ = √Σ (s_i·σ_i)² and the RSS half band 3σ (for every dimension normal at Cp = 1,
//!   σ_i = t_i/3 and 3σ = √Σ (s_i·t_i)², the textbook RSS),
//! - each dimension's share of the worst case, |s_i|·t_i / Σ|s_j|·t_j, and of the variance,
//!   (s_i·σ_i)² / σ².

use super::model::Dimension;

/// One dimension's part in a component's tolerance at one position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Share {
    /// ∂component/∂dimension (component unit per dimension unit).
    pub sensitivity: f64,
    /// Its worst-case part |s|·t.
    pub worst_case: f64,
    /// Share of the worst case, percent.
    pub pct_worst_case: f64,
    /// Share of the variance, percent.
    pub pct_variance: f64,
}

/// The linear stack-up of one component at one position.
#[derive(Debug, Clone, PartialEq)]
pub struct Linear {
    /// Mean shift Σ s_i·m_i.
    pub shift: f64,
    /// Worst-case half band Σ |s_i|·t_i.
    pub worst_case: f64,
    /// σ = √Σ (s_i·σ_i)².
    pub sigma: f64,
    /// The RSS half band 3σ.
    pub rss: f64,
    /// Per dimension, in the order of the dimensions.
    pub shares: Vec<Share>,
}

/// The stack-up of a component with sensitivities `s` (one per dimension of `dims`).
pub fn stack(s: &[f64], dims: &[Dimension]) -> Linear {
    let mut shift = 0.0;
    let mut wc = 0.0;
    let mut var = 0.0;
    for (si, d) in s.iter().zip(dims) {
        shift += si * d.mid();
        wc += si.abs() * d.half();
        var += (si * d.sigma()) * (si * d.sigma());
    }
    let shares = s
        .iter()
        .zip(dims)
        .map(|(si, d)| {
            let w = si.abs() * d.half();
            Share {
                sensitivity: *si,
                worst_case: w,
                pct_worst_case: if wc > 0.0 { 100.0 * w / wc } else { 0.0 },
                pct_variance: if var > 0.0 { 100.0 * (si * d.sigma()) * (si * d.sigma()) / var } else { 0.0 },
            }
        })
        .collect();
    let sigma = var.sqrt();
    Linear { shift, worst_case: wc, sigma, rss: 3.0 * sigma, shares }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::tolerance::model::Distribution;

    #[test]
    fn worst_case_rss_and_shares_of_two_dimensions() {
        let d = |upper: f64, lower: f64| Dimension {
            name: "d".into(),
            nominal: 1.0,
            upper,
            lower,
            distribution: Distribution::Normal { k: 3.0 },
        };
        // s = (2, −1), t = (0.1, 0.2): WC = 0.2 + 0.2 = 0.4; RSS = √(0.04 + 0.04).
        let dims = [d(0.1, -0.1), d(0.3, -0.1)];
        let l = stack(&[2.0, -1.0], &dims);
        assert!((l.worst_case - 0.4).abs() < 1e-15);
        assert!((l.rss - 0.08f64.sqrt()).abs() < 1e-15);
        assert!((l.shift - -0.1).abs() < 1e-15);
        assert!((l.shares[0].pct_worst_case - 50.0).abs() < 1e-12);
        assert!((l.shares[1].pct_variance - 50.0).abs() < 1e-12);
    }
}
