//! One scene through the pipeline: scene → solve → figure → [`Products`] → bytes → files.
//! Each kind has its own `products()` (solve, figures, tables, summary, report: no file
//! names, no writers); [`bytes`] is the one place that turns products into named byte
//! buffers, and [`output`] the one that puts them on disk, all or nothing.

pub mod bytes;
mod chain;
pub mod finite;
mod fourbar;
mod fourbar_teaching;
mod linkage;
#[cfg(feature = "cli")]
pub mod listing;
#[cfg(feature = "cli")]
pub mod output;
#[cfg(feature = "cli")]
pub mod page;
pub mod paths;
pub mod positions;
pub mod products;
pub mod report;
pub mod synthesis;
mod tolerance;
mod triad;

pub use products::Products;
#[cfg(feature = "cli")]
pub use tolerance::{merge, run_shard};

use std::path::PathBuf;

use crate::Error;
use crate::scene::{Loaded, Scene};

/// What the user asked for on the command line, besides the scene.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Output directory; `None` solves and reports without writing files.
    pub out_dir: Option<PathBuf>,
    /// Also write PNG copies of the picture and of the diagrams.
    pub png: bool,
    /// Skip the per-position SVG frames and the HTML viewer.
    pub no_frames: bool,
    /// Show a progress bar on the terminal while frames are written.
    pub progress: bool,
    /// `--drag BODY.POINT=x,y` requests (general linkages).
    pub drag: Vec<String>,
    /// DXF version and dimension encoding (`--dxf-version`, `--dxf-dimensions`); the scale
    /// to millimetres comes from the scene's units ([`Products::mm_per_unit`]).
    pub dxf: crate::draw::dxf::DxfOptions,
    /// `--sheets a4|a3`: one printed page per position (`sheets/<name>/<position>.svg`)
    /// and `<name>-sheets.pdf` (four-bar and linkage scenes).
    pub sheets: Option<crate::figure::shared::sheet::Paper>,
    /// The `--set KEY=VALUE` changes the scene was loaded with: the live page applies them
    /// to the scene file's text when it opens.
    pub sets: Vec<String>,
    /// `--positions LIST`: draw only these positions of a motion (four-bar and linkage
    /// scenes, and a synthesis's design; [`positions::Positions`]); `None` draws every
    /// position.
    pub positions: Option<positions::Positions>,
    /// Only the picture and the warnings: no sheets, printed pages, diagrams, tables, JSON
    /// summary or report (`Null` and empty). The live page's answer to a change, which makes
    /// the rest when it is asked for; kinds whose whole products are cheap (triad, chain)
    /// make everything anyway. The picture and the warnings are the same either way.
    pub picture_only: bool,
    /// `--no-analysis`: a synthesis writes its construction, its check table and the design
    /// (`<name>-design.toml`) but not the design's whole run.
    pub no_analysis: bool,
    /// The scales an earlier run of the same motion drew each frame's polygons at
    /// ([`Products::frame_scales`]): each polygon keeps its scale at a position while it
    /// fills half to all of its panel there (the live page, so that a polygon visibly grows
    /// as a field's slider moves: [`PanelFrame::hold`](crate::figure::shared::panels::PanelFrame::hold)).
    /// Empty: the frames' own choice, as the command line makes it.
    pub held_scales: Vec<crate::figure::shared::panels::FrameScales>,
}

/// Whether [`RunOptions::picture_only`] makes less than a whole run of `scene`: it does for
/// the kinds whose runs sweep many positions (four-bar, linkage); a triad's or a chain's run
/// is made whole.
pub fn picture_alone(scene: &Scene) -> bool {
    matches!(scene, Scene::Fourbar(_) | Scene::Linkage(_) | Scene::Synthesis(_))
}

/// Millimetres per model unit of a scene in `units` (its drawings are in model units; the
/// DXF is written in millimetres).
pub(crate) fn mm_per_unit(units: crate::scene::Units) -> f64 {
    match units {
        crate::scene::Units::Mm => 1.0,
        crate::scene::Units::Si => 1000.0,
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

/// Solves `loaded` and builds what a run of it produces, without writing anything.
pub fn products(loaded: &Loaded, opts: &RunOptions) -> Result<Products, Error> {
    let file = loaded.path.display().to_string();
    if !opts.drag.is_empty() && !matches!(loaded.scene, Scene::Linkage(_)) {
        return Err(Error::Option {
            option: "--drag".into(),
            message: format!("only a linkage scene can be dragged; {file} is a {} scene", loaded.scene.kind()),
        });
    }
    if opts.sheets.is_some() && !matches!(loaded.scene, Scene::Fourbar(_) | Scene::Linkage(_) | Scene::Synthesis(_)) {
        return Err(Error::Option {
            option: "--sheets".into(),
            message: format!(
                "per-position sheets are drawn for four-bar and linkage scenes (and a synthesis's design); {file} is a {} scene",
                loaded.scene.kind()
            ),
        });
    }
    if let Some(p) = &opts.positions {
        let drawn_one = match &loaded.scene {
            Scene::Fourbar(_) => None,
            Scene::Linkage(_) if !opts.drag.is_empty() => Some("--drag draws one configuration".to_string()),
            Scene::Linkage(_) => None,
            // The design's run draws them (its motion: crank angles or times, as its kind's).
            Scene::Synthesis(_) if !opts.no_analysis => None,
            Scene::Synthesis(_) => Some(format!("{file} is a synthesis run with --no-analysis: its design is not run")),
            other => Some(format!("{file} is a {} scene with one drawing", other.kind())),
        };
        if let Some(why) = drawn_one {
            return Err(Error::Option {
                option: format!("--positions {p}"),
                message: format!("positions are chosen from the motion of a four-bar or linkage scene; {why}"),
            });
        }
    }
    match &loaded.scene {
        Scene::Triad(s) => triad::products(s, &file),
        Scene::Fourbar(s) => fourbar::products(s, &file, opts),
        Scene::Linkage(s) => linkage::products(s, &file, opts),
        Scene::Chain(s) => chain::products(s, &file),
        Scene::Synthesis(s) => synthesis::products(s, &file, opts),
    }
}

/// The positions of a motion a run draws: those `--positions` asks for (in its order), or
/// every one; `values` are the drive's values at the run's positions.
pub(crate) fn drawn_positions(
    positions: Option<&positions::Positions>,
    values: &[f64],
    axis: positions::DriveAxis,
) -> Result<Vec<usize>, Error> {
    match positions {
        None => Ok((0..values.len()).collect()),
        Some(p) => {
            p.select(values, axis).map_err(|message| Error::Option { option: format!("--positions {p}"), message })
        }
    }
}

/// Solves `loaded` and writes its outputs as `opts` asks (the file system and the
/// terminal: feature `cli`; the core's products go to bytes with [`bytes::to_files`]).
#[cfg(feature = "cli")]
pub fn run(loaded: &Loaded, opts: &RunOptions) -> Result<Outcome, Error> {
    if opts.out_dir.is_some() && opts.drag.is_empty() {
        // Before solving: a mistyped step is refused at once, not after a million positions.
        check_positions(&loaded.scene, &loaded.path.display().to_string())?;
    }
    let p = products(loaded, opts)?;
    let Some(dir) = &opts.out_dir else {
        return Ok(Outcome { summary: p.summary, report: p.report, warnings: p.warnings, written: Vec::new() });
    };
    if let (products::Picture::Motion(a), Some(source)) = (&p.picture, p.positions) {
        check_drawn(&loaded.path.display().to_string(), source.field, a.len(), source.advice)?;
    }
    let mut out = output::Output::new(dir)?;
    let frames = match &p.picture {
        products::Picture::Motion(a) if !opts.no_frames => a.len(),
        _ => 0,
    };
    let bar = progress_bar(opts.progress, frames);
    let tick = || {
        if let Some(b) = &bar {
            b.inc(1);
        }
    };
    let wopts = bytes::WriteOptions { png: opts.png, no_frames: opts.no_frames, dxf: opts.dxf };
    // The live page `<name>.html` (every kind), unless --no-frames: written while the
    // products become files.
    let page_rel = paths::RelPath::join(&[&format!("{}.html", p.name)])?;
    let (order, page) = crate::par::join(
        || bytes::write(&p, &wopts, &tick, &out),
        || -> Result<bool, Error> {
            if opts.no_frames {
                return Ok(false);
            }
            let file =
                loaded.path.file_name().map_or_else(|| "scene.toml".into(), |f| f.to_string_lossy().into_owned());
            let page = page::LivePage::new(&loaded.text, &file, &opts.sets);
            bytes::Sink::put(&out, &[(page_rel.clone(), page.pieces(page::Module::Inline))])?;
            Ok(true)
        },
    );
    let (order, page) = (order?, page?);
    if let Some(b) = &bar {
        b.finish_and_clear();
    }
    out.record_paths(order.into_iter().map(PathBuf::from));
    if page {
        out.record_paths([PathBuf::from(page_rel)]);
    }
    let written = out.commit()?;
    Ok(Outcome { summary: p.summary, report: p.report, warnings: p.warnings, written })
}

/// `mechdraw report`: builds the report of `loaded` ([`report::report`]: every check of the
/// options and every solve first, so that bad input writes nothing), then stages its files
/// ([`bytes::report_files`]) in `out_dir` and moves them in, all or nothing. Returns the
/// report (its warnings, parts and summary) and the files written.
#[cfg(feature = "cli")]
pub fn report_run(
    loaded: &Loaded,
    opts: &report::ReportOptions,
    out_dir: &std::path::Path,
    png: bool,
) -> Result<(report::Report, Vec<PathBuf>), Error> {
    let r = report::report(loaded, opts)?;
    let files = bytes::report_files(&r, png)?;
    let mut out = output::Output::new(out_dir)?;
    for (rel, b) in &files {
        out.write(rel, b)?;
    }
    let written = out.commit()?;
    Ok((r, written))
}

/// A terminal progress bar over `n` frames, when asked for and there are frames.
#[cfg(feature = "cli")]
fn progress_bar(on: bool, n: usize) -> Option<indicatif::ProgressBar> {
    if !on || n == 0 {
        return None;
    }
    let bar = indicatif::ProgressBar::new(n as u64);
    if let Ok(style) = indicatif::ProgressStyle::with_template("frames {bar:40.cyan/blue} {pos}/{len} {elapsed}") {
        bar.set_style(style);
    }
    Some(bar)
}

/// Width of every PNG a run writes with `--png` (pictures and diagrams alike), pixels.
pub const PNG_WIDTH_PX: u32 = 1600;

/// Most positions a run draws: each is a DXF layer and an SVG frame (~20 KB each for the
/// four-bar, and a linkage frame also carries the whole paths, so its frames grow with the
/// square of the count). 3600 is a 0.1° crank step over a turn. The library can still
/// solve a finer scene without an output directory ([`RunOptions::out_dir`] = `None`).
pub const MAX_DRAWN_POSITIONS: usize = 3600;

/// Refuses, before solving, a scene whose motion has more than [`MAX_DRAWN_POSITIONS`]
/// positions to draw (the message names the field that sets their number); a still scene
/// draws one.
pub fn check_positions(scene: &Scene, file: &str) -> Result<(), Error> {
    let (count, field, advice) = match scene {
        Scene::Fourbar(s) => (s.spec.sweep.count(), "phi1_deg.step", "use a larger step"),
        Scene::Linkage(s) => (s.times.len(), "time.steps", "use fewer steps"),
        // A synthesis draws its construction; its design's positions are ours (checked when it runs).
        Scene::Triad(_) | Scene::Chain(_) | Scene::Synthesis(_) => return Ok(()),
    };
    check_drawn(file, field, count, advice)
}

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

/// The figures' scale choice for the scene's `[frames] scales`.
pub(crate) fn scale_choice(s: crate::scene::FrameScales) -> crate::figure::shared::panels::ScaleChoice {
    use crate::figure::shared::panels::ScaleChoice;
    match s {
        crate::scene::FrameScales::PerFrame => ScaleChoice::PerFrame,
        crate::scene::FrameScales::Fixed => ScaleChoice::Fixed,
    }
}
