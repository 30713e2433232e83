//! The triad through the binary: outputs, the JSON summary, `--set`, `check`, and bad
//! input (exit code 2, a message naming the file and the field, nothing written).

#![allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the library calls"
)]

mod common;

use std::path::Path;

use serde_json::Value;

const TEMPLATE: &str = "templates/triad-popa.toml";

fn template_text() -> String {
    std::fs::read_to_string(common::root().join(TEMPLATE)).unwrap()
}

fn run_json(args: &[&str]) -> Value {
    let tmp = tempfile::tempdir().unwrap();
    let out = common::mechdraw()
        .args(["run", TEMPLATE, "--quiet", "--json", "--out"])
        .arg(tmp.path().join("out"))
        .args(args)
        .current_dir(common::root())
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap()
}

fn pt(v: &Value) -> (f64, f64) {
    (v[0].as_f64().unwrap(), v[1].as_f64().unwrap())
}

fn dist(a: (f64, f64), b: (f64, f64)) -> f64 {
    ((a.0 - b.0).powi(2) + (a.1 - b.1).powi(2)).sqrt()
}

/// Checks every solution of a summary against the six equations of the template's data
/// (with l12 as given).
fn assert_solutions_close(s: &Value, l12: f64) {
    let o = [(15.0, 30.0), (90.0, 20.0), (150.0, 40.0)];
    let r = [50.0, 60.0, 84.0];
    for sol in s["solutions"].as_array().unwrap() {
        let a = [pt(&sol["A1"]), pt(&sol["A2"]), pt(&sol["A3"])];
        for i in 0..3 {
            assert!((dist(a[i], o[i]) - r[i]).abs() < 1e-9, "{sol}");
            let phi = sol[format!("phi{}_deg", i + 1)].as_f64().unwrap().to_radians();
            assert!(dist(a[i], (o[i].0 + r[i] * phi.cos(), o[i].1 + r[i] * phi.sin())) < 1e-9);
        }
        assert!((dist(a[0], a[1]) - l12).abs() < 1e-9);
        assert!((dist(a[1], a[2]) - 50.0).abs() < 1e-9);
        assert!((dist(a[0], a[2]) - 92.0).abs() < 1e-9);
        assert!(sol["residual"].as_f64().unwrap() <= 1e-10);
        assert!(["ccw", "cw"].contains(&sol["orientation"].as_str().unwrap()));
    }
}

#[test]
fn run_writes_dxf_svg_and_json_and_prints_the_summary() {
    let tmp = tempfile::tempdir().unwrap();
    let out = common::mechdraw()
        .args(["run", TEMPLATE, "--json", "--out"])
        .arg(tmp.path())
        .current_dir(common::root())
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    for f in ["triad-popa.dxf", "triad-popa.svg", "triad-popa-modes.dxf", "triad-popa-modes.svg", "triad-popa.json"] {
        assert!(tmp.path().join(f).is_file(), "{f} missing");
    }
    let s: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(s["kind"], "triad");
    let phi1 = s["pattern"]["phi1_deg"].as_f64().unwrap();
    assert!((phi1 - 75.77).abs() <= 0.005, "{phi1}");
    assert!(s["pattern"]["iterations"].as_u64().unwrap() >= 1);
    assert!(s["pattern"]["residual"].as_f64().unwrap() < 1e-5);
    assert_eq!(s["solutions"].as_array().unwrap().len(), 8);
    assert_solutions_close(&s, 50.0);
    // The file holds the same summary.
    let file: Value =
        serde_json::from_str(&std::fs::read_to_string(tmp.path().join("triad-popa.json")).unwrap()).unwrap();
    assert_eq!(file, s);
    // The terminal report names the method and the modes.
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("pattern method") && err.contains("8 assembly modes"), "{err}");
}

#[test]
fn set_override_changes_the_result() {
    let base = run_json(&[]);
    // l12 = 55: every mode moves; on the seed's A2 branch the pattern method now leaves the
    // range where A2 exists, and says so by name instead of failing the run.
    let changed = run_json(&["--set", "l12=55"]);
    assert_solutions_close(&changed, 55.0);
    let phis = |s: &Value| -> Vec<f64> {
        s["solutions"].as_array().unwrap().iter().map(|x| x["phi1_deg"].as_f64().unwrap()).collect()
    };
    assert!(phis(&base).iter().zip(phis(&changed)).all(|(a, b)| (a - b).abs() > 0.1));
    let err = changed["pattern"]["error"].as_str().unwrap();
    assert!(err.contains("A2 does not exist"), "{err}");
    // R3 = 86: the pattern method converges elsewhere, onto one of the modes.
    let r3 = run_json(&["--set", "r[2]=86"]);
    let p = r3["pattern"]["phi1_deg"].as_f64().unwrap();
    assert!((p - base["pattern"]["phi1_deg"].as_f64().unwrap()).abs() > 0.1);
    assert!(phis(&r3).iter().any(|m| (m - p).abs() < 1e-4), "{p} not among {:?}", phis(&r3));
    // Orientation filter through --set.
    let ccw = run_json(&["--set", "orientation=ccw"]);
    assert!(ccw["solutions"].as_array().unwrap().iter().all(|s| s["orientation"] == "ccw"));
    assert_eq!(ccw["solutions"].as_array().unwrap().len(), 4);
}

#[test]
fn check_validates_without_solving() {
    let out = common::mechdraw().args(["check", TEMPLATE]).current_dir(common::root()).output().unwrap();
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).contains("ok (triad scene \"triad-popa\")"));
    let out =
        common::mechdraw().args(["check", TEMPLATE, "--set", "l23=-1"]).current_dir(common::root()).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("field `l23`"));
}

/// Runs a broken scene; expects exit code 2, a message with the file and every `needles`,
/// and no output directory.
fn assert_rejected(scene_text: &str, needles: &[&str]) {
    let tmp = tempfile::tempdir().unwrap();
    let scene = tmp.path().join("bad-triad.toml");
    std::fs::write(&scene, scene_text).unwrap();
    let out_dir = tmp.path().join("out");
    let out = common::mechdraw().arg("run").arg(&scene).arg("--out").arg(&out_dir).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("bad-triad.toml"), "no file name in: {err}");
    for n in needles {
        assert!(err.contains(n), "`{n}` not in: {err}");
    }
    assert!(!out_dir.exists() || std::fs::read_dir(&out_dir).unwrap().next().is_none(), "something was written");
    assert!(!Path::new(&out_dir).join("triad-popa.svg").exists());
}

#[test]
fn bad_input_exits_2_naming_file_and_field_and_writes_nothing() {
    let t = template_text();
    assert_rejected(&t.replace("l12 = 50.0", "l12 = 50,0"), &["not valid TOML"]);
    assert_rejected(&t.replace("l12 = 50.0", "l12 = 50.0\nl14 = 3.0"), &["field `l14`", "unknown field"]);
    assert_rejected(&t.replace("l23 = 50.0", ""), &["field `l23`", "missing field"]);
    assert_rejected(&t.replace("l12 = 50.0", "l12 = -5.0"), &["field `l12`", "positive"]);
    assert_rejected(&t.replace("l13 = 92.0", "l13 = 120.0"), &["field `l13`", "l12 + l23 = 100"]);
    assert_rejected(&t.replace("step_deg = 0.01", "step_deg = 0.0"), &["field `pattern.step_deg`"]);
    // Impossible geometry: O2 so far away that A1 and A2 can never be l12 apart ...
    assert_rejected(&t.replace("o2 = [90.0, 20.0]", "o2 = [400.0, 20.0]"), &["l12", "o2", "r[1]"]);
    // ... and circle 3 so small that A3 never reaches it.
    assert_rejected(&t.replace("r = [50.0, 60.0, 84.0]", "r = [50.0, 60.0, 8.0]"), &["no configuration", "r[2]"]);
}

#[test]
fn mode_chooses_the_assembly_mode_the_picture_draws() {
    let plain = run_json(&[]);
    let solutions = plain["solutions"].as_array().unwrap();
    assert_eq!(solutions.len(), 8);
    // The pattern method's mode by default ...
    let pattern_phi1 = plain["pattern"]["phi1_deg"].as_f64().unwrap();
    let primary = plain["primary"].as_u64().unwrap() as usize;
    assert!((solutions[primary]["phi1_deg"].as_f64().unwrap() - pattern_phi1).abs() < 1e-3);
    // ... and any other by `mode` (numbered from 1 as the report lists them).
    for mode in [1, 3, 8] {
        let tmp = tempfile::tempdir().unwrap();
        let out = common::mechdraw()
            .args(["run", TEMPLATE, "--json", "--set", &format!("mode={mode}"), "--out"])
            .arg(tmp.path())
            .current_dir(common::root())
            .output()
            .unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let json: Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(json["primary"], mode - 1, "mode {mode}");
        // The modes found do not depend on which one is drawn.
        assert_eq!(json["solutions"], plain["solutions"]);
        let report = String::from_utf8_lossy(&out.stderr);
        let drawn: Vec<&str> = report.lines().filter(|l| l.ends_with("(drawn)")).collect();
        assert_eq!(drawn.len(), 1, "{report}");
        assert!(drawn[0].trim_start().starts_with(&format!("{mode} ")), "{report}");
        let svg = std::fs::read_to_string(tmp.path().join("triad-popa.svg")).unwrap();
        assert!(svg.contains(&format!("Solid: mode {mode} of 8")), "the caption names mode {mode}");
        // The DXF read by ezdxf: its one closed triangle on MECHANISM closes the triad's six
        // equations (the template's pivots, radii and sides) at mode `mode`'s vertices.
        let out = std::process::Command::new(common::python())
            .arg(common::root().join("tests/ezdxf_inspect.py"))
            .arg(tmp.path().join("triad-popa.dxf"))
            .output()
            .unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let inspected: Value = serde_json::from_slice(&out.stdout).unwrap();
        // Closed three-point polylines: the triad's triangle and the ground symbols under
        // the pivots; the triangle is by far the largest.
        let area = |p: &[(f64, f64)]| {
            ((p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[2].0 - p[0].0) * (p[1].1 - p[0].1)).abs() / 2.0
        };
        let a: Vec<(f64, f64)> = inspected["polylines"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|p| p["layer"] == "MECHANISM" && p["closed"] == true && p["points"].as_array().unwrap().len() == 3)
            .map(|p| p["points"].as_array().unwrap().iter().map(pt).collect::<Vec<_>>())
            .max_by(|p, q| area(p).total_cmp(&area(q)))
            .expect("the triangle on MECHANISM");
        let o = [(15.0, 30.0), (90.0, 20.0), (150.0, 40.0)];
        let r = [50.0, 60.0, 84.0];
        for i in 0..3 {
            assert!((dist(a[i], o[i]) - r[i]).abs() < 1e-6, "mode {mode}: |O{}A{}|", i + 1, i + 1);
        }
        assert!((dist(a[0], a[1]) - 50.0).abs() < 1e-6 && (dist(a[1], a[2]) - 50.0).abs() < 1e-6);
        assert!((dist(a[0], a[2]) - 92.0).abs() < 1e-6);
        let sol = &solutions[mode as usize - 1];
        for (i, v) in ["A1", "A2", "A3"].iter().enumerate() {
            assert!(dist(a[i], pt(&sol[*v])) < 1e-6, "mode {mode}: {v} drawn at {:?}, not {}", a[i], sol[*v]);
        }
    }
    let t = template_text();
    let with_mode = |m: &str| t.replace("orientation = \"both\"", &format!("orientation = \"both\"\nmode = {m}"));
    assert_rejected(&with_mode("9"), &["mode = 9", "8 assembly modes", "1 to 8"]);
    assert_rejected(&with_mode("0"), &["field `mode`", "1 or more"]);
}
