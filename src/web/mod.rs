//! The browser's entry: a scene's TOML text in, its products out as named byte buffers — the
//! same bytes `mechdraw run` writes for it — or the command line's error message; and the
//! live page's session over one scene (docs/web.md).
//!
//! [`scene_files`] is the whole of a run and builds on every target (the native tests check
//! it against the command line, byte for byte). [`Session`] keeps a scene open: a field, a
//! drag or a build step changes the student's TOML ([`edit`], [`build`]: one value at a
//! time, comments and layout kept) and solves it again. [`fields`] names every number of a
//! scene as a person reads it, [`share`] packs a scene into a link. On `wasm32` the `js`
//! module exports all of it to the page through wasm-bindgen.
//!
//! No file system, no terminal, no threads: the module is built without the feature
//! `parallel`, so the run's parallel iterators run in order (src/par.rs), and the Monte
//! Carlo of a chain is seeded from the scene (the same bits on any thread count).

pub mod build;
pub mod edit;
pub mod fields;
#[cfg(target_arch = "wasm32")]
pub mod js;
pub mod print;
pub mod reshape;
mod session;
pub mod share;
pub mod synthesis;

use std::path::PathBuf;

pub use fields::Parameter;
pub use session::Session;

use crate::Error;
use crate::run::bytes::{self, WriteOptions};
use crate::run::products::Picture;
use crate::run::{self, RunOptions};
use crate::scene::{self, Loaded};

/// What the page refuses besides what the command line refuses.
#[derive(Debug, thiserror::Error)]
pub enum PageError {
    /// What the command line says about the scene (its exact words).
    #[error(transparent)]
    Run(#[from] Error),
    /// A share link that does not open.
    #[error(transparent)]
    Share(#[from] share::ShareError),
    /// A build step that cannot be made. Example: a driver on a link with no ground pivot.
    #[error("{0}")]
    Build(String),
    /// A drag in edit mode that changes nothing it could. Example: a triad's picture.
    #[error("{0}")]
    Reshape(String),
}

/// What the page asks for besides the scene.
#[derive(Debug, Clone, Copy, Default)]
pub struct WebOptions {
    /// A motion's per-position SVG frames and its HTML viewer too (the command line's
    /// default; `false` is `--no-frames`).
    pub frames: bool,
    /// PNG copies of every SVG (`--png`; refused in a build without the `png` feature, as
    /// the page's module is).
    pub png: bool,
}

/// One scene's run in memory.
#[derive(Debug, Clone)]
pub struct SceneFiles {
    /// The files, paths relative to the output directory (`/`-separated), in the canonical
    /// order of [`bytes::write`](fn@bytes::write): what `mechdraw run SCENE --out DIR`
    /// writes into `DIR`, byte for byte.
    pub files: Vec<(String, Vec<u8>)>,
    /// The JSON summary (`--json`).
    pub summary: serde_json::Value,
    /// The short report the command line prints on stderr.
    pub report: String,
    /// Warnings (skipped positions, dead points, ...), one line each.
    pub warnings: Vec<String>,
}

/// Solves the scene in `text` and returns its files as `mechdraw run` writes them, with the
/// command line's default DXF options. `file` names the scene in messages (as the path does
/// on the command line). The error's text is what the command line prints after `error: `.
pub fn scene_files(text: &str, file: &str, opts: WebOptions) -> Result<SceneFiles, Error> {
    let loaded = Loaded { path: PathBuf::from(file), scene: scene::parse(text, file, &[])?, text: text.to_string() };
    let ropts = RunOptions { png: opts.png, no_frames: !opts.frames, ..RunOptions::default() };
    // Before solving, as the command line: a mistyped step is refused at once.
    run::check_positions(&loaded.scene, file)?;
    let p = run::products(&loaded, &ropts)?;
    if let (Picture::Motion(a), Some(source)) = (&p.picture, p.positions) {
        run::check_drawn(file, source.field, a.len(), source.advice)?;
    }
    let wopts = WriteOptions { png: ropts.png, no_frames: ropts.no_frames, dxf: ropts.dxf };
    let files = bytes::to_files(&p, &wopts)?;
    Ok(SceneFiles { files, summary: p.summary, report: p.report, warnings: p.warnings })
}

/// The report of the scene in `text` (`mechdraw report`: [`crate::run::report`]) as named
/// byte buffers, as `mechdraw report SCENE --paper PAPER [--positions LIST]` writes them:
/// the pages as SVG, the chosen positions' table and the JSON; the PDF too in a build with
/// the PDF writer (feature `pdf`; the live page's module leaves it out, so the page offers
/// the pages to print). `paper` is `a4` or `a3`; `positions` as `--positions` takes it
/// (`""`: the report's choice). Errors are the command line's words.
pub fn report_files(text: &str, file: &str, paper: &str, positions: &str) -> Result<SceneFiles, Error> {
    let opts = report_options(paper, positions)?;
    let loaded = Loaded { path: PathBuf::from(file), scene: scene::parse(text, file, &[])?, text: text.to_string() };
    let r = run::report::report(&loaded, &opts)?;
    let files = bytes::report_files(&r, false)?;
    let report = r.parts.iter().map(|(t, p)| format!("p. {p:>2}  {t}")).collect::<Vec<_>>().join("\n");
    Ok(SceneFiles { files, summary: r.summary, report, warnings: r.warnings })
}

/// The live page's "report" download of the scene in `text` ([`report_files`]'s report):
/// `<name>-report.html`, every page in one document to print ([`print::print_document`]:
/// the page's module has no PDF writer; the browser's Print → Save as PDF makes the PDF),
/// then the PDF where the build has its writer, the chosen positions' table and the JSON,
/// as the command line writes them. The pages' SVGs are in the document, not offered apart.
pub fn report_download(text: &str, file: &str, paper: &str, positions: &str) -> Result<SceneFiles, Error> {
    let mut r = report_files(text, file, paper, positions)?;
    let paper = report_options(paper, positions)?.paper;
    let name = r.summary.get("name").and_then(serde_json::Value::as_str).unwrap_or("scene").to_string();
    let (pages, rest): (Vec<_>, Vec<_>) = r.files.into_iter().partition(|(n, _)| n.starts_with("report/"));
    let svgs: Vec<&str> = pages.iter().filter_map(|(_, b)| std::str::from_utf8(b).ok()).collect();
    let html = print::print_document(&format!("{name} — report"), paper, &svgs);
    r.files = std::iter::once((format!("{name}-report.html"), html.into_bytes())).chain(rest).collect();
    Ok(r)
}

/// `--paper` and `--positions` as the command line reads them.
pub fn report_options(paper: &str, positions: &str) -> Result<run::report::ReportOptions, Error> {
    let paper = paper.parse().map_err(|message| Error::Option { option: "--paper".into(), message })?;
    let positions = if positions.trim().is_empty() {
        None
    } else {
        let values = positions
            .parse::<run::positions::Positions>()
            .map_err(|message| Error::Option { option: "--positions".into(), message })?;
        Some(values)
    };
    Ok(run::report::ReportOptions { paper, positions })
}
