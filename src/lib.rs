//! # mechdraw
//!
//! Planar mechanisms (triads, four-bars, general linkages with revolute and prismatic
//! joints) and dimensional chains: solved to machine precision and written as drawings
//! (DXF for any CAD program, SVG frames, a live HTML page), diagrams, CSV and a JSON summary.
//!
//! The pipeline, one module per arrow:
//!
//! ```text
//! scene (TOML) ─► scene::Scene ─► solve ─► figure ─► draw::Drawing ─► draw::{dxf, svg} (+ run::page, the live page)
//!                                    └──────────────► report (JSON, CSV)
//! ```
//!
//! Angles are radians inside and degrees (`_deg`) in scene files and reports, measured
//! from +x, counter-clockwise positive.
#![forbid(unsafe_code)]
#![warn(missing_docs)]

#[cfg(feature = "cli")]
pub mod bench;
#[cfg(feature = "cli")]
pub mod diff;
pub mod draw;
mod error;
pub mod figure;
pub mod geom;
mod par;
pub mod report;
pub mod run;
pub mod scene;
pub mod solve;
pub mod text;
pub mod web;

pub use error::Error;
