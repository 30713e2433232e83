//! Diagrams: quantities against a parameter (phi1, t), and histograms, as a neutral
//! [`Drawing`] (axes, ticks, units, title, legend) that the SVG writer turns into a
//! picture. Shared by every mechanism kind.
//!
//! (API fixed by the skeleton; the drawing is filled in by the four-bar kinematics issue.)

use crate::draw::{DimStyle, Drawing};

/// One curve of a diagram.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend label (e.g. `omega2`).
    pub label: String,
    /// Abscissae, same length as `y`.
    pub x: Vec<f64>,
    /// Ordinates; non-finite values break the curve (never drawn).
    pub y: Vec<f64>,
}

/// A line diagram: one or more series against a common x axis.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagram {
    /// Title above the plot (e.g. `Angular velocity of the coupler`).
    pub title: String,
    /// x-axis label with unit (e.g. `φ1 [°]`).
    pub x_label: String,
    /// y-axis label with unit (e.g. `ω2 [rad/s]`).
    pub y_label: String,
    /// The curves.
    pub series: Vec<Series>,
}

/// A histogram: counts of samples in equal bins.
#[derive(Debug, Clone, PartialEq)]
pub struct Histogram {
    /// Title above the plot.
    pub title: String,
    /// x-axis label with unit.
    pub x_label: String,
    /// Left edge of the first bin.
    pub x0: f64,
    /// Bin width (> 0).
    pub bin_width: f64,
    /// Sample count per bin.
    pub counts: Vec<u64>,
    /// Vertical marker lines (e.g. spec limits, mean) with labels.
    pub markers: Vec<(f64, String)>,
}

/// Draws a line diagram.
pub fn diagram(d: &Diagram) -> Drawing {
    let _ = d;
    Drawing::new(DimStyle { text_height: 1.0, arrow_size: 1.0 })
}

/// Draws a histogram.
pub fn histogram(h: &Histogram) -> Drawing {
    let _ = h;
    Drawing::new(DimStyle { text_height: 1.0, arrow_size: 1.0 })
}
