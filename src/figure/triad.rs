//! Figure: triad. (Placeholder: filled in by its issue.)
