//! Figure: linkage. (Placeholder: filled in by its issue.)
