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
use crate::draw::Drawing;
use crate::draw::svg::{self, SvgOptions};
use crate::figure::shared::animation::{Drive, DriveState};
use crate::geom::Point;
use crate::run::bytes::{self, WriteOptions};
use crate::run::products::{Picture, Products};
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
    /// One printed sheet per position and their PDF (`--sheets a4|a3`; four-bar and
    /// linkage scenes).
    pub sheets: Option<crate::figure::shared::sheet::Paper>,
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
    let ropts = RunOptions { png: opts.png, no_frames: !opts.frames, sheets: opts.sheets, ..RunOptions::default() };
    let p = run::products(&loaded, &ropts)?;
    if let (Picture::Motion(a), Some(source)) = (&p.picture, p.positions) {
        run::check_drawn(file, source.field, a.len(), source.advice)?;
    }
    let wopts = WriteOptions { png: ropts.png, no_frames: ropts.no_frames, dxf: ropts.dxf };
    let files = bytes::to_files(&p, &wopts)?;
    Ok(SceneFiles { files, summary: p.summary, report: p.report, warnings: p.warnings })
}

/// A number of the scene that the page offers as a field or slider: its `--set` path and
/// its value in the scene's text.
#[derive(Debug, Clone, PartialEq)]
pub struct Parameter {
    /// The `--set` path (`l_bc`, `phi1_deg.step`, `dynamics.force[0].value`,
    /// `body[1].points.B[0]`).
    pub path: String,
    /// Its value (with the session's changes applied).
    pub value: f64,
    /// Whether the scene writes it as an integer (a count: set it as one).
    pub integer: bool,
}

impl Parameter {
    /// The value as `--set` takes it (`12` for an integer, `0.125` for a float).
    pub fn text(&self) -> String {
        if self.integer { format!("{}", self.value as i64) } else { format!("{:?}", self.value) }
    }
}

/// Every number in `table`, depth first in the table's order, as `--set` paths.
fn numbers(prefix: &str, value: &toml::Value, out: &mut Vec<Parameter>) {
    match value {
        toml::Value::Integer(i) => out.push(Parameter { path: prefix.to_string(), value: *i as f64, integer: true }),
        toml::Value::Float(f) => out.push(Parameter { path: prefix.to_string(), value: *f, integer: false }),
        toml::Value::Array(items) => {
            for (i, v) in items.iter().enumerate() {
                numbers(&format!("{prefix}[{i}]"), v, out);
            }
        }
        toml::Value::Table(t) => {
            for (k, v) in t {
                let path = if prefix.is_empty() { k.clone() } else { format!("{prefix}.{k}") };
                numbers(&path, v, out);
            }
        }
        _ => {}
    }
}

/// A scene open in the page: its text, the changes made to it (as `--set` overrides, applied
/// in order), and its products. A change solves the scene again and draws its picture (the
/// motion with its polygons and forces at every position: [`RunOptions::picture_only`]);
/// the rest of the products (sheets, diagrams, tables, the summary, the files) is made when
/// first asked for. A change that the scene does not accept leaves the session as it was
/// (the page keeps its picture) and returns the command line's message.
pub struct Session {
    file: String,
    text: String,
    sets: Vec<(String, String)>,
    /// The products of the scene as it stands.
    made: Made,
    /// A motion's frame options and its base written once (frames splice each position onto
    /// it).
    motion: Option<(SvgOptions, String)>,
    /// Where the last drag left the drive: (nearest position, drive value).
    dragged: Option<(usize, f64)>,
    /// Every position's named points, solved at the first drag (the nearest position of every
    /// later pointer event is looked up here).
    positions_points: std::sync::OnceLock<Vec<Vec<(String, Point)>>>,
}

/// What a change made: everything (a kind whose whole run is cheap), or the picture and the
/// warnings, with the rest made on first ask.
enum Made {
    /// Everything `mechdraw run` makes.
    Complete(Products),
    /// The picture and the warnings ([`RunOptions::picture_only`]), and everything once asked.
    Picture(Products, Box<std::sync::OnceLock<Products>>),
}

impl Made {
    /// The products the picture and the warnings come from.
    fn shown(&self) -> &Products {
        match self {
            Made::Complete(p) | Made::Picture(p, _) => p,
        }
    }
}

/// Relative step of the drive's central differences (of its span) in a drag.
const DRAG_STEP_REL: f64 = 1e-6;

/// A drag's drive value is found to this fraction of the drive's span.
const DRAG_TOL_REL: f64 = 1e-13;

impl std::fmt::Debug for Session {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Session").field("file", &self.file).field("sets", &self.sets).finish_non_exhaustive()
    }
}

impl Session {
    /// Opens the scene in `text` (named `file` in messages).
    pub fn new(text: &str, file: &str) -> Result<Session, Error> {
        let (products, motion) = solve(text, file, &[])?;
        Ok(Session {
            file: file.to_string(),
            text: text.to_string(),
            sets: Vec::new(),
            made: products,
            motion,
            dragged: None,
            positions_points: std::sync::OnceLock::new(),
        })
    }

    /// Sets the number (or any TOML value) at `path` to `value`, as `--set path=value` would,
    /// and solves again; on an error nothing changes.
    pub fn set(&mut self, path: &str, value: &str) -> Result<(), Error> {
        let mut sets = self.sets.clone();
        sets.retain(|(p, _)| p != path);
        sets.push((path.to_string(), value.to_string()));
        let (products, motion) = solve(&self.text, &self.file, &sets)?;
        (self.sets, self.made, self.motion, self.dragged) = (sets, products, motion, None);
        self.positions_points = std::sync::OnceLock::new();
        Ok(())
    }

    /// Replaces the scene's text (the page's TOML editor) and forgets the changes made
    /// field by field; on an error nothing changes.
    pub fn replace(&mut self, text: &str) -> Result<(), Error> {
        let (products, motion) = solve(text, &self.file, &[])?;
        (self.text, self.sets, self.made, self.motion, self.dragged) =
            (text.to_string(), Vec::new(), products, motion, None);
        self.positions_points = std::sync::OnceLock::new();
        Ok(())
    }

    /// The scene's text with the changes written into it (what a download of the scene is).
    pub fn scene_text(&self) -> Result<String, Error> {
        let table = table_with(&self.text, &self.file, &self.sets)?;
        toml::to_string(&table).map_err(|e| Error::Export { what: self.file.clone(), message: e.to_string() })
    }

    /// Every number of the scene, with the changes applied: the page's fields.
    pub fn parameters(&self) -> Result<Vec<Parameter>, Error> {
        let mut out = Vec::new();
        numbers("", &toml::Value::Table(table_with(&self.text, &self.file, &self.sets)?), &mut out);
        Ok(out)
    }

    /// All the products of the scene as it stands, as `mechdraw run` makes them (made on the
    /// first call after a change).
    pub fn products(&self) -> Result<&Products, Error> {
        let full = match &self.made {
            Made::Complete(p) => return Ok(p),
            Made::Picture(_, full) => full,
        };
        if let Some(p) = full.get() {
            return Ok(p);
        }
        let loaded = loaded(&self.text, &self.file, &self.sets)?;
        let p = run::products(&loaded, &RunOptions { no_frames: true, ..RunOptions::default() })?;
        Ok(full.get_or_init(|| p))
    }

    /// A triad's assembly modes as the page lists them: `{"phi1_deg": [...], "pattern_phi1_deg":
    /// 75.77 or null, "drawn": index}` (from the JSON summary's `solutions`, `pattern` and
    /// `primary`); `None` for the other kinds.
    pub fn modes(&self) -> Result<Option<serde_json::Value>, Error> {
        let s = &self.products()?.summary;
        if s["kind"] != "triad" {
            return Ok(None);
        }
        let phi1: Vec<serde_json::Value> =
            s["solutions"].as_array().map_or(&[][..], Vec::as_slice).iter().map(|m| m["phi1_deg"].clone()).collect();
        Ok(Some(serde_json::json!({
            "phi1_deg": phi1,
            "pattern_phi1_deg": s["pattern"]["phi1_deg"],
            "drawn": s["primary"],
        })))
    }

    /// The warnings of the scene as it stands (gaps, dead points, γ_min, ...), one line each.
    pub fn warnings(&self) -> &[String] {
        &self.made.shown().warnings
    }

    /// Number of positions of a motion (1 for a still picture).
    pub fn positions(&self) -> usize {
        match &self.made.shown().picture {
            Picture::Motion(a) => a.len().max(1),
            Picture::Still(_) => 1,
        }
    }

    /// The label of position `k` (`φ1 = 90°`, `t = 0.2500 s`; empty for a still picture).
    pub fn label(&self, k: usize) -> String {
        match &self.made.shown().picture {
            Picture::Motion(a) => a.labels.get(k).cloned().unwrap_or_default(),
            Picture::Still(_) => String::new(),
        }
    }

    /// Position `k`'s frame as an SVG document: for a motion, byte for byte the command
    /// line's `frames/<name>/<position>.svg`; for a still picture, `<name>.svg`. `None` past
    /// the last position.
    pub fn frame(&self, k: usize) -> Option<String> {
        match &self.made.shown().picture {
            Picture::Still(d) => (k == 0).then(|| bytes::picture_svg(d)),
            Picture::Motion(a) if k < a.len() => self.whole(&a.pose(k)),
            Picture::Motion(_) => None,
        }
    }

    /// A motion's base: what every frame shares (the header, the ground, the traced paths,
    /// the scales and titles), an SVG document of its own. `None` for a still picture.
    pub fn base(&self) -> Option<&str> {
        self.motion.as_ref().map(|(_, base)| base.as_str())
    }

    /// What position `k`'s frame draws on top of [`Session::base`]: the frame is the base's
    /// document with these elements inserted before its closing tag (what the page replaces
    /// as the motion plays or a point is dragged). `None` past the last position, for a still
    /// picture, or when the frame cannot be split so (then draw [`Session::frame`] whole).
    pub fn moving(&self, k: usize) -> Option<String> {
        let Picture::Motion(a) = &self.made.shown().picture else { return None };
        self.part(&(k < a.len()).then(|| a.pose(k))?)
    }

    /// What the frame where the last drag left the mechanism draws on top of
    /// [`Session::base`] (as [`Session::moving`]).
    pub fn dragged_moving(&self) -> Option<String> {
        self.part(&self.dragged_pose()?)
    }

    /// What moves in the frame where the last drag left the mechanism.
    fn dragged_pose(&self) -> Option<Drawing> {
        let (k, s) = self.dragged?;
        (self.drive()?.draw)(k, s).ok()
    }

    /// A motion's frame with `pose` on its base, whole (as the command line writes it).
    fn whole(&self, pose: &Drawing) -> Option<String> {
        let Picture::Motion(a) = &self.made.shown().picture else { return None };
        let (opts, base) = self.motion.as_ref()?;
        Some(svg::splice(base, &svg::to_string(pose, opts)).unwrap_or_else(|| svg::to_string(&a.frame_of(pose), opts)))
    }

    /// What `pose` draws on the motion's base (`None` when the frame does not split so).
    fn part(&self, pose: &Drawing) -> Option<String> {
        let (opts, base) = self.motion.as_ref()?;
        svg::spliced_part(base, &svg::to_string(pose, opts)).map(str::to_string)
    }

    /// SVG user units per model unit of the frames (paper millimetres per model unit, or 1):
    /// a frame's user point (x, y) is the model point (x, −y) / this.
    pub fn user_units_per_model(&self) -> f64 {
        match &self.made.shown().picture {
            Picture::Motion(a) => a.base.paper_mm_per_unit.unwrap_or(1.0),
            Picture::Still(d) => d.paper_mm_per_unit.unwrap_or(1.0),
        }
    }

    fn drive(&self) -> Option<&Drive> {
        match &self.made.shown().picture {
            Picture::Motion(a) => a.drive.as_ref(),
            Picture::Still(_) => None,
        }
    }

    /// The named points of position `k` of a motion (model units), for picking one to drag.
    pub fn points(&self, k: usize) -> Option<DriveState> {
        let d = self.drive()?;
        (d.solve)(k, *d.values.get(k)?).ok()
    }

    /// Drags `point` (a name of [`Session::points`]) towards `target` (model units): the
    /// mechanism moves as its joints allow, to the drive value at which the point comes
    /// nearest the target (for a crank pin, exactly the crank angle of the target). The
    /// search starts at the position whose point is nearest and stays in its assembly mode.
    pub fn drag(&mut self, point: &str, target: Point) -> Result<DriveState, Error> {
        let bad = |message: String| Error::Option { option: "drag".into(), message };
        let d = self.drive().ok_or_else(|| bad("only a motion with a drive can be dragged".into()))?;
        let n = d.values.len();
        let at = |k: usize, s: f64| -> Option<Point> {
            let st = (d.solve)(k, s).ok()?;
            st.points.iter().find(|(name, _)| name == point).map(|(_, p)| *p)
        };
        if self.points(0).is_some_and(|st| st.points.iter().all(|(name, _)| name != point)) {
            let names: Vec<String> = self.points(0).into_iter().flat_map(|st| st.points).map(|(n, _)| n).collect();
            return Err(bad(format!("no point `{point}` in the mechanism; its points: {}", names.join(", "))));
        }
        // The position whose point is nearest the target.
        let all = self.positions_points.get_or_init(|| {
            (0..n).map(|k| (d.solve)(k, d.values[k]).map(|st| st.points).unwrap_or_default()).collect()
        });
        let k = all
            .iter()
            .enumerate()
            .filter_map(|(k, pts)| pts.iter().find(|(name, _)| name == point).map(|(_, p)| (k, (*p - target).norm())))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(k, _)| k)
            .ok_or_else(|| bad(format!("`{point}` could not be placed at any position")))?;
        let span = (d.values[n - 1] - d.values[0]).abs().max(f64::MIN_POSITIVE);
        let h = DRAG_STEP_REL * span;
        // g(s) = (p(s) − target)·p'(s): zero where the point is nearest the target.
        let g = |s: f64| -> Option<f64> {
            let (p, lo, hi) = (at(k, s)?, at(k, s - h)?, at(k, s + h)?);
            Some((p - target).dot(&((hi - lo) / (2.0 * h))))
        };
        let mut best = (d.values[k], at(k, d.values[k]).map_or(f64::INFINITY, |p| (p - target).norm()));
        let neighbours = [k.checked_sub(1), (k + 1 < n).then_some(k + 1)];
        for j in neighbours.into_iter().flatten() {
            let (a, b) = (d.values[k].min(d.values[j]), d.values[k].max(d.values[j]));
            if let Some(s) = root(&g, a, b, DRAG_TOL_REL * span)
                && let Some(p) = at(k, s)
                && (p - target).norm() < best.1
            {
                best = (s, (p - target).norm());
            }
        }
        let state = (d.solve)(k, best.0).map_err(bad)?;
        self.dragged = Some((k, best.0));
        Ok(state)
    }

    /// Where the last drag left the drive: (nearest position, drive value).
    pub fn dragged(&self) -> Option<(usize, f64)> {
        self.dragged
    }

    /// The frame where the last drag left the mechanism (as [`Session::frame`] draws a
    /// position, at the run's scales).
    pub fn dragged_frame(&self) -> Option<String> {
        self.whole(&self.dragged_pose()?)
    }

    /// The scene's sheets (a triad's modes, a four-bar's centres and Joukowski's lever) as
    /// the CLI's `<name>-<suffix>.svg`: (suffix, SVG).
    pub fn sheets(&self) -> Result<Vec<(String, String)>, Error> {
        Ok(self.products()?.sheets.iter().map(|s| (s.suffix.clone(), bytes::picture_svg(&s.drawing))).collect())
    }

    /// The scene's diagrams as the CLI's `diagrams/<name>/<stem>.svg`: (stem, SVG).
    pub fn diagrams(&self) -> Result<Vec<(String, String)>, Error> {
        Ok(self
            .products()?
            .diagrams
            .iter()
            .map(|d| (d.stem.clone(), svg::to_string(&d.drawing, &SvgOptions::default())))
            .collect())
    }

    /// The files `mechdraw run` writes for the scene as it stands (without the frames and
    /// the viewer: `--no-frames`), for downloads.
    pub fn files(&self) -> Result<Vec<(String, Vec<u8>)>, Error> {
        bytes::to_files(self.products()?, &WriteOptions { png: false, no_frames: true, dxf: Default::default() })
    }
}

/// A root of `g` in [a, b] when g changes sign there (Illinois false position), to `tol`.
fn root(g: &impl Fn(f64) -> Option<f64>, mut a: f64, mut b: f64, tol: f64) -> Option<f64> {
    let (mut ga, mut gb) = (g(a)?, g(b)?);
    if ga == 0.0 {
        return Some(a);
    }
    if gb == 0.0 {
        return Some(b);
    }
    if ga.signum() == gb.signum() {
        return None;
    }
    let mut side = 0;
    for _ in 0..200 {
        let c = (a * gb - b * ga) / (gb - ga);
        let c = if c.is_finite() && c > a && c < b { c } else { 0.5 * (a + b) };
        let gc = g(c)?;
        if gc == 0.0 || (b - a) <= tol {
            return Some(c);
        }
        if gc.signum() == gb.signum() {
            (b, gb) = (c, gc);
            if side == -1 {
                ga *= 0.5;
            }
            side = -1;
        } else {
            (a, ga) = (c, gc);
            if side == 1 {
                gb *= 0.5;
            }
            side = 1;
        }
        if (b - a) <= tol {
            return Some(0.5 * (a + b));
        }
    }
    Some(0.5 * (a + b))
}

/// The scene's TOML table with `sets` applied (checked as `--set` checks them).
fn table_with(text: &str, file: &str, sets: &[(String, String)]) -> Result<toml::Table, Error> {
    let mut table: toml::Table = text.parse().map_err(|e: toml::de::Error| {
        Error::from(scene::SceneError::Syntax { file: file.to_string(), message: e.to_string().trim_end().to_string() })
    })?;
    for o in overrides(sets)? {
        o.apply(&mut table)?;
    }
    Ok(table)
}

fn overrides(sets: &[(String, String)]) -> Result<Vec<scene::Override>, Error> {
    sets.iter().map(|(p, v)| format!("{p}={v}").parse::<scene::Override>().map_err(Error::from)).collect()
}

/// The products of `text` with `sets`, and a motion's frame options and base SVG.
type Solved = (Made, Option<(SvgOptions, String)>);

/// The scene in `text` with `sets` applied, as the command line loads it.
fn loaded(text: &str, file: &str, sets: &[(String, String)]) -> Result<Loaded, Error> {
    Ok(Loaded {
        path: PathBuf::from(file),
        scene: scene::parse(text, file, &overrides(sets)?)?,
        text: text.to_string(),
    })
}

fn solve(text: &str, file: &str, sets: &[(String, String)]) -> Result<Solved, Error> {
    let loaded = loaded(text, file, sets)?;
    let alone = run::picture_alone(&loaded.scene);
    let p = run::products(&loaded, &RunOptions { no_frames: true, picture_only: alone, ..RunOptions::default() })?;
    if let (Picture::Motion(a), Some(source)) = (&p.picture, p.positions) {
        run::check_drawn(file, source.field, a.len(), source.advice)?;
    }
    let motion = match &p.picture {
        Picture::Motion(a) => {
            // The window of every frame: the animation's own, or fitted as the writer fits it.
            let opts = if a.fixed_window.is_some() {
                bytes::frame_options(a, &[])
            } else {
                bytes::frame_options(a, &a.poses())
            };
            let base = svg::to_string(&a.base, &opts);
            Some((opts, base))
        }
        Picture::Still(_) => None,
    };
    Ok((if alone { Made::Picture(p, Box::default()) } else { Made::Complete(p) }, motion))
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

    /// A scene open in the page ([`Session`](super::Session)): every method that changes it
    /// throws the command line's message and leaves it as it was on an error.
    #[wasm_bindgen]
    pub struct Live(super::Session);

    #[wasm_bindgen]
    impl Live {
        /// Opens the scene in `toml`, named `file` in messages.
        #[wasm_bindgen(constructor)]
        pub fn new(toml: &str, file: &str) -> Result<Live, String> {
            super::Session::new(toml, file).map(Live).map_err(|e| e.to_string())
        }

        /// `--set path=value`, and solve again.
        pub fn set(&mut self, path: &str, value: &str) -> Result<(), String> {
            self.0.set(path, value).map_err(|e| e.to_string())
        }

        /// A new scene text (the TOML editor), and solve again.
        pub fn replace(&mut self, toml: &str) -> Result<(), String> {
            self.0.replace(toml).map_err(|e| e.to_string())
        }

        /// The scene's text with the changes written in.
        pub fn scene_text(&self) -> Result<String, String> {
            self.0.scene_text().map_err(|e| e.to_string())
        }

        /// Every number of the scene as JSON:
        /// `[{"path": "l_bc", "value": 0.125, "integer": false}, ...]`.
        pub fn parameters(&self) -> Result<String, String> {
            let ps = self.0.parameters().map_err(|e| e.to_string())?;
            let list: Vec<serde_json::Value> = ps
                .iter()
                .map(|p| serde_json::json!({ "path": p.path, "value": p.value, "integer": p.integer }))
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

        /// SVG user units per model unit of the frames.
        pub fn user_units_per_model(&self) -> f64 {
            self.0.user_units_per_model()
        }

        /// Drags `point` towards the model point (`x`, `y`); returns the state reached as
        /// [`Live::points`] gives it, with `"drive"` (φ1 in degrees, or t in seconds).
        pub fn drag(&mut self, point: &str, x: f64, y: f64) -> Result<String, String> {
            let st = self.0.drag(point, crate::geom::Point::new(x, y)).map_err(|e| e.to_string())?;
            let mut v: serde_json::Value = serde_json::from_str(&state_json(&st)).unwrap_or_default();
            if let Some((_, s)) = self.0.dragged() {
                v["drive"] = serde_json::json!(s);
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
            let sheets = self.0.sheets().map_err(|e| e.to_string())?;
            serde_json::to_string(&sheets).map_err(|e| e.to_string())
        }

        /// The scene's diagrams as JSON: `[[stem, svg], ...]` (made when first asked for
        /// after a change).
        pub fn diagrams(&self) -> Result<String, String> {
            let diagrams = self.0.diagrams().map_err(|e| e.to_string())?;
            serde_json::to_string(&diagrams).map_err(|e| e.to_string())
        }

        /// The JSON summary, pretty (made when first asked for after a change).
        pub fn summary(&self) -> Result<String, String> {
            let p = self.0.products().map_err(|e| e.to_string())?;
            serde_json::to_string_pretty(&p.summary).map_err(|e| e.to_string())
        }

        /// A triad's modes as JSON (`{"phi1_deg": [...], "pattern_phi1_deg", "drawn"}`), `""`
        /// for the other kinds.
        pub fn modes(&self) -> Result<String, String> {
            Ok(self.0.modes().map_err(|e| e.to_string())?.map(|m| m.to_string()).unwrap_or_default())
        }

        /// The warnings, one a line.
        pub fn warnings(&self) -> String {
            self.0.warnings().join("\n")
        }

        /// The files of the scene as it stands (without frames), for downloads.
        pub fn files(&self) -> Result<Files, String> {
            let p = self.0.products().map_err(|e| e.to_string())?;
            let files = self.0.files().map_err(|e| e.to_string())?;
            Ok(Files(SceneFiles {
                files,
                summary: p.summary.clone(),
                report: p.report.clone(),
                warnings: p.warnings.clone(),
            }))
        }
    }

    fn state_json(st: &crate::figure::shared::animation::DriveState) -> String {
        let points: Vec<serde_json::Value> = st.points.iter().map(|(n, p)| serde_json::json!([n, p.x, p.y])).collect();
        serde_json::json!({ "label": st.label, "points": points, "residual": st.residual }).to_string()
    }

    /// Solves the scene in `toml` (named `file` in messages) and returns its files, with a
    /// motion's frames and viewer when `frames`; throws the command line's error message.
    #[wasm_bindgen]
    pub fn run_scene(toml: &str, file: &str, frames: bool) -> Result<Files, String> {
        scene_files(toml, file, WebOptions { frames, ..WebOptions::default() }).map(Files).map_err(|e| e.to_string())
    }

    /// [`run_scene`] with the command line's `--png` and `--sheets` (`""`, `"a4"` or `"a3"`):
    /// every file `mechdraw run` can write, for the tests that compare the module's bytes
    /// with the native build's (tests/wasm_bytes.rs).
    #[wasm_bindgen]
    pub fn run_scene_with(toml: &str, file: &str, frames: bool, png: bool, sheets: &str) -> Result<Files, String> {
        let sheets = match sheets {
            "" => None,
            paper => Some(paper.parse()?),
        };
        scene_files(toml, file, WebOptions { frames, png, sheets }).map(Files).map_err(|e| e.to_string())
    }
}
