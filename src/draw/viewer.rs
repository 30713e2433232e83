//! The self-contained HTML viewer: SVG frames with a slider, play/pause and speed, that
//! works from `file://` (everything inline, no network).
//!
//! (API fixed by the skeleton; the page is filled in by the four-bar kinematics issue.)

/// One frame of the viewer.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// Label shown with the slider (e.g. `φ1 = 90°` or `t = 0.250 s`).
    pub label: String,
    /// The frame as an SVG document.
    pub svg: String,
}

/// The viewer page for `frames`, titled `title`.
pub fn html(title: &str, frames: &[Frame]) -> String {
    let _ = frames;
    format!("<!doctype html><title>{title}</title>")
}
