//! The synthesis pipeline: the requirement solved ([`crate::solve::synthesis`]), the
//! construction drawn ([`crate::figure::synthesis`]), the design written as a scene file
//! (`<name>-design.toml`, `design.rs`), that file parsed back and analysed by mechdraw's own
//! solvers for the check table (`check.rs`), and — unless `--no-analysis` — the design's
//! whole run beside it, under its own name.
//!
//! Files: `<name>.dxf`, `<name>.svg` (the construction), `<name>.csv` (the check table:
//! quantity, required, achieved, error, tolerance, ok), `<name>-design.toml`, `<name>.json`,
//! `diagrams/<name>/family.svg` (γ_min over the free choice) or `structural-error.svg`, and
//! the design's files `<name>-design.*`.

mod check;
mod crank_rocker;
mod design;
mod function;
mod motion;
mod quick_return;
mod slider_crank;

use std::path::PathBuf;

use serde_json::{Value, json};

use super::products::{Diagram, Picture, Products, Table, TextFile};
use super::{RunOptions, solve_err};
use crate::Error;
use crate::draw::Drawing;
use crate::figure::shared::vocab::ModelUnits;
use crate::report::Csv;
use crate::scene::synthesis::{SynthesisScene, Task};
use crate::scene::{Loaded, Units};
use crate::solve::synthesis::SynthesisError;

pub use check::{Check, Row, TOL_FUNCTION, TOL_POSE, TOL_REL};

/// What a task makes; [`products`] turns it into the run's products.
struct Made {
    /// The construction.
    picture: Drawing,
    /// The family's chart or the structural error.
    diagrams: Vec<Diagram>,
    /// The design's scene file.
    design: String,
    /// The check table.
    check: Check,
    /// The requirement, the construction, the design and its quality, for the JSON.
    summary: Value,
    /// The report's lines (the design and its quality).
    report: Vec<String>,
    /// Defects and other warnings.
    warnings: Vec<String>,
}

/// What every task needs besides its requirement.
struct Context<'a> {
    /// The scene.
    scene: &'a SynthesisScene,
    /// The scene file, for messages.
    file: &'a str,
    /// `<name>-design`.
    design_name: String,
}

impl Context<'_> {
    /// The drawings' units.
    fn units(&self) -> ModelUnits {
        match self.scene.units {
            Units::Mm => ModelUnits::MM,
            Units::Si => ModelUnits::SI,
        }
    }

    /// The length unit's symbol.
    fn unit(&self) -> &'static str {
        self.scene.units.length()
    }

    /// The header of the design file: where it comes from (the scene file's name alone: the
    /// same bytes from any directory, and from the live page).
    fn header(&self, what: &str) -> Vec<String> {
        let from = std::path::Path::new(self.file).file_name().map_or(self.file.into(), |n| n.to_string_lossy());
        vec![
            format!("Designed by mechdraw from {from} (task {}): {what}.", self.scene.task.name()),
            "Run it with `mechdraw run` like any scene; docs/synthesis.md says how it was found.".into(),
        ]
    }

    /// The design file's name.
    fn design_file(&self) -> String {
        format!("{}.toml", self.design_name)
    }

    /// The design, parsed back from its text as `mechdraw run` parses it (an error here is
    /// ours: the design we wrote does not load).
    fn parse(&self, text: &str) -> Result<crate::scene::Scene, Error> {
        check::parse(text, &self.design_file()).map_err(|e| self.internal(e))
    }

    /// An error of the analysis of our own design.
    fn internal(&self, message: String) -> Error {
        Error::Export { what: format!("{}'s check", self.design_file()), message }
    }
}

/// Solves the requirement and builds the run's products.
pub(super) fn products(scene: &SynthesisScene, file: &str, opts: &RunOptions) -> Result<Products, Error> {
    let cx = Context { scene, file, design_name: format!("{}-design", scene.name) };
    let made = match &scene.task {
        Task::CrankRocker(r) => crank_rocker::made(&cx, r)?,
        Task::SliderCrank(r) => slider_crank::made(&cx, r)?,
        Task::QuickReturn(r) => quick_return::made(&cx, r)?,
        Task::Motion(r) => motion::made(&cx, r)?,
        Task::Function { requirement, function } => function::made(&cx, requirement, function)?,
    };
    let mut warnings = made.warnings;
    for r in made.check.rows.iter().filter(|r| !r.ok) {
        warnings.push(format!(
            "check: {} is {} by the analysis of {}, {} required (error {:.3e} > {:.1e})",
            r.quantity,
            r.achieved,
            cx.design_file(),
            r.required,
            r.error,
            r.tolerance
        ));
    }
    let design_scene = cx.parse(&made.design)?;
    // The design's run (picture-only when only the picture is asked for: the warnings are
    // the same either way, as RunOptions::picture_only promises).
    let derived = if opts.no_analysis {
        Vec::new()
    } else {
        let loaded = Loaded { path: PathBuf::from(cx.design_file()), scene: design_scene, text: made.design.clone() };
        let dopts = RunOptions { no_analysis: true, ..opts.clone() };
        let p = super::products(&loaded, &dopts)?;
        warnings.extend(p.warnings.iter().map(|w| format!("{}: {w}", cx.design_file())));
        vec![p]
    };
    let mut report = format!("synthesis ({}):\n", scene.task.name());
    for line in &made.report {
        report.push_str(&format!("  {line}\n"));
    }
    report.push_str(&format!("check ({}):\n", made.check.route));
    for r in &made.check.rows {
        report.push_str(&format!(
            "  {:<24} required {:>18}  achieved {:>18}  error {:.1e}{}\n",
            r.quantity,
            crate::report::number(r.required),
            crate::report::number(r.achieved),
            r.error,
            if r.ok { "" } else { "  NOT MET" }
        ));
    }
    report.push_str(&format!(
        "design: {} ({})\n",
        cx.design_file(),
        if derived.is_empty() { "not analysed: --no-analysis" } else { "analysed below" }
    ));
    for d in &derived {
        report.push_str(&d.report);
    }
    let mut summary = made.summary;
    summary["kind"] = json!("synthesis");
    summary["name"] = json!(scene.name);
    summary["task"] = json!(scene.task.name());
    summary["units"] = json!(scene.units.length());
    summary["omega1"] = json!(scene.omega1);
    summary["check"] = json!({ "route": made.check.route, "rows": made.check.rows, "ok": made.check.ok() });
    summary["design_file"] = json!(cx.design_file());
    summary["analysed"] = json!(!derived.is_empty());
    let (summary, report) = if opts.picture_only { (Value::Null, String::new()) } else { (summary, report) };
    Ok(Products {
        name: scene.name.clone(),
        mm_per_unit: super::mm_per_unit(scene.units),
        picture: Picture::Still(made.picture),
        positions: None,
        sheets: Vec::new(),
        pages: Vec::new(),
        diagrams: if opts.picture_only { Vec::new() } else { made.diagrams },
        tables: vec![Table { suffix: String::new(), csv: table(&made.check) }],
        texts: vec![TextFile { suffix: "-design.toml".into(), text: made.design }],
        summary,
        report,
        warnings,
        derived,
        frame_scales: Vec::new(),
    })
}

/// The check table as CSV: one row per compared quantity.
fn table(c: &Check) -> Csv {
    let mut csv = Csv::new(["quantity", "required", "achieved", "error", "tolerance", "ok"]);
    for r in &c.rows {
        csv.row_text([
            r.quantity.clone(),
            crate::report::number(r.required),
            crate::report::number(r.achieved),
            crate::report::number(r.error),
            crate::report::number(r.tolerance),
            r.ok.to_string(),
        ]);
    }
    csv
}

/// A family of designs charted: γ_min (radians, NaN where the choice gives none) against
/// the free choice `x`, the design and the family's best marked, the usual 40° limit drawn.
struct FamilyChart<'a> {
    /// The chart's title.
    title: &'a str,
    /// The free choice's axis label, with its unit.
    x_label: String,
    /// Samples (x, γ_min).
    samples: Vec<(f64, f64)>,
    /// The design: (x, γ_min).
    design: (f64, f64),
    /// The family's best: (x, γ_min).
    best: (f64, f64),
    /// How far the best must lie from the design to be marked apart.
    apart: f64,
}

impl FamilyChart<'_> {
    fn diagram(self) -> Diagram {
        use crate::figure::shared::plot::{Diagram as Plot, Level, Mark, Marks, Series, diagram_marked};
        use crate::figure::synthesis::deg;
        let (x, y): (Vec<f64>, Vec<f64>) = self.samples.iter().map(|(x, g)| (*x, g.to_degrees())).unzip();
        let plot = Plot {
            title: self.title.into(),
            x_label: self.x_label,
            y_label: "γ_min [°]".into(),
            series: vec![Series { label: "γ_min".into(), x, y }],
        };
        let (dx, dg) = self.design;
        let mut points =
            // "design" alone: the free choice's value is the abscissa's, and a longer label
            // finds no room beside a steep family (the crank-rocker's at d = c).
            vec![Mark { x: dx, y: dg.to_degrees(), label: "design".into() }];
        let (bx, bg) = self.best;
        if (bx - dx).abs() > self.apart {
            points.push(Mark { x: bx, y: bg.to_degrees(), label: format!("best: γ_min = {}", deg(bg)) });
        }
        let limit = crate::solve::fourbar::transmission::GAMMA_LIMIT_DEG;
        let marks = Marks { levels: vec![Level { y: limit, label: "40° (usual limit)".into() }], points };
        // Not against the positions of a motion: no track for the page's marker.
        Diagram { stem: "family".into(), drawing: diagram_marked(&plot, &marks), track: Vec::new() }
    }
}

/// The rows of a stroke's check: H and K by the analysis of the linkage scene `text`.
fn stroke_rows(cx: &Context, text: &str, stroke: f64, time_ratio: f64) -> Result<Vec<Row>, Error> {
    let parsed = cx.parse(text)?;
    let scene = check::linkage_scene(&parsed).map_err(|e| cx.internal(e))?;
    let (h, k) = check::stroke(scene).map_err(|e| cx.internal(e))?;
    Ok(vec![
        Row::new(format!("H [{}]", cx.unit()), stroke, h, TOL_REL * stroke),
        Row::new("K", time_ratio, k, TOL_REL * time_ratio),
    ])
}

/// A synthesis error as the run's error: a field error when one field of the scene is to
/// blame (`field` says which, from the error), else the solver's error.
fn serr<'a>(
    file: &'a str,
    field: impl Fn(&SynthesisError) -> Option<String> + 'a,
) -> impl Fn(SynthesisError) -> Error + 'a {
    move |e| match field(&e) {
        Some(field) => {
            Error::Scene(crate::scene::SceneError::Field { file: file.to_string(), field, message: e.to_string() })
        }
        None => solve_err(file)(e.into()),
    }
}

/// A point as JSON.
fn pt(p: crate::geom::Point) -> Value {
    crate::report::point(p)
}
