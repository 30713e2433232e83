//! The constraints' first and second variations at any coordinates, for the tolerance
//! studies' sensitivities of the rates (issue 34): Φq·v, γ(q, q̇) (Φq·q̈ = γ) and γ's
//! derivative along a change of q. With them the derivative of the velocity equation
//! Φq·q̇ = −Φt and of the acceleration equation with respect to a dimension is a linear
//! system in Φq again (see `solve::tolerance::linkage`).
//!
//! γ is a homogeneous quadratic in q̇ but for the drivers' f″ (which depends on neither q
//! nor q̇): γ(q, v) = −B(v, v) + f″, B(v, w) = (Φq·v)_q·w the symmetric second variation
//! of Φ. So B(v, w) = (γ(v − w) − γ(v + w))/4 exactly, but for rounding
//! ([`Solver::second_variation_at`]).

use super::kinematics::{Con, GuideTerms, Solver, con_gamma, con_jacobian};
use super::{LinkageError, Pose, col, fill_poses, pz, rate};
use crate::geom::perp;

impl Solver {
    /// Φq(q)·v at the coordinates `q` (raw rows, in the solver's constraint order).
    pub fn jacobian_times_at(&self, q: &[f64], v: &[f64]) -> Vec<f64> {
        let mut poses = Vec::with_capacity(q.len() / 3);
        fill_poses(q, &mut poses);
        let mut out = vec![0.0; self.m];
        let mut r = 0;
        for c in &self.cons {
            con_jacobian(c, &poses, |row, a, dx, dy, dphi| {
                if let Some(k) = col(a) {
                    out[r + row] += dx * v[k] + dy * v[k + 1] + dphi * v[k + 2];
                }
            });
            r += c.rows();
        }
        out
    }

    /// γ at time `t`, coordinates `q` and velocities `qd` (Φq·q̈ = γ; raw rows).
    pub fn gamma_at(&mut self, t: f64, q: &[f64], qd: &[f64]) -> Result<Vec<f64>, LinkageError> {
        self.eval_laws(t)?;
        let mut poses = Vec::with_capacity(q.len() / 3);
        fill_poses(q, &mut poses);
        let mut out = vec![0.0; self.m];
        let mut r = 0;
        for c in &self.cons {
            con_gamma(c, &poses, qd, &self.laws, &mut out[r..r + c.rows()]);
            r += c.rows();
        }
        Ok(out)
    }

    /// B(v, w) = (Φq·v)_q·w at time `t` and coordinates `q` (symmetric in v and w), from γ
    /// by polarisation: (γ(v − λw) − γ(v + λw))/(4λ), λ = |v|/|w| so that neither
    /// vector is lost in the other's rounding.
    pub fn second_variation_at(&mut self, t: f64, q: &[f64], v: &[f64], w: &[f64]) -> Result<Vec<f64>, LinkageError> {
        let norm = |x: &[f64]| x.iter().map(|a| a * a).sum::<f64>().sqrt();
        let (nv, nw) = (norm(v), norm(w));
        if nv == 0.0 || nw == 0.0 {
            return Ok(vec![0.0; self.m]);
        }
        let l = nv / nw;
        let minus: Vec<f64> = v.iter().zip(w).map(|(a, b)| a - l * b).collect();
        let plus: Vec<f64> = v.iter().zip(w).map(|(a, b)| a + l * b).collect();
        let (gm, gp) = (self.gamma_at(t, q, &minus)?, self.gamma_at(t, q, &plus)?);
        Ok(gm.iter().zip(&gp).map(|(m, p)| (m - p) / (4.0 * l)).collect())
    }

    /// ∂γ/∂q·dq at coordinates `q` and velocities `qd` (raw rows; the drivers' f″ does not
    /// depend on q): each constraint's γ differentiated along the bodies' changes
    /// (dx, dy, dφ) in `dq`.
    pub fn gamma_derivative_at(&self, q: &[f64], qd: &[f64], dq: &[f64]) -> Vec<f64> {
        let mut poses = Vec::with_capacity(q.len() / 3);
        fill_poses(q, &mut poses);
        let mut out = vec![0.0; self.m];
        let mut r = 0;
        for c in &self.cons {
            con_gamma_derivative(c, &poses, qd, dq, &mut out[r..r + c.rows()]);
            r += c.rows();
        }
        out
    }
}

/// One constraint's ∂γ/∂q·dq (its rows into `out`), γ as `con_gamma` makes it.
fn con_gamma_derivative(c: &Con, q: &[Pose], qd: &[f64], dq: &[f64], out: &mut [f64]) {
    match *c {
        Con::Coincide { a, b } => {
            // γ = s_a·ω_a² − s_b·ω_b², s = A(φ)·local: ds = s⊥·dφ.
            let (pa, pb) = (pz(q, a.body), pz(q, b.body));
            let (wa, wb) = (rate(qd, a.body).1, rate(qd, b.body).1);
            let (fa, fb) = (rate(dq, a.body).1, rate(dq, b.body).1);
            let g = perp(pa.rot(a.local)) * (fa * wa * wa) - perp(pb.rot(b.local)) * (fb * wb * wb);
            out[0] = g.x;
            out[1] = g.y;
        }
        Con::Angle { .. } => out[0] = 0.0,
        Con::OnLine { p, q: qa, guide, u } | Con::Distance { p, q: qa, guide, u, .. } => {
            let GuideTerms { sp, sq, d, dd, ug, ng, centripetal, wp, wg } = GuideTerms::new(q, qd, p, qa, guide, u);
            let (drp, fp) = rate(dq, p.body);
            let (drg, fg) = rate(dq, guide);
            // Their changes along dq.
            let (dsp, dsq) = (perp(sp) * fp, perp(sq) * fg);
            let d_d = drp + dsp - drg - dsq;
            let d_dd = perp(dsp) * wp - perp(dsq) * wg;
            let (d_ug, d_ng) = (ng * fg, -ug * fg);
            let d_c = dsp * (wp * wp) - dsq * (wg * wg);
            out[0] = match *c {
                // γ = ωg²·n·d + 2ωg·u·ḋ + n·c
                Con::OnLine { .. } => {
                    wg * wg * (d_ng.dot(&d) + ng.dot(&d_d))
                        + 2.0 * wg * (d_ug.dot(&dd) + ug.dot(&d_dd))
                        + d_ng.dot(&centripetal)
                        + ng.dot(&d_c)
                }
                // γ = f″ + ωg²·u·d − 2ωg·n·ḋ + u·c
                _ => {
                    wg * wg * (d_ug.dot(&d) + ug.dot(&d_d)) - 2.0 * wg * (d_ng.dot(&dd) + ng.dot(&d_dd))
                        + d_ug.dot(&centripetal)
                        + ug.dot(&d_c)
                }
            };
        }
    }
}
