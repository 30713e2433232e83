//! Basins of attraction of the triad's methods: which assembly mode each start phi1 leads
//! to, per method, over a full turn of starts.

use super::reference;
use crate::geom::{Side, angle_of, rad};
use crate::solve::triad::{
    Configuration, NewtonOptions, Orientation, PatternOptions, Triad, TriadError, newton, pattern, pattern::construct,
};

/// Where one start led.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Basin {
    /// Converged to the reference mode with this index.
    Mode(usize),
    /// The start triangle does not exist at this phi1 (circle (A1, l12) misses circle 2).
    NoStart,
    /// The method failed by name (stalled, no intersection mid-way, not converged, singular).
    Failed,
    /// Converged to a configuration that is no reference mode (must never happen).
    Stray,
}

/// One method's strip: its name and the outcome of every start.
#[derive(Debug, Clone, PartialEq)]
pub struct Strip {
    /// Method and branch, e.g. `pattern (A2 right, ccw)`.
    pub method: String,
    /// Outcomes for starts phi1 = k · 360°/n, k = 0 … n−1.
    pub outcomes: Vec<Basin>,
}

/// A result is the mode it is when within this relative distance of it.
pub const SAME_MODE_REL: f64 = 1e-5;

fn classify(t: &Triad, modes: &[Configuration], r: Result<Configuration, TriadError>) -> Basin {
    match r {
        Ok(c) => match reference::nearest_mode(t, modes, &c.a) {
            Some((k, d)) if d <= SAME_MODE_REL => Basin::Mode(k),
            _ => Basin::Stray,
        },
        Err(_) => Basin::Failed,
    }
}

/// The strips of the pattern method (the seed's branches A2 right/ccw, and A2 left/ccw)
/// and of Newton–Raphson started from the pattern method's start triangle, for `n` starts.
pub fn triad_basins(t: &Triad, modes: &[Configuration], n: usize) -> Vec<Strip> {
    let starts: Vec<f64> = (0..n).map(|k| rad(360.0 * k as f64 / n as f64)).collect();
    let mut strips = Vec::new();
    for (a2, name) in [(Side::Right, "pattern, A2 right"), (Side::Left, "pattern, A2 left")] {
        let outcomes = starts
            .iter()
            .map(|&phi1| {
                if construct(t, phi1, a2, Orientation::Ccw).is_none() {
                    return Basin::NoStart;
                }
                let o = PatternOptions { phi1_start: phi1, a2, tol: 1e-9, ..Default::default() };
                classify(t, modes, pattern(t, &o).map(|s| s.configuration))
            })
            .collect();
        strips.push(Strip { method: format!("{name}, ccw"), outcomes });
    }
    for (a2, name) in [(Side::Right, "Newton from A2 right"), (Side::Left, "Newton from A2 left")] {
        let outcomes = starts
            .iter()
            .map(|&phi1| {
                let Some(a) = construct(t, phi1, a2, Orientation::Ccw) else { return Basin::NoStart };
                let start = [0, 1, 2].map(|i| angle_of(a[i] - t.o[i]));
                classify(t, modes, newton(t, &NewtonOptions { start, max_iterations: 50 }).map(|s| s.configuration))
            })
            .collect();
        strips.push(Strip { method: format!("{name}, ccw"), outcomes });
    }
    strips
}
