//! The linkage pipeline end to end through the CLI: every output of the shaper is written
//! and consistent (DXF audited by ezdxf, one layer per position; frames and viewer; a
//! diagram per column; CSV and JSON with the same columns), and `--drag` moves the crank
//! pin to the nearest reachable point.

#![allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the library calls"
)]

mod common;

use std::path::Path;

fn run(args: &[&str], out: &Path) -> std::process::Output {
    common::mechdraw().args(args).arg("--out").arg(out).current_dir(common::root()).output().unwrap()
}

#[test]
fn shaper_run_writes_every_output() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("shaper");
    // 90 steps keep the debug-build test short; the solver tests cover the 360-step motion.
    let o = run(&["run", "templates/shaper.toml", "--set", "time.steps=90", "--png", "--quiet"], &out);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let dxf = out.join("shaper.dxf");
    common::assert_ezdxf_clean(&[&dxf]);
    let text = std::fs::read_to_string(&dxf).unwrap();
    assert!(text.contains("POS_000") && text.contains("POS_090") && !text.contains("POS_091"));
    assert!(text.contains("TRAJECTORY"));
    // One SVG frame per step, each with its PNG (--png).
    let frames: Vec<String> = std::fs::read_dir(out.join("frames/shaper"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(frames.iter().filter(|n| n.ends_with(".svg")).count(), 91);
    assert_eq!(frames.iter().filter(|n| n.ends_with(".png")).count(), 91);
    let html = std::fs::read_to_string(out.join("shaper.html")).unwrap();
    assert!(html.contains("shaper"));
    for col in ["E.x", "E.vx", "E.ax", "rocker.angle_deg", "rocker.omega", "rocker.eps"] {
        assert!(out.join(format!("diagrams/shaper/{col}.svg")).exists(), "{col}.svg");
        assert!(out.join(format!("diagrams/shaper/{col}.png")).exists(), "{col}.png");
    }
    // CSV: header, 91 rows; the first row is the start position (phi1 = 0), whose ram
    // position follows from the geometry: rocker through A = (125, 300), B at 600 along it,
    // E at 150 from B on y = 600.
    let csv = std::fs::read_to_string(out.join("shaper.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next().unwrap(), "t,E.x,E.vx,E.ax,rocker.angle_deg,rocker.omega,rocker.eps");
    let rows: Vec<Vec<f64>> = lines.map(|l| l.split(',').map(|v| v.parse().unwrap()).collect()).collect();
    assert_eq!(rows.len(), 91);
    let th = 300f64.atan2(125.0);
    let (bx, by) = (600.0 * th.cos(), 600.0 * th.sin());
    let xe = bx + (150f64.powi(2) - (600.0 - by).powi(2)).sqrt();
    assert!((rows[0][1] - xe).abs() < 1e-9, "{} vs {xe}", rows[0][1]);
    assert!((rows[0][4] - th.to_degrees()).abs() < 1e-9);
    assert!((rows[90][0] - 1.0).abs() < 1e-15);
    // JSON: the same numbers, keyed by column.
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("shaper.json")).unwrap()).unwrap();
    let samples = json["samples"].as_array().unwrap();
    assert_eq!(samples.len(), 91);
    assert_eq!(samples[30]["E.vx"].as_f64().unwrap(), rows[30][2]);
    assert_eq!(samples[30]["t"].as_f64().unwrap(), rows[30][0]);
    assert!(json["max_residual"].as_f64().unwrap() <= 1e-12);
}

#[test]
fn drag_moves_the_crank_pin_to_the_nearest_reachable_point() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("drag");
    // A is on the crank circle (O1 = (0, 300), r = 125): towards (0, 700) it can reach (0, 425).
    let o = run(&["run", "templates/shaper.toml", "--drag", "crank.A=0,700", "--quiet"], &out);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("shaper.json")).unwrap()).unwrap();
    let reached = &json["drag"][0]["reached"];
    let (x, y) = (reached[0].as_f64().unwrap(), reached[1].as_f64().unwrap());
    assert!(x.abs() < 1e-6 && (y - 425.0).abs() < 1e-6, "reached ({x}, {y})");
    assert!(json["max_residual"].as_f64().unwrap() <= 1e-12);
    // The rest of the mechanism followed: the ram point is still on its line, E right of B.
    let bodies = json["bodies"].as_array().unwrap();
    let point = |body: &str, p: &str| {
        let b = bodies.iter().find(|b| b["name"] == body).unwrap();
        (b["points"][p][0].as_f64().unwrap(), b["points"][p][1].as_f64().unwrap())
    };
    let (e, b) = (point("ram", "E"), point("rocker", "B"));
    assert!((e.1 - 600.0).abs() < 1e-9 && e.0 > b.0);
    common::assert_ezdxf_clean(&[&out.join("shaper.dxf")]);
}

/// A time step exactly on a dead point (the Chebyshev four-bar driven by its rocker down to
/// the rocker's smallest angle, 78.463°, reached at t* = 0.67128949 s) is reported by the
/// run: one warning naming t*, the driver value and the loop's joints, saying velocities
/// and accelerations there are unreliable; the JSON summary lists the step and flags its
/// sample (and no other). The shaper run has an empty list and no such warning.
#[test]
fn dead_point_step_is_reported_in_warnings_and_json() {
    let t_star = (1.7722121 - 0.0096f64.sqrt().atan2(0.02)) / 0.6;
    let text = std::fs::read_to_string(common::root().join("templates/fourbar-linkage.toml"))
        .unwrap()
        .replace("body = \"crank\"\nlaw = \"20*t\"", "body = \"rocker\"\nlaw = \"1.7722121 - 0.6*t\"")
        .replace("to = 0.3141592653589793, steps = 360", &format!("to = {t_star:.17}, steps = 40"));
    assert!(text.contains("law = \"1.7722121 - 0.6*t\"") && text.contains("steps = 40"), "template changed");
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("rocker.toml");
    std::fs::write(&path, text).unwrap();
    let loaded = mechdraw::scene::load(&path, &[]).unwrap();
    let outcome = mechdraw::run::run(&loaded, &mechdraw::run::RunOptions::default()).unwrap();
    let near: Vec<&String> = outcome.warnings.iter().filter(|w| w.contains("near-singular")).collect();
    assert_eq!(near.len(), 1, "{:?}", outcome.warnings);
    let w = near[0];
    assert!(w.contains(&format!("t = {t_star} s")), "{w}");
    assert!(w.contains("driver `rocker` = 78.4630°"), "{w}");
    assert!(w.contains("revolute joint `A`") && w.contains("revolute joint `B`"), "{w}");
    assert!(w.contains("velocities and accelerations there are unreliable"), "{w}");
    let list = outcome.summary["near_singular"].as_array().unwrap();
    assert_eq!(list.len(), 1);
    assert_eq!(list[0]["t"].as_f64().unwrap(), t_star);
    assert!(list[0]["constraints"].as_str().unwrap().contains("revolute joint `A`"));
    let samples = outcome.summary["samples"].as_array().unwrap();
    assert_eq!(samples.len(), 41);
    assert_eq!(samples[40]["near_singular"], serde_json::json!(true));
    assert!(samples[..40].iter().all(|s| s.get("near_singular").is_none()));

    let shaper = mechdraw::scene::load(&common::root().join("templates/shaper.toml"), &[]).unwrap();
    let outcome = mechdraw::run::run(&shaper, &mechdraw::run::RunOptions::default()).unwrap();
    assert!(outcome.summary["near_singular"].as_array().unwrap().is_empty());
    assert!(outcome.warnings.iter().all(|w| !w.contains("near-singular")), "{:?}", outcome.warnings);
}
