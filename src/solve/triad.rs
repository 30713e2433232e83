//! Triad solver. (Placeholder: filled in by the triad issue.)

/// Why a triad cannot be solved.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TriadError {
    /// Not implemented yet.
    #[error("the triad solver is not implemented yet")]
    NotImplemented,
}
