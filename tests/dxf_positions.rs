//! A motion's DXF opens on one position (issue 29): read back with ezdxf, exactly the base
//! layers and the first drawn position's layer are shown, every other position's layer is
//! off and frozen (AutoCAD and ezdxf hide an off layer, LibreCAD a frozen one). And
//! `--positions LIST` draws only the positions asked for (DXF layers, frames, sheets) and
//! refuses what the run does not have (exit 2, nothing written).

mod common;

use std::path::{Path, PathBuf};
use std::process::Output;

use serde_json::Value;

fn out_dir(name: &str) -> PathBuf {
    let d = common::root().join("target/test-out/dxf_positions").join(name);
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn run(scene: &Path, args: &[&str], dir: &Path) -> Output {
    common::mechdraw()
        .arg("run")
        .arg(scene)
        .args(["--out", dir.to_str().unwrap(), "-q"])
        .args(args)
        .output()
        .expect("run mechdraw")
}

/// The layers as ezdxf reads them: name → (on, frozen).
fn layers(dxf: &Path) -> Vec<(String, bool, bool)> {
    let out = std::process::Command::new(common::python())
        .arg(common::root().join("tests/ezdxf_vectors.py"))
        .arg(dxf)
        .output()
        .expect("run python with ezdxf (bash .ci/test makes target/venv)");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    let mut layers: Vec<(String, bool, bool)> = v["layers"]
        .as_object()
        .unwrap()
        .iter()
        .map(|(name, s)| (name.clone(), s[0].as_bool().unwrap(), s[1].as_bool().unwrap()))
        .collect();
    layers.sort();
    layers
}

/// The position layers shown (on and not frozen), and whether every other layer is shown
/// (the base: content layers, `0`) and every hidden position layer both off and frozen.
fn shown_positions(dxf: &Path) -> Vec<String> {
    let all = layers(dxf);
    let mut shown = Vec::new();
    for (name, on, frozen) in &all {
        if name.starts_with("POS_") {
            if *on && !*frozen {
                shown.push(name.clone());
            } else {
                assert!(!on && *frozen, "{}: {name} is hidden only half (on {on}, frozen {frozen})", dxf.display());
            }
        } else {
            assert!(*on && !frozen, "{}: base layer {name} is not shown", dxf.display());
        }
    }
    shown
}

fn position_layers(dxf: &Path) -> Vec<String> {
    layers(dxf).into_iter().map(|l| l.0).filter(|n| n.starts_with("POS_")).collect()
}

/// Every motion template (at fewer positions, which changes nothing here): one position
/// shown, the first.
#[test]
fn every_motion_dxf_opens_on_its_first_position() {
    let mut motions = 0;
    for (path, set) in common::reduced_templates() {
        let stem = path.file_stem().unwrap().to_string_lossy().into_owned();
        let dir = out_dir(&format!("open/{stem}"));
        let mut args: Vec<&str> = vec!["--no-frames"];
        for s in &set {
            args.extend(["--set", s.as_str()]);
        }
        let out = run(&path, &args, &dir);
        assert!(out.status.success(), "{stem}: {}", String::from_utf8_lossy(&out.stderr));
        let dxf = dir.join(format!("{stem}.dxf"));
        let all = position_layers(&dxf);
        if all.is_empty() {
            // A still drawing (triad, chain): every layer shown.
            assert!(shown_positions(&dxf).is_empty());
            continue;
        }
        motions += 1;
        assert!(all.len() > 5, "{stem}: {} positions", all.len());
        assert_eq!(shown_positions(&dxf), vec![all[0].clone()], "{stem}: the first position alone is shown");
    }
    assert!(motions >= 6, "every motion template: {motions}");
}

/// `--positions 90,0,180`: three position layers, frames and sheets; the first asked for is
/// the one shown.
#[test]
fn positions_choose_what_a_four_bar_run_draws() {
    let scene = common::root().join("templates/fourbar-chebyshev.toml");
    let dir = out_dir("fourbar");
    let out = run(&scene, &["--positions", "90,0,180", "--sheets", "a4"], &dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let dxf = dir.join("fourbar-chebyshev.dxf");
    assert_eq!(position_layers(&dxf), ["POS_000", "POS_090", "POS_180"]);
    assert_eq!(shown_positions(&dxf), ["POS_090"]);
    let files = |sub: &str| {
        let mut v: Vec<String> = std::fs::read_dir(dir.join(sub).join("fourbar-chebyshev"))
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    };
    assert_eq!(files("frames"), ["pos_000.svg", "pos_090.svg", "pos_180.svg"]);
    let pages: Vec<String> = ["000", "090", "180"]
        .iter()
        .flat_map(|p| ["forces", "mechanism", "polygons"].map(|k| format!("pos_{p}-{k}.svg")))
        .collect();
    assert_eq!(files("sheets"), pages);
    // The first frame drawn is the first asked for; the CSV keeps every position.
    let svg = std::fs::read_to_string(dir.join("fourbar-chebyshev.svg")).unwrap();
    // φ_1 drawn with a subscript: read through its tspan.
    assert!(common::svg_plain(&svg).contains("φ1 = 90°"), "the picture is the first position asked for");
    let csv = std::fs::read_to_string(dir.join("fourbar-chebyshev.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 360);
}

/// A linkage's positions are its times: `every=0.0625` is every 120th of 361 samples.
#[test]
fn positions_choose_what_a_linkage_run_draws() {
    let scene = common::root().join("templates/slider-crank.toml");
    let dir = out_dir("slider-crank");
    let out = run(&scene, &["--positions", "every=0.0625", "--no-frames"], &dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let dxf = dir.join("slider-crank.dxf");
    assert_eq!(position_layers(&dxf), ["POS_000", "POS_120", "POS_240", "POS_360"]);
    assert_eq!(shown_positions(&dxf), ["POS_000"]);
}

/// A synthesis's design is a motion of its own: `--positions` chooses what its run draws
/// (its crank angles, as a four-bar's); the construction is one drawing either way.
#[test]
fn positions_choose_what_a_synthesis_designs_run_draws() {
    let scene = common::root().join("templates/synthesis-crank-rocker.toml");
    let dir = out_dir("synthesis");
    let out = run(&scene, &["--positions", "every=90"], &dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let design = dir.join("synthesis-crank-rocker-design.dxf");
    assert_eq!(position_layers(&design), ["POS_000", "POS_090", "POS_180", "POS_270"]);
    let mut frames: Vec<String> = std::fs::read_dir(dir.join("frames/synthesis-crank-rocker-design"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    frames.sort();
    assert_eq!(frames, ["pos_000.svg", "pos_090.svg", "pos_180.svg", "pos_270.svg"]);
    let csv = std::fs::read_to_string(dir.join("synthesis-crank-rocker-design.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 360, "the design's table keeps every position");
}

/// What the run does not have, an empty list, a step ≤ 0, a duplicate, a scene with no
/// motion: refused naming the option and what is valid, exit 2, nothing written.
#[test]
fn bad_positions_are_refused_before_anything_is_written() {
    let fourbar = common::root().join("templates/fourbar-chebyshev.toml");
    let linkage = common::root().join("templates/slider-crank.toml");
    let triad = common::root().join("templates/triad-popa.toml");
    let synthesis = common::root().join("templates/synthesis-crank-rocker.toml");
    let cases: [(&Path, &str, &[&str]); 10] = [
        (&fourbar, "45.5", &["45.5°", "nearest is 45°", "0° to 359°"]),
        (&fourbar, "400", &["400°", "not a position"]),
        (&fourbar, "", &["empty", "0,90,180"]),
        (&fourbar, "every=0", &["greater than 0", "every=30"]),
        (&fourbar, "every=-30", &["greater than 0"]),
        (&fourbar, "every=2.5", &["multiple of the run's step, 1°"]),
        (&fourbar, "0,90,0", &["listed twice"]),
        (&linkage, "0.1001", &["t = 0.1001 s", "nearest is 0.1 s"]),
        (&triad, "0", &["four-bar or linkage", "triad scene"]),
        (&synthesis, "0", &["--no-analysis", "its design is not run"]),
    ];
    for (k, (scene, list, says)) in cases.iter().enumerate() {
        let dir = out_dir(&format!("bad{k}"));
        let mut args = vec!["--positions", list];
        if scene.ends_with("synthesis-crank-rocker.toml") {
            args.push("--no-analysis");
        }
        let out = run(scene, &args, &dir);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "--positions {list:?}: {err}");
        assert!(err.contains("--positions"), "--positions {list:?}: the message names the option: {err}");
        for s in *says {
            assert!(err.contains(s), "--positions {list:?}: {s:?} not in {err}");
        }
        assert!(!dir.exists(), "--positions {list:?}: something was written");
    }
}
