//! The chain as the solver takes it: features (nodes), independent dimensions between them
//! (edges), the dependent dimensions to analyse, and the distribution of the deviations.
//! A `chain` scene is checked into these types (`scene::chain`); the solver knows nothing
//! of scene files.

use serde::Deserialize;

/// Where the features came from: it decides whether coinciding end points are merged.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Form {
    /// The seed's matrix N: feature 0 is the zero point, feature i+1 the end of `W[i]`;
    /// end points that coincide are not merged yet (the analysis merges them).
    Matrix,
    /// Named features.
    Named,
}

/// One independent dimension: an edge from feature `from` to feature `to`.
#[derive(Debug, Clone, PartialEq)]
pub struct Dimension {
    /// Name (`w1`... or as given).
    pub name: String,
    /// Index of the base feature.
    pub from: usize,
    /// Index of the end feature.
    pub to: usize,
    /// Nominal x_to − x_from (signed).
    pub nominal: f64,
    /// Upper deviation of the size |x_to − x_from| (≥ lower).
    pub upper: f64,
    /// Lower deviation of the size.
    pub lower: f64,
}

impl Dimension {
    /// Middle of the tolerance band (the mean shift of the size).
    pub fn mid(&self) -> f64 {
        0.5 * (self.upper + self.lower)
    }
    /// Half the tolerance band (the symmetric tolerance about `mid`).
    pub fn half(&self) -> f64 {
        0.5 * (self.upper - self.lower)
    }
    /// +1 when the dimension points along the axis (x_to > x_from), −1 otherwise.
    pub fn sign(&self) -> f64 {
        if self.nominal < 0.0 { -1.0 } else { 1.0 }
    }
}

/// A dependent dimension Z = x_right − x_left.
#[derive(Debug, Clone, PartialEq)]
pub struct Dependent {
    /// Name (`Z1`...).
    pub name: String,
    /// Left end feature index (b_l).
    pub left: usize,
    /// Right end feature index (b_p).
    pub right: usize,
    /// How the ends were written (for reports): `[25, 80]` or `[A, B]`.
    pub label: String,
    /// Specification limits [LSL, USL].
    pub spec: Option<[f64; 2]>,
}

/// A system of parallel dimensional chains: what [`super::analyse`] takes.
#[derive(Debug, Clone, PartialEq)]
pub struct Chain {
    /// Which input form the features came from.
    pub form: Form,
    /// Feature names (matrix form: `0` for the zero point, else the value of the
    /// dimension ending there).
    pub features: Vec<String>,
    /// Independent dimensions.
    pub dimensions: Vec<Dimension>,
    /// Dependent dimensions.
    pub dependent: Vec<Dependent>,
}

/// Statistical distribution of each dimension inside its tolerance band (Monte Carlo).
/// Deserialized from its lowercase name, as written in scene files.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Distribution {
    /// Normal with 3σ = half the tolerance band (not truncated).
    #[default]
    Normal,
    /// Uniform over the tolerance band.
    Uniform,
    /// Symmetric triangular over the tolerance band, peak at its middle.
    Triangular,
}

impl Distribution {
    /// Standard deviation of a deviation with half-band `t` under this distribution.
    pub fn sigma(self, t: f64) -> f64 {
        match self {
            Distribution::Normal => t / 3.0,
            Distribution::Uniform => t / 3f64.sqrt(),
            Distribution::Triangular => t / 6f64.sqrt(),
        }
    }

    /// The name as written in scene files.
    pub fn name(self) -> &'static str {
        match self {
            Distribution::Normal => "normal",
            Distribution::Uniform => "uniform",
            Distribution::Triangular => "triangular",
        }
    }
}
