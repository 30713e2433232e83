//! Figure: fourbar. (Placeholder: filled in by its issue.)
