//! A scene open in the page: the student's TOML text as it stands, its products, and what
//! a drag left on the screen.

use std::path::PathBuf;
use std::sync::OnceLock;

use super::PageError;
use super::fields::{self, Parameter};
use crate::Error;
use crate::draw::Drawing;
use crate::draw::svg::{self, SvgOptions};
use crate::figure::shared::animation::{Drive, DriveState};
use crate::figure::shared::panels::FrameScales;
use crate::geom::Point;
use crate::run::bytes::{self, WriteOptions};
use crate::run::products::{Picture, Products};
use crate::run::{self, RunOptions};
use crate::scene::{self, Loaded};

/// A scene open in the page: its text as it stands (the student's TOML with every change
/// written into it, comments and layout kept: [`Session::set`]) and its products. A change
/// solves the scene again and draws its picture (the motion with its polygons and forces at
/// every position: [`RunOptions::picture_only`]); the rest of the products (sheets,
/// diagrams, tables, the summary, the files) is made when first asked for. A change that the
/// scene does not accept leaves the session as it was (the page keeps its picture) and
/// returns the command line's message.
pub struct Session {
    file: String,
    text: String,
    /// The products of the scene as it stands.
    made: Made,
    /// A motion's frame options and its base written once (frames splice each position onto
    /// it).
    motion: Option<(SvgOptions, String)>,
    /// Where the last drag left the drive: (nearest position, drive value).
    dragged: Option<(usize, f64)>,
    /// Every position's named points, solved at the first drag (the nearest position of every
    /// later pointer event is looked up here).
    positions_points: OnceLock<Vec<Vec<(String, Point)>>>,
}

/// What a change made: everything (a kind whose whole run is cheap), or the picture and the
/// warnings, with the rest made on first ask.
enum Made {
    /// Everything `mechdraw run` makes.
    Complete(Products),
    /// The picture and the warnings ([`RunOptions::picture_only`]), and everything once asked.
    Picture(Products, Box<OnceLock<Products>>),
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
        f.debug_struct("Session").field("file", &self.file).finish_non_exhaustive()
    }
}

impl Session {
    /// Opens the scene in `text` (named `file` in messages).
    pub fn new(text: &str, file: &str) -> Result<Session, Error> {
        let (products, motion) = solve(text, file, &[])?;
        Ok(Session {
            file: file.to_string(),
            text: text.to_string(),
            made: products,
            motion,
            dragged: None,
            positions_points: OnceLock::new(),
        })
    }

    /// Sets the number (or any TOML value) at `path` to `value`, as `--set path=value` would,
    /// writing it into the scene's text (that value alone changes: [`super::edit::set`]),
    /// and solves again; on an error nothing changes.
    pub fn set(&mut self, path: &str, value: &str) -> Result<(), Error> {
        self.set_many(&[(path.to_string(), value.to_string())])
    }

    /// Sets several values at once (a drag that changes two lengths), then solves once.
    pub fn set_many(&mut self, changes: &[(String, String)]) -> Result<(), Error> {
        let text = super::edit::set(&self.text, &self.file, changes)?;
        self.replace(&text)
    }

    /// Replaces the scene's text (the page's TOML editor, an undo, a build step); on an error
    /// nothing changes. The picture keeps the scales its polygons and force figures were
    /// drawn at, position by position, while each still fills half to all of its panel
    /// ([`RunOptions::held_scales`]): as a field's slider moves, a polygon is seen to grow
    /// and shrink, and its scale steps only when it would leave its panel or shrink under
    /// half of it. (The files, [`Session::products`], are the command line's for the text.)
    pub fn replace(&mut self, text: &str) -> Result<(), Error> {
        let held = self.made.shown().frame_scales.clone();
        let (products, motion) = solve(text, &self.file, &held)?;
        (self.text, self.made, self.motion, self.dragged) = (text.to_string(), products, motion, None);
        self.positions_points = OnceLock::new();
        Ok(())
    }

    /// The scene's text as it stands: what a download of the scene is, what the share link
    /// and the browser's storage keep.
    pub fn scene_text(&self) -> &str {
        &self.text
    }

    /// The file name the scene's messages give.
    pub fn file(&self) -> &str {
        &self.file
    }

    /// Every number of the scene, named as a person reads it: the page's fields.
    pub fn parameters(&self) -> Result<Vec<Parameter>, Error> {
        Ok(fields::parameters(&table(&self.text, &self.file)?))
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
        let p =
            run::products(&loaded(&self.text, &self.file)?, &RunOptions { no_frames: true, ..RunOptions::default() })?;
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

    /// The scene a synthesis designed, as its file `<name>-design.toml` reads (what "open the
    /// design" switches the page to: a `fourbar` or `linkage` scene, opened with
    /// [`Session::new`]); `None` for the other kinds. Made with every change, picture-only
    /// answers included.
    pub fn design_text(&self) -> Option<String> {
        let p = self.made.shown();
        p.texts.iter().find(|t| t.suffix == "-design.toml").map(|t| t.text.clone())
    }

    /// The file name of the scene a synthesis designed (`<name>-design.toml`, as the command
    /// line writes it: the name "open the design" gives the page); `None` for the other kinds.
    pub fn design_file(&self) -> Option<String> {
        // The design's own `name` (`<name>-design`), the stem of the file the command line writes.
        let table: toml::Table = self.design_text()?.parse().ok()?;
        table.get("name")?.as_str().map(|n| format!("{n}.toml"))
    }

    /// Names the scene `file` in messages from now on (the page opened another scene: a
    /// synthesis's design); the text and the products stay as they are.
    pub fn rename(&mut self, file: &str) {
        self.file = file.to_string();
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
    /// line's `frames/<name>/<position>.svg` (after a change, with the polygons at the
    /// scales held from the picture before it: [`Session::replace`]); for a still picture,
    /// `<name>.svg`. `None` past the last position.
    pub fn frame(&self, k: usize) -> Option<String> {
        match &self.made.shown().picture {
            Picture::Still(d) => (k == 0).then(|| bytes::picture_svg(d)),
            Picture::Motion(a) if k < a.len() => self.whole(&a.pose(k)),
            Picture::Motion(_) => None,
        }
    }

    /// The scales each position's frame draws its polygons and force figures at (empty for
    /// a still picture): the command line's when the scene was opened, then held from
    /// change to change ([`Session::replace`]).
    pub fn frame_scales(&self) -> &[FrameScales] {
        &self.made.shown().frame_scales
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

    /// The state on screen at position `k`: where the last drag left the mechanism, else
    /// position `k`.
    fn shown_state(&self, k: usize) -> Option<DriveState> {
        match self.dragged {
            Some((j, v)) => (self.drive()?.solve)(j, v).ok(),
            None => self.points(k),
        }
    }

    /// The points edit mode drags at position `k` (or where the last drag left the
    /// mechanism): the state's named points and a linkage's ground points, model units.
    /// For a synthesis, the construction's points that carry a requirement or a free choice
    /// ([`super::synthesis`]), whatever `k`.
    pub fn edit_points(&self, k: usize) -> Option<Vec<(String, Point)>> {
        if let Some(s) = self.synthesis() {
            return Some(super::synthesis::grips(&s));
        }
        Some(super::reshape::grips(&table(&self.text, &self.file).ok()?, &self.shown_state(k)?))
    }

    /// The scene as a synthesis, when it is one.
    fn synthesis(&self) -> Option<crate::scene::synthesis::SynthesisScene> {
        match loaded(&self.text, &self.file).ok()?.scene {
            scene::Scene::Synthesis(s) => Some(s),
            _ => None,
        }
    }

    /// Edit mode: `point` dragged to `target` (model units) at position `k` changes the
    /// dimensions it carries ([`super::reshape`]), written with `decimals` decimals, and the
    /// scene is solved again; on an error (the new shape cannot be assembled) nothing changes.
    ///
    /// A synthesis's point changes the requirement or the free choice it carries
    /// ([`super::synthesis`]).
    pub fn reshape(&mut self, point: &str, target: Point, k: usize, decimals: usize) -> Result<(), PageError> {
        if let Some(s) = self.synthesis() {
            let text = super::synthesis::reshape(&self.text, &self.file, &s, point, target, decimals)
                .map_err(PageError::Reshape)?;
            return Ok(self.replace(&text)?);
        }
        let state =
            self.shown_state(k).ok_or_else(|| PageError::Reshape("only a motion's points can be dragged".into()))?;
        let changes = super::reshape::changes(&table(&self.text, &self.file)?, &state, point, target, decimals)
            .map_err(PageError::Reshape)?;
        Ok(self.set_many(&changes)?)
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

    /// Where each diagram's curve is at position `k`, in its SVG's user units (the order of
    /// [`Session::diagrams`]; `None` for a diagram without a value there, or not against the
    /// positions): the page's marker that moves with the mechanism.
    pub fn diagram_markers(&self, k: usize) -> Result<Vec<Option<(f64, f64)>>, Error> {
        // A diagram is drawn on paper (1 user unit = 1 mm), y flipped.
        let n = self.positions();
        Ok(self
            .products()?
            .diagrams
            .iter()
            .map(|d| (d.track.len() == n).then(|| d.track.get(k).copied().flatten().map(|p| (p.x, -p.y))).flatten())
            .collect())
    }

    /// The report of the scene as it stands, as [`super::report_files`] makes it: the
    /// "report" download of the current scene.
    pub fn report(&self, paper: &str, positions: &str) -> Result<super::SceneFiles, Error> {
        super::report_files(&self.text, &self.file, paper, positions)
    }

    /// The page's "report" download of the scene as it stands ([`super::report_download`]):
    /// the pages in one document to print, the table and the JSON.
    pub fn report_download(&self, paper: &str, positions: &str) -> Result<super::SceneFiles, Error> {
        super::report_download(&self.text, &self.file, paper, positions)
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

/// The scene's TOML table, or the command line's message for a text that is not TOML.
pub(super) fn table(text: &str, file: &str) -> Result<toml::Table, Error> {
    text.parse().map_err(|e: toml::de::Error| {
        Error::from(scene::SceneError::Syntax { file: file.to_string(), message: e.to_string().trim_end().to_string() })
    })
}

/// The products of `text`, and a motion's frame options and base SVG.
type Solved = (Made, Option<(SvgOptions, String)>);

/// The scene in `text`, as the command line loads it.
fn loaded(text: &str, file: &str) -> Result<Loaded, Error> {
    Ok(Loaded { path: PathBuf::from(file), scene: scene::parse(text, file, &[])?, text: text.to_string() })
}

/// Solves `text` (named `file` in messages): the picture (and for the kinds whose whole run
/// is cheap, everything), its polygons at the scales `held` of an earlier picture where they
/// still fill half to all of their panels.
fn solve(text: &str, file: &str, held: &[FrameScales]) -> Result<Solved, Error> {
    let loaded = loaded(text, file)?;
    let alone = run::picture_alone(&loaded.scene);
    // Before solving, as the command line: a mistyped step is refused at once.
    run::check_positions(&loaded.scene, file)?;
    let opts = RunOptions { no_frames: true, picture_only: alone, held_scales: held.to_vec(), ..RunOptions::default() };
    let p = run::products(&loaded, &opts)?;
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
