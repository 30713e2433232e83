//! The live pages (issues 17 and 32) in a real browser: headless Chromium driven over the
//! DevTools protocol (`web/page_checks.py` through `web/cdp.py`) does what a student does —
//! reads a triad's modes, drags the four-bar's crank pin and the shaper's rocker, sets
//! `l_bc` in its field and a refused value in another, reshapes the four-bar by dragging C
//! in edit mode, undoes and redoes, shares a link and opens it in a fresh tab, builds the
//! Chebyshev four-bar from an empty page by clicks, drags the crank with a finger on a
//! phone-sized screen, opens bad files and links, downloads the files, drags a synthesis's
//! required position, changes its ψ and opens its design — and this test
//! compares what the pages show with the command line and with closed forms. Screenshots are
//! kept in target/web/screens/ for people to look at.
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
    // The scrubber follows the drag, and the diagrams' marker with it; Play goes on from there.
    let k = num(&d["slider"]) as usize;
    assert_eq!(k, d["state"]["position"].as_u64().unwrap() as usize);
    assert!((k as f64 - drive).abs() <= 1.0, "the scrubber at {k} for φ1 = {drive}°");
    assert_eq!(d["marker"].as_str().map(|x| x.parse::<f64>().unwrap()), d["marker_expected"][0].as_f64(), "{d}");
    let played = num(&d["after_play"]);
    assert!(played > k as f64 && played < k as f64 + 60.0, "Play went on from {k} (now {played})");
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
    assert_eq!(page["marked_line"], 14, "the editor marks the line the message names");
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

/// The template's text.
fn template_text(name: &str) -> String {
    std::fs::read_to_string(template(name)).unwrap()
}

/// The CLI's CSV of `path` with `set`, as rows of named numbers.
fn csv_rows(text: &str) -> Vec<BTreeMap<String, f64>> {
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().unwrap_or("").split(',').collect();
    lines
        .map(|l| head.iter().zip(l.split(',')).filter_map(|(h, v)| Some((h.to_string(), v.parse().ok()?))).collect())
        .collect()
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and the live pages (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn the_page_says_what_to_do_and_fills_the_screen() {
    let o = &observed()["fourbar_open"];
    assert!(o["hint"].as_str().unwrap().starts_with("Drag a joint"), "{o}");
    assert_eq!(o["viewport"], "width=device-width, initial-scale=1");
    // The error box is at the top, under the header and the hint, not under the editor.
    assert!(num(&o["error_top"]) < 150.0, "{o}");
    // The picture is the largest thing on a 1366 × 768 screen, and the crank is not a speck.
    let stage = o["stage"].as_array().unwrap();
    assert!(num(&stage[2]) >= 600.0, "the picture is {} px wide", stage[2]);
    // The frame gives the mechanism its large panel (the polygons smaller beside it, the
    // forces under both: issue 31), so the crank is 32 px on the page.
    assert!(num(&o["crank_px"]) >= 30.0, "the crank is {} px long", o["crank_px"]);
    // The diagrams sit beside the picture, each with its marker.
    assert!(num(&o["diagrams_top"]) < 200.0, "the first diagram starts {} px down", o["diagrams_top"]);
    assert!(num(&o["markers"]) >= 10.0 && o["markers"] == o["diagrams"], "{o}");
    // The status line times from navigation.
    assert!(o["status"].as_str().unwrap().contains("after navigation"), "{o}");
    // Play and the picture come early in the tab order.
    let order: Vec<&str> = o["tab_order"].as_array().unwrap().iter().map(|v| v.as_str().unwrap()).collect();
    let play = order.iter().position(|t| *t == "play").unwrap();
    let stage_at = order.iter().position(|t| *t == "stage").unwrap();
    assert!(play <= 2 && stage_at <= 16, "Play is tab stop {play}, the picture {stage_at}: {order:?}");
    // Hovering a joint: a grab pointer and a ring.
    let h = &observed()["fourbar_hover"];
    assert_eq!(h["cursor"], "grab");
    assert!(num(&h["ring"]) >= 1.0);
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and the live pages (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn fields_are_named_by_what_they_are_with_units() {
    let labels: Vec<String> =
        observed()["build"]["labels"].as_array().unwrap().iter().map(|v| v.as_str().unwrap().to_string()).collect();
    assert!(labels.iter().any(|l| l == "link1 O1A [m]"), "{labels:?}");
    assert!(labels.iter().any(|l| l == "link2 AB [m]"), "{labels:?}");
    let r = &observed()["refused_field"];
    assert_eq!(r["label"], "crank O1A [m]");
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and the live pages (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn a_refused_field_says_why_at_the_field_and_goes_back_to_the_models_value() {
    let r = &observed()["refused_field"];
    let tmp = tempfile::tempdir().unwrap();
    let out = common::mechdraw()
        .current_dir(common::root().join("templates"))
        .args(["run", "fourbar-chebyshev.toml", "--set", "l1=-0.04", "--out"])
        .arg(tmp.path())
        .arg("-q")
        .output()
        .unwrap();
    let cli = String::from_utf8(out.stderr).unwrap();
    assert_eq!(r["message"].as_str().unwrap(), cli.trim_end().strip_prefix("error: ").unwrap());
    assert_eq!(r["refused"], true);
    assert_eq!(r["value"], "0.04", "the field shows the model's value again");
    assert_eq!(num(&r["model"]), 0.04);
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and the live pages (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn dragging_c_in_edit_mode_moves_c_in_the_toml_and_keeps_every_comment() {
    let e = &observed()["edit_c"];
    assert_eq!(e["error"], "", "{e}");
    let (before, after) = (e["before"].as_str().unwrap(), e["after"].as_str().unwrap());
    assert_eq!(before, template_text("fourbar-chebyshev"));
    // c moved by the drag's offset (5 grid steps right, 2 up: the pointer snapped to the
    // page's grid), written in place.
    let grid = num(&e["grid"]["step"]);
    assert!(grid <= 0.005 + 1e-12, "the grid is {grid} m for a 0.08 m ground link");
    let c: Vec<f64> = e["c"].as_array().unwrap().iter().map(num).collect();
    let target: Vec<f64> = e["target"].as_array().unwrap().iter().map(num).collect();
    assert!((target[0] - (0.08 + 5.0 * grid)).abs() < 1e-12 && (target[1] - 2.0 * grid).abs() < 1e-12);
    assert!((c[0] - target[0]).abs() < 1e-12 && (c[1] - target[1]).abs() < 1e-12, "c = {c:?}, dragged to {target:?}");
    let line = after.lines().find(|l| l.starts_with("c = ")).unwrap();
    let written: toml::Table = line.parse().unwrap();
    let w: Vec<f64> = written["c"].as_array().unwrap().iter().map(|v| v.as_float().unwrap()).collect();
    assert_eq!(w, c, "the TOML's c is the field's");
    assert_eq!(after, before.replace("c = [0.08, 0.0]", line), "one value changed, nothing else");
    assert_eq!(e["session_text"], e["after"]);
    for line in before.lines().filter(|l| l.contains('#')) {
        let comment = &line[line.find('#').unwrap()..];
        assert!(after.contains(comment), "the comment `{comment}` is gone");
    }
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and the live pages (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn undo_restores_the_toml_byte_for_byte_and_redo_reapplies_it() {
    let (e, u, r) = (&observed()["edit_c"], &observed()["undo"], &observed()["redo"]);
    assert_eq!(u["text"], e["before"]);
    assert_eq!(u["session"], e["before"]);
    assert_eq!(num(&u["c0"]), 0.08);
    assert_eq!(r["text"], e["after"]);
    assert_eq!(r["session"], e["after"]);
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and the live pages (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn a_share_link_opens_the_same_scene_and_picture_in_a_fresh_tab() {
    let s = &observed()["share"];
    assert_eq!(s["link_prefix"], "scene=v1.");
    assert_eq!(s["same_text"], true, "{s}");
    assert_eq!(s["same_session"], true);
    // The same picture: the fresh tab's frames are the command line's for the shared text,
    // byte for byte. (The edited page's own frames may differ from them only in the scales
    // it held while the scene was edited: Session::replace keeps a polygon's scale while it
    // fills half to all of its panel, where a fresh run steps along the motion.)
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("fourbar-chebyshev.toml");
    std::fs::write(&scene, observed()["redo"]["text"].as_str().unwrap()).unwrap();
    let out =
        common::mechdraw().arg("run").arg(&scene).arg("--out").arg(dir.path().join("out")).arg("-q").output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let shown = s["frames"].as_array().unwrap();
    for (k, frame) in [0, 90, 200].iter().zip(shown) {
        let cli =
            std::fs::read_to_string(dir.path().join(format!("out/frames/fourbar-chebyshev/pos_{k:03}.svg"))).unwrap();
        assert_eq!(frame.as_str().unwrap(), cli, "the shared tab's frame {k}");
    }
    assert_eq!(s["error"], "");
    // A link cut short, or from a newer mechdraw: said so, and the page's own scene opens.
    let cut = &observed()["share_cut"];
    assert!(cut["error"].as_str().unwrap().contains("cut short or damaged"), "{cut}");
    assert_eq!(cut["text_is_original"], true);
    assert!(observed()["share_newer"]["error"].as_str().unwrap().contains("format v7, from a newer mechdraw"));
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and the live pages (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn the_scene_is_kept_across_reloads_and_a_broken_saved_one_loses_nothing() {
    let r = &observed()["reload"];
    assert_eq!(r["text"], observed()["redo"]["text"], "the edit is back after a reload");
    assert!(r["notice"].as_str().unwrap().contains("kept in this browser"), "{r}");
    let b = &observed()["saved_broken"];
    let err = b["error"].as_str().unwrap();
    assert!(err.contains("field `l_bc`: must be a positive length"), "{err}");
    assert!(b["editor"].as_str().unwrap().contains("l_bc = -0.10"), "the saved text is in the editor");
    assert_eq!(b["session"].as_str().unwrap(), template_text("fourbar-chebyshev"), "the page's scene is shown");
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and the live pages (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn opening_a_file_that_is_not_a_scene_keeps_the_scene_on_screen() {
    let o = &observed()["open_file"];
    let e = o["not_scene"]["error"].as_str().unwrap();
    assert!(e.contains("notes.toml") && e.contains("kind"), "{e}");
    assert_eq!(o["not_scene"]["picture_kept"], true);
    let e = o["not_text"]["error"].as_str().unwrap();
    assert!(e.contains("picture.toml is not a text file"), "{e}");
    assert_eq!(o["not_text"]["picture_kept"], true);
    assert_eq!(o["undo"], true, "undo brings the scene back");
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and the live pages (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn the_chebyshev_four_bar_built_by_clicks_gives_the_templates_numbers() {
    let sk = &observed()["build_sketch"];
    for s in sk["steps"].as_array().unwrap() {
        assert!(num(&s["grid"]) <= 0.01 + 1e-12, "{s}");
    }
    let b = &observed()["build"];
    assert_eq!(b["error"], "", "{b}");
    for (path, e) in b["typed"].as_object().unwrap() {
        assert_eq!(e, "", "{path}");
    }
    // At φ1 = 90° (position 90 of one turn in 360 steps) the points are the template's.
    let st = &b["points_90"];
    let (_, json, _) = cli(&template("fourbar-chebyshev"), &[]);
    let _ = json;
    let tmp = tempfile::tempdir().unwrap();
    let out = common::mechdraw()
        .arg("run")
        .arg(template("fourbar-chebyshev"))
        .args(["--no-frames", "-q", "--out"])
        .arg(tmp.path())
        .output()
        .unwrap();
    assert!(out.status.success());
    let rows = csv_rows(&std::fs::read_to_string(tmp.path().join("fourbar-chebyshev.csv")).unwrap());
    let row = rows.iter().find(|r| r["phi1_deg"] == 90.0).unwrap();
    let close = |a: f64, b: f64, what: &str| {
        assert!((a - b).abs() <= 1e-9 * (1.0 + b.abs()), "{what}: {a} vs the template's {b}")
    };
    for (mine, theirs) in [("link1.A", "A"), ("link2.B", "B"), ("link2.C", "M")] {
        let (x, y) = point(st, mine);
        close(x, row[&format!("{theirs}_x")], mine);
        close(y, row[&format!("{theirs}_y")], mine);
    }
    // The traced point's velocity and acceleration in the built scene's CSV (its row at
    // φ1 = 90°), against the template's vM and aM.
    let built = csv_rows(b["csv"].as_str().unwrap());
    let mine = &built[90];
    for (q, theirs) in [("x", "M_x"), ("y", "M_y"), ("vx", "vM_x"), ("vy", "vM_y"), ("ax", "aM_x"), ("ay", "aM_y")] {
        close(mine[&format!("C.{q}")], row[theirs], q);
    }
    // The built scene is a file the command line reads, with the same numbers.
    let toml = b["toml"].as_str().unwrap();
    let path = tmp.path().join("built.toml");
    std::fs::write(&path, toml).unwrap();
    let out = common::mechdraw()
        .arg("run")
        .arg(&path)
        .args(["--no-frames", "-q", "--out"])
        .arg(tmp.path().join("b"))
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let on_disk = std::fs::read_dir(tmp.path().join("b"))
        .unwrap()
        .filter_map(|e| e.ok())
        .find(|e| e.path().extension().is_some_and(|x| x == "csv"))
        .unwrap();
    assert_eq!(std::fs::read_to_string(on_disk.path()).unwrap(), b["csv"].as_str().unwrap());
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and the live pages (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn a_build_step_that_cannot_solve_says_why_and_keeps_the_picture_and_the_draft() {
    let b = &observed()["build_bad_step"];
    let err = b["error"].as_str().unwrap();
    assert!(err.starts_with("error: fourbar-chebyshev.toml: "), "{err}");
    assert_eq!(b["picture_kept"], true);
    assert_eq!(b["draft_kept"], true);
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and the live pages (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn on_a_phone_the_picture_is_full_width_and_a_finger_turns_the_crank() {
    let p = &observed()["phone"];
    assert_eq!(num(&p["inner_width"]), 390.0, "the viewport meta tag makes the page phone-sized");
    assert!(num(&p["stage_width"]) >= 350.0, "the picture is {} px wide", p["stage_width"]);
    // Dragged straight above O1: φ1 = 90° (to a pixel at 3 device pixels per CSS pixel).
    assert!((num(&p["drive"]) - 90.0).abs() < 2.0, "φ1 = {}", p["drive"]);
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and the live pages (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn the_keyboard_picks_a_joint_and_moves_it() {
    let k = &observed()["keyboard"];
    // N picks O1, then A; ↑ three times drags the crank pin up: the crank turns
    // counter-clockwise from φ1 = 0 by a few degrees.
    assert_eq!(k["picked"], "A");
    let drive: f64 = k["drive"].as_str().unwrap().parse().unwrap();
    assert!(drive > 0.5 && drive < 45.0, "φ1 = {drive}°");
    assert!(k["label"].as_str().unwrap().contains("dragging A"), "{k}");
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and the live pages (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn no_page_reports_a_console_error() {
    let errors = observed()["console_errors"].as_object().unwrap();
    assert!(errors.is_empty(), "{errors:?}");
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and the live pages (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn the_gallery_works_from_files_and_from_a_web_server() {
    let g = &observed()["gallery"];
    for how in ["file", "http"] {
        let pages = g[how].as_object().unwrap();
        assert_eq!(pages.len(), common::template_paths().len(), "{how}");
        for (name, p) in pages {
            assert_eq!(p["error"], "", "{how} {name}");
            assert!(num(&p["positions"]) >= 1.0);
        }
    }
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and the live pages (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn the_download_menu_shows_each_files_size() {
    let sizes = observed()["download_sizes"]["fourbar-chebyshev"].as_object().unwrap();
    assert!(sizes["fourbar-chebyshev.dxf"].as_str().unwrap().ends_with(" MB"), "{sizes:?}");
    assert!(sizes.values().all(|s| s.as_str().unwrap().chars().next().unwrap().is_ascii_digit()));
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and the live pages (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn a_synthesis_page_drags_a_required_position_and_the_construction_follows() {
    let d = &observed()["synthesis_drag"];
    assert_eq!(d["error"], "", "{d}");
    // No mode to pick: the page opens in Move and a synthesis's points drag there.
    assert_eq!(d["mode"], "move");
    let grips: Vec<&str> = d["grips"].as_array().unwrap().iter().map(|g| g.as_str().unwrap()).collect();
    assert_eq!(grips, ["P1", "P1 line", "P2", "P2 line", "P3", "P3 line", "A1", "B1"]);
    let hint = d["hint"].as_str().unwrap();
    assert!(
        hint.starts_with("A synthesis: drag P1, P2, P3, A1, B1 (and each position line's far end: its angle)")
            && hint.contains("Open the design"),
        "{hint}"
    );
    assert_eq!(d["design_shown"], true);
    // P2 dragged to the grid point 5 steps right and 2 up of the grid point nearest it
    // (P2 at (50, 15) need not be on the page's grid), written into its position, the fields
    // and the construction's P2 with it.
    assert_eq!(d["grid"], d["grid_after"], "the drag kept the picture's scale");
    let target: Vec<f64> = d["target"].as_array().unwrap().iter().map(num).collect();
    let step = num(&d["grid"]["step"]);
    let on_grid = |v: f64| (v / step + 0.5).floor() * step;
    assert!(
        (target[0] - (on_grid(50.0) + 5.0 * step)).abs() < 1e-9
            && (target[1] - (on_grid(15.0) + 2.0 * step)).abs() < 1e-9,
        "{target:?} at a grid step of {step}"
    );
    let fields: Vec<f64> = d["fields"].as_array().unwrap().iter().map(num).collect();
    let p2: Vec<f64> = d["p2"].as_array().unwrap().iter().map(num).collect();
    for i in 0..2 {
        assert!(
            (fields[i] - target[i]).abs() < 1e-9 && (p2[i] - target[i]).abs() < 1e-9,
            "{fields:?} {p2:?} {target:?}"
        );
    }
    let before = template_text("synthesis-motion");
    let after = d["text"].as_str().unwrap();
    let line = after.lines().find(|l| l.contains("angle_deg = -25.0")).unwrap();
    assert_eq!(after, before.replace("    { at = [50.0, 15.0], angle_deg = -25.0 },", line), "one value changed");
    // The picture is the command line's construction for the same text.
    let set = format!("positions[1].at=[{}, {}]", fields[0], fields[1]);
    let (files, _, _) = cli(&template("synthesis-motion"), &[&set]);
    assert_eq!(d["picture"].as_str().unwrap(), String::from_utf8(files["synthesis-motion.svg"].clone()).unwrap());
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and the live pages (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn a_synthesis_page_follows_psi_and_opens_the_design_undo_comes_back() {
    let p = &observed()["synthesis_psi"];
    assert_eq!(p["refused"], "", "{p}");
    assert_eq!(p["error"], "", "{p}");
    let (files, _, _) = cli(&template("synthesis-crank-rocker"), &["psi_deg=45"]);
    let svg = String::from_utf8(files["synthesis-crank-rocker.svg"].clone()).unwrap();
    assert_eq!(p["picture"].as_str().unwrap(), svg, "the construction for ψ = 45° is the command line's");
    assert!(svg.contains("ψ = 45°"));
    let design = String::from_utf8(files["synthesis-crank-rocker-design.toml"].clone()).unwrap();
    assert_eq!(p["design"].as_str().unwrap(), design, "the design is the command line's, byte for byte");
    // Open the design: the page's scene is the design, animated; the button goes.
    let o = &observed()["synthesis_open"];
    assert_eq!(o["error"], "", "{o}");
    assert_eq!(o["text"], p["design"]);
    assert_eq!(o["editor"], p["design"]);
    assert!(num(&o["positions"]) > 1.0, "the design's motion");
    assert_eq!(o["design_shown"], false);
    assert!(o["frame0"].as_str().unwrap().contains("<svg"));
    // The design is a scene of its own: its name in the title and in messages, its text kept
    // under its own key; the synthesis's key keeps the synthesis.
    assert_eq!(o["title"], "mechdraw live: synthesis-crank-rocker-design.toml", "{o}");
    assert_eq!(o["heading"], "mechdraw live: synthesis-crank-rocker-design.toml", "{o}");
    assert_eq!(o["file"], "synthesis-crank-rocker-design.toml");
    assert_eq!(o["stored_design"], p["design"]);
    assert_eq!(o["stored_synthesis"], p["text"]);
    // Undo: the synthesis as it was, under its own name.
    let back = &observed()["synthesis_back"];
    assert_eq!(back["text"], p["text"]);
    assert_eq!(back["design_shown"], true);
    assert_eq!(back["title"], "mechdraw live: synthesis-crank-rocker.toml", "{back}");
    assert_eq!(back["file"], "synthesis-crank-rocker.toml");
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and the live pages (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn the_report_download_is_the_command_lines_report_with_its_pages_to_print() {
    let r = &observed()["report"];
    assert_eq!(r["error"], "", "{r}");
    // What the page offers: the pages to print first (the module has no PDF writer), the
    // table and the JSON.
    let order: Vec<&str> = r["order"].as_array().unwrap().iter().map(|v| v.as_str().unwrap()).collect();
    assert_eq!(
        order,
        ["fourbar-chebyshev-report.html", "fourbar-chebyshev-report.csv", "fourbar-chebyshev-report.json"]
    );
    let saved = |f: &str| std::fs::read(pages().join("downloads/report").join(f)).unwrap();
    // The table and the JSON are the command line's bytes.
    let tmp = tempfile::tempdir().unwrap();
    let ok = common::mechdraw()
        .args([
            "report",
            "templates/fourbar-chebyshev.toml",
            "--paper",
            "a3",
            "--positions",
            "0,90",
            "--quiet",
            "--out",
        ])
        .arg(tmp.path())
        .current_dir(common::root())
        .status()
        .unwrap();
    assert!(ok.success());
    for f in ["fourbar-chebyshev-report.csv", "fourbar-chebyshev-report.json"] {
        assert!(saved(f) == std::fs::read(tmp.path().join(f)).unwrap(), "{f} differs from the command line's");
    }
    // The document to print holds the command line's pages, every SVG byte for byte, in order
    // (tests/report.rs prints it in Chromium against the command line's PDF).
    let html = String::from_utf8(saved("fourbar-chebyshev-report.html")).unwrap();
    let mut svgs: Vec<_> =
        std::fs::read_dir(tmp.path().join("report/fourbar-chebyshev")).unwrap().map(|e| e.unwrap().path()).collect();
    svgs.sort();
    assert_eq!(svgs.len(), html.matches("<div class=\"sheet\">").count());
    let mut at = 0;
    for s in &svgs {
        let svg = std::fs::read_to_string(s).unwrap();
        let svg = svg.trim();
        at += html[at..].find(svg).unwrap_or_else(|| panic!("{} not in the document, or not in order", s.display()))
            + svg.len();
    }
    // A position outside the motion: the command line's words under the report's button, no file.
    let bad = &r["bad"];
    let e = bad["error"].as_str().unwrap();
    assert!(e.contains("--positions") && e.contains("outside the motion"), "{e}");
    assert_eq!(bad["files"], 0);
}
