//! The page's session (`mechdraw::web::Session`, issue 17): a scene open in the browser,
//! changed field by field (`--set` paths) or by a new text, gives the command line's bytes:
//! every frame is the CLI's `frames/<name>/<position>.svg`, the downloads are the CLI's
//! files, the JSON after a change is the CLI's JSON for the same `--set`; a change the scene
//! refuses gives the CLI's message and leaves the session as it was.

#![allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the library calls"
)]

mod common;

use std::path::Path;

use mechdraw::web::{self, Session, WebOptions};

/// The command line's files for `path` with `set` (frames included), sorted by name.
fn cli_files(path: &Path, set: &[String]) -> Vec<(String, Vec<u8>)> {
    let tmp = tempfile::tempdir().unwrap();
    let mut cmd = common::mechdraw();
    cmd.arg("run").arg(path).arg("--out").arg(tmp.path()).arg("-q");
    for s in set {
        cmd.arg("--set").arg(s);
    }
    let out = cmd.output().unwrap();
    assert!(out.status.success(), "{}: {}", path.display(), String::from_utf8_lossy(&out.stderr));
    let mut files = Vec::new();
    common::read_tree(tmp.path(), Path::new(""), &mut files);
    files.sort();
    files
}

/// The JSON the command line prints for `path` with `set` (`--json`).
fn cli_json(path: &Path, set: &[String]) -> serde_json::Value {
    let tmp = tempfile::tempdir().unwrap();
    let mut cmd = common::mechdraw();
    cmd.arg("run").arg(path).arg("--out").arg(tmp.path()).arg("-q").arg("--json").arg("--no-frames");
    for s in set {
        cmd.arg("--set").arg(s);
    }
    let out = cmd.output().unwrap();
    assert!(out.status.success(), "{}: {}", path.display(), String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn every_frame_and_download_is_the_command_lines() {
    for (path, set) in common::reduced_templates() {
        let file = path.display().to_string();
        let session = Session::new(&common::text_with(&path, &set), &file).unwrap_or_else(|e| panic!("{file}: {e}"));
        let cli = cli_files(&path, &set);
        // The scene's own frames (a synthesis writes its design's under the design's name).
        let own = format!("frames/{}/", session.products().unwrap().name);
        let frames: Vec<&(String, Vec<u8>)> = cli.iter().filter(|(n, _)| n.starts_with(&own)).collect();
        if frames.is_empty() {
            // A still picture: the one frame is `<name>.svg`.
            assert_eq!(session.positions(), 1, "{file}");
            let name = &session.products().unwrap().name;
            let svg = cli.iter().find(|(n, _)| *n == format!("{name}.svg")).expect("picture");
            assert!(session.frame(0).unwrap().as_bytes() == svg.1, "{file}: the picture");
        } else {
            assert_eq!(session.positions(), frames.len(), "{file}: positions");
            let base = session.base().expect("a motion has a base");
            let head = base.strip_suffix("</svg>").expect("the base is an SVG document");
            for (k, (name, bytes)) in frames.iter().enumerate() {
                assert!(session.frame(k).unwrap().as_bytes() == bytes.as_slice(), "{file}: frame {k} is not {name}");
                // The page draws the base once and each frame's moving part on it.
                let moving = session.moving(k).unwrap_or_else(|| panic!("{file}: frame {k} does not split"));
                let spliced = format!("{head}{moving}</svg>");
                assert!(spliced.as_bytes() == bytes.as_slice(), "{file}: base + moving part {k} is not {name}");
            }
            assert!(session.moving(frames.len()).is_none(), "{file}: no moving part past the last");
            assert!(session.frame(frames.len()).is_none(), "{file}: no frame past the last");
        }
        // The sheets shown under the picture: the CLI's `<name>-<suffix>.svg`.
        for (suffix, svg) in session.sheets().unwrap() {
            let name = format!("{}-{suffix}.svg", session.products().unwrap().name);
            let on_disk = cli.iter().find(|(n, _)| *n == name).unwrap_or_else(|| panic!("{file}: no {name}"));
            assert!(on_disk.1 == svg.as_bytes(), "{file}: the sheet {suffix} differs from {name}");
        }
        // The diagrams shown on the page: the CLI's `diagrams/<name>/<stem>.svg`.
        for (stem, svg) in session.diagrams().unwrap() {
            let name = format!("diagrams/{}/{stem}.svg", session.products().unwrap().name);
            let on_disk = cli.iter().find(|(n, _)| *n == name).unwrap_or_else(|| panic!("{file}: no {name}"));
            assert!(on_disk.1 == svg.as_bytes(), "{file}: the diagram {stem} differs from {name}");
        }
        // The downloads: the CLI's files without the frames and the viewer.
        let downloads = session.files().unwrap();
        let no_frames = web::scene_files(&common::text_with(&path, &set), &file, WebOptions::default()).unwrap();
        assert_eq!(downloads.len(), no_frames.files.len(), "{file}");
        // The warnings the page shows at once (from the picture alone) are the run's.
        assert_eq!(session.warnings(), no_frames.warnings.as_slice(), "{file}: warnings");
        for ((n, b), (m, c)) in downloads.iter().zip(&no_frames.files) {
            assert_eq!(n, m, "{file}");
            assert!(b == c, "{file}: {n}");
            let on_disk =
                cli.iter().find(|(d, _)| d == n).unwrap_or_else(|| panic!("{file}: {n} not written by the CLI"));
            assert!(on_disk.1 == *b, "{file}: {n} differs from the CLI's");
        }
    }
}

#[test]
fn a_length_that_breaks_grashof_shows_the_command_lines_gaps() {
    let path = common::root().join("templates/fourbar-chebyshev.toml");
    let file = path.display().to_string();
    let mut session = Session::new(&std::fs::read_to_string(&path).unwrap(), &file).unwrap();
    assert_eq!(session.products().unwrap().summary["grashof"], "grashof");
    assert_eq!(session.products().unwrap().summary["gaps"], serde_json::json!([]));
    session.set("l_bc", "0.2").unwrap();
    let cli = cli_json(&path, &["l_bc=0.2".to_string()]);
    assert_eq!(session.products().unwrap().summary, cli, "the JSON after the change is the CLI's for --set l_bc=0.2");
    let gaps = cli["gaps"].as_array().unwrap();
    assert_eq!(gaps.len(), 2);
    // Where a coupler of 0.10 cannot reach a rocker of 0.20 (|O1C|, crank 0.04): the
    // assembly limits in closed form, cos φ1 = (l1² + d² − (l_bc − l_ab)²) / (2·l1·d).
    let limits = cli_limits(&session);
    assert!((gaps[0]["to_deg"].as_f64().unwrap() - limits).abs() < 1e-9, "{} vs {limits}", gaps[0]["to_deg"]);
    // The parameters show the change.
    let l_bc = session.parameters().unwrap().into_iter().find(|p| p.path == "l_bc").unwrap();
    assert_eq!(l_bc.value, 0.2);
}

/// The crank angle (degrees) at which the dyad stretched to |AC| = l_bc − l_ab first
/// assembles again after 0°, in closed form from the scene's lengths and the pivot C.
fn cli_limits(s: &Session) -> f64 {
    let params = s.parameters().unwrap();
    let get = |p: &str| params.iter().find(|q| q.path == p).unwrap_or_else(|| panic!("{p}")).value;
    let (l1, l_ab, l_bc) = (get("l1"), get("l_ab"), get("l_bc"));
    let (cx, cy) = (get("c[0]"), get("c[1]"));
    let (ox, oy) = (get("o1[0]"), get("o1[1]"));
    let (dx, dy) = (cx - ox, cy - oy);
    let d = dx.hypot(dy);
    let ac = l_bc - l_ab;
    let half = ((l1 * l1 + d * d - ac * ac) / (2.0 * l1 * d)).acos();
    (dy.atan2(dx) + half).to_degrees().rem_euclid(360.0)
}

#[test]
fn a_change_the_scene_refuses_gives_the_command_lines_message_and_keeps_the_picture() {
    let path = common::root().join("templates/fourbar-chebyshev.toml");
    let file = path.display().to_string();
    let text = std::fs::read_to_string(&path).unwrap();
    let mut session = Session::new(&text, &file).unwrap();
    session.set("phi1_deg.step", "30").unwrap();
    let before = session.frame(3).unwrap();

    // A negative crank, as a field: the CLI's message for --set l1=-0.04.
    let err = session.set("l1", "-0.04").unwrap_err().to_string();
    let tmp = tempfile::tempdir().unwrap();
    let out = common::mechdraw()
        .args(["run", &file, "--set", "l1=-0.04", "--out"])
        .arg(tmp.path())
        .arg("-q")
        .output()
        .unwrap();
    assert!(!out.status.success());
    let cli = String::from_utf8(out.stderr).unwrap();
    assert_eq!(err, cli.trim_end().strip_prefix("error: ").unwrap());
    assert_eq!(session.frame(3).unwrap(), before, "the picture stays");

    // A TOML edit with a syntax error: the CLI's message, naming the line.
    let broken = text.replace("l_bc = 0.10", "l_bc = = 0.10");
    let err = session.replace(&broken).unwrap_err().to_string();
    let bad = tmp.path().join("fourbar-chebyshev.toml");
    std::fs::write(&bad, &broken).unwrap();
    let out =
        common::mechdraw().arg("run").arg(&bad).arg("--out").arg(tmp.path().join("o")).arg("-q").output().unwrap();
    let cli = String::from_utf8(out.stderr).unwrap();
    let cli = cli.trim_end().strip_prefix("error: ").unwrap().replace(&bad.display().to_string(), &file);
    assert_eq!(err, cli);
    assert!(err.contains("line 14"), "{err}");
    assert_eq!(session.frame(3).unwrap(), before, "the picture stays");
}

#[test]
fn every_number_of_a_scene_is_a_field_that_sets_it() {
    for (path, set) in common::reduced_templates() {
        let file = path.display().to_string();
        let mut session = Session::new(&common::text_with(&path, &set), &file).unwrap();
        let params = session.parameters().unwrap();
        assert!(params.len() >= 3, "{file}: {params:?}");
        let summary = session.products().unwrap().summary.clone();
        // Setting every field to its own value changes nothing.
        for p in &params {
            session.set(&p.path, &p.text()).unwrap_or_else(|e| panic!("{file}: {}: {e}", p.path));
        }
        assert_eq!(session.products().unwrap().summary, summary, "{file}: every field set to its own value");
    }
}

#[test]
fn the_triad_lists_its_eight_assembly_modes_and_the_pattern_methods_angle() {
    let path = common::root().join("templates/triad-popa.toml");
    let session = Session::new(&std::fs::read_to_string(&path).unwrap(), &path.display().to_string()).unwrap();
    let s = &session.products().unwrap().summary;
    assert_eq!(s["solutions"].as_array().unwrap().len(), 8);
    let phi1 = s["pattern"]["phi1_deg"].as_f64().unwrap();
    assert_eq!(format!("{phi1:.2}"), "75.77");
}

/// A point by name in a drive state.
fn point_of(st: &mechdraw::figure::shared::animation::DriveState, name: &str) -> mechdraw::geom::Point {
    st.points.iter().find(|(n, _)| n == name).unwrap_or_else(|| panic!("no point {name}")).1
}

#[test]
fn dragging_the_crank_pin_turns_the_crank_to_the_pointers_angle() {
    let path = common::root().join("templates/fourbar-chebyshev.toml");
    let file = path.display().to_string();
    let mut session = Session::new(&std::fs::read_to_string(&path).unwrap(), &file).unwrap();
    let params = session.parameters().unwrap();
    let get = |p: &str| params.iter().find(|q| q.path == p).unwrap().value;
    let (ox, oy, l1) = (get("o1[0]"), get("o1[1]"), get("l1"));
    // The pointer off the crank circle (1.37 l1 from O1), between two sampled angles: the
    // crank turns to the pointer's direction from O1, computed here with atan2.
    for theta_deg in [123.4567_f64, 0.25, 271.9] {
        let th = theta_deg.to_radians();
        let target = mechdraw::geom::Point::new(ox + 1.37 * l1 * th.cos(), oy + 1.37 * l1 * th.sin());
        let st = session.drag("A", target).unwrap();
        let (_, phi1) = session.dragged().unwrap();
        assert!((phi1 - theta_deg).abs() < 1e-7, "φ1 = {phi1}° for a pointer at {theta_deg}°");
        assert!(st.residual <= 1e-9, "loop residual {}", st.residual);
        // The loop closes, measured here: |O1A| = l1, |AB| = l_ab, |CB| = l_bc.
        let (a, b) = (point_of(&st, "A"), point_of(&st, "B"));
        let c = mechdraw::geom::Point::new(get("c[0]"), get("c[1]"));
        assert!(((a - mechdraw::geom::Point::new(ox, oy)).norm() - l1).abs() <= 1e-12);
        assert!(((b - a).norm() - get("l_ab")).abs() <= 1e-12);
        assert!(((b - c).norm() - get("l_bc")).abs() <= 1e-12);
        let frame = session.dragged_frame().unwrap();
        let shown = mechdraw::figure::fourbar::angle_text(theta_deg);
        // φ_1 drawn with a subscript: read through its tspan.
        let frame = common::svg_plain(&frame);
        assert!(frame.contains(&format!("φ1 = {shown}°")), "the frame shows φ1 = {shown}°");
    }
    // A fixed pivot cannot be dragged anywhere: the drive stays at the nearest position.
    let st = session.drag("C", mechdraw::geom::Point::new(1.0, 1.0)).unwrap();
    assert!(st.residual <= 1e-9);
    assert!(
        session.drag("Z", mechdraw::geom::Point::new(0.0, 0.0)).unwrap_err().to_string().contains("O1, A, B, M, C")
    );
}

#[test]
fn dragging_a_shaper_point_keeps_every_joint_together() {
    let path = common::root().join("templates/shaper.toml");
    let file = path.display().to_string();
    let mut session = Session::new(&std::fs::read_to_string(&path).unwrap(), &file).unwrap();
    use mechdraw::geom::Point;
    for target in [Point::new(-150.0, 520.0), Point::new(210.0, 560.0), Point::new(80.0, 590.0)] {
        let st = session.drag("rocker.B", target).unwrap();
        assert!(st.residual <= 1e-9, "solver residual {}", st.residual);
        // Every joint measured from the points: pivots on the ground, pins together, the
        // block on the rocker's line, the ram on its guide y = 600.
        let p = |n: &str| point_of(&st, n);
        let close = |a: Point, b: Point| (a - b).norm() <= 1e-9 * 600.0;
        assert!(close(p("crank.O1"), Point::new(0.0, 300.0)));
        assert!(close(p("rocker.O3"), Point::new(0.0, 0.0)));
        assert!(close(p("crank.A"), p("block.A")));
        assert!(close(p("rocker.B"), p("link.B")));
        assert!(close(p("link.E"), p("ram.E")));
        assert!((p("ram.E").y - 600.0).abs() <= 1e-9 * 600.0);
        let (o3, b, a) = (p("rocker.O3"), p("rocker.B"), p("block.A"));
        let u = (b - o3) / (b - o3).norm();
        assert!(((a - o3).x * u.y - (a - o3).y * u.x).abs() <= 1e-9 * 600.0, "the block is on the rocker");
        // The drive went where rocker.B is nearest the pointer: no nearby time is nearer.
        let (k, t) = session.dragged().unwrap();
        let d = |st: &mechdraw::figure::shared::animation::DriveState| (point_of(st, "rocker.B") - target).norm();
        let here = d(&st);
        let drive = match &session.products().unwrap().picture {
            mechdraw::run::products::Picture::Motion(a) => a.drive.as_ref().unwrap(),
            _ => unreachable!(),
        };
        for dt in [-1e-4, 1e-4] {
            let there = (drive.solve)(k, t + dt).unwrap();
            assert!(d(&there) >= here - 1e-12, "t = {t} is not the nearest ({dt:+})");
        }
    }
}

#[test]
fn a_field_change_keeps_the_students_toml_for_every_template() {
    for path in common::template_paths() {
        let file = path.display().to_string();
        let text = std::fs::read_to_string(&path).unwrap();
        let mut session = Session::new(&text, &file).unwrap();
        // The first positive decimal number (a length, a mass, a tolerance) scaled by 1.01,
        // written as the field writes it.
        let params = session.parameters().unwrap();
        let p = params.iter().find(|p| !p.integer && p.value > 0.0).unwrap_or_else(|| panic!("{file}: {params:?}"));
        let new = format!("{:?}", p.value * 1.01);
        session.set(&p.path, &new).unwrap_or_else(|e| panic!("{file}: {}: {e}", p.path));
        let after = session.scene_text();
        // One line changed, and on it only the number.
        let changed: Vec<(&str, &str)> = text.lines().zip(after.lines()).filter(|(a, b)| a != b).collect();
        assert_eq!(text.lines().count(), after.lines().count(), "{file}");
        assert_eq!(changed.len(), 1, "{file}: {changed:?}");
        let (a, b) = changed[0];
        assert!(b.contains(&new), "{file}: {b}");
        if let Some(i) = a.find('#') {
            assert!(b.ends_with(&a[i..]), "{file}: the comment after the value stays: {b}");
        }
        // And the field shows it.
        let shown = session.parameters().unwrap().into_iter().find(|q| q.path == p.path).unwrap();
        assert_eq!(shown.text(), new, "{file}");
    }
}

#[test]
fn a_field_change_holds_each_polygons_scale_while_it_fills_half_its_panel() {
    // ω1 from 20 to 23 rad/s: every velocity 1.15 times, every acceleration 1.32 times.
    let path = common::root().join("templates/fourbar-chebyshev.toml");
    let file = path.display().to_string();
    let text = common::text_with(&path, &["phi1_deg.step=10".to_string()]);
    let mut session = Session::new(&text, &file).unwrap();
    let before = session.frame_scales().to_vec();
    assert_eq!(before.len(), 36);
    session.set("omega1", "23.0").unwrap();
    let held = session.frame_scales().to_vec();
    // A fresh run of the changed text: the command line's choice.
    let fresh = Session::new(session.scene_text(), &file).unwrap().frame_scales().to_vec();
    let kept = |s: &[mechdraw::figure::shared::panels::FrameScales]| {
        s.iter().zip(&before).map(|(a, b)| usize::from(a.k_v == b.k_v) + usize::from(a.k_a == b.k_a)).sum::<usize>()
    };
    assert!(kept(&held) > kept(&fresh), "held {} of 72 scales, a fresh run {}", kept(&held), kept(&fresh));
    // The picture prints the scales it holds, position by position.
    for (k, s) in held.iter().enumerate() {
        let svg = session.frame(k).unwrap();
        let k_v = mechdraw::figure::shared::vocab::scale_text(s.k_v.unwrap());
        // k_v with its subscript: "kv" once the tspans are taken off.
        assert!(common::svg_plain(&svg).contains(&format!("kv = {k_v} ")), "frame {k}: k_v = {k_v} not printed");
    }
    // The files stay the command line's for the text.
    assert_eq!(session.products().unwrap().frame_scales, fresh);
}
