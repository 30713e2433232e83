//! Issue 14 item 10 on the four-bar template through the binary: the transmission angle
//! γ(φ1) and γ_min (diagram, JSON, warning), the instantaneous centres sheet, and
//! Joukowski's lever (JSON and CSV `me1_joukowski`, the sheet), each checked against an
//! independent route: the law of cosines from the crank angle alone, the instantaneous
//! centre constructed from the CSV's joint columns, and the reactions route's Me1.

#![allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the library calls"
)]

mod common;

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use common::{assert_ezdxf_clean, mechdraw, root};

const NAME: &str = "fourbar-chebyshev";
const L1: f64 = 0.04;
const L_AB: f64 = 0.10;
const L_BC: f64 = 0.10;
const D: f64 = 0.08; // |O1C|

struct Run {
    dir: tempfile::TempDir,
    stderr: String,
}

fn run(args: &[&str]) -> Run {
    let dir = tempfile::tempdir().unwrap();
    let out = mechdraw()
        .arg("run")
        .arg(root().join("templates/fourbar-chebyshev.toml"))
        .arg("--out")
        .arg(dir.path())
        .arg("--no-frames")
        .args(args)
        .output()
        .expect("run mechdraw");
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(out.status.success(), "mechdraw run {args:?} failed:\n{stderr}");
    Run { dir, stderr }
}

/// The template as it is, run once per test binary.
fn template() -> &'static Run {
    static RUN: OnceLock<Run> = OnceLock::new();
    RUN.get_or_init(|| run(&[]))
}

fn path(r: &Run, f: &str) -> PathBuf {
    r.dir.path().join(f)
}

fn read(p: &Path) -> String {
    std::fs::read_to_string(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

fn json(r: &Run) -> serde_json::Value {
    serde_json::from_str(&read(&path(r, &format!("{NAME}.json")))).unwrap()
}

/// CSV columns by name.
fn csv(r: &Run) -> std::collections::HashMap<String, Vec<f64>> {
    let text = read(&path(r, &format!("{NAME}.csv")));
    let mut lines = text.lines();
    let header: Vec<String> = lines.next().unwrap().split(',').map(str::to_string).collect();
    let mut cols: std::collections::HashMap<String, Vec<f64>> =
        header.iter().map(|h| (h.clone(), Vec::new())).collect();
    for line in lines {
        for (h, f) in header.iter().zip(line.split(',')) {
            cols.get_mut(h).unwrap().push(f.parse().unwrap());
        }
    }
    cols
}

/// γ by the law of cosines: |AC| from the triangle O1AC (crank angle only), then the angle
/// at B of the triangle ABC, folded to 0…90°.
fn gamma_closed_form_deg(phi1_deg: f64) -> f64 {
    let phi = phi1_deg.to_radians();
    let ac2 = L1 * L1 + D * D - 2.0 * L1 * D * phi.cos();
    let theta = ((L_AB * L_AB + L_BC * L_BC - ac2) / (2.0 * L_AB * L_BC)).acos().to_degrees();
    theta.min(180.0 - theta)
}

#[test]
fn gamma_column_and_gamma_min_agree_with_the_law_of_cosines() {
    let r = template();
    let c = csv(r);
    for (i, phi) in c["phi1_deg"].iter().enumerate() {
        let g = gamma_closed_form_deg(*phi);
        assert!((c["gamma_deg"][i] - g).abs() < 1e-9, "{phi}°: {} vs {g}", c["gamma_deg"][i]);
    }
    let j = json(r);
    let expected = 0.92f64.acos().to_degrees(); // |AC| = 0.04 at φ1 = 0
    assert!((j["gamma_min_deg"].as_f64().unwrap() - expected).abs() < 1e-9);
    assert_eq!(j["gamma_min_phi1_deg"].as_f64(), Some(0.0));
    assert!(j["outputs"].as_array().unwrap().iter().any(|o| o == "centres"));
}

#[test]
fn gamma_diagram_marks_gamma_min_and_the_40_deg_limit_and_the_report_warns() {
    let r = template();
    let svg = read(&path(r, &format!("diagrams/{NAME}/gamma.svg")));
    // γ_min with "min" a subscript (the `_` not drawn): read as a browser reads it.
    assert!(common::svg_plain(&svg).contains("γmin = 23.07° at φ1 = 0°"), "no γ_min mark");
    assert!(!svg.contains("γ_min"), "γ_min drawn with its underscore");
    assert!(svg.contains("usual limit 40°"), "no 40° line label");
    assert!(svg.contains("stroke-dasharray"), "the limit line is not dashed");
    assert!(
        r.stderr.contains("warning: transmission angle γ_min = 23.07° at φ1 = 0° is below the usual 40° limit"),
        "{}",
        r.stderr
    );
    assert!(r.stderr.contains("\nγ_min = 23.07° at φ1 = 0°") || r.stderr.contains("γ_min = 23.07° at φ1 = 0°\n"));
}

#[test]
fn joukowski_me1_agrees_with_the_reactions_route_at_every_position() {
    let r = template();
    let j = json(r);
    let positions = j["positions"].as_array().unwrap();
    assert_eq!(positions.len(), 360);
    let me1: Vec<f64> = positions.iter().map(|p| p["Me1"].as_f64().unwrap()).collect();
    let mj: Vec<f64> = positions.iter().map(|p| p["me1_joukowski"].as_f64().unwrap()).collect();
    let largest = me1.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    let worst = me1.iter().zip(&mj).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    eprintln!("max |Me1_J − Me1| = {worst:e} of max |Me1| = {largest}");
    assert!(worst <= 1e-9 * largest, "{worst} of {largest}");
    // The CSV carries the same numbers, after Me1.
    let c = csv(r);
    assert_eq!(c["me1_joukowski"].len(), 360);
    for (a, b) in c["me1_joukowski"].iter().zip(&mj) {
        assert_eq!(a.to_bits(), b.to_bits());
    }
}

#[test]
fn joukowski_in_a_mm_scene_is_in_n_mm() {
    let mm = run(&[
        "--set",
        "units=\"mm\"",
        "--set",
        "c=[80, 0]",
        "--set",
        "l1=40",
        "--set",
        "l_ab=100",
        "--set",
        "l_bm=100",
        "--set",
        "l_bc=100",
    ]);
    let (si, mm) = (json(template()), json(&mm));
    for k in [0usize, 90, 135, 200, 300] {
        let (a, b) = (
            si["positions"][k]["me1_joukowski"].as_f64().unwrap(),
            mm["positions"][k]["me1_joukowski"].as_f64().unwrap(),
        );
        assert!((b - 1000.0 * a).abs() <= 1e-9 * b.abs().max(1.0), "{k}: {b} N·mm vs {a} N·m");
        let me1 = mm["positions"][k]["Me1"].as_f64().unwrap();
        assert!((b - me1).abs() <= 1e-9 * me1.abs().max(1.0), "{k}");
    }
    assert!((mm["gamma_min_deg"].as_f64().unwrap() - si["gamma_min_deg"].as_f64().unwrap()).abs() < 1e-9);
}

#[test]
fn the_coupler_turns_about_i20_built_from_the_csv_columns() {
    // I20 = O1A ∩ CB from the joint columns; then ω2 = v_A / |A I20| and v_M ⊥ I20 M,
    // |v_M| = |ω2|·|I20 M| with the CSV's own velocities.
    let c = csv(template());
    let mut checked = 0;
    for (i, _) in c["phi1_deg"].iter().enumerate() {
        let (ax, ay, bx, by) = (c["A_x"][i], c["A_y"][i], c["B_x"][i], c["B_y"][i]);
        let (ux, uy, vx, vy) = (ax, ay, bx - D, by);
        let s = ux * vy - uy * vx;
        if s.abs() < 1e-6 * L1 * L_BC {
            continue; // I20 at (or near) infinity: the coupler translates
        }
        let t = (D * vy - 0.0 * vx) / s; // O1 + t·u = C + w·v
        let (ix, iy) = (t * ux, t * uy);
        let va = c["vA_mag"][i];
        let w2 = va / (ax - ix).hypot(ay - iy);
        let omega2 = c["omega2"][i];
        assert!((w2 - omega2.abs()).abs() <= 1e-9 * w2.max(1.0), "row {i}: {w2} vs {omega2}");
        let (rx, ry) = (c["M_x"][i] - ix, c["M_y"][i] - iy);
        let (vmx, vmy) = (c["vM_x"][i], c["vM_y"][i]);
        assert!((vmx * rx + vmy * ry).abs() <= 1e-9 * c["vM_mag"][i].max(1e-3) * rx.hypot(ry), "row {i}");
        assert!((c["vM_mag"][i] - omega2.abs() * rx.hypot(ry)).abs() <= 1e-9 * c["vM_mag"][i].max(1.0), "row {i}");
        checked += 1;
    }
    assert!(checked >= 350, "{checked}");
}

#[test]
fn the_sheets_are_written_named_and_clean() {
    let r = template();
    // The positions' titles φ_1 = 30° drawn with a subscript: read through the tspans.
    let centres = common::svg_plain(&read(&path(r, &format!("{NAME}-centres.svg"))));
    for name in ["I10", "I30", "I12", "I23", "I20", "I13", "Kennedy's lines", "φ1 = 30°", "φ1 = 330°"] {
        assert!(centres.contains(name), "centres sheet lacks {name}");
    }
    assert!(!centres.contains("NaN"));
    // Names drawn with subscripts (G_21) read through their tspans.
    let lever = common::svg_plain(&read(&path(r, &format!("{NAME}-joukowski.svg"))));
    for name in ["φ1 = 135°", "φ1 = 200°", "G21", "Fi3", "FM2", "Fb", "c21", "Me1 = −Σ Mp(Fi) / ω1 = "] {
        assert!(lever.contains(name), "Joukowski sheet lacks {name}");
    }
    assert!(!lever.contains("NaN"));
    // The printed Me1 at 200° is the JSON's, to four significant digits.
    let j = json(r);
    let p200 = j["positions"].as_array().unwrap().iter().find(|p| p["phi1_deg"] == 200.0).unwrap();
    let printed = format!("= {:.5} N·m", p200["me1_joukowski"].as_f64().unwrap()).replace('-', "−");
    assert!(lever.contains(&printed), "{printed}");
    assert_ezdxf_clean(&[&path(r, &format!("{NAME}-centres.dxf")), &path(r, &format!("{NAME}-joukowski.dxf"))]);
}
