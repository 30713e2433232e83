//! The `mechdraw` command line: parses arguments, calls the library, prints errors.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use mechdraw::draw::dxf::{Dimensions, DxfOptions, DxfVersion};
use mechdraw::figure::shared::sheet::Paper;
use mechdraw::run::RunOptions;
use mechdraw::run::positions::Positions;
use mechdraw::scene::{self, Override};

/// mimalloc keeps freed pages for the next allocation: a run builds and drops tens of MB of
/// drawings and file bytes, and glibc's malloc gave each large buffer fresh pages from the
/// kernel (a page fault per 4 KB touched).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// Planar mechanisms and dimensional chains, solved and drawn: DXF, SVG, diagrams, CSV, JSON.
#[derive(Debug, Parser)]
#[command(name = "mechdraw", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Solve a scene and write its drawings and data into a directory.
    Run {
        /// The scene file (TOML; see templates/).
        scene: PathBuf,
        /// Output directory: DIR/<name>.dxf, DIR/<name>.svg, DIR/<name>.html (the live page:
        /// the scene solved and drawn in the browser), and per kind frames/<name>/,
        /// diagrams/<name>/, <name>.csv, <name>.json. Several scenes can share DIR.
        #[arg(short, long, value_name = "DIR", default_value = "out")]
        out: PathBuf,
        /// Override a scene field, checked like the file: `l12=55`, `pattern.tol=1e-7`,
        /// `r[2]=84` (repeatable).
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Print the JSON summary on stdout.
        #[arg(long)]
        json: bool,
        /// Also write PNG copies (1600 px wide) of every SVG: the picture, the extra sheets,
        /// the diagrams, the frames (`frames/<name>/<position>.png`) and the printed pages
        /// (`sheets/<name>/<position>.png`).
        #[arg(long)]
        png: bool,
        /// Do not write the per-position SVG frames and the live page (<name>.html).
        #[arg(long)]
        no_frames: bool,
        /// Four-bar and linkage scenes: also one printed sheet per position on `a4` (297 × 210
        /// mm) or `a3` (420 × 297 mm) landscape — border, title block (φ1 or t, k_l, k_v, k_a,
        /// k_f), the position's values, the mechanism and each polygon at its own nice scale — as
        /// DIR/sheets/<name>/<position>.svg and one PDF, DIR/<name>-sheets.pdf, to print at 100 %.
        #[arg(long, value_name = "PAPER")]
        sheets: Option<Paper>,
        /// Four-bar and linkage scenes, and a synthesis's design: draw only these positions (the DXF's position layers, the
        /// frames, the sheets): crank angles φ1 in degrees for a four-bar, times t in seconds for
        /// a linkage, as the frames label them, e.g. `0,90,180`; or `every=STEP`, the first
        /// position and every STEP after it (`every=30`). Each must be a position of the run
        /// (STEP a multiple of its step). The CSV, JSON and diagrams keep every position.
        #[arg(long, value_name = "LIST")]
        positions: Option<Positions>,
        /// Linkage scenes: move BODY.POINT as close as the constraints allow to (x, y) and
        /// write that configuration, e.g. `--drag crank.A=10,20`.
        #[arg(long, value_name = "BODY.POINT=X,Y")]
        drag: Vec<String>,
        /// DXF version: R12 (the default: every CAD program reads it), R2000 or R2007
        /// (text in UTF-8). See docs/dxf.md for what each reader shows.
        #[arg(long, value_name = "VERSION", default_value = "R12")]
        dxf_version: DxfVersion,
        /// DXF dimensions: `entities` (DIMENSION entities with their blocks, the default) or
        /// `exploded` (plain lines, arcs, arrowheads and text that every reader shows).
        #[arg(long, value_name = "HOW", default_value = "entities")]
        dxf_dimensions: Dimensions,
        /// Synthesis scenes: write the construction, the check table and the design
        /// (DIR/<name>-design.toml) but not the design's whole run.
        #[arg(long)]
        no_analysis: bool,
        /// Scenes with [tolerances]: run only the share K of N of the Monte Carlo and write its
        /// partial statistics, DIR/<name>-shard-K-of-N.json, for `mechdraw merge` (any batch
        /// engine can run the shards: docs/tolerances.md).
        #[arg(long, value_name = "K/N")]
        shard: Option<String>,
        /// No progress bar and no report on stderr.
        #[arg(short, long)]
        quiet: bool,
        /// List every file written (`wrote DIR/…` one a line) instead of a count per folder.
        #[arg(short, long)]
        verbose: bool,
    },
    /// Write the graph-analytical report a student hands in: DIR/<name>-report.pdf (title page,
    /// structural analysis, kinematic diagram, plan of positions, the chosen positions'
    /// polygons and forces, the diagrams; a triad's or a chain's own parts), the same pages as
    /// DIR/report/<name>/NN-<part>.svg, the chosen positions' values DIR/<name>-report.csv and
    /// DIR/<name>-report.json (docs/report.md). A linkage with a redundant link, which `run`
    /// refuses, gets its title page, structural analysis and kinematic diagram.
    Report {
        /// The scene file (TOML; see templates/).
        scene: PathBuf,
        /// Output directory.
        #[arg(short, long, value_name = "DIR", default_value = "out")]
        out: PathBuf,
        /// Override a scene field (repeatable), as for `run`.
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// The paper, landscape: `a4` (297 × 210 mm) or `a3` (420 × 297 mm).
        #[arg(long, value_name = "PAPER", default_value = "a4")]
        paper: Paper,
        /// Four-bar and linkage scenes: the positions to analyse (a set of pages each, and the
        /// plan's positions), as `run --positions` takes them: values of the drive the frames
        /// label them by — crank angles φ1 in degrees for a four-bar, times t in seconds for a
        /// linkage — each a position of the run, once, e.g. `0,90,180`; or `every=STEP`.
        /// Default: four evenly spaced and the dead positions, twelve on the plan.
        #[arg(long, value_name = "LIST")]
        positions: Option<Positions>,
        /// Also a PNG of every page (report/<name>/NN-<part>.png).
        #[arg(long)]
        png: bool,
        /// No report on stderr.
        #[arg(short, long)]
        quiet: bool,
    },
    /// Merge the shards of a tolerance study (`run --shard K/N`) into exactly the statistics
    /// of one run with the same seed, and write its tolerance files: <name>-tolerances.csv,
    /// <name>-contributions.csv, <name>.json (its `tolerances`), the band drawing, the
    /// diagrams and charts.
    Merge {
        /// The shard files, every K of one N once.
        shards: Vec<PathBuf>,
        /// Output directory.
        #[arg(short, long, value_name = "DIR", default_value = "out")]
        out: PathBuf,
        /// Print the JSON summary on stdout.
        #[arg(long)]
        json: bool,
        /// Also write PNG copies of the drawings and diagrams.
        #[arg(long)]
        png: bool,
        /// No report on stderr.
        #[arg(short, long)]
        quiet: bool,
        /// List every file written (`wrote DIR/…` one a line) instead of a count per folder.
        #[arg(short, long)]
        verbose: bool,
    },
    /// Write the live pages of scenes, the module they share and an index.html linking them:
    /// a gallery to publish as static files or open from disk (each page solves and draws
    /// its scene in the browser, no server; docs/web.md).
    Web {
        /// Scene files (default: every bundled template).
        scenes: Vec<PathBuf>,
        /// Output directory: DIR/<scene file stem>.html for each scene, DIR/mechdraw-module.js
        /// (the WebAssembly module, once), DIR/index.html.
        #[arg(short, long, value_name = "DIR", default_value = "web-out")]
        out: PathBuf,
    },
    /// Validate a scene file (and overrides) without solving.
    Check {
        /// The scene file.
        scene: PathBuf,
        /// Override a scene field (repeatable), as for `run`.
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
    },
    /// Compare two runs' output directories, as a CI job checks a course's golden files:
    /// CSV and JSON cell by cell, SVG and PNG pixel by pixel (a red/white diff PNG for each
    /// changed picture), DXF entity by entity, PDF pages and text. Prints a summary; exits 0
    /// when NEW is OLD within the tolerances, 1 when it is not, 2 on bad input. See docs/ci.md.
    Diff {
        /// The reference run's directory (the golden files).
        old: PathBuf,
        /// The run to check.
        new: PathBuf,
        /// Relative tolerance of numbers: a CSV cell, JSON value or DXF coordinate differs when
        /// it moved by more than X times its column's scale (the largest magnitude in that
        /// column, key path or drawing).
        #[arg(long, value_name = "X", default_value_t = mechdraw::diff::DEFAULT_TOL_REL, value_parser = tolerance)]
        tol_rel: f64,
        /// Channel tolerance of pictures: a pixel differs when its red, green, blue or alpha
        /// (0–255) moved by more than N.
        #[arg(long, value_name = "N", default_value_t = mechdraw::diff::DEFAULT_TOL_PX)]
        tol_px: u8,
        /// Where the diff PNGs of changed pictures go (DIFF_DIR/<path>.diff.png).
        #[arg(long, value_name = "DIFF_DIR", default_value = "diff-out")]
        out: PathBuf,
    },
    /// Time every solving method against its accuracy and write a chart, CSV and table.
    Bench {
        /// Output directory for the chart, CSV and Markdown table (the timed runs write into a
        /// scratch directory inside it: on a RAM file system such as /dev/shm the disk stays
        /// out of their times).
        #[arg(short, long, value_name = "DIR", default_value = "bench-out")]
        out: PathBuf,
        /// Fewer repetitions (a smoke run).
        #[arg(long)]
        quick: bool,
        /// The Python that runs the pylinkage peer's cold sweeps (default `python3`; a Python
        /// without pylinkage gives a line saying so, and no row). docs/bench.md, "Peers".
        #[arg(long, value_name = "PATH")]
        peers_python: Option<PathBuf>,
    },
}

/// Prints a run's JSON (when asked), warnings, report and written files.
fn finish(
    outcome: mechdraw::run::Outcome,
    out: &std::path::Path,
    json: bool,
    quiet: bool,
    verbose: bool,
) -> anyhow::Result<()> {
    if json {
        print_stdout(&serde_json::to_string_pretty(&outcome.summary)?)?;
    }
    if !quiet {
        for w in &outcome.warnings {
            eprintln!("warning: {w}");
        }
        if !outcome.report.is_empty() {
            eprintln!("{}", outcome.report.trim_end());
        }
        eprint!("{}", mechdraw::run::listing::summary(out, &outcome.written, verbose));
    }
    Ok(())
}

/// `--shard K/N`.
fn parse_shard(spec: &str) -> Result<(u64, u64), mechdraw::Error> {
    let bad = || mechdraw::Error::Option {
        option: "--shard".into(),
        message: format!("`{spec}` is not K/N (e.g. 2/4: the second of four shards)"),
    };
    let (k, n) = spec.split_once('/').ok_or_else(bad)?;
    Ok((k.trim().parse().map_err(|_| bad())?, n.trim().parse().map_err(|_| bad())?))
}

fn overrides(set: &[String]) -> Result<Vec<Override>, mechdraw::Error> {
    set.iter().map(|s| s.parse::<Override>().map_err(mechdraw::Error::from)).collect()
}

/// Writes a line to stdout; a closed pipe (`mechdraw run … --json | head`) is not an error.
fn print_stdout(text: &str) -> anyhow::Result<()> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    match writeln!(out, "{text}").and_then(|()| out.flush()) {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        other => Ok(other?),
    }
}

/// `--tol-rel`: a finite number ≥ 0.
fn tolerance(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() && x >= 0.0 => Ok(x),
        _ => Err(format!("`{s}` is not a tolerance: give a number ≥ 0, e.g. 1e-6")),
    }
}

/// `mechdraw diff`: the summary on stdout; exit 0 within the tolerances, 1 not, 2 on bad input.
fn diff(old: &std::path::Path, new: &std::path::Path, opts: &mechdraw::diff::DiffOptions) -> ExitCode {
    match mechdraw::diff::compare(old, new, opts) {
        Ok(report) => {
            if let Err(e) = print_stdout(report.summary().trim_end()) {
                eprintln!("error: {e}");
                return ExitCode::from(2);
            }
            if report.passed() { ExitCode::SUCCESS } else { ExitCode::from(1) }
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    // SIGINT, SIGTERM, SIGHUP: a run's staging directory removed, exit 130, 143, 129.
    if let Err(e) = mechdraw::run::output::remove_staging_on_signals() {
        eprintln!("warning: {e}");
    }
    if let Command::Diff { old, new, tol_rel, tol_px, out } = &cli.command {
        return diff(old, new, &mechdraw::diff::DiffOptions { tol_rel: *tol_rel, tol_px: *tol_px, out: out.clone() });
    }
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            // Library errors carry their context in their own message; print it once.
            eprintln!("error: {e}");
            let code = e.downcast_ref::<mechdraw::Error>().map_or(1, mechdraw::Error::exit_code);
            ExitCode::from(code as u8)
        }
    }
}

fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Run {
            scene,
            out,
            set,
            json,
            png,
            no_frames,
            sheets,
            positions,
            drag,
            dxf_version,
            dxf_dimensions,
            no_analysis,
            shard,
            quiet,
            verbose,
        } => {
            let loaded = scene::load(&scene, &overrides(&set)?).map_err(mechdraw::Error::from)?;
            if let Some(spec) = shard {
                let outcome = mechdraw::run::run_shard(&loaded, parse_shard(&spec)?, &set, &out)?;
                return finish(outcome, &out, json, quiet, verbose);
            }
            let opts = RunOptions {
                out_dir: Some(out.clone()),
                png,
                no_frames,
                progress: !quiet && std::io::stderr().is_terminal(),
                drag,
                dxf: DxfOptions { version: dxf_version, dimensions: dxf_dimensions, ..DxfOptions::default() },
                sheets,
                positions,
                sets: set.clone(),
                picture_only: false,
                no_analysis,
                held_scales: Vec::new(),
            };
            let outcome = mechdraw::run::run(&loaded, &opts)?;
            finish(outcome, &out, json, quiet, verbose)
        }
        Command::Merge { shards, out, json, png, quiet, verbose } => {
            let opts = RunOptions { out_dir: Some(out.clone()), png, ..RunOptions::default() };
            let outcome = mechdraw::run::merge(&shards, &opts)?;
            finish(outcome, &out, json, quiet, verbose)
        }
        Command::Report { scene, out, set, paper, positions, png, quiet } => {
            // A redundant link is accepted: the report draws the structure and says why it
            // stops there.
            let loaded = scene::load_with(&scene, &overrides(&set)?, scene::linkage::Redundancy::Accepted)
                .map_err(mechdraw::Error::from)?;
            let opts = mechdraw::run::report::ReportOptions { paper, positions };
            let (report, written) = mechdraw::run::report_run(&loaded, &opts, &out, png)?;
            if !quiet {
                for w in &report.warnings {
                    eprintln!("warning: {w}");
                }
                eprintln!("report of {}: {} pages", report.name, report.pages.len());
                for (part, first) in &report.parts {
                    eprintln!("  p. {first:>2}  {part}");
                }
                for f in &written {
                    if !f.starts_with(out.join("report")) {
                        eprintln!("wrote {}", f.display());
                    }
                }
                eprintln!("wrote {} (the pages as SVG)", out.join("report").join(&report.name).display());
            }
            Ok(())
        }
        Command::Web { scenes, out } => {
            let scenes: Vec<(String, String)> = if scenes.is_empty() {
                mechdraw::run::page::TEMPLATES.iter().map(|(f, t)| (f.to_string(), t.to_string())).collect()
            } else {
                scenes
                    .iter()
                    .map(|p| {
                        let text = std::fs::read_to_string(p).map_err(|source| {
                            mechdraw::Error::from(scene::SceneError::Read { file: p.display().to_string(), source })
                        })?;
                        Ok((p.display().to_string(), text))
                    })
                    .collect::<Result<_, mechdraw::Error>>()?
            };
            let written = mechdraw::run::page::gallery(&scenes, &out)?;
            let pages = written.len().saturating_sub(2);
            eprintln!("wrote {pages} pages, their module and {}", out.join("index.html").display());
            Ok(())
        }
        Command::Check { scene, set } => {
            let loaded = scene::load(&scene, &overrides(&set)?).map_err(mechdraw::Error::from)?;
            print_stdout(&format!(
                "{}: ok ({} scene \"{}\")",
                scene.display(),
                loaded.scene.kind(),
                loaded.scene.name()
            ))?;
            Ok(())
        }
        // Answered in main: its exit code says whether the runs differ.
        Command::Diff { .. } => Ok(()),
        Command::Bench { out, quick, peers_python } => {
            let report = mechdraw::bench::run(&mechdraw::bench::BenchOptions { out_dir: out, quick, peers_python })?;
            print!("{}", mechdraw::bench::markdown(&report));
            for f in &report.written {
                eprintln!("wrote {}", f.display());
            }
            Ok(())
        }
    }
}
