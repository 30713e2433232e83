//! Driver laws: expressions of t, parsed once and differentiated exactly.
//! (Placeholder: filled in by the general-linkage issue.)
