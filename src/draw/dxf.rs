//! DXF writer (R12 by default) through the `dxf` crate. See ../shared/dxf-notes.md.
//! Implemented with the drawing-layer work of the triad issue.
