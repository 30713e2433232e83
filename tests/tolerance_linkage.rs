//! Tolerances of a general linkage (issue 34) on the slider-crank and the shaper templates:
//! the sensitivities (implicit function theorem on the position equations) against central
//! finite differences of the Assur route, the Monte Carlo's σ against the linear σ, the
//! worst case bounding every sample, shards merged into the single run, samples that cannot
//! be assembled, and bad input.

mod common;

use common::tolerance::{
    assert_merged_equals_single, assert_monte_carlo_sigma_is_linear, central_differences, channel_components,
    run_sharded, scaled,
};

use std::path::Path;

use mechdraw::scene::Scene;
use mechdraw::scene::linkage::LinkageScene;
use mechdraw::solve::tolerance::linkage::LinkageModel;
use mechdraw::solve::tolerance::monte_carlo::{self, Model, chunk_count};
use mechdraw::solve::tolerance::{Distribution, linear_all, ranges};

/// The slider-crank's tolerances: the crank pin, the rod's length, the crank pivot, the
/// line of stroke's two points (its offset and its tilt).
const SLIDER_CRANK: &str = r#"
[tolerances]
body = [{ points.A = [0.05, 0.05] }, { points.B = [0.1] }]
ground.points.O = [0.05, 0.05]
ground.points.G1 = [0.05, 0.05]
ground.points.G2 = [0.05, 0.05]

[tolerances.outputs]
points = ["piston.B", "rod.B"]
angles = ["rod"]
"#;

/// The shaper's: the crank pin, the rocker's pivot and its far pin (which is also the
/// slide's second line point), the link, the ram guide's height and the block's locked
/// angle on the rocker.
const SHAPER: &str = r#"
[tolerances]
"body[0].points.A" = [0.05, 0.05]
"ground.points.O3" = [0.05, 0.05]
"body[2].points.B" = [0.1, 0.1]
"body[3].points.E[0]" = 0.1
"ground.points.G1[1]" = 0.05
"ground.points.G2[1]" = 0.05
"joint[2].prismatic.angle_deg" = 0.02

[tolerances.outputs]
points = ["ram.E", "link.B"]
angles = ["rocker", "link"]
"#;

/// A template with a `[tolerances]` table appended and `steps` positions.
fn scene_text(template: &str, tolerances: &str, steps: u32) -> String {
    let text = std::fs::read_to_string(common::root().join("templates").join(template)).unwrap();
    let re = regex_steps(&text, steps);
    format!("{re}\n{tolerances}")
}

/// The template's `steps = …` of its time line replaced.
fn regex_steps(text: &str, steps: u32) -> String {
    let mut out = String::new();
    for line in text.lines() {
        if line.starts_with("time = ") {
            let (head, tail) = line.split_once("steps = ").unwrap();
            let rest = tail.trim_start_matches(|c: char| c.is_ascii_digit());
            out.push_str(&format!("{head}steps = {steps}{rest}\n"));
        } else {
            out.push_str(line);
            out.push('\n');
        }
    }
    out
}

fn scene(template: &str, tolerances: &str, steps: u32) -> LinkageScene {
    let text = scene_text(template, tolerances, steps);
    let Scene::Linkage(s) = mechdraw::scene::parse(&text, template, &[]).unwrap() else { panic!() };
    s
}

fn model(s: &LinkageScene) -> LinkageModel {
    let tol = s.tolerances.as_ref().unwrap();
    LinkageModel::new(s.mechanism.clone(), &s.times, tol.study.params.clone(), tol.outputs.clone()).unwrap()
}

/// Sensitivities against central differences of the samples' own route (the Assur
/// solver from the nominal's first pose), h = 1e-4 of the field's unit (mm, °), at 8
/// positions spread over the motion.
fn check_sensitivities(template: &str, tolerances: &str) {
    let s = scene(template, tolerances, 72);
    let m = model(&s);
    let dims = &s.tolerances.as_ref().unwrap().study.dims;
    let np = dims.len();
    let fd = central_differences(&m, np, 1e-4);
    for k in (0..8).map(|i| 4 + 9 * i) {
        let exact = m.sensitivities(k).expect("a regular position");
        let scale = exact.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        for (i, (e, f)) in exact.iter().zip(&fd[k]).enumerate() {
            let (c, j) = (i / np, i % np);
            assert!(
                (e - f).abs() <= 1e-6 * scale,
                "{template} position {k}, channel {c}, field {}: exact {e} vs central difference {f}",
                dims[j].name
            );
        }
        assert!(scale > 0.0);
    }
}

#[test]
fn slider_crank_sensitivities_equal_central_differences_at_eight_positions() {
    check_sensitivities("slider-crank.toml", SLIDER_CRANK);
}

#[test]
fn shaper_sensitivities_equal_central_differences_at_eight_positions() {
    check_sensitivities("shaper.toml", SHAPER);
}

#[test]
fn for_small_normal_tolerances_monte_carlo_sigma_tends_to_the_linear_sigma() {
    // 12 positions of the shaper, 1e5 samples: σ's sampling error is σ/√(2N) = 0.22 %.
    let s = scene("shaper.toml", SHAPER, 11);
    let m = model(&s);
    let dims = scaled(&s.tolerances.as_ref().unwrap().study.dims, 1.0, Distribution::Normal { k: 3.0 });
    assert_monte_carlo_sigma_is_linear(&m, &dims, 100_000, 0.0);
}

#[test]
fn the_worst_case_bounds_every_monte_carlo_sample_in_the_linear_regime() {
    let s = scene("slider-crank.toml", SLIDER_CRANK, 24);
    let m = model(&s);
    let dims = scaled(&s.tolerances.as_ref().unwrap().study.dims, 0.01, Distribution::Uniform);
    let comps = channel_components(m.channels());
    let linear = linear_all(&m, &dims, &comps);
    let n = 20_000;
    let mc = monte_carlo::run(&m, &dims, &comps, &ranges(&linear, comps.len()), 100, n, 3, 0..chunk_count(n));
    for (k, lin) in linear.iter().enumerate() {
        for c in 0..comps.len() {
            let l = &lin.as_ref().unwrap()[c];
            let t = &mc.tallies[k * comps.len() + c];
            // The second-order terms: (0.01 × 0.1 mm)² over ~100 mm, far below 1e-6 of the band.
            let slack = 1e-6 * l.worst_case;
            assert!(
                t.min >= l.shift - l.worst_case - slack && t.max <= l.shift + l.worst_case + slack,
                "position {k}, channel {c}: samples [{}, {}] beyond the worst case ±{}",
                t.min,
                t.max,
                l.worst_case
            );
            assert!(l.worst_case == 0.0 || t.max - t.min > 0.5 * l.worst_case, "{} vs {}", t.max - t.min, l.worst_case);
        }
    }
}

fn run(args: &[&str]) -> std::process::Output {
    common::mechdraw().args(args).output().unwrap()
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The slider-crank with its tolerances written to `dir` (36 positions, `samples`).
fn scene_file(dir: &Path, samples: u32) -> String {
    let text =
        scene_text("slider-crank.toml", SLIDER_CRANK, 36) + &format!("\n[tolerances.settings]\nsamples = {samples}\n");
    let path = dir.join("slider-crank-tol.toml");
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

#[test]
fn shards_one_to_three_merged_equal_the_single_run() {
    let tmp = tempfile::tempdir().unwrap();
    let t = scene_file(tmp.path(), 3000);
    let s = run_sharded(tmp.path(), &t, "slider-crank", 3, &["-q"], &["--no-frames"], false);
    let (single, merged) = (&s.single, &s.merged);
    assert_merged_equals_single(
        &s,
        &["slider-crank-tolerances.csv", "slider-crank-contributions.csv", "slider-crank-tolerance-band.svg"],
    );
    let (a, b) = (json(&single.join("slider-crank.json")), json(&merged.join("slider-crank.json")));
    assert_eq!(a["tolerances"], b["tolerances"]);
    assert_eq!(a["tolerances"]["drawn"], 3000);
}

#[test]
fn samples_that_cannot_be_assembled_are_counted_located_and_never_nan() {
    let tmp = tempfile::tempdir().unwrap();
    let t = scene_file(tmp.path(), 2000);
    let out = tmp.path().join("out");
    // The line of stroke moved up to ±450 mm (uniform): a rod of 495 mm on a crank of
    // 110 mm cannot reach a line more than 385 mm from the crank pivot at φ1 near 90° or 270°.
    let o = run(&[
        "run",
        &t,
        "--no-frames",
        "-q",
        "--out",
        out.to_str().unwrap(),
        "--set",
        "tolerances.ground.points.G1=[0.05, { tol = 450, distribution = \"uniform\" }]",
        "--set",
        "tolerances.ground.points.G2=[0.05, { tol = 450, distribution = \"uniform\" }]",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v = json(&out.join("slider-crank.json"));
    let tol = &v["tolerances"];
    let failed = tol["failed_samples"].as_u64().unwrap();
    assert!(failed > 0 && failed < 2000, "{failed} samples failed");
    let at: Vec<u64> = tol["positions"].as_array().unwrap().iter().map(|p| p["failed"].as_u64().unwrap()).collect();
    assert!(at.iter().all(|&n| n <= failed) && at.iter().any(|&n| n > 0));
    // Never at the dead centres (φ1 = 0°, 180°: the line of stroke's offset there only tilts the rod).
    assert_eq!((at[0], at[18], at[36]), (0, 0, 0), "{at:?}");
    for p in tol["positions"].as_array().unwrap() {
        if p["failed"].as_u64().unwrap() > 0 {
            assert_eq!(p["linear_trusted"], false);
        }
    }
    for f in ["slider-crank-tolerances.csv", "slider-crank.json", "slider-crank-tolerance-band.svg"] {
        let text = std::fs::read_to_string(out.join(f)).unwrap();
        assert!(!text.contains("NaN") && !text.contains("inf"), "{f} holds a non-finite number");
    }
}

#[test]
fn bad_tolerances_name_the_file_and_field_and_write_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let t = scene_file(tmp.path(), 100);
    for (set, field) in [
        ("tolerances.body[0].points.Q=[0.1, 0.1]", "tolerances.body[0].points.Q[0]"),
        ("tolerances.ground.points.Z=[0.1, 0.1]", "tolerances.ground.points.Z[0]"),
        ("tolerances.ground.points.O=[0.1, 0.1, 0.1]", "tolerances.ground.points.O[2]"),
        ("tolerances.joint=[{ prismatic.angle_deg = 0.1 }]", "tolerances.joint[0].prismatic.angle_deg"),
        ("tolerances.body[0].at=[0.1, 0.1]", "tolerances.body[0].at[0]"),
        ("tolerances.body[0].points.A=[-0.1, 0.1]", "tolerances.body[0].points.A[0]"),
        ("tolerances.body[0].points.A=[\"x\", 0.1]", "tolerances.body[0].points.A[0]"),
        ("tolerances.outputs.points=[\"piston.Q\"]", "tolerances.outputs.points[0]"),
        ("tolerances.outputs.points=[\"ground.O\"]", "tolerances.outputs.points[0]"),
        ("tolerances.outputs.angles=[\"wheel\"]", "tolerances.outputs.angles[0]"),
        ("tolerances.settings.samples=0", "tolerances.settings.samples"),
    ] {
        let out = tmp.path().join("out");
        let o = run(&["run", &t, "--out", out.to_str().unwrap(), "--set", set]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{set}: {err}");
        assert!(err.contains("slider-crank-tol.toml") && err.contains(&format!("field `{field}`")), "{set}: {err}");
        assert!(!out.exists(), "{set}: something was written");
    }
}

/// An independent route to a sample: the scene parsed again with each toleranced field set
/// (`--set <field>=<nominal + deviation>`: the fields are the paths `--set` takes), solved
/// from the scene's own placement by a fresh solver; its watched points and angles against
/// the Monte Carlo's sample (the model's solver refitted and swept from the nominal's pose).
fn check_samples_against_fresh_solves(template: &str, tolerances: &str) {
    use mechdraw::scene::Override;
    use mechdraw::solve::linkage::AssurSolver;
    use mechdraw::solve::tolerance::linkage::LinkageOutput;
    use mechdraw::solve::tolerance::monte_carlo::sample_deviations;
    let text = scene_text(template, tolerances, 36);
    let s = scene(template, tolerances, 36);
    let m = model(&s);
    let tol = s.tolerances.as_ref().unwrap();
    let dims = &tol.study.dims;
    let (nc, n) = (m.channels(), m.positions());
    let mut work = m.work();
    let mut out = vec![0.0; n * nc];
    let mut failed = vec![false; n];
    let scale = s.mechanism.length_scale;
    for j in [0u64, 1, 77, 300, 4095] {
        let dev = sample_deviations(dims, 11, j);
        assert!(!m.evaluate(&mut work, &dev, &mut out, &mut failed), "sample {j} failed");
        let sets: Vec<Override> =
            dims.iter().zip(&dev).map(|(d, e)| format!("{}={:e}", d.name, d.nominal + e).parse().unwrap()).collect();
        let Scene::Linkage(t) = mechdraw::scene::parse(&text, template, &sets).unwrap() else { panic!() };
        let states = AssurSolver::new(t.mechanism.clone()).unwrap().run(&t.times).unwrap();
        for (k, st) in states.iter().enumerate() {
            let mut c = 0;
            // A rate against the fresh solve's, to 1e-10 of the nominal's size (or of 1).
            let close = |fresh: f64, c: usize, what: &str| {
                let (nominal, mc) = (m.nominal()[k * nc + c], out[k * nc + c]);
                assert!(
                    (fresh - nominal - mc).abs() <= 1e-10 * nominal.abs().max(1.0),
                    "{template} sample {j}, position {k}, {what}: fresh {} vs Monte Carlo {mc}",
                    fresh - nominal
                );
            };
            for o in &tol.outputs {
                match o {
                    LinkageOutput::Point { name, .. } => {
                        let p = st.point(t.anchor(name).unwrap());
                        let nominal = mechdraw::geom::Point::new(m.nominal()[k * nc + c], m.nominal()[k * nc + c + 1]);
                        let d = p - nominal;
                        let (x, y) = (out[k * nc + c], out[k * nc + c + 1]);
                        assert!(
                            (d.x - x).abs() <= 1e-11 * scale && (d.y - y).abs() <= 1e-11 * scale,
                            "{template} sample {j}, position {k}, {name}: fresh ({}, {}) vs Monte Carlo ({x}, {y})",
                            d.x,
                            d.y
                        );
                        c += 2;
                    }
                    LinkageOutput::Angle { name, body } => {
                        let d = st.q[3 * body + 2].to_degrees() - m.nominal()[k * nc + c];
                        assert!((d - out[k * nc + c]).abs() <= 1e-10, "{name}: {d} vs {}", out[k * nc + c]);
                        c += 1;
                    }
                    LinkageOutput::Velocity { name, .. } | LinkageOutput::Acceleration { name, .. } => {
                        let (point, rate) = name.rsplit_once('.').unwrap();
                        let a = t.anchor(point).unwrap();
                        let v = if rate == "v" { st.velocity(a) } else { st.acceleration(a) };
                        close(v.x, c, name);
                        close(v.y, c + 1, name);
                        c += 2;
                    }
                    LinkageOutput::Omega { name, body } | LinkageOutput::Eps { name, body } => {
                        let (_, w, e) = st.angular(mechdraw::solve::linkage::Attach::Body(*body));
                        close(if name.ends_with(".omega") { w } else { e }, c, name);
                        c += 1;
                    }
                }
            }
        }
    }
}

#[test]
fn monte_carlo_samples_equal_fresh_solves_of_the_scene_with_its_fields_set() {
    check_samples_against_fresh_solves("slider-crank.toml", SLIDER_CRANK);
    check_samples_against_fresh_solves("shaper.toml", SHAPER);
    // The rates: each sample's velocities and accelerations re-solved.
    let rates =
        "\nvelocities = [\"ram.E\", \"link.B\", \"rocker\"]\naccelerations = [\"ram.E\", \"link.B\", \"rocker\"]\n";
    check_samples_against_fresh_solves("shaper.toml", &format!("{SHAPER}{rates}"));
}

/// A CSV as header → column index and rows of fields.
fn csv(path: &Path) -> (std::collections::HashMap<String, usize>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').enumerate().map(|(i, h)| (h.to_string(), i)).collect();
    (header, lines.map(|l| l.split(',').map(str::to_string).collect()).collect())
}

#[test]
fn the_slider_crank_tolerance_template_runs_end_to_end_and_its_numbers_hold() {
    use mechdraw::scene::Override;
    use mechdraw::solve::linkage::AssurSolver;
    const NAME: &str = "slider-crank-tolerances";
    let path = common::root().join("templates").join(format!("{NAME}.toml"));
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let o = run(&["run", path.to_str().unwrap(), "--no-frames", "-q", "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(&path).unwrap();
    let Scene::Linkage(s) = mechdraw::scene::parse(&text, NAME, &[]).unwrap() else { panic!() };
    let tol = s.tolerances.as_ref().unwrap();
    let (piston, rod) = (s.anchor("piston.B").unwrap(), 1usize);
    // piston.B's x and y, the rod's angle (degrees), piston.B's velocity's and
    // acceleration's x at every position, of the scene with the fields `sets` — solved from
    // scratch by the Assur route, as a run solves it.
    let solve = |sets: &[Override]| -> Vec<[f64; 5]> {
        let Scene::Linkage(t) = mechdraw::scene::parse(&text, NAME, sets).unwrap() else { panic!() };
        let states = AssurSolver::new(t.mechanism.clone()).unwrap().run(&t.times).unwrap();
        states
            .iter()
            .map(|st| {
                let p = st.point(piston);
                let (v, a) = (st.velocity(piston), st.acceleration(piston));
                [p.x, p.y, st.q[3 * rod + 2].to_degrees(), v.x, a.x]
            })
            .collect()
    };
    // Sensitivities in the contributions table against central differences of the solver
    // at 8 positions (h = 1e-4 mm: 1e-7 of the mechanism's size).
    let (h_idx, rows) = csv(&out.join(format!("{NAME}-contributions.csv")));
    let np = tol.study.dims.len();
    // Components: piston.B's x, y, normal, along; rod_deg.value; piston.B.v's and
    // piston.B.a's x, y, normal, along.
    let per_position = 13 * np;
    assert_eq!(rows.len(), s.times.len() * per_position);
    let h = 1e-4;
    let set = |d: &mechdraw::solve::tolerance::Dimension, v: f64| -> Override {
        format!("{}={v:e}", d.name).parse().unwrap()
    };
    type Sweep = Vec<[f64; 5]>;
    let diffs: Vec<(Sweep, Sweep)> =
        tol.study.dims.iter().map(|d| (solve(&[set(d, d.nominal + h)]), solve(&[set(d, d.nominal - h)]))).collect();
    for k in (20..360).step_by(45) {
        for (j, d) in tol.study.dims.iter().enumerate() {
            let (plus, minus) = (&diffs[j].0[k], &diffs[j].1[k]);
            let watched = [
                (0, "piston.B.x", 0),
                (1, "piston.B.y", 1),
                (4, "rod_deg.value", 2),
                (5, "piston.B.v.x", 3),
                (9, "piston.B.a.x", 4),
            ];
            for (c, name, ch) in watched {
                let row = &rows[k * per_position + c * np + j];
                assert_eq!(
                    (row[h_idx["component"]].as_str(), row[h_idx["dimension"]].as_str()),
                    (name, d.name.as_str())
                );
                let s_csv: f64 = row[h_idx["sensitivity"]].parse().unwrap();
                let fd = (plus[ch] - minus[ch]) / (2.0 * h);
                assert!(
                    (s_csv - fd).abs() <= 1e-6 * (1.0 + fd.abs()),
                    "position {k}, ∂{name}/∂{}: table {s_csv} vs central difference {fd}",
                    d.name
                );
            }
        }
    }
    // Monte Carlo against the linear stack-up, per position, away from the dead centres
    // (0° and 180°: there x is second order in the offsets and σ's ratio is not linear).
    let (t_idx, trows) = csv(&out.join(format!("{NAME}-tolerances.csv")));
    let n = tol.study.settings.samples as f64;
    let f = |row: &[String], col: &str| -> f64 { row[t_idx[col]].parse().unwrap() };
    for (k, row) in trows.iter().enumerate() {
        for comp in
            ["piston.B.x", "piston.B.y", "piston.B.along", "rod_deg.value", "piston.B.v.along", "piston.B.a.along"]
        {
            let (sigma, mc) = (f(row, &format!("{comp}.sigma")), f(row, &format!("{comp}.mc_sigma")));
            let (wc, shift) = (f(row, &format!("{comp}.wc")), f(row, &format!("{comp}.shift")));
            let nominal = f(row, &format!("{comp}.nominal"));
            let (lo, hi) =
                (f(row, &format!("{comp}.mc_p0.135")) - nominal, f(row, &format!("{comp}.mc_p99.865")) - nominal);
            // The ±3σ percentiles lie inside the worst case (RSS ≤ WC), to a bin's width.
            let bin = 4.0 * wc / tol.study.settings.bins as f64;
            assert!(lo >= shift - wc - bin && hi <= shift + wc + bin, "position {k}, {comp}: [{lo}, {hi}] vs WC {wc}");
            let crank_deg = 360.0 * k as f64 / 360.0;
            if (crank_deg % 180.0).min(180.0 - crank_deg % 180.0) < 10.0 || sigma <= 1e-9 * wc {
                continue;
            }
            // σ's sampling error σ/√(2N) (0.5 % at N = 2e4): 5 of them, plus 1 % for the
            // second order of ±0.1 mm on a 495 mm rod.
            let bound = 5.0 / (2.0 * n).sqrt() + 0.01;
            assert!((mc / sigma - 1.0).abs() <= bound, "position {k}, {comp}: MC σ {mc} vs linear σ {sigma}");
        }
    }
    let v = json(&out.join(format!("{NAME}.json")));
    assert_eq!(v["tolerances"]["failed_samples"], 0);
    assert_eq!(v["tolerances"]["drawn"], tol.study.settings.samples);
}
