//! One scene through the pipeline: scene → solve → figure → writers, and a report.
//! Each kind has its own pipeline file; this module holds what they share: the options,
//! the outcome and the dispatch. Nothing is written unless everything could be
//! (see [`output::Output`]).

mod chain;
mod fourbar;
mod linkage;
pub mod output;
mod triad;

use std::path::PathBuf;

use crate::Error;
use crate::scene::{Loaded, Scene};

/// What the user asked for on the command line, besides the scene.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Output directory; `None` solves and reports without writing files.
    pub out_dir: Option<PathBuf>,
    /// Also write PNG copies of the diagrams.
    pub png: bool,
    /// Skip the per-position SVG frames and the HTML viewer.
    pub no_frames: bool,
    /// Show a progress bar on the terminal while frames are written.
    pub progress: bool,
    /// `--drag BODY.POINT=x,y` requests (general linkages).
    pub drag: Vec<String>,
    /// DXF version and dimension encoding (`--dxf-version`, `--dxf-dimensions`); the scale
    /// is set per scene from its units (`RunOptions::dxf_for`).
    pub dxf: crate::draw::dxf::DxfOptions,
}

impl RunOptions {
    /// The DXF options for a scene in `units`: its model units written as millimetres.
    pub(crate) fn dxf_for(&self, units: crate::scene::Units) -> crate::draw::dxf::DxfOptions {
        let mm_per_unit = match units {
            crate::scene::Units::Mm => 1.0,
            crate::scene::Units::Si => 1000.0,
        };
        crate::draw::dxf::DxfOptions { mm_per_unit, ..self.dxf }
    }
}

/// What a run produced.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// The JSON summary (printed with `--json`).
    pub summary: serde_json::Value,
    /// A short human-readable report for the terminal.
    pub report: String,
    /// Warnings (skipped positions, dead points, ...), one line each.
    pub warnings: Vec<String>,
    /// Files written, in order.
    pub written: Vec<PathBuf>,
}

/// Solves `loaded` and writes its outputs as `opts` asks.
pub fn run(loaded: &Loaded, opts: &RunOptions) -> Result<Outcome, Error> {
    let file = loaded.path.display().to_string();
    if !opts.drag.is_empty() && !matches!(loaded.scene, Scene::Linkage(_)) {
        return Err(Error::Option {
            option: "--drag".into(),
            message: format!("only a linkage scene can be dragged; {file} is a {} scene", loaded.scene.kind()),
        });
    }
    match &loaded.scene {
        Scene::Triad(s) => triad::run(s, &file, opts),
        Scene::Fourbar(s) => fourbar::run(s, &file, opts),
        Scene::Linkage(s) => linkage::run(s, &file, opts),
        Scene::Chain(s) => chain::run(s, &file, opts),
    }
}

/// Most positions a run draws: each is a DXF layer and an SVG frame (~20 KB each for the
/// four-bar, and a linkage frame also carries the whole paths, so its frames grow with the
/// square of the count). 3600 is a 0.1° crank step over a turn. The library can still
/// solve a finer scene without an output directory ([`RunOptions::out_dir`] = `None`).
pub const MAX_DRAWN_POSITIONS: usize = 3600;

/// Refuses to draw more than [`MAX_DRAWN_POSITIONS`] positions, naming the field that sets
/// their number (so that a mistyped step does not fill the disk).
pub(crate) fn check_drawn(file: &str, field: &str, count: usize, advice: &str) -> Result<(), Error> {
    if count <= MAX_DRAWN_POSITIONS {
        return Ok(());
    }
    Err(Error::Scene(crate::scene::SceneError::Field {
        file: file.to_string(),
        field: field.to_string(),
        message: format!(
            "gives {count} positions to draw; a run draws at most {MAX_DRAWN_POSITIONS} (each is a DXF layer and an SVG frame, so a mistyped value would fill the disk): {advice}"
        ),
    }))
}

/// Wraps a solver error with the scene file.
pub(crate) fn solve_err(file: &str) -> impl FnOnce(crate::solve::SolveError) -> Error + '_ {
    move |source| Error::Solve { file: file.to_string(), source }
}
