//! Tolerances of the 6R triad (issue 34) on templates/triad-tolerances.toml (seed 000's
//! triad): the sensitivities (implicit function theorem on the closure equations) against
//! central finite differences of the all-modes solver (the degree-6 polynomial, another
//! route than the Newton the samples take), the Monte Carlo's samples against that route,
//! its σ against the linear σ, the worst case bounding every uniform sample, shards merged
//! into the single run, samples that lose their mode, and bad input.

mod common;

use common::tolerance::{assert_merged_equals_single, channel_components, run_sharded, scaled};

use std::path::Path;

use mechdraw::scene::triad::TriadScene;
use mechdraw::scene::{Override, Scene};
use mechdraw::solve::tolerance::monte_carlo::{self, Model, chunk_count, sample_deviations};
use mechdraw::solve::tolerance::triad::{TriadModel, TriadOutput, TriadParam};
use mechdraw::solve::tolerance::{Distribution, linear_all, ranges};
use mechdraw::solve::triad::{Configuration, Triad, all_modes};

const TEMPLATE: &str = "triad-tolerances.toml";

fn text() -> String {
    std::fs::read_to_string(common::root().join("templates").join(TEMPLATE)).unwrap()
}

fn scene(sets: &[&str]) -> TriadScene {
    let overrides: Vec<Override> = sets.iter().map(|s| s.parse().unwrap()).collect();
    let Scene::Triad(s) = mechdraw::scene::parse(&text(), TEMPLATE, &overrides).unwrap() else { panic!() };
    s
}

fn triad_of(s: &TriadScene) -> Triad {
    Triad::new(s.o, s.r, s.l12, s.l23, s.l13).unwrap()
}

fn every_output() -> Vec<TriadOutput> {
    vec![
        TriadOutput::Vertex(0),
        TriadOutput::Vertex(1),
        TriadOutput::Vertex(2),
        TriadOutput::Phi(0),
        TriadOutput::Phi(1),
        TriadOutput::Phi(2),
        TriadOutput::Triangle,
    ]
}

/// The nominal's modes and a model watching every output under every field.
fn model() -> (Triad, Vec<Configuration>, TriadModel) {
    let t = triad_of(&scene(&[]));
    let modes = all_modes(&t, None).unwrap();
    let m = TriadModel::new(t, modes.clone(), TriadParam::ALL.to_vec(), every_output());
    (t, modes, m)
}

/// The mode of `t` nearest (largest vertex distance) to configuration `near`, by the
/// all-modes solver: the polynomial route.
fn nearest_mode(t: &Triad, near: &Configuration) -> Configuration {
    let d = |c: &Configuration| (0..3).map(|i| (c.a[i] - near.a[i]).norm()).fold(0.0, f64::max);
    all_modes(t, None).unwrap().into_iter().min_by(|a, b| d(a).total_cmp(&d(b))).unwrap()
}

/// The channels of a configuration as the model lays them out (A1..A3 as x, y; φ1..φ3 and
/// the triangle's angle in degrees).
fn channels(c: &Configuration) -> Vec<f64> {
    let tri = mechdraw::geom::angle_of(c.a[1] - c.a[0]).to_degrees();
    let mut v: Vec<f64> = c.a.iter().flat_map(|p| [p.x, p.y]).collect();
    v.extend(c.phi.map(f64::to_degrees));
    v.push(tri);
    v
}

fn wrap(d: f64) -> f64 {
    (d + 180.0).rem_euclid(360.0) - 180.0
}

#[test]
fn sensitivities_equal_central_differences_of_the_all_modes_solver_in_every_mode() {
    let (t, modes, m) = model();
    assert_eq!(modes.len(), 8, "seed 000's triad has 8 assembly modes");
    let np = TriadParam::ALL.len();
    for (k, mode) in modes.iter().enumerate() {
        let exact = m.sensitivities(k).unwrap();
        for (j, p) in TriadParam::ALL.iter().enumerate() {
            // 1e-6 of the triad's size (150 mm).
            let h = 1e-6 * t.scale();
            let (mut tp, mut tm) = (t, t);
            p.apply(&mut tp, h);
            p.apply(&mut tm, -h);
            let (cp, cm) = (channels(&nearest_mode(&tp, mode)), channels(&nearest_mode(&tm, mode)));
            for ch in 0..cp.len() {
                let fd = (if ch >= 6 { wrap(cp[ch] - cm[ch]) } else { cp[ch] - cm[ch] }) / (2.0 * h);
                let s = exact[ch * np + j];
                assert!(
                    (s - fd).abs() <= 1e-6 * (1.0 + s.abs()),
                    "mode {}, d(channel {ch})/d({}): exact {s} vs central difference {fd}",
                    k + 1,
                    p.field()
                );
            }
        }
    }
}

#[test]
fn monte_carlo_samples_equal_the_all_modes_solver_of_the_scene_with_its_fields_set() {
    let s = scene(&[]);
    let tol = s.tolerances.as_ref().unwrap();
    let t = triad_of(&s);
    let modes = all_modes(&t, None).unwrap();
    let m = TriadModel::new(t, modes.clone(), tol.study.params.clone(), every_output());
    let dims = &tol.study.dims;
    let (nc, n) = (m.channels(), m.positions());
    let (mut out, mut failed) = (vec![0.0; n * nc], vec![false; n]);
    for j in [0u64, 1, 77, 300, 4095] {
        let dev = sample_deviations(dims, 5, j);
        assert!(!m.evaluate(&mut (), &dev, &mut out, &mut failed), "sample {j} lost a mode");
        // The scene parsed again with every toleranced field --set to the sample's value.
        let sets: Vec<String> = dims.iter().zip(&dev).map(|(d, e)| format!("{}={:e}", d.name, d.nominal + e)).collect();
        let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
        let ts = triad_of(&scene(&sets));
        for (k, mode) in modes.iter().enumerate() {
            let got = channels(&nearest_mode(&ts, mode));
            let want = channels(mode);
            for ch in 0..got.len() {
                let d = if ch >= 6 { wrap(got[ch] - want[ch]) } else { got[ch] - want[ch] };
                let tol = if ch >= 6 { 1e-10 } else { 1e-12 * t.scale() };
                assert!(
                    (d - out[k * nc + ch]).abs() <= tol,
                    "sample {j}, mode {}, channel {ch}: polynomial route {d} vs Monte Carlo {}",
                    k + 1,
                    out[k * nc + ch]
                );
            }
        }
    }
}

#[test]
fn for_small_normal_tolerances_monte_carlo_sigma_tends_to_the_linear_sigma() {
    let s = scene(&[]);
    let tol = s.tolerances.as_ref().unwrap();
    let t = triad_of(&s);
    let m = TriadModel::new(t, all_modes(&t, None).unwrap(), tol.study.params.clone(), every_output());
    // A tenth of the template's tolerances: the linear regime.
    let dims = scaled(&tol.study.dims, 0.1, Distribution::Normal { k: 3.0 });
    let comps = channel_components(m.channels());
    let lin = linear_all(&m, &dims, &comps);
    let n = 100_000u64;
    let mc = monte_carlo::run(&m, &dims, &comps, &ranges(&lin, comps.len()), 400, n, 3, 0..chunk_count(n));
    assert_eq!(mc.failed_samples, 0);
    for (k, lk) in lin.iter().enumerate() {
        for c in 0..comps.len() {
            let l = &lk.as_ref().unwrap()[c];
            let st = mc.tallies[k * comps.len() + c].summary().unwrap();
            // σ's sampling error at N = 1e5 is σ/√(2N) = 0.22 %: 5 of them, plus the second
            // order of a tenth of the template's band.
            assert!(
                (st.sigma / l.sigma - 1.0).abs() < 0.011 + 0.01,
                "mode {}, channel {c}: MC σ {} vs linear σ {}",
                k + 1,
                st.sigma,
                l.sigma
            );
        }
    }
}

#[test]
fn the_worst_case_bounds_every_uniform_sample_in_the_linear_regime() {
    let s = scene(&[]);
    let tol = s.tolerances.as_ref().unwrap();
    let t = triad_of(&s);
    let m = TriadModel::new(t, all_modes(&t, None).unwrap(), tol.study.params.clone(), every_output());
    let dims = scaled(&tol.study.dims, 0.01, Distribution::Uniform);
    let comps = channel_components(m.channels());
    let lin = linear_all(&m, &dims, &comps);
    let n = 20_000u64;
    let mc = monte_carlo::run(&m, &dims, &comps, &ranges(&lin, comps.len()), 100, n, 8, 0..chunk_count(n));
    for (k, lk) in lin.iter().enumerate() {
        for c in 0..comps.len() {
            let l = &lk.as_ref().unwrap()[c];
            let st = mc.tallies[k * comps.len() + c].summary().unwrap();
            // Second-order terms at 1 % of the template's band: far below 1e-3 of the band.
            let slack = 1e-3 * l.worst_case;
            assert!(st.min >= -l.worst_case - slack && st.max <= l.worst_case + slack, "mode {}, ch {c}", k + 1);
            // Uniform samples reach well into the band's corners' direction.
            assert!(st.max - st.min > 0.5 * l.worst_case, "mode {}, ch {c}: samples too narrow", k + 1);
        }
    }
}

fn run(args: &[&str]) -> std::process::Output {
    common::mechdraw().args(args).output().unwrap()
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The template with `samples` written to `dir`.
fn scene_file(dir: &Path, samples: u32) -> String {
    let t = text().replace("samples = 100000", &format!("samples = {samples}"));
    let path = dir.join("triad-tol.toml");
    std::fs::write(&path, t).unwrap();
    path.display().to_string()
}

#[test]
fn the_template_runs_end_to_end_and_shards_merge_into_the_single_run() {
    let tmp = tempfile::tempdir().unwrap();
    let t = scene_file(tmp.path(), 3000);
    let s = run_sharded(tmp.path(), &t, "triad-tolerances", 4, &["-q"], &[], false);
    let (single, merged) = (&s.single, &s.merged);
    assert_merged_equals_single(&s, &["triad-tolerances-tolerances.csv", "triad-tolerances-contributions.csv"]);
    let (a, b) = (json(&single.join("triad-tolerances.json")), json(&merged.join("triad-tolerances.json")));
    assert_eq!(a["tolerances"], b["tolerances"]);
    let tol = &a["tolerances"];
    assert_eq!(tol["drawn"], 3000);
    assert_eq!(tol["position"], "mode");
    // One row per assembly mode, the modes as the triad's own summary lists them.
    let positions = tol["positions"].as_array().unwrap();
    let solutions = a["solutions"].as_array().unwrap();
    assert_eq!(positions.len(), solutions.len());
    for (k, (p, sol)) in positions.iter().zip(solutions).enumerate() {
        // A mode is a whole number, written as one (`1`, not `1.0`).
        assert!(p["mode"].is_u64() && p["mode"] == k + 1, "mode {}", p["mode"]);
        let nominal = p["values"]["A2.x"]["nominal"].as_f64().unwrap();
        assert_eq!(nominal, sol["A2"][0].as_f64().unwrap());
        let wc = p["values"]["A2.x"]["wc"].as_f64().unwrap();
        let rss = p["values"]["A2.x"]["rss"].as_f64().unwrap();
        assert!(wc > rss && rss > 0.0, "A2.x: wc {wc}, rss {rss}");
    }
    for c in tol["components"].as_array().unwrap() {
        assert!(c["worst"]["mode"].is_u64(), "{}: widest mode {}", c["name"], c["worst"]["mode"]);
    }
    // Pareto charts of the vertices' coordinates and the angle; no band drawing (no path).
    let diagrams = single.join("diagrams").join("triad-tolerances");
    for f in ["A1.x-pareto.svg", "A3.y-pareto.svg", "phi1_deg.value-pareto.svg"] {
        assert!(diagrams.join(f).exists(), "{f}");
    }
    assert!(!single.join("triad-tolerances-tolerance-band.svg").exists());
    // The contributions' worst cases add up to the stack's, per mode and component.
    let csv = std::fs::read_to_string(single.join("triad-tolerances-contributions.csv")).unwrap();
    let mut sums = std::collections::BTreeMap::<(String, String), f64>::new();
    for line in csv.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        *sums.entry((f[0].to_string(), f[1].to_string())).or_default() += f[4].parse::<f64>().unwrap();
    }
    for (k, p) in positions.iter().enumerate() {
        let wc = p["values"]["A1.y"]["wc"].as_f64().unwrap();
        let sum = sums[&((k + 1).to_string(), "A1.y".to_string())];
        assert!((sum - wc).abs() <= 1e-12 * wc, "mode {}: Σ|s|t = {sum} vs wc {wc}", k + 1);
    }
}

#[test]
fn samples_that_lose_their_mode_are_counted_located_and_never_nan() {
    // Mode 1 of seed 000 sits where O1A1, O2A2, O3A3 nearly meet (J's relative determinant
    // 0.026); ±5 mm on l13 makes some samples lose it (the mode merges with another and
    // the pair vanishes), and only it.
    let tmp = tempfile::tempdir().unwrap();
    let t = scene_file(tmp.path(), 2000);
    let out = tmp.path().join("out");
    let o = run(&["run", &t, "--out", out.to_str().unwrap(), "--set", "tolerances.l13=5.0"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v = json(&out.join("triad-tolerances.json"));
    let tol = &v["tolerances"];
    let failed = tol["failed_samples"].as_u64().unwrap();
    assert!(failed > 0 && failed < 2000, "failed samples: {failed}");
    let positions = tol["positions"].as_array().unwrap();
    assert_eq!(positions[0]["failed"].as_u64().unwrap(), failed, "located in mode 1");
    assert!(positions[1..].iter().all(|p| p["failed"] == 0));
    let notes = positions[0]["notes"].as_array().unwrap();
    assert!(notes.iter().any(|n| n.as_str().unwrap().starts_with("near a dead point")), "{notes:?}");
    assert_eq!(positions[0]["linear_trusted"], false);
    for f in ["triad-tolerances-tolerances.csv", "triad-tolerances.json"] {
        let text = std::fs::read_to_string(out.join(f)).unwrap();
        assert!(!text.contains("NaN") && !text.contains("inf"), "{f} holds a non-finite number");
    }
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("cannot be assembled in some assembly mode (first at mode = 1)"), "{err}");
}

#[test]
fn bad_tolerances_name_the_file_and_field_and_write_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let t = scene_file(tmp.path(), 100);
    for (set, field) in [
        ("tolerances.o4=[0.1, 0.1]", "tolerances.o4[0]"),
        ("tolerances.newton=0.1", "tolerances.\"newton\""),
        ("tolerances.l12=-0.1", "tolerances.\"l12\""),
        ("tolerances.l12={ upper = -0.1, lower = 0.1 }", "tolerances.\"l12\".upper"),
        ("tolerances.l13=\"x\"", "tolerances.\"l13\""),
        ("tolerances.outputs.points=[\"A4\"]", "tolerances.outputs.points[0]"),
        ("tolerances.outputs.angles=[\"crank\"]", "tolerances.outputs.angles[0]"),
        ("tolerances.outputs.velocities=[\"A1\"]", "tolerances.outputs.velocities"),
        ("tolerances.settings.samples=0", "tolerances.settings.samples"),
    ] {
        let out = tmp.path().join("out");
        let o = run(&["run", &t, "--out", out.to_str().unwrap(), "--set", set]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{set}: {err}");
        assert!(err.contains("triad-tol.toml") && err.contains(&format!("field `{field}`")), "{set}: {err}");
        assert!(!out.exists(), "{set}: something was written");
    }
}

/// The drawing's polylines on `layer`, in drawing order.
fn polylines(d: &mechdraw::draw::Drawing, layer: &str) -> Vec<Vec<mechdraw::geom::Point>> {
    let l = d.layers.iter().position(|x| x.name == layer).unwrap();
    d.entities
        .iter()
        .filter(|e| e.layer == l)
        .filter_map(|e| match &e.shape {
            mechdraw::draw::Shape::Polyline { points, .. } => Some(points.clone()),
            _ => None,
        })
        .collect()
}

#[test]
fn the_tolerance_zones_drawing_holds_each_modes_rss_ellipses_and_monte_carlo_boxes() {
    let tmp = tempfile::tempdir().unwrap();
    let t = scene_file(tmp.path(), 5000);
    let out = tmp.path().join("out");
    let o = run(&["run", &t, "-q", "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // The same study as products (same seed and samples): its drawing's numbers against the table's.
    let loaded = mechdraw::scene::load(Path::new(&t), &[]).unwrap();
    let p = mechdraw::run::products(&loaded, &mechdraw::run::RunOptions::default()).unwrap();
    let d = &p.sheets.iter().find(|s| s.suffix == "tolerance-zones").expect("a zones sheet").drawing;
    let texts: Vec<&str> = d.entities.iter().filter_map(|e| e.shape.text()).collect();
    let mags: Vec<f64> = texts
        .iter()
        .filter_map(|t| t.strip_prefix("deviations × "))
        .map(|t| t.split(':').next().unwrap().parse().unwrap())
        .collect();
    let csv = std::fs::read_to_string(out.join("triad-tolerances-tolerances.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let rows: Vec<Vec<f64>> = lines.map(|l| l.split(',').map(|v| v.parse().unwrap_or(f64::NAN)).collect()).collect();
    assert_eq!(mags.len(), rows.len(), "a magnification per mode");
    let (ellipses, boxes) = (polylines(d, "TOL_RSS"), polylines(d, "TOL_MC"));
    assert_eq!((ellipses.len(), boxes.len()), (3 * rows.len(), 3 * rows.len()));
    let span = |pts: &[mechdraw::geom::Point], x: bool| {
        let v: Vec<f64> = pts.iter().map(|p| if x { p.x } else { p.y }).collect();
        v.iter().fold(f64::MIN, |a, b| a.max(*b)) - v.iter().fold(f64::MAX, |a, b| a.min(*b))
    };
    for (k, row) in rows.iter().enumerate() {
        let col = |c: &str| row[header.iter().position(|h| *h == c).unwrap()];
        for (i, v) in ["A1", "A2", "A3"].iter().enumerate() {
            let (e, b) = (&ellipses[3 * k + i], &boxes[3 * k + i]);
            for (x, part) in [(true, "x"), (false, "y")] {
                // The 3σ ellipse's extent in x (y) is the RSS of x (y): 72 points draw it to
                // within 1 − cos(2.5°) of it.
                let rss = col(&format!("{v}.{part}.rss"));
                let half = 0.5 * span(e, x) / mags[k];
                assert!(
                    half <= rss * (1.0 + 1e-12) && half >= rss * (1.0 - 1e-3),
                    "mode {}, {v}.{part}: ellipse ±{half} vs RSS {rss}",
                    k + 1
                );
                // The box is the Monte Carlo's 0.135–99.865 % of x (y).
                let mc = col(&format!("{v}.{part}.mc_p99.865")) - col(&format!("{v}.{part}.mc_p0.135"));
                let drawn = span(b, x) / mags[k];
                assert!((drawn - mc).abs() <= 1e-9 * mc, "mode {}, {v}.{part}: box {drawn} vs MC {mc}", k + 1);
            }
        }
    }
    // Every zone named, in every mode.
    for v in ["A1", "A2", "A3"] {
        assert_eq!(texts.iter().filter(|t| **t == v).count(), rows.len(), "{v}");
    }
    let svg = std::fs::read_to_string(out.join("triad-tolerances-tolerance-zones.svg")).unwrap();
    common::assert_golden_png("triad-tolerances-zones.png", &svg);
    common::assert_ezdxf_clean(&[&out.join("triad-tolerances-tolerance-zones.dxf")]);
}
