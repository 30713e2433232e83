//! `mechdraw run` of the four-bar template: the files it writes (frames, DXF, viewer,
//! diagrams, CSV, JSON), golden frames and DXF, and the data checked against closed forms
//! and finite differences (independent of the solver's own formulas).

#![allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the library calls"
)]

mod common;

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use common::{assert_ezdxf_clean, assert_golden_png, assert_golden_text, mechdraw, root};

const NAME: &str = "fourbar-chebyshev";
/// Template values (design.md §3).
const L1: f64 = 0.04;
const L_AB: f64 = 0.10;
const L_BC: f64 = 0.10;
const OMEGA1: f64 = 20.0;
const C: [f64; 2] = [0.08, 0.0];

fn template() -> PathBuf {
    root().join("templates/fourbar-chebyshev.toml")
}

/// Runs the template with `args` into a fresh directory; panics with the output on failure.
fn run(dir: &Path, args: &[&str]) -> std::process::Output {
    let out = mechdraw().arg("run").arg(template()).arg("--out").arg(dir).args(args).output().expect("run mechdraw");
    assert!(
        out.status.success(),
        "mechdraw run {args:?} failed:\n{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// The full template (positions, velocities, accelerations, forces), run once per test binary.
fn full() -> &'static Path {
    static DIR: OnceLock<tempfile::TempDir> = OnceLock::new();
    DIR.get_or_init(|| {
        let d = tempfile::tempdir().unwrap();
        run(d.path(), &["--png"]);
        d
    })
    .path()
}

/// The template with kinematics only (no forces), run once per test binary.
fn kinematics_only() -> &'static Path {
    static DIR: OnceLock<tempfile::TempDir> = OnceLock::new();
    DIR.get_or_init(|| {
        let d = tempfile::tempdir().unwrap();
        run(d.path(), &["--set", r#"outputs=["position", "velocity", "acceleration"]"#]);
        d
    })
    .path()
}

fn read(p: &Path) -> String {
    std::fs::read_to_string(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

#[test]
fn golden_frame_000() {
    assert_golden_png("fourbar/frame_000.png", &read(&kinematics_only().join(format!("frames/{NAME}/pos_000.svg"))));
}

#[test]
fn golden_frame_090() {
    assert_golden_png("fourbar/frame_090.png", &read(&kinematics_only().join(format!("frames/{NAME}/pos_090.svg"))));
}

#[test]
fn golden_frame_180() {
    assert_golden_png("fourbar/frame_180.png", &read(&kinematics_only().join(format!("frames/{NAME}/pos_180.svg"))));
}

#[test]
fn golden_force_frame_000() {
    assert_golden_png("fourbar/forces_000.png", &read(&full().join(format!("frames/{NAME}/pos_000.svg"))));
}

#[test]
fn golden_force_frame_090() {
    assert_golden_png("fourbar/forces_090.png", &read(&full().join(format!("frames/{NAME}/pos_090.svg"))));
}

#[test]
fn golden_force_frame_180() {
    assert_golden_png("fourbar/forces_180.png", &read(&full().join(format!("frames/{NAME}/pos_180.svg"))));
}

#[test]
fn golden_dxf_of_three_positions_and_the_full_dxf_audit_clean() {
    let d = tempfile::tempdir().unwrap();
    run(d.path(), &["--set", "phi1_deg.step=120", "--no-frames"]);
    let small = d.path().join(format!("{NAME}.dxf"));
    assert_golden_text("fourbar/fourbar-3-positions.dxf", &read(&small));
    let big = full().join(format!("{NAME}.dxf"));
    assert_ezdxf_clean(&[&small, &big, &root().join("golden/fourbar/fourbar-3-positions.dxf")]);
    // One layer per position, plus the content layers.
    let text = read(&big);
    for layer in ["POS_000", "POS_090", "POS_359", "MECHANISM", "COUPLER_CURVE", "DIMENSIONS"] {
        assert!(
            text.contains(&format!("\n{layer}\r\n")) || text.contains(&format!("\n{layer}\n")),
            "layer {layer} missing"
        );
    }
}

#[test]
fn every_output_is_written() {
    let dir = full();
    for f in [
        format!("{NAME}.dxf"),
        format!("{NAME}.svg"),
        format!("{NAME}.html"),
        format!("{NAME}.csv"),
        format!("{NAME}.json"),
    ] {
        assert!(dir.join(&f).is_file(), "{f} missing");
    }
    // One SVG frame per position, each with its PNG (the run is made with --png).
    let names: Vec<String> = std::fs::read_dir(dir.join(format!("frames/{NAME}")))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names.iter().filter(|n| n.ends_with(".svg")).count(), 360);
    assert_eq!(names.iter().filter(|n| n.ends_with(".png")).count(), 360);
    for q in [
        "phi2_deg", "phi3_deg", "gamma", "omega2", "omega3", "eps2", "eps3", "vM", "aM", "R_A", "R_B", "R_C", "R_O",
        "Me1",
    ] {
        let svg = dir.join(format!("diagrams/{NAME}/{q}.svg"));
        assert!(read(&svg).starts_with("<svg"), "{q}.svg");
        let png = std::fs::read(dir.join(format!("diagrams/{NAME}/{q}.png"))).unwrap();
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n", "{q}.png is not a PNG");
    }
    // The viewer is self-contained: no external script, style, image or font.
    let html = read(&dir.join(format!("{NAME}.html")));
    for external in ["<script src", "@import", "url(http"] {
        assert!(!html.contains(external), "viewer refers to something outside: {external}");
    }
    // Its one <link> is the empty icon, inline (no request for /favicon.ico on a server).
    for (i, _) in html.match_indices("<link") {
        assert!(html[i..].starts_with(r#"<link rel="icon" href="data:,">"#), "viewer links something outside");
    }
    assert!(html.contains(r#"id="frame-label""#) && html.contains(r#"id="slider""#));
}

#[test]
fn no_frames_skips_frames_and_viewer() {
    let d = tempfile::tempdir().unwrap();
    run(d.path(), &["--no-frames", "--set", "phi1_deg.step=30"]);
    assert!(!d.path().join("frames").exists());
    assert!(!d.path().join(format!("{NAME}.html")).exists());
    assert!(d.path().join(format!("{NAME}.dxf")).is_file());
    assert!(d.path().join(format!("diagrams/{NAME}/omega2.svg")).is_file());
    // Without --png no PNG copies.
    assert!(!d.path().join(format!("diagrams/{NAME}/omega2.png")).exists());
}

#[test]
fn positions_only_scene_has_no_polygons_and_no_kinematic_columns() {
    let d = tempfile::tempdir().unwrap();
    run(d.path(), &["--set", r#"outputs=["position"]"#, "--set", "phi1_deg.step=45"]);
    let frame = read(&d.path().join(format!("frames/{NAME}/pos_045.svg")));
    assert!(frame.contains("layer-MECHANISM"));
    assert!(
        !frame.contains("layer-VELOCITY") && !frame.contains("layer-ACCELERATION") && !frame.contains("layer-FORCES")
    );
    let csv = read(&d.path().join(format!("{NAME}.csv")));
    let header = csv.lines().next().unwrap();
    assert!(header.starts_with("phi1_deg,A_x,A_y"));
    assert!(!header.contains("omega2") && !header.contains("eps2") && !header.contains("R_A"));
    assert!(
        !d.path().join(format!("diagrams/{NAME}/omega2.svg")).exists()
            && d.path().join(format!("diagrams/{NAME}/phi2_deg.svg")).exists()
    );
}

/// The CSV as columns by name.
fn csv_columns(text: &str) -> (Vec<String>, HashMap<String, Vec<f64>>) {
    let mut lines = text.lines();
    let header: Vec<String> = lines.next().unwrap().split(',').map(str::to_string).collect();
    let mut cols: HashMap<String, Vec<f64>> = header.iter().map(|h| (h.clone(), Vec::new())).collect();
    for line in lines {
        let fields: Vec<&str> = line.split(',').collect();
        assert_eq!(fields.len(), header.len(), "ragged row: {line}");
        for (h, f) in header.iter().zip(fields) {
            let v: f64 = f.parse().unwrap_or_else(|_| panic!("{h}: `{f}` is not a number"));
            assert!(v.is_finite(), "{h} is not finite");
            cols.get_mut(h).unwrap().push(v);
        }
    }
    (header, cols)
}

/// Column names documented in docs/fourbar-output.md for the full template.
const DOCUMENTED_COLUMNS: &[&str] = &[
    "phi1_deg",
    "A_x",
    "A_y",
    "B_x",
    "B_y",
    "M_x",
    "M_y",
    "phi2_deg",
    "phi3_deg",
    "transmission_deg",
    "gamma_deg",
    "omega2",
    "omega3",
    "vA_x",
    "vA_y",
    "vA_mag",
    "vB_x",
    "vB_y",
    "vB_mag",
    "vM_x",
    "vM_y",
    "vM_mag",
    "vBA_x",
    "vBA_y",
    "vBA_mag",
    "eps2",
    "eps3",
    "aA_x",
    "aA_y",
    "aA_mag",
    "aB_x",
    "aB_y",
    "aB_mag",
    "aM_x",
    "aM_y",
    "aM_mag",
    "aBA_n_x",
    "aBA_n_y",
    "aBA_t_x",
    "aBA_t_y",
    "aBC_n_x",
    "aBC_n_y",
    "aBC_t_x",
    "aBC_t_y",
    "aG1_x",
    "aG1_y",
    "aG21_x",
    "aG21_y",
    "aG22_x",
    "aG22_y",
    "aG3_x",
    "aG3_y",
    "R_A_x",
    "R_A_y",
    "R_A_mag",
    "R_B_x",
    "R_B_y",
    "R_B_mag",
    "R_C_x",
    "R_C_y",
    "R_C_mag",
    "R_O_x",
    "R_O_y",
    "R_O_mag",
    "R_An_x",
    "R_An_y",
    "R_At_x",
    "R_At_y",
    "R_Cn_x",
    "R_Cn_y",
    "R_Ct_x",
    "R_Ct_y",
    "Fi1_x",
    "Fi1_y",
    "Fi21_x",
    "Fi21_y",
    "Fi22_x",
    "Fi22_y",
    "Fi3_x",
    "Fi3_y",
    "F_x",
    "F_y",
    "G1_x",
    "G1_y",
    "G21_x",
    "G21_y",
    "G22_x",
    "G22_y",
    "G3_x",
    "G3_y",
    "Mi1",
    "Mi21",
    "Mi22",
    "Mi3",
    "Me1",
    "me1_joukowski",
];

#[test]
fn csv_has_the_documented_columns_and_numbers_agree_with_closed_forms() {
    let (header, c) = csv_columns(&read(&full().join(format!("{NAME}.csv"))));
    assert_eq!(header, DOCUMENTED_COLUMNS, "CSV header differs from the documented columns");
    let doc = read(&root().join("docs/fourbar-output.md"));
    for h in &header {
        assert!(doc.contains(&format!("`{h}`")), "column {h} is not documented in docs/fourbar-output.md");
    }
    let n = c["phi1_deg"].len();
    assert_eq!(n, 360);
    for (i, phi_deg) in c["phi1_deg"].iter().enumerate() {
        let phi = phi_deg.to_radians();
        let close = |a: f64, b: f64, what: &str| {
            assert!((a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1.0), "{what} at row {i}: {a} vs {b}")
        };
        // Crank pin and its motion: closed forms of a crank turning at constant omega1.
        close(c["A_x"][i], L1 * phi.cos(), "A_x");
        close(c["A_y"][i], L1 * phi.sin(), "A_y");
        close(c["vA_x"][i], -OMEGA1 * L1 * phi.sin(), "vA_x");
        close(c["aA_y"][i], -OMEGA1 * OMEGA1 * L1 * phi.sin(), "aA_y");
        // Loop closure from the columns.
        let ab = (c["B_x"][i] - c["A_x"][i]).hypot(c["B_y"][i] - c["A_y"][i]);
        let bc = (c["B_x"][i] - C[0]).hypot(c["B_y"][i] - C[1]);
        close(ab, L_AB, "|AB|");
        close(bc, L_BC, "|BC|");
        // Magnitude columns are the norms of their components.
        close(c["vM_mag"][i], c["vM_x"][i].hypot(c["vM_y"][i]), "vM_mag");
        close(c["R_A_mag"][i], c["R_A_x"][i].hypot(c["R_A_y"][i]), "R_A_mag");
    }
    // vM and aM against central finite differences of the M columns (1° steps: h = 1/20 ·
    // π/180 s; the truncation error is ~h²/6 of the third derivative, well under 2e-3).
    let h = 1f64.to_radians() / OMEGA1;
    for i in 0..n {
        let (p, q) = ((i + n - 1) % n, (i + 1) % n);
        for (pos, vel, acc) in [("M_x", "vM_x", "aM_x"), ("M_y", "vM_y", "aM_y")] {
            let v_fd = (c[pos][q] - c[pos][p]) / (2.0 * h);
            let a_fd = (c[pos][q] - 2.0 * c[pos][i] + c[pos][p]) / (h * h);
            let vmax = c["vM_mag"].iter().cloned().fold(0.0, f64::max);
            let amax = c["aM_mag"].iter().cloned().fold(0.0, f64::max);
            assert!((v_fd - c[vel][i]).abs() < 2e-3 * vmax, "{vel} at {i}: {} vs fd {v_fd}", c[vel][i]);
            assert!((a_fd - c[acc][i]).abs() < 2e-3 * amax, "{acc} at {i}: {} vs fd {a_fd}", c[acc][i]);
        }
    }
}

#[test]
fn json_has_the_documented_keys_and_matches_the_csv() {
    let json: serde_json::Value = serde_json::from_str(&read(&full().join(format!("{NAME}.json")))).unwrap();
    let doc = read(&root().join("docs/fourbar-output.md"));
    let top = json.as_object().unwrap();
    for k in [
        "kind",
        "name",
        "units",
        "omega1",
        "epsilon1",
        "sweep",
        "outputs",
        "grashof",
        "solved",
        "gaps",
        "dead_points",
        "scales",
        "positions",
    ] {
        assert!(top.contains_key(k), "JSON lacks `{k}`");
        assert!(doc.contains(&format!("`{k}`")), "JSON key {k} is not documented");
    }
    for k in top.keys() {
        assert!(doc.contains(&format!("`{k}`")), "JSON key {k} is not documented");
    }
    let positions = json["positions"].as_array().unwrap();
    assert_eq!(positions.len(), 360);
    let keys = [
        "phi1_deg",
        "A",
        "B",
        "M",
        "phi2_deg",
        "phi3_deg",
        "transmission_deg",
        "gamma_deg",
        "omega2",
        "omega3",
        "eps2",
        "eps3",
        "vA",
        "vB",
        "vM",
        "vBA",
        "aA",
        "aB",
        "aM",
        "R_A",
        "R_B",
        "R_C",
        "R_O",
        "R_A_mag",
        "R_B_mag",
        "R_C_mag",
        "R_O_mag",
        "vA_mag",
        "vB_mag",
        "vM_mag",
        "vBA_mag",
        "aA_mag",
        "aB_mag",
        "aM_mag",
        "Me1",
        "me1_joukowski",
        "scales",
    ];
    for k in keys {
        assert!(doc.contains(&format!("`{k}`")), "position key {k} is not documented");
    }
    let (_, c) = csv_columns(&read(&full().join(format!("{NAME}.csv"))));
    for (i, p) in positions.iter().enumerate() {
        let rec = p.as_object().unwrap();
        for k in keys {
            assert!(rec.contains_key(k), "position {i} lacks `{k}`");
        }
        assert_eq!(rec.len(), keys.len(), "position {i} has undocumented keys: {:?}", rec.keys());
        // The same f64 in both files, bit for bit: both writers print the shortest round-trip
        // form, and the tests parse JSON with serde_json's correctly rounded `float_roundtrip`.
        let same = |j: &serde_json::Value, v: f64, what: &str| {
            let j = j.as_f64().unwrap();
            assert_eq!(j.to_bits(), v.to_bits(), "{what} at {i}: JSON {j} vs CSV {v}");
        };
        same(&p["phi2_deg"], c["phi2_deg"][i], "phi2_deg");
        same(&p["omega3"], c["omega3"][i], "omega3");
        same(&p["M"][0], c["M_x"][i], "M_x");
        same(&p["aM"][1], c["aM_y"][i], "aM_y");
        same(&p["R_B"][0], c["R_B_x"][i], "R_B_x");
        same(&p["Me1"], c["Me1"][i], "Me1");
    }
    // Scales as stated on the drawings.
    let kv = json["scales"]["k_v"]["value"].as_f64().unwrap();
    let frame = read(&full().join(format!("frames/{NAME}/pos_000.svg")));
    // k_v drawn with a subscript v: `kv` once the tspans are read through.
    let shown = format!("kv = {} (m/s)/mm", mechdraw::figure::fourbar::scale_text(kv));
    assert!(common::svg_plain(&frame).contains(&shown), "frame does not show `{shown}`");
    // --json prints the same summary on stdout.
    let d = tempfile::tempdir().unwrap();
    let out = run(d.path(), &["--json", "--no-frames", "-q"]);
    let printed: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(printed, json);
}

#[test]
fn unassemblable_angles_produce_no_frame_and_a_warning() {
    // With a 0.15 m crank, |AC|² = l1² + |O1C|² − 2·l1·|O1C|·cos φ1 exceeds (l_ab + l_bc)² when
    // cos φ1 < (0.15² + 0.08² − 0.2²) / (2 · 0.15 · 0.08) = −0.4625: φ1 in (117.55°, 242.45°).
    let limit = ((0.15f64 * 0.15 + 0.08 * 0.08 - 0.2 * 0.2) / (2.0 * 0.15 * 0.08)).acos().to_degrees();
    let d = tempfile::tempdir().unwrap();
    let out = run(d.path(), &["--set", "l1=0.15", "--set", r#"outputs=["position", "velocity", "acceleration"]"#]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("warning:") && stderr.contains("cannot be assembled"), "{stderr}");
    let skipped: Vec<u32> = (0..360).filter(|&k| (k as f64) > limit && (k as f64) < 360.0 - limit).collect();
    assert_eq!(skipped.len(), 125);
    for k in 0..360u32 {
        let f = d.path().join(format!("frames/{NAME}/pos_{k:03}.svg"));
        assert_eq!(f.exists(), !skipped.contains(&k), "frame {k}");
    }
    let json: serde_json::Value = serde_json::from_str(&read(&d.path().join(format!("{NAME}.json")))).unwrap();
    let gap = &json["gaps"][0];
    assert!((gap["from_deg"].as_f64().unwrap() - limit).abs() < 1e-9, "{gap}");
    assert_eq!(json["positions"].as_array().unwrap().len(), 235);
    // No NaN anywhere in the frames or the CSV.
    let csv = read(&d.path().join(format!("{NAME}.csv")));
    assert!(!csv.to_lowercase().contains("nan"));
    for e in std::fs::read_dir(d.path().join(format!("frames/{NAME}"))).unwrap() {
        assert!(!read(&e.unwrap().path()).contains("NaN"));
    }
}

/// A mistyped step (0.05° gives 7181 crank angles) is refused before anything is written,
/// naming the field and the limit of drawn positions; exit code 2.
#[test]
fn a_sweep_finer_than_a_run_draws_is_refused() {
    let d = tempfile::tempdir().unwrap();
    let out_dir = d.path().join("o");
    let o = mechdraw()
        .args(["run", "-q", "--set", "phi1_deg.step=0.05", "--out"])
        .arg(&out_dir)
        .arg(root().join("templates/fourbar-chebyshev.toml"))
        .output()
        .unwrap();
    let e = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(e.contains("field `phi1_deg.step`") && e.contains("7181 positions") && e.contains("at most 3600"), "{e}");
    assert!(!out_dir.exists(), "something was written");
}
