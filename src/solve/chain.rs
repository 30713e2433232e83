//! Chain solver. (Placeholder: filled in by the chain issue.)

/// Why a chain cannot be solved.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ChainError {
    /// Not implemented yet.
    #[error("the chain solver is not implemented yet")]
    NotImplemented,
}
