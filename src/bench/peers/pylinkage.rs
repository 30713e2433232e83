//! pylinkage's cold sweeps, run by `examples/peers/pylinkage_cold.py` (embedded here and run
//! with `python -c`, so the command works from any directory) in a child Python: the
//! Chebyshev four-bar and the shaper, a fresh linkage per sweep of 360 positions. The script
//! times its sweeps and prints every position's points as JSON; the error columns are
//! measured here, against the same references as mechdraw's rows.

use super::{FOURBAR_PROBLEM, POSITIONS, SHAPER_PROBLEM, coupler_point_polar, fourbar_error, shaper_error};
use crate::bench::Measurement;
use crate::bench::reference::shaper;
use crate::geom::Point;
use crate::solve::fourbar::{Geometry, Prepared};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::io::Read;
use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The script (also runnable alone: `python3 examples/peers/pylinkage_cold.py`).
pub const SCRIPT: &str = include_str!("../../../examples/peers/pylinkage_cold.py");

/// The script's exit status when `import pylinkage` fails.
pub const EXIT_NOT_FOUND: i32 = 3;

/// How long the script may run before it is stopped (a full run takes ≈ 9 s, `--quick` ≈ 3 s).
pub const TIMEOUT: Duration = Duration::from_secs(300);

/// Why pylinkage gave no rows.
#[derive(Debug, thiserror::Error)]
pub enum PylinkageError {
    /// The Python could not be started.
    #[error("{python} could not be started ({source}); pass --peers-python PATH to a Python with pylinkage")]
    NoPython {
        /// The Python tried.
        python: String,
        /// Why.
        source: std::io::Error,
    },
    /// `import pylinkage` failed in that Python.
    #[error("pylinkage not found by {python} ({message}); `pip install pylinkage numba`, or --peers-python PATH")]
    NotFound {
        /// The Python tried.
        python: String,
        /// Its error line.
        message: String,
    },
    /// The script failed or timed out.
    #[error("the script failed under {python}: {message}")]
    Script {
        /// The Python tried.
        python: String,
        /// Its exit status and last lines of stderr.
        message: String,
    },
    /// The script's output is not what it promises.
    #[error("its output does not parse: {0}")]
    Output(String),
}

/// The script's output.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct Output {
    /// Always `pylinkage`.
    pub peer: String,
    /// pylinkage's version.
    pub version: String,
    /// numba's version (`None`: pylinkage ran in pure Python).
    pub numba: Option<String>,
    /// The Python's version.
    pub python: String,
    /// One per problem: `four-bar`, `shaper`.
    pub problems: Vec<Problem>,
}

/// One problem's cold sweep.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct Problem {
    /// `four-bar` or `shaper`.
    pub problem: String,
    /// Positions per sweep (360).
    pub positions: usize,
    /// Median nanoseconds per position over the batches.
    pub ns_per_position: f64,
    /// Every position's points by name (A, B, M; A, B, E), `null` where pylinkage assembled
    /// nothing.
    pub points: BTreeMap<String, Vec<Option<[f64; 2]>>>,
}

impl Output {
    /// Parses and checks the script's JSON: both problems, [`POSITIONS`] positions each, the
    /// named points present, times positive and finite.
    pub fn parse(json: &str) -> Result<Output, PylinkageError> {
        let out: Output = serde_json::from_str(json).map_err(|e| PylinkageError::Output(e.to_string()))?;
        for (name, points) in [("four-bar", ["A", "B", "M"]), ("shaper", ["A", "B", "E"])] {
            let p = out.problem(name).ok_or_else(|| PylinkageError::Output(format!("no problem `{name}`")))?;
            if p.positions != POSITIONS || !(p.ns_per_position.is_finite() && p.ns_per_position > 0.0) {
                return Err(PylinkageError::Output(format!(
                    "`{name}`: {} positions (expected {POSITIONS}), {} ns per position",
                    p.positions, p.ns_per_position
                )));
            }
            for point in points {
                let n = p.points.get(point).map_or(0, Vec::len);
                if n != POSITIONS {
                    return Err(PylinkageError::Output(format!("`{name}`: {n} positions of {point}")));
                }
            }
        }
        Ok(out)
    }

    /// The problem named `name`.
    pub fn problem(&self, name: &str) -> Option<&Problem> {
        self.problems.iter().find(|p| p.problem == name)
    }

    /// The row's setting: the route and whether numba ran it.
    pub fn setting(&self) -> String {
        match &self.numba {
            Some(v) => format!("step_fast, numba {v}"),
            None => "step_fast, no numba".into(),
        }
    }
}

impl Problem {
    /// The named points' positions as (p0, p1, p2) per position (`None` where any is null).
    pub fn triples(&self, names: [&str; 3]) -> Vec<Option<[Point; 3]>> {
        let get = |n: &str, k: usize| self.points.get(n).and_then(|v| v.get(k).copied().flatten());
        (0..self.positions)
            .map(|k| {
                let [a, b, c] = names.map(|n| get(n, k));
                Some([a?, b?, c?].map(|p| Point::new(p[0], p[1])))
            })
            .collect()
    }
}

/// The geometry the script is given (`--geometry`), from mechdraw's own templates: the
/// Chebyshev four-bar (M by distance and angle from A, B's start on the template's branch) and
/// the closed-form shaper's numbers.
pub fn geometry_json(g: &Geometry) -> serde_json::Value {
    let (l_am, angle_am) = coupler_point_polar(g);
    let b0 = Prepared::new(g).position(0.0, g.branch).map_or([g.c.x, g.c.y + g.l_bc], |p| [p.b.x, p.b.y]);
    serde_json::json!({
        "fourbar": {
            "o1": [g.o1.x, g.o1.y], "c": [g.c.x, g.c.y], "l1": g.l1, "l_ab": g.l_ab, "l_bc": g.l_bc,
            "l_am": l_am, "angle_am": angle_am, "b0": b0,
        },
        "shaper": {
            "o1": [0.0, shaper::H_PIVOT], "o3": [0.0, 0.0], "r": shaper::R, "l": shaper::L,
            "l_be": shaper::LBE, "y_ram": shaper::Y_RAM, "e0": [null, shaper::Y_RAM],
        },
    })
}

/// Runs the script under `opts.python` (or `python3`) and returns its two rows, "pylinkage
/// (cold)" on the four-bar and on the shaper, scored by [`fourbar_error`] and [`shaper_error`].
pub fn run(opts: &super::PeerOptions) -> Result<Vec<Measurement>, PylinkageError> {
    let g = crate::bench::suite::chebyshev_geometry().map_err(|e| PylinkageError::Output(e.to_string()))?;
    let python = opts.python.clone().unwrap_or_else(|| PathBuf::from("python3"));
    let mut args = vec!["--geometry".to_string(), geometry_json(&g).to_string()];
    if opts.quick {
        args.push("--quick".into());
    }
    let stdout = run_script(&python, &args)?;
    let out = Output::parse(&stdout)?;
    Ok(rows(&out, &g))
}

/// The rows of a parsed output, scored against mechdraw's references.
pub fn rows(out: &Output, g: &Geometry) -> Vec<Measurement> {
    let setting = out.setting();
    let mut rows = Vec::new();
    if let Some(p) = out.problem("four-bar") {
        let (res, dist) = fourbar_error(g, &p.triples(["A", "B", "M"]));
        rows.push(Measurement::new(FOURBAR_PROBLEM, "pylinkage (cold)", &setting, p.ns_per_position, res, dist));
    }
    if let Some(p) = out.problem("shaper") {
        let (res, dist) = shaper_error(&p.triples(["A", "B", "E"]));
        rows.push(Measurement::new(SHAPER_PROBLEM, "pylinkage (cold)", &setting, p.ns_per_position, res, dist));
    }
    rows
}

/// Runs the embedded script with `args` under `python`, at most [`TIMEOUT`]; its stdout.
pub fn run_script(python: &std::path::Path, args: &[String]) -> Result<String, PylinkageError> {
    let name = python.display().to_string();
    let mut child = Command::new(python)
        .arg("-c")
        .arg(SCRIPT)
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|source| PylinkageError::NoPython { python: name.clone(), source })?;
    // Both pipes drained while the script runs (its JSON is larger than a pipe's buffer).
    let drain = |r: Option<Box<dyn Read + Send>>| {
        std::thread::spawn(move || {
            let mut s = String::new();
            if let Some(mut r) = r {
                let _ = r.read_to_string(&mut s);
            }
            s
        })
    };
    let out = drain(child.stdout.take().map(|r| Box::new(r) as Box<dyn Read + Send>));
    let err = drain(child.stderr.take().map(|r| Box::new(r) as Box<dyn Read + Send>));
    let t0 = Instant::now();
    let status = loop {
        match child.try_wait() {
            Ok(Some(status)) => break Some(status),
            Ok(None) if t0.elapsed() < TIMEOUT => std::thread::sleep(Duration::from_millis(50)),
            _ => {
                let _ = child.kill();
                let _ = child.wait();
                break None;
            }
        }
    };
    let (stdout, stderr) = (out.join().unwrap_or_default(), err.join().unwrap_or_default());
    let last = stderr.lines().rfind(|l| !l.trim().is_empty()).unwrap_or("").trim().to_string();
    match status {
        None => Err(PylinkageError::Script { python: name, message: format!("stopped after {} s", TIMEOUT.as_secs()) }),
        Some(s) if s.code() == Some(EXIT_NOT_FOUND) => {
            let message = last.strip_prefix("pylinkage not found: ").unwrap_or(&last).to_string();
            Err(PylinkageError::NotFound { python: name, message })
        }
        Some(s) if !s.success() => Err(PylinkageError::Script { python: name, message: format!("{s}: {last}") }),
        Some(_) => Ok(stdout),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Side;

    fn output(points_ok: bool) -> String {
        let g = crate::bench::suite::chebyshev_geometry().unwrap();
        let prepared = Prepared::new(&g);
        let pts = |f: &dyn Fn(usize) -> [f64; 2]| (0..POSITIONS).map(f).collect::<Vec<_>>();
        let pos = |k: usize| prepared.position(super::super::angle(k), Side::Left).unwrap();
        let mut m = pts(&|k| [pos(k).m.x, pos(k).m.y]);
        if !points_ok {
            m[5][1] += 1e-6;
        }
        let fourbar = serde_json::json!({
            "problem": "four-bar", "positions": POSITIONS, "ns_per_position": 400.0,
            "points": { "A": pts(&|k| [pos(k).a.x, pos(k).a.y]), "B": pts(&|k| [pos(k).b.x, pos(k).b.y]), "M": m },
        });
        let sh = |k: usize| shaper::closed_form(super::super::angle(k) / shaper::OMEGA);
        let shaper = serde_json::json!({
            "problem": "shaper", "positions": POSITIONS, "ns_per_position": 500.0,
            "points": {
                "A": pts(&|k| { let a = crate::geom::polar(Point::new(0.0, shaper::H_PIVOT), shaper::R, super::super::angle(k)); [a.x, a.y] }),
                "B": pts(&|k| { let b = crate::geom::polar(Point::origin(), shaper::L, sh(k).1[0]); [b.x, b.y] }),
                "E": pts(&|k| [sh(k).0[0], shaper::Y_RAM]),
            },
        });
        serde_json::json!({ "peer": "pylinkage", "version": "1.3.0", "numba": null, "python": "3.11",
            "problems": [fourbar, shaper] })
        .to_string()
    }

    #[test]
    fn an_output_parses_and_scores_against_the_references() {
        let g = crate::bench::suite::chebyshev_geometry().unwrap();
        let out = Output::parse(&output(true)).unwrap();
        assert_eq!(out.setting(), "step_fast, no numba");
        let r = rows(&out, &g);
        assert_eq!(r.len(), 2);
        assert_eq!((r[0].problem.as_str(), r[0].ns_per_solve), (FOURBAR_PROBLEM, 400.0));
        assert!(r.iter().all(|m| m.error.unwrap() < 1e-14), "{r:?}");
        let bad = rows(&Output::parse(&output(false)).unwrap(), &g);
        assert!((bad[0].error.unwrap() - 1e-6 / 0.1).abs() < 1e-12, "{bad:?}");
    }

    #[test]
    fn a_short_or_malformed_output_is_refused_by_name() {
        let short = output(true).replacen("\"positions\":360", "\"positions\":359", 1);
        let e = Output::parse(&short).unwrap_err().to_string();
        assert!(e.contains("359 positions"), "{e}");
        let e = Output::parse("{\"peer\": \"pylinkage\"").unwrap_err().to_string();
        assert!(e.starts_with("its output does not parse"), "{e}");
    }

    #[test]
    fn a_missing_python_is_named() {
        let opts = super::super::PeerOptions { python: Some("/nonexistent/python3".into()), quick: true };
        let e = run(&opts).unwrap_err().to_string();
        assert!(e.contains("/nonexistent/python3 could not be started"), "{e}");
    }
}
