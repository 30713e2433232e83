//! Numbers only: the solvers. Nothing here knows about drawings or files.

pub mod chain;
pub mod expr;
pub mod fourbar;
pub mod linkage;
pub mod stroke;
pub mod synthesis;
pub mod tolerance;
pub mod triad;

/// A solver failure, by mechanism kind.
#[derive(Debug, thiserror::Error)]
pub enum SolveError {
    /// Triad solver.
    #[error(transparent)]
    Triad(#[from] triad::TriadError),
    /// Four-bar kinematics.
    #[error(transparent)]
    Fourbar(#[from] fourbar::FourbarError),
    /// General linkage solver.
    #[error(transparent)]
    Linkage(#[from] linkage::LinkageError),
    /// Dimensional chains.
    #[error(transparent)]
    Chain(#[from] chain::ChainError),
    /// Kinematic synthesis: a requirement that cannot be met.
    #[error(transparent)]
    Synthesis(#[from] synthesis::SynthesisError),
}
