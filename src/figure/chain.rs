//! Figure: chain. (Placeholder: filled in by its issue.)
