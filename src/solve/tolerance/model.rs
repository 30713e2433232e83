//! What a tolerance analysis is given: the toleranced dimensions (band and distribution)
//! and the watched outputs' components.

use crate::geom::Vector;

/// How a dimension's deviation is spread over its band in the Monte Carlo (and which σ the
/// RSS takes for it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Distribution {
    /// Normal about the band's middle, not truncated, with the half band t = k·σ (k = 3·Cp:
    /// k = 3 for Cp = 1, the ±3σ process filling its tolerance).
    Normal {
        /// The half band in standard deviations, > 0.
        k: f64,
    },
    /// Uniform over the band: σ = t/√3.
    Uniform,
    /// Symmetric triangular over the band: σ = t/√6.
    Triangular,
}

impl Distribution {
    /// σ of a deviation with half band `half`.
    pub fn sigma(self, half: f64) -> f64 {
        match self {
            Distribution::Normal { k } => half / k,
            Distribution::Uniform => half / 3f64.sqrt(),
            Distribution::Triangular => half / 6f64.sqrt(),
        }
    }

    /// The name the scene and the reports use: `normal`, `uniform`, `triangular`.
    pub fn name(self) -> &'static str {
        match self {
            Distribution::Normal { .. } => "normal",
            Distribution::Uniform => "uniform",
            Distribution::Triangular => "triangular",
        }
    }
}

/// One toleranced dimension: a number of the scene, its band of deviations and its
/// distribution. Deviations are in the scene field's own unit (degrees for `alpha_deg`).
#[derive(Debug, Clone, PartialEq)]
pub struct Dimension {
    /// The scene field, as `--set` names it (`l_ab`, `c[0]`, `body[2].points.B[1]`).
    pub name: String,
    /// Its nominal value.
    pub nominal: f64,
    /// Upper deviation (+a), ≥ `lower`.
    pub upper: f64,
    /// Lower deviation (−b), ≤ `upper`.
    pub lower: f64,
    /// How the Monte Carlo spreads it.
    pub distribution: Distribution,
}

impl Dimension {
    /// Middle of the band: the mean shift (upper + lower)/2.
    pub fn mid(&self) -> f64 {
        0.5 * (self.upper + self.lower)
    }

    /// Half band t = (upper − lower)/2.
    pub fn half(&self) -> f64 {
        0.5 * (self.upper - self.lower)
    }

    /// σ of the deviation under its distribution.
    pub fn sigma(&self) -> f64 {
        self.distribution.sigma(self.half())
    }
}

/// What one reported component is made of, from the model's channels (a point's x and y
/// deviations, an angle's).
#[derive(Debug, Clone, PartialEq)]
pub enum Projection {
    /// One channel as it is.
    Channel(usize),
    /// The component of the vector (channel `x`, channel `y`) along a direction given per
    /// position (unit vectors; a zero vector where it is undefined).
    Along {
        /// Channel of the x deviation.
        x: usize,
        /// Channel of the y deviation.
        y: usize,
        /// The direction at each position.
        dirs: Vec<Vector>,
    },
}

impl Projection {
    /// The component at position `k` from that position's channel values.
    #[inline]
    pub fn of(&self, k: usize, channels: &[f64]) -> f64 {
        match self {
            Projection::Channel(c) => channels[*c],
            Projection::Along { x, y, dirs } => {
                let d = dirs[k];
                d.x * channels[*x] + d.y * channels[*y]
            }
        }
    }
}

/// A reported component: its column name and how it is made.
#[derive(Debug, Clone, PartialEq)]
pub struct Component {
    /// `M.x`, `M.normal`, `phi3_deg.value`: the CSV's column prefix.
    pub name: String,
    /// The watched output it belongs to (`M`, `phi3_deg`).
    pub output: String,
    /// `x`, `y`, `normal`, `along` or `value`.
    pub part: &'static str,
    /// Whether its nominal value is the output's own (x, y, value) or 0 (a deviation
    /// component: normal, along).
    pub absolute: bool,
    /// How it is made from the channels.
    pub projection: Projection,
}
