//! The JavaScript side (wasm32 only): [`run_scene`] and the [`Files`] it returns, the live
//! page's [`Live`] session, and the build, sketch and share-link functions. Every function
//! that can fail throws its message as a string: the command line's words for the scene.

use wasm_bindgen::prelude::*;

use super::{PageError, SceneFiles, WebOptions, build, scene_files, share};
use crate::geom::Point;

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

fn msg(e: impl std::fmt::Display) -> String {
    e.to_string()
}

fn points_json(points: &[(String, Point)]) -> serde_json::Value {
    points.iter().map(|(n, p)| serde_json::json!([n, p.x, p.y])).collect()
}

fn state_json(st: &crate::figure::shared::animation::DriveState) -> String {
    serde_json::json!({ "label": st.label, "points": points_json(&st.points), "residual": st.residual }).to_string()
}

/// A scene open in the page ([`Session`](super::Session)): every method that changes it
/// throws the command line's message and leaves it as it was on an error.
#[wasm_bindgen]
pub struct Live(super::Session);

#[wasm_bindgen]
impl Live {
    /// Opens the scene in `toml`, named `file` in messages.
    #[wasm_bindgen(constructor)]
    pub fn new(toml: &str, file: &str) -> Result<Live, String> {
        super::Session::new(toml, file).map(Live).map_err(msg)
    }

    /// `--set path=value` written into the text, and solve again.
    pub fn set(&mut self, path: &str, value: &str) -> Result<(), String> {
        self.0.set(path, value).map_err(msg)
    }

    /// A new scene text (the TOML editor, an undo, a build step), and solve again.
    pub fn replace(&mut self, toml: &str) -> Result<(), String> {
        self.0.replace(toml).map_err(msg)
    }

    /// The scene's text as it stands.
    pub fn scene_text(&self) -> String {
        self.0.scene_text().to_string()
    }

    /// Every number of the scene as JSON: `[{"path", "value", "integer", "label", "unit",
    /// "group", "min", "max", "detail"}, ...]`.
    pub fn parameters(&self) -> Result<String, String> {
        let ps = self.0.parameters().map_err(msg)?;
        let list: Vec<serde_json::Value> = ps
            .iter()
            .map(|p| {
                serde_json::json!({ "path": p.path, "value": p.value, "integer": p.integer, "label": p.label,
                    "unit": p.unit, "group": p.group, "min": p.min, "max": p.max, "detail": p.detail })
            })
            .collect();
        Ok(serde_json::Value::Array(list).to_string())
    }

    /// Number of positions (1 for a still picture).
    pub fn positions(&self) -> usize {
        self.0.positions()
    }

    /// Position `k`'s label.
    pub fn label(&self, k: usize) -> String {
        self.0.label(k)
    }

    /// Position `k`'s frame, an SVG document (`""` past the last).
    pub fn frame(&self, k: usize) -> String {
        self.0.frame(k).unwrap_or_default()
    }

    /// Position `k`'s named points as JSON (`{"label", "points": [[name, x, y], ...],
    /// "residual"}`, model units; `""` for a still picture).
    pub fn points(&self, k: usize) -> String {
        self.0.points(k).map(|st| state_json(&st)).unwrap_or_default()
    }

    /// The points edit mode drags at position `k`, as JSON `[[name, x, y], ...]` (`""`
    /// for a still picture).
    pub fn edit_points(&self, k: usize) -> String {
        self.0.edit_points(k).map(|p| points_json(&p).to_string()).unwrap_or_default()
    }

    /// Edit mode: `point` dragged to (`x`, `y`) at position `k` changes the dimensions it
    /// carries (written with `decimals` decimals); the scene is solved again.
    pub fn reshape(&mut self, point: &str, x: f64, y: f64, k: usize, decimals: usize) -> Result<(), String> {
        self.0.reshape(point, Point::new(x, y), k, decimals).map_err(msg)
    }

    /// SVG user units per model unit of the frames.
    pub fn user_units_per_model(&self) -> f64 {
        self.0.user_units_per_model()
    }

    /// Drags `point` towards the model point (`x`, `y`); returns the state reached as
    /// [`Live::points`] gives it, with `"drive"` (φ1 in degrees, or t in seconds) and
    /// `"position"` (the nearest position).
    pub fn drag(&mut self, point: &str, x: f64, y: f64) -> Result<String, String> {
        let st = self.0.drag(point, Point::new(x, y)).map_err(msg)?;
        let mut v: serde_json::Value = serde_json::from_str(&state_json(&st)).unwrap_or_default();
        if let Some((k, s)) = self.0.dragged() {
            v["drive"] = serde_json::json!(s);
            v["position"] = serde_json::json!(k);
        }
        Ok(v.to_string())
    }

    /// The frame where the last drag left the mechanism (`""` before any drag).
    pub fn dragged_frame(&self) -> String {
        self.0.dragged_frame().unwrap_or_default()
    }

    /// A motion's base SVG, shared by every frame (`""` for a still picture).
    pub fn base(&self) -> String {
        self.0.base().unwrap_or_default().to_string()
    }

    /// What position `k`'s frame draws on the base (`""`: draw [`Live::frame`] whole).
    pub fn moving(&self, k: usize) -> String {
        self.0.moving(k).unwrap_or_default()
    }

    /// What the dragged frame draws on the base (`""`: draw [`Live::dragged_frame`]).
    pub fn dragged_moving(&self) -> String {
        self.0.dragged_moving().unwrap_or_default()
    }

    /// The scene's sheets as JSON: `[[suffix, svg], ...]` (made when first asked for
    /// after a change).
    pub fn sheets(&self) -> Result<String, String> {
        serde_json::to_string(&self.0.sheets().map_err(msg)?).map_err(msg)
    }

    /// The scene's diagrams as JSON: `[[stem, svg], ...]` (made when first asked for
    /// after a change).
    pub fn diagrams(&self) -> Result<String, String> {
        serde_json::to_string(&self.0.diagrams().map_err(msg)?).map_err(msg)
    }

    /// Each diagram's marker at position `k` as JSON `[[x, y] or null, ...]`, SVG user units.
    pub fn diagram_markers(&self, k: usize) -> Result<String, String> {
        serde_json::to_string(&self.0.diagram_markers(k).map_err(msg)?).map_err(msg)
    }

    /// The JSON summary, pretty (made when first asked for after a change).
    pub fn summary(&self) -> Result<String, String> {
        let p = self.0.products().map_err(msg)?;
        serde_json::to_string_pretty(&p.summary).map_err(msg)
    }

    /// A triad's modes as JSON (`{"phi1_deg": [...], "pattern_phi1_deg", "drawn"}`), `""`
    /// for the other kinds.
    pub fn modes(&self) -> Result<String, String> {
        Ok(self.0.modes().map_err(msg)?.map(|m| m.to_string()).unwrap_or_default())
    }

    /// The warnings, one a line.
    pub fn warnings(&self) -> String {
        self.0.warnings().join("\n")
    }

    /// A synthesis's designed scene (`<name>-design.toml`), to open in the page; `""` for the
    /// other kinds.
    pub fn design(&self) -> String {
        self.0.design_text().unwrap_or_default()
    }

    /// The file name of a synthesis's designed scene (`<name>-design.toml`: the page's title
    /// and storage key once the design is opened); `""` for the other kinds.
    pub fn design_file(&self) -> String {
        self.0.design_file().unwrap_or_default()
    }

    /// The scene's file name in messages from now on (`file`, a design's `<name>-design.toml`).
    pub fn rename(&mut self, file: &str) {
        self.0.rename(file);
    }

    /// The scene's file name, as messages give it.
    pub fn file(&self) -> String {
        self.0.file().to_string()
    }

    /// The report of the scene as it stands (`paper` `a4` or `a3`, `positions` as
    /// `--positions` takes it, `""` for the report's choice), as the page offers it: its
    /// pages in one HTML document to print to PDF, its table and JSON (the PDF is the command
    /// line's: this module has no PDF writer).
    pub fn report(&self, paper: &str, positions: &str) -> Result<Files, String> {
        self.0.report_download(paper, positions).map(Files).map_err(msg)
    }

    /// The files of the scene as it stands (without frames), for downloads.
    pub fn files(&self) -> Result<Files, String> {
        let p = self.0.products().map_err(msg)?;
        let files = self.0.files().map_err(msg)?;
        Ok(Files(SceneFiles {
            files,
            summary: p.summary.clone(),
            report: p.report.clone(),
            warnings: p.warnings.clone(),
        }))
    }
}

/// Solves the scene in `toml` (named `file` in messages) and returns its files, with a
/// motion's frames and viewer when `frames`; throws the command line's error message.
#[wasm_bindgen]
pub fn run_scene(toml: &str, file: &str, frames: bool) -> Result<Files, String> {
    scene_files(toml, file, WebOptions { frames, png: false }).map(Files).map_err(msg)
}

/// `toml` after a build step (JSON, [`build::Step`]: `{"tool": "link", "ends": ["ground.O1",
/// [0.04, 0.0]]}`), coordinates written with `decimals` decimals.
#[wasm_bindgen]
pub fn build_step(toml: &str, file: &str, step: &str, decimals: usize) -> Result<String, String> {
    let step: build::Step =
        serde_json::from_str(step).map_err(|e| PageError::Build(format!("not a build step: {e}"))).map_err(msg)?;
    build::apply(toml, file, &step, decimals).map_err(msg)
}

/// The sketch of `toml` as JSON ([`build::Sketch`]); `""` when the text is not TOML.
#[wasm_bindgen]
pub fn sketch(toml: &str) -> String {
    toml.parse::<toml::Table>().ok().and_then(|t| serde_json::to_string(&build::sketch(&t)).ok()).unwrap_or_default()
}

/// The share link's fragment value for `toml` (`v1.…`).
#[wasm_bindgen]
pub fn share_link(toml: &str) -> String {
    share::encode(toml)
}

/// The scene's text in a share link's fragment value; throws what is wrong with the link.
#[wasm_bindgen]
pub fn open_share_link(link: &str) -> Result<String, String> {
    share::decode(link).map_err(msg)
}
