//! Linkage solver. (Placeholder: filled in by the linkage issue.)

/// Why a linkage cannot be solved.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LinkageError {
    /// Not implemented yet.
    #[error("the linkage solver is not implemented yet")]
    NotImplemented,
}
