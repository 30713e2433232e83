//! Tolerances of the four-bar (issue 34): the sensitivities against central finite
//! differences of the solver, the Monte Carlo against the linear stack-up and against a
//! brute-force route written here, shards merged into the single run, samples that cannot
//! be assembled, bad input, and the goldens of the band drawing and the Pareto chart.

mod common;

use common::tolerance::{assert_merged_equals_single, channel_components, run_sharded, scaled};

use std::path::Path;

use mechdraw::geom::{Point, Side, Vector};
use mechdraw::scene::{Override, Scene};
use mechdraw::solve::fourbar::{Geometry, Position, solve_motion};
use mechdraw::solve::tolerance::fourbar::{FourbarModel, FourbarOutput, FourbarParam, FourbarPoint};
use mechdraw::solve::tolerance::monte_carlo::{self, CHUNK, Model, chunk_count, sample_deviations};
use mechdraw::solve::tolerance::{Distribution, linear_all, ranges};

const TEMPLATE: &str = "fourbar-tolerances.toml";

/// The template (with overrides) as a checked four-bar scene, its solved positions, and its
/// model watching every point and angle under every field's tolerance.
fn template(sets: &[&str]) -> (mechdraw::scene::fourbar::FourbarScene, Vec<Position>) {
    let text = std::fs::read_to_string(common::root().join("templates").join(TEMPLATE)).unwrap();
    let overrides: Vec<Override> = sets.iter().map(|s| s.parse().unwrap()).collect();
    let Scene::Fourbar(s) = mechdraw::scene::parse(&text, TEMPLATE, &overrides).unwrap() else { panic!() };
    let motion = solve_motion(&s.spec).unwrap();
    (s, motion.positions)
}

fn every_output() -> Vec<FourbarOutput> {
    vec![
        FourbarOutput::Point(FourbarPoint::A),
        FourbarOutput::Point(FourbarPoint::B),
        FourbarOutput::Point(FourbarPoint::M),
        FourbarOutput::Phi2,
        FourbarOutput::Phi3,
    ]
}

/// The channels of the position at `phi1` of geometry `g` on `side`, as the model lays them
/// out (A, B, M as x, y; φ2, φ3 in degrees), from the solver.
fn channels(g: &Geometry, phi1: f64, side: Side) -> Vec<f64> {
    let p = mechdraw::solve::fourbar::position(g, phi1, side).unwrap();
    vec![p.a.x, p.a.y, p.b.x, p.b.y, p.m.x, p.m.y, p.phi2().to_degrees(), p.phi3().to_degrees()]
}

#[test]
fn sensitivities_equal_central_differences_of_the_solver_at_eight_positions() {
    let (s, positions) = template(&[]);
    let g = s.spec.geometry;
    let params = FourbarParam::ALL.to_vec();
    let model = FourbarModel::new(g, &positions, params.clone(), every_output());
    let np = params.len();
    for k in (0..360).step_by(45) {
        let pos = &positions[k];
        let side = pos.side(&g).unwrap();
        let exact = model.sensitivities(k).unwrap();
        for (j, p) in params.iter().enumerate() {
            // A step of 1e-6 of the mechanism's size (0.1 m; 1e-4° for alpha_deg).
            let h = if *p == FourbarParam::AlphaDeg { 1e-4 } else { 1e-7 };
            let (mut gp, mut gm) = (g, g);
            p.apply(&mut gp, h);
            p.apply(&mut gm, -h);
            let (cp, cm) = (channels(&gp, pos.phi1, side), channels(&gm, pos.phi1, side));
            for c in 0..cp.len() {
                let fd = (cp[c] - cm[c]) / (2.0 * h);
                let e = exact[c * np + j];
                // Relative 1e-6; an entry far below the channel's largest sensitivity to
                // 1e-6 of that one (the differences' rounding is 2e-16 · 0.2 m / 1e-7 m).
                let scale = (0..np).map(|i| exact[c * np + i].abs()).fold(0.0, f64::max);
                assert!(
                    common::rel_close(e, fd, 1e-6, scale),
                    "phi1 = {k}°, ∂channel {c}/∂{}: exact {e}, central difference {fd}",
                    p.field()
                );
            }
        }
    }
}

#[test]
fn for_small_normal_tolerances_monte_carlo_sigma_tends_to_the_linear_sigma() {
    // Eight positions, 1e5 samples: σ's sampling error is σ/√(2N) = 0.22 %.
    let (s, positions) = template(&["phi1_deg.step=45"]);
    let tol = s.tolerances.as_ref().unwrap();
    let dims = scaled(&tol.study.dims, 0.01, Distribution::Normal { k: 3.0 });
    let model = FourbarModel::new(s.spec.geometry, &positions, tol.study.params.clone(), every_output());
    let comps = channel_components(model.channels());
    let linear = linear_all(&model, &dims, &comps);
    let n = 100_000;
    let mc = monte_carlo::run(&model, &dims, &comps, &ranges(&linear, comps.len()), 400, n, 7, 0..chunk_count(n));
    assert_eq!(mc.failed_samples, 0);
    let se = 1.0 / (2.0 * n as f64).sqrt();
    for (k, lin) in linear.iter().enumerate() {
        for c in 0..comps.len() {
            let l = &lin.as_ref().unwrap()[c];
            let m = mc.tallies[k * comps.len() + c].summary().unwrap();
            if l.sigma < 1e-15 {
                // A channel no toleranced field moves (A.y at φ1 = 0°): no sample moves it
                // beyond rounding (the template's σ are ~1e-7 m and ~1e-3°).
                assert!(m.sigma < 1e-15, "position {k}, channel {c}: MC σ {}", m.sigma);
                continue;
            }
            assert!(
                (m.sigma / l.sigma - 1.0).abs() < 5.0 * se,
                "position {k}, channel {c}: MC σ {} vs linear σ {}",
                m.sigma,
                l.sigma
            );
            // The ±3σ percentiles: RSS within the histogram's resolution and the sampling error.
            assert!((m.p_high - l.rss).abs() < 0.03 * l.rss, "p99.865 {} vs RSS {}", m.p_high, l.rss);
        }
    }
}

#[test]
fn the_worst_case_bounds_every_monte_carlo_sample_in_the_linear_regime() {
    let (s, positions) = template(&["phi1_deg.step=15"]);
    let tol = s.tolerances.as_ref().unwrap();
    // Uniform: every sample inside its band; one thousandth of the template's tolerances.
    let dims = scaled(&tol.study.dims, 0.001, Distribution::Uniform);
    let model = FourbarModel::new(s.spec.geometry, &positions, tol.study.params.clone(), every_output());
    let comps = channel_components(model.channels());
    let linear = linear_all(&model, &dims, &comps);
    let n = 20_000;
    let mc = monte_carlo::run(&model, &dims, &comps, &ranges(&linear, comps.len()), 100, n, 3, 0..chunk_count(n));
    for (k, lin) in linear.iter().enumerate() {
        for c in 0..comps.len() {
            let l = &lin.as_ref().unwrap()[c];
            let t = &mc.tallies[k * comps.len() + c];
            assert!(
                t.min >= l.shift - l.worst_case && t.max <= l.shift + l.worst_case,
                "position {k}, channel {c}: samples [{}, {}] beyond the worst case ±{}",
                t.min,
                t.max,
                l.worst_case
            );
            // …and the samples come near it: the band is not loose by more than half.
            assert!(l.worst_case == 0.0 || t.max - t.min > 0.5 * l.worst_case, "{} vs {}", t.max - t.min, l.worst_case);
        }
    }
}

/// The four-bar written out here: A on the crank, B where the circles about A (l_ab) and
/// C (l_bc) meet on `side` of A→C, M = B + (l_bm/l_ab)·R(α)·(A − B).
fn brute_force(g: &Geometry, phi1: f64, side: Side) -> Option<[Point; 3]> {
    let a = g.o1 + Vector::new(libm::cos(phi1), libm::sin(phi1)) * g.l1;
    let ac = g.c - a;
    let d = ac.norm();
    let x = (g.l_ab * g.l_ab - g.l_bc * g.l_bc + d * d) / (2.0 * d);
    let h2 = g.l_ab * g.l_ab - x * x;
    if h2 < 0.0 {
        return None;
    }
    let u = ac / d;
    let left = Vector::new(-u.y, u.x);
    let sign = if side == Side::Left { 1.0 } else { -1.0 };
    let b = a + u * x + left * (sign * h2.sqrt());
    let (sa, ca) = libm::sincos(g.alpha);
    let v = (a - b) * (g.l_bm / g.l_ab);
    let m = b + Vector::new(ca * v.x - sa * v.y, sa * v.x + ca * v.y);
    Some([a, b, m])
}

#[test]
fn monte_carlo_samples_equal_a_brute_force_closed_form_and_so_do_their_statistics() {
    let (s, positions) = template(&["phi1_deg.step=30"]);
    let tol = s.tolerances.as_ref().unwrap();
    let (dims, params) = (tol.study.dims.clone(), tol.study.params.clone());
    let g0 = s.spec.geometry;
    let outputs = vec![FourbarOutput::Point(FourbarPoint::M), FourbarOutput::Point(FourbarPoint::B)];
    let model = FourbarModel::new(g0, &positions, params.clone(), outputs);
    let comps = channel_components(model.channels());
    let n = 3 * CHUNK + 10;
    let seed = 11;
    // Every sample: its deviations replayed, the geometry perturbed field by field here, the
    // closed form solved here, against the model's evaluation of the same sample.
    let np = positions.len();
    let mut sums = vec![0.0; np * 4];
    #[allow(clippy::let_unit_value)] // the four-bar's model needs no buffers
    let mut work = model.work();
    let (mut out, mut failed) = (vec![0.0; np * 4], vec![false; np]);
    for j in 0..n {
        let dev = sample_deviations(&dims, seed, j);
        let mut g = g0;
        for (p, d) in params.iter().zip(&dev) {
            match p {
                FourbarParam::L1 => g.l1 += d,
                FourbarParam::Lab => g.l_ab += d,
                FourbarParam::Lbm => g.l_bm += d,
                FourbarParam::Lbc => g.l_bc += d,
                FourbarParam::Cx => g.c.x += d,
                FourbarParam::Cy => g.c.y += d,
                other => panic!("{other:?} is not in the template"),
            }
        }
        assert!(!model.evaluate(&mut work, &dev, &mut out, &mut failed));
        for (k, pos) in positions.iter().enumerate() {
            let [_, b, m] = brute_force(&g, pos.phi1, pos.side(&g0).unwrap()).unwrap();
            let want = [m.x - pos.m.x, m.y - pos.m.y, b.x - pos.b.x, b.y - pos.b.y];
            for c in 0..4 {
                let got = out[k * 4 + c];
                assert!(
                    (got - want[c]).abs() <= 1e-12 * 0.1,
                    "sample {j}, position {k}, channel {c}: {got} vs {}",
                    want[c]
                );
                sums[k * 4 + c] += want[c];
            }
        }
    }
    let mc = monte_carlo::run(
        &model,
        &dims,
        &comps,
        &ranges(&linear_all(&model, &dims, &comps), 4),
        50,
        n,
        seed,
        0..chunk_count(n),
    );
    for (i, (t, sum)) in mc.tallies.iter().zip(&sums).enumerate() {
        let mean = t.summary().unwrap().mean;
        let want = sum / n as f64;
        assert!((mean - want).abs() <= 1e-12 * 1e-4, "mean {i}: {mean} vs brute force {want}");
    }
}

fn run(args: &[&str]) -> std::process::Output {
    common::mechdraw().args(args).output().unwrap()
}

fn template_path() -> String {
    common::root().join("templates").join(TEMPLATE).display().to_string()
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn shards_one_to_four_merged_equal_the_single_run() {
    let tmp = tempfile::tempdir().unwrap();
    let sets = ["--set", "tolerances.settings.samples=5000", "--set", "phi1_deg.step=5", "-q"];
    // Shards written in reverse order, each into the same directory, and merged in that order.
    let s = run_sharded(tmp.path(), &template_path(), "fourbar-tolerances", 4, &sets, &["--no-frames"], true);
    let (single, merged, files) = (&s.single, &s.merged, &s.files);
    // Only the shard files are written by a shard run.
    assert_eq!(std::fs::read_dir(&s.shards).unwrap().count(), 4);
    assert_merged_equals_single(
        &s,
        &[
            "fourbar-tolerances-tolerances.csv",
            "fourbar-tolerances-contributions.csv",
            "fourbar-tolerances-tolerance-band.svg",
            "fourbar-tolerances-tolerance-band.dxf",
            "diagrams/fourbar-tolerances/M.normal-band.svg",
            "diagrams/fourbar-tolerances/M.normal-pareto.svg",
        ],
    );
    let (a, b) = (json(&single.join("fourbar-tolerances.json")), json(&merged.join("fourbar-tolerances.json")));
    assert_eq!(a["tolerances"], b["tolerances"]);
    assert_eq!(a["tolerances"]["drawn"], 5000);
    // A shard missing or given twice is refused, nothing written.
    let bad = tmp.path().join("bad");
    for list in [&files[..3], &[files[0].clone(), files[0].clone(), files[1].clone(), files[2].clone()][..]] {
        let mut args = vec!["merge".to_string(), "--out".into(), bad.display().to_string()];
        args.extend(list.iter().map(|f| f.display().to_string()));
        let o = common::mechdraw().args(&args).output().unwrap();
        assert_eq!(o.status.code(), Some(2), "{}", String::from_utf8_lossy(&o.stderr));
        assert!(!bad.exists());
    }
}

#[test]
fn samples_that_cannot_be_assembled_are_counted_located_and_never_nan() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    // ±50 mm on the rocker, uniform: where |AC| is shortest (0.04 m at φ1 = 0°) a sample
    // whose |l_ab − l_bc| exceeds it cannot close its dyad.
    let o = run(&[
        "run",
        &template_path(),
        "--no-frames",
        "-q",
        "--out",
        out.to_str().unwrap(),
        "--set",
        "tolerances.l_bc={ tol = 0.05, distribution = \"uniform\" }",
        "--set",
        "tolerances.settings.samples=4000",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v = json(&out.join("fourbar-tolerances.json"));
    let t = &v["tolerances"];
    let failed = t["failed_samples"].as_u64().unwrap();
    assert!(failed > 0 && failed < 4000, "{failed} samples failed");
    // Located: the positions where samples fail, and only there; each failed sample fails
    // somewhere, none more often than it was drawn.
    let at: Vec<u64> = t["positions"].as_array().unwrap().iter().map(|p| p["failed"].as_u64().unwrap()).collect();
    assert!(at.iter().all(|&n| n <= failed) && at.iter().any(|&n| n > 0));
    assert!(at.iter().filter(|&&n| n > 0).count() < 360, "failures everywhere?");
    let worst = at.iter().enumerate().max_by_key(|(_, n)| **n).unwrap().0;
    assert!(!(60..=300).contains(&worst), "most failures at φ1 = {worst}°");
    // The positions with failures are marked untrusted.
    for p in t["positions"].as_array().unwrap() {
        if p["failed"].as_u64().unwrap() > 0 {
            assert_eq!(p["linear_trusted"], false);
        }
    }
    for f in ["fourbar-tolerances-tolerances.csv", "fourbar-tolerances.json", "fourbar-tolerances-tolerance-band.svg"] {
        let text = std::fs::read_to_string(out.join(f)).unwrap();
        assert!(!text.contains("NaN") && !text.contains("inf"), "{f} holds a non-finite number");
    }
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(stderr.is_empty() || !stderr.contains("panic"));
}

#[test]
fn bad_tolerances_name_the_file_and_field_and_write_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let t = template_path();
    for (set, field) in [
        ("tolerances.l_ac=0.0001", "tolerances.\"l_ac\""),
        ("tolerances.omega1=0.1", "tolerances.\"omega1\""),
        ("tolerances.l_ab=\"small\"", "tolerances.\"l_ab\""),
        ("tolerances.l_ab=-0.0001", "tolerances.\"l_ab\""),
        ("tolerances.l_ab={ upper = -0.0001, lower = 0.0001 }", "tolerances.\"l_ab\".upper"),
        ("tolerances.settings.samples=0", "tolerances.settings.samples"),
        ("tolerances.settings.samples=100000000000", "tolerances.settings.samples"),
        ("tolerances.settings.bins=10001", "tolerances.settings.bins"),
        ("tolerances.outputs.points=[\"Q\"]", "tolerances.outputs.points[0]"),
    ] {
        let out = tmp.path().join("out");
        let o = run(&["run", &t, "--out", out.to_str().unwrap(), "--set", set]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{set}: {err}");
        assert!(err.contains(TEMPLATE) && err.contains(&format!("field `{field}`")), "{set}: {err}");
        assert!(!out.exists(), "{set}: something was written");
    }
    // The N above the memory: a million positions' worth of statistics.
    let out = tmp.path().join("out");
    let o = run(&[
        "run",
        &t,
        "--out",
        out.to_str().unwrap(),
        "--set",
        "phi1_deg.step=0.01",
        "--set",
        "tolerances.settings.bins=5000",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("GB of statistics"));
    assert!(!out.exists());
}

#[test]
fn band_drawing_and_pareto_chart_goldens() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let o = run(&[
        "run",
        &template_path(),
        "--no-frames",
        "-q",
        "--out",
        out.to_str().unwrap(),
        "--set",
        "tolerances.settings.samples=5000",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let svg = std::fs::read_to_string(out.join("fourbar-tolerances-tolerance-band.svg")).unwrap();
    common::assert_golden_png("fourbar-tolerances-band.png", &svg);
    let svg = std::fs::read_to_string(out.join("diagrams/fourbar-tolerances/M.normal-pareto.svg")).unwrap();
    common::assert_golden_png("fourbar-tolerances-pareto.png", &svg);
    let svg = std::fs::read_to_string(out.join("diagrams/fourbar-tolerances/M.normal-band.svg")).unwrap();
    common::assert_golden_png("fourbar-tolerances-M-normal-band.png", &svg);
    common::assert_ezdxf_clean(&[&out.join("fourbar-tolerances-tolerance-band.dxf")]);
}
