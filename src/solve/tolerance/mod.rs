//! Tolerances of a mechanism (issue 34): seed 001's stack-up (worst case, RSS, Monte Carlo,
//! each dimension's share) applied to a linkage's outputs over its whole motion.
//!
//! A tolerance study has
//! - the toleranced dimensions ([`Dimension`]: a scene number, its band, its distribution),
//! - a model of the mechanism ([`Model`]: the nominal solved over its positions, and a
//!   sample — every dimension deviated — solved at the same positions on the nominal's
//!   assembly mode; [`Sensitive`]: the exact ∂channel/∂dimension at each position),
//! - the reported components ([`Component`]: a point's x, y, and its deviation normal to
//!   and along its nominal path; an angle's value).
//!
//! [`linear_all`] stacks each component up at each position from its sensitivities
//! ([`linear::stack`]); [`monte_carlo::run`] samples the whole motion, streaming each
//! component's deviation into per-position statistics ([`stats::Tally`], over a range fixed
//! from the linear result by [`ranges`]); [`verdicts`] says where the linear result is not
//! to be trusted. Nothing here knows scene files or drawings.

pub mod exact;
pub mod fourbar;
pub mod linear;
pub mod linkage;
pub mod model;
pub mod monte_carlo;
pub mod stats;
pub mod triad;

pub use linear::{Linear, Share};
pub use model::{Component, Dimension, Distribution, Projection};
pub use monte_carlo::{Model, MonteCarlo};
pub use stats::{Summary, Tally};

/// The histogram's range about a component's linear mean shift, in worst-case half bands:
/// the Monte Carlo's samples fall inside it unless the motion is far from linear there
/// (those beyond are still counted, in the end bins, with the extremes).
pub const RANGE_WORST_CASES: f64 = 2.0;
/// Default histogram bins per component and position.
pub const DEFAULT_BINS: usize = 400;
/// Default fraction by which the Monte Carlo's σ may differ from the linear σ before a
/// position's linear result is called untrustworthy.
pub const DEFAULT_TRUST_FRACTION: f64 = 0.1;

/// A linear σ under this fraction of its output's worst-case band is rounding, not a
/// deviation ([`verdicts`] does not compare it with the Monte Carlo's).
pub const ROUNDING: f64 = 1e-9;
/// A position is near a dead point when the tolerances' worst case can move its dyad by
/// more than this fraction of its distance from the dead point (see
/// [`Sensitive::dead_point`]).
pub const DEAD_POINT_FRACTION: f64 = 0.5;

/// An angle difference in degrees wrapped into (−180, 180] (a sample's angle less the
/// nominal's).
#[inline]
pub(crate) fn wrap_deg(d: f64) -> f64 {
    let w = d - 360.0 * libm::floor((d + 180.0) / 360.0);
    if w == -180.0 { 180.0 } else { w }
}

/// A model whose channels have exact sensitivities.
pub trait Sensitive: Model {
    /// ∂channel/∂dimension at position `k`, channel-major (`channels · dimensions`
    /// values); `None` at a singular position (a dead point).
    fn sensitivities(&self, k: usize) -> Option<Vec<f64>>;
    /// At position `k`, why the linear result is not to be trusted there because of a
    /// dead point, if it is not: the tolerances' worst case (dimensions `dims`) can move the
    /// mechanism by more than [`DEAD_POINT_FRACTION`] of its distance from one.
    fn dead_point(&self, k: usize, dims: &[Dimension]) -> Option<String>;
}

/// A component's sensitivities at position `k` from the channels' (`s`, channel-major,
/// `np` dimensions).
pub fn component_sensitivities(comp: &Component, k: usize, s: &[f64], np: usize) -> Vec<f64> {
    (0..np)
        .map(|j| match &comp.projection {
            Projection::Channel(c) => s[c * np + j],
            Projection::Along { x, y, dirs } => dirs[k].x * s[x * np + j] + dirs[k].y * s[y * np + j],
        })
        .collect()
}

/// The linear stack-up of every component (`comps`) at every position, position-major;
/// `None` at a singular position.
pub fn linear_all<M: Sensitive>(model: &M, dims: &[Dimension], comps: &[Component]) -> Vec<Option<Vec<Linear>>> {
    use crate::par::prelude::*;
    (0..model.positions())
        .into_par_iter()
        .map(|k| {
            let s = model.sensitivities(k)?;
            Some(comps.iter().map(|c| linear::stack(&component_sensitivities(c, k, &s, dims.len()), dims)).collect())
        })
        .collect()
}

/// Each position's and component's histogram range (position-major, as the tallies): the
/// linear mean shift ± [`RANGE_WORST_CASES`] worst cases; at a singular position, the
/// component's widest range elsewhere; never empty.
pub fn ranges(linear: &[Option<Vec<Linear>>], components: usize) -> Vec<(f64, f64)> {
    let mut widest = vec![0.0f64; components];
    for l in linear.iter().flatten() {
        for (w, c) in widest.iter_mut().zip(l) {
            *w = w.max(c.worst_case);
        }
    }
    let floor = widest.iter().fold(0.0f64, |a, b| a.max(*b)) * 1e-9;
    let floor = if floor > 0.0 { floor } else { 1e-15 };
    let mut out = Vec::with_capacity(linear.len() * components);
    for l in linear {
        for c in 0..components {
            let (centre, wc) = match l {
                Some(l) => (l[c].shift, l[c].worst_case),
                None => (0.0, widest[c]),
            };
            let half = (RANGE_WORST_CASES * wc).max(floor);
            out.push((centre - half, centre + half));
        }
    }
    out
}

/// Each position's dead-point note ([`Sensitive::dead_point`]; at a singular position,
/// that the sensitivities are unbounded).
pub fn dead_points<M: Sensitive>(model: &M, dims: &[Dimension], linear: &[Option<Vec<Linear>>]) -> Vec<Option<String>> {
    (0..model.positions())
        .map(|k| match linear[k] {
            None => Some("dead point: the sensitivities are unbounded".to_string()),
            Some(_) => model.dead_point(k, dims),
        })
        .collect()
}

/// Where the linear result is not to be trusted, per position (empty: trusted): a dead
/// point near (`dead`, from [`dead_points`]), samples that cannot be assembled there, or a
/// component whose Monte Carlo σ differs from the linear σ by more than `fraction` of it
/// (or whose mean departs from the linear mean shift by more than `fraction` of σ). A
/// component whose linear σ is at rounding level — under [`ROUNDING`] of its own worst case,
/// or of the largest worst case of any component of the same output over the motion (a
/// slider's velocity across its guide, identically 0) — is not compared: its Monte Carlo σ
/// is rounding too, and their ratio says nothing.
pub fn verdicts(
    dead: &[Option<String>],
    comps: &[Component],
    linear: &[Option<Vec<Linear>>],
    mc: &MonteCarlo,
    fraction: f64,
) -> Vec<Vec<String>> {
    // The largest worst-case band of each output, over its components and the motion.
    let mut band: std::collections::HashMap<&str, f64> = std::collections::HashMap::new();
    for lin in linear.iter().flatten() {
        for (comp, l) in comps.iter().zip(lin) {
            let b = band.entry(comp.output.as_str()).or_insert(0.0);
            *b = b.max(l.worst_case);
        }
    }
    (0..dead.len())
        .map(|k| {
            let mut notes: Vec<String> = dead[k].iter().cloned().collect();
            if mc.failed_at[k] > 0 {
                notes.push(format!("{} samples cannot be assembled here", mc.failed_at[k]));
            }
            let Some(lin) = &linear[k] else { return notes };
            for (c, comp) in comps.iter().enumerate() {
                let Some(s) = mc.tallies[k * comps.len() + c].summary() else { continue };
                let l = &lin[c];
                // σ at rounding level: nothing to compare.
                let output_band = band.get(comp.output.as_str()).copied().unwrap_or(0.0);
                if l.sigma == 0.0 || l.sigma <= ROUNDING * l.worst_case.max(output_band) {
                    continue;
                }
                let ratio = s.sigma / l.sigma;
                let bias = (s.mean - l.shift) / l.sigma;
                if (ratio - 1.0).abs() > fraction {
                    notes.push(format!("{}: Monte Carlo σ is {:.3} × the linear σ", comp.name, ratio));
                } else if bias.abs() > fraction {
                    notes.push(format!("{}: Monte Carlo mean is {:+.3} σ off the linear mean", comp.name, bias));
                }
            }
            notes
        })
        .collect()
}

/// Why a tolerance study cannot be made as asked.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ToleranceError {
    /// The nominal mechanism has no position to watch.
    #[error("the nominal mechanism has no solved position to study")]
    NoPositions,
}
