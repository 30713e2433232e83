//! `mechdraw bench`: every solving method on the same problems, time per solve against
//! error, written as an SVG chart (log–log), a CSV and a Markdown table.
//!
//! Error is measured against an independent, high-accuracy answer (the residual of the
//! original equations at the method's answer, and the distance to a polished root), never
//! against the method itself. Times are medians over batches, in nanoseconds per solve.

pub mod timing;

use serde::Serialize;

/// One point of the chart: a method at one setting on one problem.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Measurement {
    /// The problem (e.g. `triad-popa`, `fourbar-chebyshev`, `shaper`).
    pub problem: String,
    /// The method (e.g. `pattern`, `newton`, `all-modes`, `closed-form dyad`, `general newton`).
    pub method: String,
    /// The setting that distinguishes points of one method (e.g. `eps=1e-6`).
    pub setting: String,
    /// Median time per solve, nanoseconds.
    pub ns_per_solve: f64,
    /// Error against the independent reference (dimensionless, relative); `None` when the
    /// row measures cost only (e.g. a whole run's outputs).
    pub error: Option<f64>,
}
