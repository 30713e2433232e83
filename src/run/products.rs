//! What a run made, before any of it becomes bytes: one [`Products`] value per scene,
//! whatever its kind. Each kind's `products()` solves and builds this; [`super::bytes`]
//! turns it into named files (DXF, SVG, frames, viewer, PNG, CSV, JSON) and
//! [`super::output`] puts those on disk. A kind never names a file or calls a writer.

use crate::figure::shared::panels::FrameScales;
use serde::Serialize;

use crate::Error;
use crate::draw::{Bounds, Drawing};
use crate::figure::shared::animation::Animation;
use crate::report::Csv;

/// The scene's picture: one drawing, or a motion.
#[derive(Debug)]
pub enum Picture {
    /// One drawing: `<name>.dxf` and `<name>.svg`.
    Still(Drawing),
    /// A motion: `<name>.dxf` with a layer per position, `<name>.svg` the first position,
    /// and (unless `--no-frames`) one SVG frame per position and the HTML viewer.
    Motion(Animation),
}

impl Picture {
    /// The drawing the DXF is written from: the still drawing, or a motion with every
    /// position on its own layer ([`Animation::whole`]).
    pub fn drawing(&self) -> Drawing {
        match self {
            Picture::Still(d) => d.clone(),
            Picture::Motion(a) => a.whole(),
        }
    }
}

/// A diagram or chart beside the picture: `diagrams/<scene name>/<stem>.svg`.
#[derive(Debug, Clone)]
pub struct Diagram {
    /// File stem (`omega2`, `E.vx`, `Z1-histogram`).
    pub stem: String,
    /// The diagram, drawn.
    pub drawing: Drawing,
    /// Where its curve is at each position of the motion, on the diagram's paper (mm, y up;
    /// [`crate::figure::shared::plot::track`]); empty when the diagram is not against the
    /// positions (a histogram). The live page's marker.
    pub track: Vec<Option<crate::geom::Point>>,
}

/// A sheet beside the picture, written like it: `<scene name>-<suffix>.dxf`, `.svg` (and
/// `.png` with `--png`). The triad's assembly modes as small multiples are one
/// (`triad-popa-modes.svg`).
#[derive(Debug, Clone)]
pub struct Sheet {
    /// Appended to the scene name after a `-` (`modes`): letters, digits, `-`, `_`.
    pub suffix: String,
    /// The sheet, drawn.
    pub drawing: Drawing,
}

/// A printed page of a run's per-position sheets (`--sheets a4|a3`): written as
/// `sheets/<scene name>/<stem>.svg` and as one page of `<scene name>-sheets.pdf`.
#[derive(Debug, Clone)]
pub struct Page {
    /// File stem: the position's name (`pos_090`).
    pub stem: String,
    /// The page, drawn in paper millimetres ([`Drawing::paper_mm_per_unit`] 1).
    pub drawing: Drawing,
    /// The paper (0, 0 to its width and height, mm).
    pub window: Bounds,
    /// Thinnest stroke, paper mm.
    pub hairline_mm: f64,
}

impl Page {
    /// A printed page of position `position` (`POS_090`) on `paper`: `kind` (`mechanism`,
    /// `polygons`, `forces`) after the position's name in its stem (`pos_090-forces`).
    pub(crate) fn printed(
        position: &str,
        kind: &str,
        drawing: Drawing,
        paper: crate::figure::shared::sheet::Paper,
    ) -> Page {
        Page {
            stem: format!("{}-{kind}", position.to_lowercase()),
            drawing,
            window: paper.bounds(),
            hairline_mm: crate::figure::shared::sheet::HAIRLINE_MM,
        }
    }
}

/// A CSV table: `<scene name><suffix>.csv`.
#[derive(Debug, Clone)]
pub struct Table {
    /// Appended to the scene name: `""` for the main table, `"-contributions"`, …
    pub suffix: String,
    /// The table.
    pub csv: Csv,
}

/// Where the number of drawn positions comes from, to name it when a run would draw more
/// than [`super::MAX_DRAWN_POSITIONS`].
#[derive(Debug, Clone, Copy)]
pub struct PositionsSource {
    /// The scene field that sets the number (`phi1_deg.step`, `time.steps`).
    pub field: &'static str,
    /// What to do instead (`use a larger step`).
    pub advice: &'static str,
}

/// Everything one scene's run produced.
#[derive(Debug)]
pub struct Products {
    /// The scene's name: the stem of every file.
    pub name: String,
    /// The picture.
    pub picture: Picture,
    /// Millimetres per model unit of the drawings (1000 for a scene in metres): the DXF is
    /// written in millimetres.
    pub mm_per_unit: f64,
    /// Where the number of positions of a [`Picture::Motion`] comes from.
    pub positions: Option<PositionsSource>,
    /// Extra sheets, in order, each written as DXF, SVG (and PNG) like a still picture.
    pub sheets: Vec<Sheet>,
    /// Per-position printed pages, in order (empty unless asked for with `--sheets`).
    pub pages: Vec<Page>,
    /// Diagrams, in order.
    pub diagrams: Vec<Diagram>,
    /// CSV tables, in order.
    pub tables: Vec<Table>,
    /// The JSON summary (`<name>.json`, and `--json` on stdout).
    pub summary: serde_json::Value,
    /// A short human-readable report for the terminal.
    pub report: String,
    /// Warnings (skipped positions, dead points, ...), one line each.
    pub warnings: Vec<String>,
    /// The scales each frame of a motion draws its polygons and force figures at, one per
    /// position (empty for a still picture or a kind without polygons): what
    /// [`RunOptions::held_scales`](super::RunOptions) takes from an earlier run.
    pub frame_scales: Vec<FrameScales>,
}

/// What a run makes besides its picture and warnings (all of it empty, the summary `Null`,
/// when only the picture is asked for: [`RunOptions::picture_only`](super::RunOptions)).
#[derive(Default)]
pub(crate) struct Extras {
    /// Extra sheets.
    pub sheets: Vec<Sheet>,
    /// Per-position printed pages.
    pub pages: Vec<Page>,
    /// Diagrams.
    pub diagrams: Vec<Diagram>,
    /// CSV tables.
    pub tables: Vec<Table>,
    /// The JSON summary.
    pub summary: serde_json::Value,
    /// The terminal's report.
    pub report: String,
}

impl Extras {
    /// The products of a motion: its picture, where its number of positions comes from, its
    /// warnings, and these.
    pub(crate) fn with_motion(
        self,
        name: String,
        mm_per_unit: f64,
        animation: Animation,
        positions: PositionsSource,
        warnings: Vec<String>,
        frame_scales: Vec<FrameScales>,
    ) -> Products {
        Products {
            name,
            mm_per_unit,
            picture: Picture::Motion(animation),
            positions: Some(positions),
            sheets: self.sheets,
            pages: self.pages,
            diagrams: self.diagrams,
            tables: self.tables,
            summary: self.summary,
            report: self.report,
            warnings,
            frame_scales,
        }
    }
}

/// A typed summary as the JSON value the products carry (keys in the order serde_json
/// keeps them: sorted).
/// A number in it that is not finite fails ([`super::finite::check_summary`]: JSON would
/// write it as `null`).
pub fn summary_value(summary: &impl Serialize, name: &str) -> Result<serde_json::Value, Error> {
    super::finite::check_summary(summary, &format!("{name}.json"))?;
    serde_json::to_value(summary).map_err(|e| Error::Export { what: format!("{name}.json"), message: e.to_string() })
}
