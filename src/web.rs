//! The browser's entry: a scene's TOML text in, its products out as named byte buffers — the
//! same bytes `mechdraw run` writes for it — or the command line's error message.
//!
//! [`scene_files`] is the whole of it and builds on every target (the native tests check it
//! against the command line, byte for byte). On `wasm32` the `js` module exports it to
//! JavaScript through wasm-bindgen:
//!
//! ```js
//! const files = mechdraw.run_scene(tomlText, "fourbar.toml", /* frames */ false);
//! for (let i = 0; i < files.count(); i++) download(files.name(i), files.bytes(i));
//! ```
//!
//! No file system, no terminal, no thread pool of its own: rayon runs its parallel
//! iterators on the calling thread where threads cannot be spawned (wasm32-unknown-unknown),
//! and the Monte Carlo of a chain is seeded from the scene.

use std::path::PathBuf;

use crate::Error;
use crate::run::bytes::{self, WriteOptions};
use crate::run::products::Picture;
use crate::run::{self, RunOptions};
use crate::scene::{self, Loaded};

/// What the page asks for besides the scene.
#[derive(Debug, Clone, Copy, Default)]
pub struct WebOptions {
    /// A motion's per-position SVG frames and its HTML viewer too (the command line's
    /// default; `false` is `--no-frames`).
    pub frames: bool,
    /// PNG copies of every SVG (`--png`).
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
    let loaded = Loaded { path: PathBuf::from(file), scene: scene::parse(text, file, &[])? };
    let ropts = RunOptions { png: opts.png, no_frames: !opts.frames, ..RunOptions::default() };
    let p = run::products(&loaded, &ropts)?;
    if let (Picture::Motion(a), Some(source)) = (&p.picture, p.positions) {
        run::check_drawn(file, source.field, a.len(), source.advice)?;
    }
    let wopts = WriteOptions { png: ropts.png, no_frames: ropts.no_frames, dxf: ropts.dxf };
    let files = bytes::to_files(&p, &wopts)?;
    Ok(SceneFiles { files, summary: p.summary, report: p.report, warnings: p.warnings })
}

/// The JavaScript side (wasm32 only): [`run_scene`](js::run_scene) and the [`Files`](js::Files)
/// it returns.
#[cfg(target_arch = "wasm32")]
pub mod js {
    use wasm_bindgen::prelude::*;

    use super::{SceneFiles, WebOptions, scene_files};

    /// A run's files, handed to JavaScript one by one.
    #[wasm_bindgen]
    pub struct Files(SceneFiles);

    #[wasm_bindgen]
    impl Files {
        /// How many files.
        pub fn count(&self) -> usize {
            self.0.files.len()
        }

        /// File `i`'s path relative to the output directory (`""` past the end).
        pub fn name(&self, i: usize) -> String {
            self.0.files.get(i).map(|(n, _)| n.clone()).unwrap_or_default()
        }

        /// File `i`'s bytes (a `Uint8Array`; empty past the end).
        pub fn bytes(&self, i: usize) -> Vec<u8> {
            self.0.files.get(i).map(|(_, b)| b.clone()).unwrap_or_default()
        }

        /// The JSON summary, pretty (as `--json` prints it).
        pub fn summary(&self) -> String {
            serde_json::to_string_pretty(&self.0.summary).unwrap_or_default()
        }

        /// The report the command line prints on stderr.
        pub fn report(&self) -> String {
            self.0.report.clone()
        }

        /// The warnings, one a line.
        pub fn warnings(&self) -> String {
            self.0.warnings.join("\n")
        }
    }

    /// Solves the scene in `toml` (named `file` in messages) and returns its files, with a
    /// motion's frames and viewer when `frames`; throws the command line's error message.
    #[wasm_bindgen]
    pub fn run_scene(toml: &str, file: &str, frames: bool) -> Result<Files, String> {
        scene_files(toml, file, WebOptions { frames, png: false }).map(Files).map_err(|e| e.to_string())
    }
}
