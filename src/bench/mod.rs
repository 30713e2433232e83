//! `mechdraw bench`: every solving method on the same problems, time per solve against
//! error, written as an SVG chart (log–log), a CSV and a Markdown table; what a scene's
//! `outputs` cost; and the basins of the triad's methods.
//!
//! Error is measured against an independent, high-accuracy answer (the residual of the
//! original equations at the method's answer, and the distance to a polished root), never
//! against the method itself. Times are medians over batches, in nanoseconds per solve.

pub mod basins;
pub mod chart;
pub mod peers;
pub mod reference;
pub mod suite;
pub mod timing;
pub mod tolerance;

use crate::draw::svg::{self, SvgOptions};
use crate::error::Error;
use crate::run::output::Output;
use serde::Serialize;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// One point of the chart: a method at one setting on one problem.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Measurement {
    /// The problem (e.g. `triad-popa`, `fourbar-chebyshev`, `shaper`).
    pub problem: String,
    /// The method (e.g. `pattern`, `newton`, `all-modes`, `closed-form dyad`, `general newton`).
    pub method: String,
    /// The setting that distinguishes points of one method (e.g. `eps=1e-6`).
    pub setting: String,
    /// Median time per solve, nanoseconds.
    pub ns_per_solve: f64,
    /// Error against the independent reference (dimensionless, relative): the larger of
    /// [`Measurement::residual`] and [`Measurement::distance`]; `None` when the row
    /// measures cost only.
    pub error: Option<f64>,
    /// Residual of the original equations at the method's answer (relative).
    pub residual: Option<f64>,
    /// Distance to the independent polished root or closed form (relative).
    pub distance: Option<f64>,
}

impl Measurement {
    /// A measurement with error = max(residual, distance).
    pub fn new(problem: &str, method: &str, setting: &str, ns_per_solve: f64, residual: f64, distance: f64) -> Self {
        Measurement {
            problem: problem.into(),
            method: method.into(),
            setting: setting.into(),
            ns_per_solve,
            error: Some(residual.max(distance)),
            residual: Some(residual),
            distance: Some(distance),
        }
    }
}

/// The cost of one whole run of a scene with some `outputs`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunCost {
    /// The scene.
    pub scene: String,
    /// What its `outputs` asked for.
    pub outputs: String,
    /// Whether the per-position frames and the viewer were written.
    pub frames: bool,
    /// Files written by one run.
    pub files: usize,
    /// Median wall time of one `run::run`, milliseconds.
    pub ms_per_run: f64,
}

/// What `mechdraw bench` is asked to do.
#[derive(Debug, Clone, PartialEq)]
pub struct BenchOptions {
    /// Where to write the chart, CSVs and tables.
    pub out_dir: PathBuf,
    /// Smaller timing budgets (a smoke run).
    pub quick: bool,
    /// The Python that runs the pylinkage peer (`python3` when `None`; see [`peers`]).
    pub peers_python: Option<PathBuf>,
}

/// What `mechdraw bench` measured.
#[derive(Debug, Clone, PartialEq)]
pub struct BenchReport {
    /// Method measurements (the chart).
    pub methods: Vec<Measurement>,
    /// Output costs.
    pub runs: Vec<RunCost>,
    /// The tolerance study's Monte Carlo, timed.
    pub tolerance: Vec<tolerance::MonteCarloCost>,
    /// Peers' cold sweeps (rows beside "Assur groups (cold)"), and a line per peer not found.
    pub peers: peers::PeerReport,
    /// Machine and build, one line.
    pub machine: String,
    /// Files written.
    pub written: Vec<PathBuf>,
    /// Wall time of the whole bench, seconds.
    pub seconds: f64,
}

/// Samples of the timed tolerance Monte Carlo (issue 34's target row: 1e5 × 360 positions).
pub const TOLERANCE_SAMPLES: u64 = 100_000;
/// Samples of the timed tolerance Monte Carlo in a smoke run (`--quick`).
pub const TOLERANCE_SAMPLES_QUICK: u64 = 10_000;

/// Number of starts per basin strip (every 1°).
pub const BASIN_STARTS: usize = 360;

/// CPU model and core count (Linux /proc/cpuinfo), build profile, rustc on the PATH.
pub fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split_once(':'))
                .map(|(_, v)| v.trim().into())
        })
        .unwrap_or_else(|| String::from("unknown CPU"));
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let profile = if cfg!(debug_assertions) { "debug" } else { "release" };
    let rustc = std::process::Command::new("rustc")
        .arg("--version")
        .output()
        .ok()
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .map(|s| s.trim().to_string())
        .unwrap_or_else(|| "rustc unknown".into());
    format!("{cpu}, {cores} cores; mechdraw {} ({profile} build), {rustc}", env!("CARGO_PKG_VERSION"))
}

fn sci(v: Option<f64>) -> String {
    v.map_or(String::new(), |v| format!("{v:.2e}"))
}

/// The methods' CSV: `problem, method, setting, ns_per_solve, error, residual, distance`.
pub fn methods_csv(ms: &[Measurement]) -> Vec<u8> {
    let mut csv =
        crate::report::Csv::new(["problem", "method", "setting", "ns_per_solve", "error", "residual", "distance"]);
    for m in ms {
        csv.row_text([
            m.problem.clone(),
            m.method.clone(),
            m.setting.clone(),
            format!("{:.1}", m.ns_per_solve),
            sci(m.error),
            sci(m.residual),
            sci(m.distance),
        ]);
    }
    csv.to_bytes()
}

/// The outputs' CSV: `scene, outputs, frames, files, ms_per_run`.
pub fn runs_csv(rs: &[RunCost]) -> Vec<u8> {
    let mut csv = crate::report::Csv::new(["scene", "outputs", "frames", "files", "ms_per_run"]);
    for r in rs {
        csv.row_text([
            r.scene.clone(),
            r.outputs.clone(),
            r.frames.to_string(),
            r.files.to_string(),
            format!("{:.2}", r.ms_per_run),
        ]);
    }
    csv.to_bytes()
}

/// For each problem, the fastest measurement whose error is at most `goal`.
pub fn fastest_reaching(ms: &[Measurement], goal: f64) -> Vec<&Measurement> {
    let mut problems: Vec<&str> = Vec::new();
    for m in ms {
        if !problems.contains(&m.problem.as_str()) {
            problems.push(&m.problem);
        }
    }
    problems
        .into_iter()
        .filter_map(|p| {
            ms.iter()
                .filter(|m| m.problem == p && m.error.is_some_and(|e| e <= goal))
                .min_by(|a, b| a.ns_per_solve.total_cmp(&b.ns_per_solve))
        })
        .collect()
}

fn time(ns: f64) -> String {
    if ns >= 1e6 {
        format!("{:.2} ms", ns / 1e6)
    } else if ns >= 1e3 {
        format!("{:.2} µs", ns / 1e3)
    } else {
        format!("{ns:.0} ns")
    }
}

/// The Markdown report: headline, methods table, outputs table, machine.
pub fn markdown(report: &BenchReport) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "Machine: {}. Bench wall time {:.1} s.\n", report.machine, report.seconds);
    let _ = writeln!(s, "Fastest method reaching an error of 1e-12, per problem:\n");
    for m in fastest_reaching(&report.methods, 1e-12) {
        let _ = writeln!(s, "- {}: {} ({}) in {} per solve", m.problem, m.method, m.setting, time(m.ns_per_solve));
    }
    let _ = writeln!(s, "\n| problem | method | setting | time per solve | error | residual | distance |");
    let _ = writeln!(s, "|---|---|---|---:|---:|---:|---:|");
    for m in &report.methods {
        let ns = time(m.ns_per_solve);
        md_row(&mut s, &[&m.problem, &m.method, &m.setting, &ns, &sci(m.error), &sci(m.residual), &sci(m.distance)]);
    }
    let _ = writeln!(
        s,
        "\nTolerance Monte Carlo over the whole motion (docs/tolerances.md; issue 34's target: 1e5 samples × 360 positions ≤ 5 s):\n"
    );
    let _ = writeln!(
        s,
        "| scene | samples | positions | dimensions | components | threads | wall | ns per sample-position |"
    );
    let _ = writeln!(s, "|---|---:|---:|---:|---:|---:|---:|---:|");
    for t in &report.tolerance {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {:.3} s | {:.1} |",
            t.scene, t.samples, t.positions, t.dimensions, t.components, t.threads, t.wall_s, t.ns_per_sample_position
        );
    }
    s.push_str(&peers_markdown(&report.methods, &report.peers));
    let _ = writeln!(s, "\nWhat a scene's `outputs` cost (whole `mechdraw run`, median of runs):\n");
    let _ = writeln!(s, "| scene | outputs | frames | files | ms per run |");
    let _ = writeln!(s, "|---|---|---|---:|---:|");
    for r in &report.runs {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {:.1} |",
            r.scene,
            r.outputs,
            if r.frames { "yes" } else { "no" },
            r.files,
            r.ms_per_run
        );
    }
    s
}

/// Cold sweeps against the peers (issue 34: mechdraw ≥ 1× every peer, cold): per problem,
/// mechdraw's "Assur groups (cold)" rows and each peer's row, with the peer's time over
/// mechdraw's (≥ 1: mechdraw as fast or faster); then a line per peer not measured.
pub fn peers_markdown(methods: &[Measurement], peers: &peers::PeerReport) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "\nCold sweeps against peers (a whole turn from nothing, per position; docs/bench.md, \"Peers\"):\n"
    );
    let _ = writeln!(
        s,
        "| problem | route | setting | time per position | error | peer ÷ mechdraw new | peer ÷ mechdraw refit |"
    );
    let _ = writeln!(s, "|---|---|---|---:|---:|---:|---:|");
    for problem in [peers::FOURBAR_PROBLEM, peers::SHAPER_PROBLEM] {
        let ours: Vec<&Measurement> =
            methods.iter().filter(|m| m.problem == problem && m.method == "Assur groups (cold)").collect();
        let of = |setting: &str| ours.iter().find(|m| m.setting == setting).map(|m| m.ns_per_solve);
        for m in &ours {
            let route = format!("mechdraw, {}", m.method);
            md_row(&mut s, &[&m.problem, &route, &m.setting, &time(m.ns_per_solve), &sci(m.error), "", ""]);
        }
        for m in peers.rows.iter().filter(|m| m.problem == problem) {
            let ratio = |ns: Option<f64>| ns.map_or(String::new(), |ns| format!("{:.2}×", m.ns_per_solve / ns));
            let (ns, err) = (time(m.ns_per_solve), sci(m.error));
            md_row(&mut s, &[&m.problem, &m.method, &m.setting, &ns, &err, &ratio(of("new")), &ratio(of("refit"))]);
        }
    }
    for note in &peers.notes {
        let _ = writeln!(s, "\n{note}");
    }
    s
}

/// One Markdown table row: `| a | b | … |` (an empty cell stays empty).
fn md_row(s: &mut String, cells: &[&str]) {
    s.push('|');
    for c in cells {
        s.push(' ');
        s.push_str(c);
        s.push_str(if c.is_empty() { "|" } else { " |" });
    }
    s.push('\n');
}

fn png(svg_text: &str, what: &str) -> Result<Vec<u8>, Error> {
    crate::draw::raster::to_png(svg_text, 1400).map_err(|e| Error::Export { what: what.into(), message: e.to_string() })
}

/// Runs every measurement and writes, under `opts.out_dir`: `chart.svg`/`.png` (speed
/// against accuracy), `methods.csv`, `peers.csv`, `outputs.csv`, `tolerance.csv`, `bench.md`,
/// `basins.svg`/`.png`.
pub fn run(opts: &BenchOptions) -> Result<BenchReport, Error> {
    let t0 = std::time::Instant::now();
    let budget = if opts.quick { timing::Budget::QUICK } else { timing::Budget::NORMAL };
    let mut methods = suite::triad(budget)?;
    methods.extend(suite::fourbar(budget)?);
    methods.extend(suite::shaper(budget)?);
    std::fs::create_dir_all(&opts.out_dir)
        .map_err(|e| Error::Io { path: opts.out_dir.display().to_string(), source: e })?;
    let scratch = scratch_dir(&opts.out_dir);
    let runs = suite::outputs_cost(&scratch, if opts.quick { 1 } else { 3 });
    let _ = std::fs::remove_dir_all(&scratch);
    let runs = runs?;
    // The target row (1e5 samples × 360 positions); a smoke run times 1e4.
    let tolerance =
        vec![tolerance::fourbar_monte_carlo(if opts.quick { TOLERANCE_SAMPLES_QUICK } else { TOLERANCE_SAMPLES })?];

    let peers = peers::run(budget, &peers::PeerOptions { python: opts.peers_python.clone(), quick: opts.quick });

    let triad = suite::popa_triad()?;
    let modes = reference::triad_modes(&triad)
        .map_err(|e| Error::Solve { file: "triad-popa.toml".into(), source: e.into() })?;
    let strips = basins::triad_basins(&triad, &modes, BASIN_STARTS);

    let mut out = Output::new(&opts.out_dir)?;
    let speed_chart = chart::speed_accuracy_chart("Time per solve against error", &methods);
    let chart_svg = svg::to_string(&speed_chart, &SvgOptions::default());
    out.write("chart.png", png(&chart_svg, "chart.png")?)?;
    out.write("chart.svg", chart_svg)?;
    let basin_chart = chart::basins_chart("Triad (seed 000): where each start phi1 converges", &strips, &modes);
    let basin_svg = svg::to_string(&basin_chart, &SvgOptions::default());
    out.write("basins.png", png(&basin_svg, "basins.png")?)?;
    out.write("basins.svg", basin_svg)?;
    out.write("methods.csv", methods_csv(&methods))?;
    out.write("peers.csv", methods_csv(&peers.rows))?;
    out.write("outputs.csv", runs_csv(&runs))?;
    out.write("tolerance.csv", tolerance::csv(&tolerance))?;
    let mut report =
        BenchReport { methods, runs, tolerance, peers, machine: machine(), written: Vec::new(), seconds: 0.0 };
    report.seconds = t0.elapsed().as_secs_f64();
    out.write("bench.md", markdown(&report))?;
    report.written = out.commit()?;
    Ok(report)
}

fn scratch_dir(out: &Path) -> PathBuf {
    out.join(format!(".bench-scratch-{}", std::process::id()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn m(problem: &str, method: &str, ns: f64, err: f64) -> Measurement {
        Measurement::new(problem, method, "s=1", ns, err / 2.0, err)
    }

    #[test]
    fn fastest_reaching_picks_per_problem_among_those_accurate_enough() {
        let ms = [
            m("a", "slow", 900.0, 1e-15),
            m("a", "fast", 100.0, 1e-6),
            m("a", "mid", 400.0, 1e-13),
            m("b", "x", 5.0, 1e-3),
        ];
        let best = fastest_reaching(&ms, 1e-12);
        assert_eq!(best.len(), 1);
        assert_eq!(best[0].method, "mid");
        assert_eq!(ms[0].error, Some(1e-15));
    }

    #[test]
    fn the_peers_table_divides_each_peers_time_by_mechdraws_cold_rows() {
        let cold = |setting: &str, ns: f64| {
            Measurement::new(peers::FOURBAR_PROBLEM, "Assur groups (cold)", setting, ns, 1e-16, 1e-15)
        };
        let methods = [cold("new", 160.0), cold("refit", 80.0), m(peers::FOURBAR_PROBLEM, "Assur groups", 40.0, 1e-15)];
        let report = peers::PeerReport {
            rows: vec![Measurement::new(peers::FOURBAR_PROBLEM, "pylinkage (cold)", "s", 400.0, 0.0, 4e-14)],
            notes: vec!["four-bar crate (cold): not built in".into()],
        };
        let md = peers_markdown(&methods, &report);
        assert!(
            md.contains("| four-bar (seed 003) | mechdraw, Assur groups (cold) | refit | 80 ns | 1.00e-15 | | |"),
            "{md}"
        );
        assert!(
            md.contains("| four-bar (seed 003) | pylinkage (cold) | s | 400 ns | 4.00e-14 | 2.50× | 5.00× |"),
            "{md}"
        );
        assert_eq!(md.matches("Assur groups").count(), 2, "{md}");
        assert!(md.contains("\nfour-bar crate (cold): not built in\n"), "{md}");
    }

    #[test]
    fn csv_has_the_promised_columns() {
        let text = String::from_utf8(methods_csv(&[m("a", "b", 12.5, 1e-9)])).unwrap();
        let mut lines = text.lines();
        assert_eq!(lines.next(), Some("problem,method,setting,ns_per_solve,error,residual,distance"));
        assert_eq!(lines.next(), Some("a,b,s=1,12.5,1.00e-9,5.00e-10,1.00e-9"));
    }
}
