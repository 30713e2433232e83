//! Dimensional chains (seed 001, Humienny 1989): numbers only.
//!
//! - [`model`]: the solver's input, [`Chain`] (features, dimensions, dependent dimensions)
//!   and the Monte Carlo [`Distribution`]; a `chain` scene is checked into these.
//! - [`graph`]: the chain as a graph (features = nodes, dimensions = edges): feature
//!   coordinates, the seed's over-dimensioning check, redundant dimensions with the loop each
//!   one closes (a plain repeat or a contradiction), groups of features not tied to the
//!   rest (under-dimensioning), and the dimensional function of a dependent dimension
//!   Z = [b_l, b_p] (the seed's eq. 4).
//! - [`stackup`]: the tolerance stack-up of a dimensional function: worst case, RSS,
//!   modified RSS, mean shift of asymmetric tolerances, seeded Monte Carlo.

pub mod graph;
pub mod model;
pub mod stackup;

pub use graph::{Analysis, Function, Redundant, Term, analyse};
pub use model::{Chain, Dependent, Dimension, Distribution, Form};
pub use stackup::{Contribution, MonteCarlo, Stack, monte_carlo, stack};

/// Why a chain question cannot be answered.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ChainError {
    /// The two ends of a dependent dimension are not tied together by dimensions, so Z is
    /// not determined. Example: `features = ["A", "B", "C"]` with only A–B dimensioned and
    /// `dependent = [["A", "C"]]`.
    #[error("dependent dimension {z} is not determined: {why}")]
    NotDetermined {
        /// Name of the dependent dimension.
        z: String,
        /// Its ends as written, which end is not tied to which, and the untied groups.
        why: String,
    },
}
