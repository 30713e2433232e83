//! Figure: forces. (Placeholder: filled in by its issue.)
