//! The scales printed in a DXF hold in the DXF (issue 29): a CAD user measures a vector in
//! the drawing (in its millimetres), multiplies by the k the drawing prints beside it, and
//! gets the value. Checked with an independent reader: ezdxf reads the arrows (a LINE and
//! its SOLID head), the joint circles and the texts of one position's layer; the test parses
//! k_l, k_v, k_a and k_f from the DXF's own text (with their units) and compares the
//! measured vectors with the CSV, for the four-bar and a linkage, each in an SI and a mm
//! scene. Needs the venv from `.ci/test` (ezdxf).

mod common;

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use serde_json::Value;

/// Relative tolerance of a measured vector against the CSV (the DXF carries 12 decimals).
const REL_TOL: f64 = 1e-6;

/// Colours the figures draw vectors in (ACI): velocity green, acceleration blue, forces
/// magenta (reactions on the far side of a figure red).
const VELOCITY: &[i64] = &[3];
const ACCELERATION: &[i64] = &[5];
const FORCE: &[i64] = &[6, 1];

fn out_dir(name: &str) -> PathBuf {
    let d = common::root().join("target/test-out/dxf_measure").join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// `mechdraw run templates/<scene>.toml --set …` into `dir`; the DXF and CSV paths.
fn run(scene: &str, set: &[&str], dir: &Path) -> (PathBuf, PathBuf) {
    let mut cmd = common::mechdraw();
    cmd.arg("run").arg(common::root().join("templates").join(format!("{scene}.toml")));
    for s in set {
        cmd.args(["--set", s]);
    }
    let out = cmd.args(["--out", dir.to_str().unwrap(), "--no-frames", "-q"]).output().expect("run mechdraw");
    assert!(out.status.success(), "mechdraw run {scene} {set:?}: {}", String::from_utf8_lossy(&out.stderr));
    (dir.join(format!("{scene}.dxf")), dir.join(format!("{scene}.csv")))
}

/// The CSV as columns by header name.
fn csv(path: &Path) -> HashMap<String, Vec<f64>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<String> = lines.next().unwrap().split(',').map(str::to_string).collect();
    let mut cols: HashMap<String, Vec<f64>> = header.iter().map(|h| (h.clone(), Vec::new())).collect();
    for line in lines {
        for (h, v) in header.iter().zip(line.split(',')) {
            cols.get_mut(h).unwrap().push(v.parse().unwrap_or(f64::NAN));
        }
    }
    cols
}

/// What ezdxf reads of the DXF (tests/ezdxf_vectors.py).
fn read(dxf: &Path) -> Value {
    let out = std::process::Command::new(common::python())
        .arg(common::root().join("tests/ezdxf_vectors.py"))
        .arg(dxf)
        .output()
        .expect("run python with ezdxf (bash .ci/test makes target/venv)");
    assert!(out.status.success(), "ezdxf_vectors.py {}: {}", dxf.display(), String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap()
}

/// The texts of a layer.
fn texts<'a>(dxf: &'a Value, layer: &str) -> Vec<&'a str> {
    dxf["texts"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|t| t["layer"] == layer)
        .map(|t| t["text"].as_str().unwrap())
        .collect()
}

/// The scale printed as `key = value unit/mm` on the position's layer, or else on a layer
/// every position shares (not `POS_…`): (value, unit).
fn printed_scale(dxf: &Value, layer: &str, key: &str) -> (f64, String) {
    printed_scales(dxf, layer, key).swap_remove(0)
}

/// Every scale `key = value unit/mm` printed on the position's `layer` (each force figure
/// states its own k_f), then those every position shares; at least one.
fn printed_scales(dxf: &Value, layer: &str, key: &str) -> Vec<(f64, String)> {
    let needle = format!("{key} = ");
    let find = |t: &str| -> Option<(f64, String)> {
        let after = t.split(&needle).nth(1)?;
        let (value, rest) = after.split_once(' ')?;
        // The unit up to its `/mm` (a caption may state a second scale after it).
        let (unit, _) = rest.split_once("/mm")?;
        Some((value.parse().ok()?, unit.to_string()))
    };
    let mut all: Vec<(f64, String)> = texts(dxf, layer).into_iter().filter_map(find).collect();
    all.extend(
        dxf["texts"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|t| !t["layer"].as_str().unwrap().starts_with("POS_"))
            .filter_map(|t| find(t["text"].as_str().unwrap())),
    );
    assert!(!all.is_empty(), "no `{key} = …/mm` in the DXF");
    all
}

/// The position layer whose label text is `label` (`φ1 = 30°`, `t = 0.0156 s`).
fn layer_labelled(dxf: &Value, label: &str) -> String {
    let t = dxf["texts"]
        .as_array()
        .unwrap()
        .iter()
        .find(|t| t["layer"].as_str().unwrap().starts_with("POS_") && t["text"] == label);
    t.unwrap_or_else(|| panic!("no position layer labelled {label:?}"))["layer"].as_str().unwrap().to_string()
}

/// The arrows of `layer` in one of `colors`, each as its vector (DXF mm).
fn arrows(dxf: &Value, layer: &str, colors: &[i64]) -> Vec<(f64, f64)> {
    dxf["arrows"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|a| a["layer"] == layer && colors.contains(&a["color"].as_i64().unwrap()))
        .map(|a| {
            let (t, h) = (&a["tail"], &a["tip"]);
            (h[0].as_f64().unwrap() - t[0].as_f64().unwrap(), h[1].as_f64().unwrap() - t[1].as_f64().unwrap())
        })
        .collect()
}

/// Some arrow of `layer` in `colors`, times one of the printed `ks` (its figure's), is the
/// vector `want` (relative [`REL_TOL`]).
fn assert_measured(dxf: &Value, layer: &str, colors: &[i64], ks: &[f64], want: (f64, f64), what: &str) {
    let size = libm::hypot(want.0, want.1);
    assert!(size > 0.0, "{what}: a zero vector measures nothing");
    let found = arrows(dxf, layer, colors);
    let best = ks
        .iter()
        .flat_map(|k| found.iter().map(move |(x, y)| libm::hypot(k * x - want.0, k * y - want.1) / size))
        .fold(f64::INFINITY, f64::min);
    assert!(
        best <= REL_TOL,
        "{what}: no arrow on {layer} measures {want:?} at a printed k of {ks:?} (nearest off by {best:e} relative; {} arrows)",
        found.len()
    );
}

/// Some circle of `layer` has its centre (DXF mm) × `k_l` at the point `want`.
fn assert_joint(dxf: &Value, layer: &str, k_l: f64, want: (f64, f64), what: &str) {
    let size = libm::hypot(want.0, want.1).max(1e-12);
    let best = dxf["circles"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|c| c["layer"] == layer)
        .map(|c| {
            libm::hypot(
                k_l * c["center"][0].as_f64().unwrap() - want.0,
                k_l * c["center"][1].as_f64().unwrap() - want.1,
            )
        })
        .fold(f64::INFINITY, f64::min);
    assert!(best / size <= REL_TOL, "{what}: no joint on {layer} at {want:?} × 1/k_l (nearest off by {best})");
}

/// The checks for one run: the position at CSV row `row`, labelled `label`; `len` the
/// length unit the captions must state; `vectors` (CSV x and y columns, which polygon's
/// colours and scale, what) and a joint (CSV x and y columns).
struct Case<'a> {
    scene: &'a str,
    set: &'a [&'a str],
    len: &'a str,
    row: usize,
    label: String,
    joint: (&'a str, Option<&'a str>),
    vectors: Vec<(&'a str, Option<&'a str>, &'a [i64], &'a str)>,
}

fn check(case: &Case) {
    let tag = format!("{} {:?}", case.scene, case.set);
    let dir = out_dir(&format!("{}-{}", case.scene, case.len));
    let (dxf_path, csv_path) = run(case.scene, case.set, &dir);
    let dxf = read(&dxf_path);
    let cols = csv(&csv_path);
    let col = |name: &str| cols.get(name).unwrap_or_else(|| panic!("{tag}: no CSV column {name}"))[case.row];
    let layer = layer_labelled(&dxf, &case.label);

    // k_l: the mechanism is 1:1 in the DXF's millimetres.
    let (k_l, unit) = printed_scale(&dxf, &layer, "k_l");
    assert_eq!(unit, case.len, "{tag}: k_l's unit");
    let one_to_one = if case.len == "m" { 0.001 } else { 1.0 };
    assert_eq!(k_l, one_to_one, "{tag}: k_l = 1:1 in the DXF");
    let (jx, jy) = case.joint;
    assert_joint(&dxf, &layer, k_l, (col(jx), jy.map_or(0.0, col)), &format!("{tag}: joint {jx}"));

    for (x, y, colors, key) in &case.vectors {
        let printed = printed_scales(&dxf, &layer, key);
        let want_unit = match *key {
            "k_v" => format!("({}/s)", case.len),
            "k_a" => format!("({}/s²)", case.len),
            _ => "N".to_string(),
        };
        for (_, unit) in &printed {
            assert_eq!(*unit, want_unit, "{tag}: {key}'s unit");
        }
        let ks: Vec<f64> = printed.iter().map(|(k, _)| *k).collect();
        let want = (col(x), y.map_or(0.0, col));
        assert_measured(&dxf, &layer, colors, &ks, want, &format!("{tag}: {x} at {key} of {ks:?}"));
    }
}

fn fourbar_case<'a>(set: &'a [&'a str], len: &'a str) -> Case<'a> {
    Case {
        scene: "fourbar-chebyshev",
        set,
        len,
        row: 30,
        label: "φ1 = 30°".to_string(),
        joint: ("A_x", Some("A_y")),
        vectors: vec![
            ("vA_x", Some("vA_y"), VELOCITY, "k_v"),
            ("vB_x", Some("vB_y"), VELOCITY, "k_v"),
            ("vM_x", Some("vM_y"), VELOCITY, "k_v"),
            ("aA_x", Some("aA_y"), ACCELERATION, "k_a"),
            ("aM_x", Some("aM_y"), ACCELERATION, "k_a"),
            ("R_O_x", Some("R_O_y"), FORCE, "k_f"),
            ("R_C_x", Some("R_C_y"), FORCE, "k_f"),
        ],
    }
}

#[test]
fn the_four_bar_measures_true_in_its_dxf_in_si() {
    check(&fourbar_case(&[], "m"));
}

/// The same four-bar in millimetres (its lengths × 1000; g stays in m/s²).
#[test]
fn the_four_bar_measures_true_in_its_dxf_in_mm() {
    let set = ["units=mm", "c[0]=80", "l1=40", "l_ab=100", "l_bm=100", "l_bc=100"];
    check(&fourbar_case(&set, "mm"));
}

fn slider_crank_case<'a>(set: &'a [&'a str], len: &'a str) -> Case<'a> {
    // Row 30 of 361: t = 30 × 0.1875 / 360 s.
    Case {
        scene: "slider-crank",
        set,
        len,
        row: 30,
        label: format!("t = {:.4} s", 30.0 * 0.1875 / 360.0),
        joint: ("B.x", None),
        vectors: vec![
            ("B.vx", None, VELOCITY, "k_v"),
            ("B.ax", None, ACCELERATION, "k_a"),
            ("O.Fx", Some("O.Fy"), FORCE, "k_f"),
            ("A.Fx", Some("A.Fy"), FORCE, "k_f"),
        ],
    }
}

#[test]
fn a_linkage_measures_true_in_its_dxf_in_mm() {
    check(&slider_crank_case(&[], "mm"));
}

/// The slider-crank read in metres (every length a thousand times larger, the loads in N):
/// a linkage scene in SI.
#[test]
fn a_linkage_measures_true_in_its_dxf_in_si() {
    check(&slider_crank_case(&["units=SI"], "m"));
}
