//! The live pages (issue 17) in a real browser: headless Chromium driven over the DevTools
//! protocol (`web/page_checks.py` through `web/cdp.py`) does what a user does — reads a
//! triad's modes, drags the four-bar's crank pin and the shaper's rocker, sets `l_bc` in its
//! field, applies a broken TOML edit, downloads the files — and this test compares what the
//! pages show with the command line and with closed forms. Screenshots are kept in
//! target/web/screens/ for people to look at.
//!
//! Needs the pages: `bash web/build.sh` (`.ci/test` runs it: it needs the wasm32 target and
//! wasm-bindgen-cli) and Debian's chromium.

#![allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the library calls"
)]

mod common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

fn pages() -> PathBuf {
    let dir =
        std::env::var_os("CARGO_TARGET_DIR").map_or_else(|| common::root().join("target"), PathBuf::from).join("web");
    assert!(
        dir.join("fourbar-chebyshev.html").is_file(),
        "no live pages in {}: build them with `bash web/build.sh` (needs `rustup target add wasm32-unknown-unknown` \
         and `cargo install wasm-bindgen-cli --version 0.2.130`; `bash .ci/test` does all of it)",
        dir.display()
    );
    dir
}

/// What the pages showed (one browser session for every check).
fn observed() -> &'static Value {
    static OBSERVED: std::sync::OnceLock<Value> = std::sync::OnceLock::new();
    OBSERVED.get_or_init(|| {
        let out = Command::new("python3")
            .arg(common::root().join("web/page_checks.py"))
            .arg(pages())
            .output()
            .expect("run python3 web/page_checks.py");
        assert!(out.status.success(), "page checks failed:\n{}", String::from_utf8_lossy(&out.stderr));
        serde_json::from_slice(&out.stdout).expect("the checks' JSON")
    })
}

fn template(name: &str) -> PathBuf {
    common::root().join(format!("templates/{name}.toml"))
}

/// The command line's run of `path` with `set` (no frames): its files, JSON and stderr.
fn cli(path: &Path, set: &[&str]) -> (BTreeMap<String, Vec<u8>>, Value, String) {
    let tmp = tempfile::tempdir().unwrap();
    let mut cmd = common::mechdraw();
    cmd.arg("run").arg(path).arg("--out").arg(tmp.path()).args(["--no-frames", "--json"]);
    for s in set {
        cmd.arg("--set").arg(s);
    }
    let out = cmd.output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let mut files = Vec::new();
    common::read_tree(tmp.path(), Path::new(""), &mut files);
    (files.into_iter().collect(), serde_json::from_slice(&out.stdout).unwrap(), String::from_utf8(out.stderr).unwrap())
}

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// A named point of a drag state `{"points": [[name, x, y], ...]}`.
fn point(state: &Value, name: &str) -> (f64, f64) {
    let p = state["points"].as_array().unwrap().iter().find(|p| p[0] == name).unwrap_or_else(|| panic!("{name}"));
    (num(&p[1]), num(&p[2]))
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and the live pages (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn the_triad_page_lists_eight_modes_and_the_pattern_methods_angle() {
    let (_, json, _) = cli(&template("triad-popa"), &[]);
    let shown = observed()["triad"]["modes"].as_str().unwrap();
    let angles: Vec<String> =
        json["solutions"].as_array().unwrap().iter().map(|s| format!("{:.2}", num(&s["phi1_deg"]))).collect();
    assert_eq!(angles.len(), 8);
    assert!(shown.starts_with("8 assembly modes"), "{shown}");
    assert!(shown.contains(&angles.join(", ")), "{shown} vs {angles:?}");
    assert!(shown.contains("pattern method φ1 = 75.77°"), "{shown}");

    // Every mode drawn: the modes sheet is on the page.
    assert_eq!(observed()["triad"]["sheets"], serde_json::json!(["modes"]));
    assert!(num(&observed()["triad"]["modes_sheet"]) > 1000.0, "the modes sheet is drawn");
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and the live pages (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn a_triad_mode_picked_on_the_page_is_the_one_the_picture_draws() {
    let pick = &observed()["triad_pick"];
    assert_eq!(pick["error"], "", "{pick}");
    // The page's picture is the command line's for `--set mode=3`, byte for byte.
    let (files, json, _) = cli(&template("triad-popa"), &["mode=3"]);
    let svg = String::from_utf8(files["triad-popa.svg"].clone()).unwrap();
    assert_eq!(pick["picture"].as_str().unwrap(), svg, "the picture after picking mode 3");
    assert_eq!(json["primary"], 2, "the CLI draws mode 3 (index 2)");
    assert_eq!(pick["drawn"], 2);
    assert_eq!(pick["disabled"], serde_json::json!(["3"]), "mode 3's button shows it is drawn");
    assert!(pick["caption"].as_str().unwrap().contains("Solid: mode 3 of 8"), "{}", pick["caption"]);
    // And it is a different picture from the pattern method's mode.
    let (plain, _, _) = cli(&template("triad-popa"), &[]);
    assert_ne!(plain["triad-popa.svg"], files["triad-popa.svg"]);
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and the live pages (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn dragging_the_crank_pin_turns_the_crank_to_the_pointer() {
    let d = &observed()["fourbar_drag"];
    let (px, py) = (num(&d["pointer"][0]), num(&d["pointer"][1]));
    let (ox, oy) = (num(&d["o1"][0]), num(&d["o1"][1]));
    // The crank points at the pointer: φ1 = atan2 of the pointer from O1.
    let expected = (py - oy).atan2(px - ox).to_degrees().rem_euclid(360.0);
    let drive = num(&d["drive"]);
    assert!((drive - expected).abs() < 1e-7, "φ1 = {drive}° for a pointer at {expected}°");
    assert!((expected - 123.4567).abs() < 0.5, "the pointer ended near 123.46° ({expected})");
    // Every loop residual read back from the page, and the loop measured from its points.
    let st = &d["state"];
    assert!(num(&st["residual"]) <= 1e-9, "{}", st["residual"]);
    let text = std::fs::read_to_string(template("fourbar-chebyshev")).unwrap();
    let scene: toml::Table = text.parse().unwrap();
    let get = |k: &str| scene[k].as_float().unwrap();
    let c = scene["c"].as_array().unwrap();
    let (cx, cy) = (c[0].as_float().unwrap(), c[1].as_float().unwrap());
    let (a, b) = (point(st, "A"), point(st, "B"));
    let dist = |p: (f64, f64), q: (f64, f64)| (p.0 - q.0).hypot(p.1 - q.1);
    assert!((dist(a, (ox, oy)) - get("l1")).abs() <= 1e-9 * get("l_ab"));
    assert!((dist(a, b) - get("l_ab")).abs() <= 1e-9 * get("l_ab"));
    assert!((dist(b, (cx, cy)) - get("l_bc")).abs() <= 1e-9 * get("l_ab"));
    assert!(d["label"].as_str().unwrap().starts_with("φ1 = "), "{}", d["label"]);
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and the live pages (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn the_four_bars_page_shows_every_diagram_the_cli_draws() {
    let (files, _, _) = cli(&template("fourbar-chebyshev"), &[]);
    let mut cli: Vec<String> = files
        .keys()
        .filter_map(|f| f.strip_prefix("diagrams/fourbar-chebyshev/")?.strip_suffix(".svg").map(String::from))
        .collect();
    let mut shown: Vec<String> =
        observed()["fourbar_diagrams"].as_array().unwrap().iter().map(|v| v.as_str().unwrap().to_string()).collect();
    cli.sort();
    shown.sort();
    assert!(cli.len() >= 10, "{cli:?}");
    assert_eq!(shown, cli);
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and the live pages (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn dragging_a_shaper_point_keeps_every_joint() {
    let st = &observed()["shaper_drag"]["state"];
    assert!(num(&st["residual"]) <= 1e-9);
    let p = |n: &str| point(st, n);
    let close = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).hypot(a.1 - b.1) <= 1e-9 * 600.0;
    assert!(close(p("crank.O1"), (0.0, 300.0)));
    assert!(close(p("rocker.O3"), (0.0, 0.0)));
    assert!(close(p("crank.A"), p("block.A")));
    assert!(close(p("rocker.B"), p("link.B")));
    assert!(close(p("link.E"), p("ram.E")));
    assert!((p("ram.E").1 - 600.0).abs() <= 1e-9 * 600.0);
    let (o3, b, a) = (p("rocker.O3"), p("rocker.B"), p("block.A"));
    let (ux, uy) = (b.0 - o3.0, b.1 - o3.1);
    let n = ux.hypot(uy);
    assert!(((a.0 - o3.0) * uy - (a.1 - o3.1) * ux).abs() / n <= 1e-9 * 600.0, "the block is on the rocker");
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and the live pages (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn a_non_grashof_length_shows_the_command_lines_gaps() {
    let (_, json, stderr) = cli(&template("fourbar-chebyshev"), &["l_bc=0.2"]);
    let page = &observed()["fourbar_lbc"];
    assert_eq!(page["error"], "");
    assert_eq!(page["summary"]["gaps"], json["gaps"], "the gaps");
    assert_eq!(page["summary"], json, "the whole JSON");
    let warnings = page["warnings"].as_str().unwrap();
    for line in stderr.lines().filter_map(|l| l.strip_prefix("warning: ")) {
        assert!(warnings.contains(line), "the page does not show `{line}`:\n{warnings}");
    }
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and the live pages (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn an_invalid_toml_edit_shows_the_command_lines_message_and_keeps_the_picture() {
    let page = &observed()["fourbar_bad_toml"];
    assert_eq!(page["picture_kept"], true);
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(tmp.path().join("fourbar-chebyshev.toml"), page["text"].as_str().unwrap()).unwrap();
    let out = common::mechdraw()
        .current_dir(tmp.path())
        .args(["run", "fourbar-chebyshev.toml", "--out", "o", "-q"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let cli = String::from_utf8(out.stderr).unwrap();
    assert_eq!(page["error"].as_str().unwrap(), cli.trim_end());
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and the live pages (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn downloads_are_the_command_lines_bytes() {
    let offered = observed()["downloads"].as_object().unwrap();
    assert_eq!(offered.len(), common::template_paths().len(), "a page per template");
    for (name, files) in offered {
        let (cli, _, _) = cli(&template(name), &[]);
        let files: Vec<&str> = files.as_array().unwrap().iter().map(|f| f.as_str().unwrap()).collect();
        assert!(files.len() >= 4, "{name}: {files:?}");
        let mut differ = Vec::new();
        for file in &files {
            // Saved by the checks as the browser downloaded it.
            let bytes = std::fs::read(pages().join("downloads").join(name).join(file)).unwrap();
            let theirs = cli.get(*file).unwrap_or_else(|| panic!("{name}: the CLI wrote no {file}"));
            if bytes != *theirs {
                differ.push(file.to_string());
            }
        }
        assert!(differ.is_empty(), "{name}: differ from the CLI's: {differ:?}");
        for file in cli.keys() {
            assert!(files.contains(&file.as_str()), "{name}: the page offers no {file}");
        }
    }
}
