//! `mechdraw run` on a synthesis scene: the construction (golden PNGs of every template's,
//! looked at; its DXF audited by ezdxf and in golden for the crank-rocker), the check table,
//! `<name>-design.toml` and, unless `--no-analysis`, the design's whole run — the same run
//! `mechdraw run <name>-design.toml` makes; a refused requirement leaves nothing behind; the
//! live page's session takes a synthesis scene, follows a change of ψ and hands over the
//! design.

mod common;

use std::path::Path;

use mechdraw::web::Session;

const TEMPLATES: [&str; 5] =
    ["synthesis-crank-rocker", "synthesis-slider-crank", "synthesis-shaper", "synthesis-motion", "synthesis-function"];

fn run(template: &str, out: &Path, extra: &[&str]) -> std::process::Output {
    common::mechdraw()
        .args(["run", &format!("templates/{template}.toml"), "--quiet", "--no-frames", "--out"])
        .arg(out)
        .args(extra)
        .current_dir(common::root())
        .output()
        .unwrap()
}

#[test]
fn constructions_match_their_golden_pictures_and_audit_clean() {
    let tmp = tempfile::tempdir().unwrap();
    let mut dxfs = Vec::new();
    for t in TEMPLATES {
        let out = run(t, tmp.path(), &["--no-analysis"]);
        assert!(out.status.success(), "{t}: {}", String::from_utf8_lossy(&out.stderr));
        let svg = std::fs::read_to_string(tmp.path().join(format!("{t}.svg"))).unwrap();
        common::assert_golden_png(&format!("synthesis/{t}.png"), &svg);
        dxfs.push(tmp.path().join(format!("{t}.dxf")));
    }
    let text = std::fs::read_to_string(tmp.path().join("synthesis-crank-rocker.dxf")).unwrap();
    common::assert_golden_text("synthesis/synthesis-crank-rocker.dxf", &text);
    let paths: Vec<&Path> = dxfs.iter().map(|p| p.as_path()).collect();
    common::assert_ezdxf_clean(&paths);
}

#[test]
fn the_charts_match_their_golden_pictures() {
    let tmp = tempfile::tempdir().unwrap();
    for (t, chart) in [("synthesis-crank-rocker", "family"), ("synthesis-function", "structural-error")] {
        assert!(run(t, tmp.path(), &["--no-analysis"]).status.success());
        let svg = std::fs::read_to_string(tmp.path().join(format!("diagrams/{t}/{chart}.svg"))).unwrap();
        common::assert_golden_png(&format!("synthesis/{t}-{chart}.png"), &svg);
    }
}

#[test]
fn no_analysis_writes_the_design_but_not_its_run_and_the_run_is_the_designs_own() {
    let t = "synthesis-slider-crank";
    let without = tempfile::tempdir().unwrap();
    assert!(run(t, without.path(), &["--no-analysis"]).status.success());
    let mut files = Vec::new();
    common::read_tree(without.path(), Path::new(""), &mut files);
    let mut names: Vec<&str> = files.iter().map(|(n, _)| n.as_str()).collect();
    names.sort();
    assert_eq!(
        names,
        [
            "diagrams/synthesis-slider-crank/family.svg",
            "synthesis-slider-crank-design.toml",
            "synthesis-slider-crank.csv",
            "synthesis-slider-crank.dxf",
            "synthesis-slider-crank.json",
            "synthesis-slider-crank.svg",
        ]
    );
    let csv = std::fs::read_to_string(without.path().join(format!("{t}.csv"))).unwrap();
    assert!(csv.starts_with("quantity,required,achieved,error,tolerance,ok\nH [mm],50,"), "{csv}");
    assert_eq!(csv.lines().filter(|l| l.ends_with(",true")).count(), 2, "{csv}");

    // With the analysis: the design's files, the same as running the design file itself.
    let with = tempfile::tempdir().unwrap();
    assert!(run(t, with.path(), &[]).status.success());
    let alone = tempfile::tempdir().unwrap();
    let design = with.path().join(format!("{t}-design.toml"));
    let out = common::mechdraw()
        .args(["run", "--quiet", "--no-frames", "--out"])
        .arg(alone.path())
        .arg(&design)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let mut by_synthesis = Vec::new();
    common::read_tree(with.path(), Path::new(""), &mut by_synthesis);
    let mut by_itself = Vec::new();
    common::read_tree(alone.path(), Path::new(""), &mut by_itself);
    assert!(!by_itself.is_empty());
    for (name, bytes) in &by_itself {
        let mine = by_synthesis.iter().find(|(n, _)| n == name).unwrap_or_else(|| panic!("{name} not written"));
        assert!(mine.1 == *bytes, "{name} differs from the design's own run");
    }
    // The design's stroke and time ratio in its own summary: the requirement again.
    let json: serde_json::Value =
        serde_json::from_slice(&by_itself.iter().find(|(n, _)| n.ends_with("-design.json")).unwrap().1).unwrap();
    let b = &json["strokes"]["B"];
    assert!((b["H"].as_f64().unwrap() - 50.0).abs() < 1e-9 * 50.0 && (b["K"].as_f64().unwrap() - 1.2).abs() < 1e-9);
}

#[test]
fn a_refused_requirement_exits_2_and_writes_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = tmp.path().join("bad.toml");
    std::fs::write(
        &scene,
        "kind = \"synthesis\"\ntask = \"slider-crank\"\nname = \"bad\"\nunits = \"mm\"\nstroke = 50.0\ntime_ratio = 1.0\n",
    )
    .unwrap();
    let out_dir = tmp.path().join("out");
    let out = common::mechdraw().args(["run", "-q", "--out"]).arg(&out_dir).arg(&scene).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("bad.toml: field `time_ratio`: the time ratio K = 1 must be greater than 1"), "{err}");
    assert!(!out_dir.exists() || std::fs::read_dir(&out_dir).unwrap().next().is_none());
    // An unknown task is named with the valid ones.
    std::fs::write(&scene, "kind = \"synthesis\"\ntask = \"cam\"\nname = \"bad\"\nunits = \"mm\"\n").unwrap();
    let out = common::mechdraw().args(["run", "-q", "--out"]).arg(&out_dir).arg(&scene).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("field `task`: \"cam\" is not a synthesis task; valid: crank-rocker, slider-crank"), "{err}");
}

#[test]
fn the_live_session_follows_a_change_of_psi_and_hands_over_the_design() {
    let file = "synthesis-crank-rocker.toml";
    let text = std::fs::read_to_string(common::root().join("templates").join(file)).unwrap();
    let mut s = Session::new(&text, file).unwrap();
    let before = s.frame(0).unwrap();
    let design = s.design_text().unwrap();
    assert!(design.contains("kind = \"fourbar\"") && design.contains("name = \"synthesis-crank-rocker-design\""));
    s.set("psi_deg", "45.0").unwrap();
    let after = s.frame(0).unwrap();
    assert_ne!(before, after, "the construction follows ψ");
    assert!(after.contains("ψ = 45°"));
    // "Open the design": the design's text is a scene the page opens like any other.
    let d = Session::new(&s.design_text().unwrap(), "synthesis-crank-rocker-design.toml").unwrap();
    assert!(d.positions() > 1, "the design animates");
    // A change the requirement refuses leaves the session as it was.
    let e = s.set("time_ratio", "0.9").unwrap_err().to_string();
    assert!(e.contains("field `time_ratio`"), "{e}");
    assert_eq!(s.frame(0).unwrap(), after);
    // The page opens the design in the same session under the design's own file name (its
    // title, storage key and messages): the command line's `<name>-design.toml`.
    let name = s.design_file().unwrap();
    assert_eq!(name, "synthesis-crank-rocker-design.toml");
    s.rename(&name);
    s.replace(&s.design_text().unwrap()).unwrap();
    assert!(s.positions() > 1 && s.design_file().is_none(), "the design is a four-bar, animated");
    let e = s.set("l_ab", "-1").unwrap_err().to_string();
    assert!(e.contains("synthesis-crank-rocker-design.toml"), "{e}");
}

/// A grip of the session's edit points.
fn grip(s: &Session, name: &str) -> (f64, f64) {
    let p = s.edit_points(0).unwrap().into_iter().find(|(n, _)| n == name).unwrap_or_else(|| panic!("no grip {name}"));
    (p.1.x, p.1.y)
}

#[test]
fn dragging_a_constructions_point_changes_its_field_and_the_point_follows_the_pointer() {
    // (template, point, target, the field's new text): after the drag the construction is
    // solved again and the point is where it was dropped (its coordinate the drag sets).
    let cases: &[(&str, &str, (f64, f64), &str)] = &[
        ("synthesis-motion", "P2", (55.0, 20.0), "{ at = [55.0, 20.0], angle_deg = -25.0 }"),
        ("synthesis-motion", "A1", (-25.0, -40.0), "a1 = [-25.0, -40.0]"),
        ("synthesis-crank-rocker", "C", (50.0, 0.0), "ground = 50.0"),
        ("synthesis-slider-crank", "B2", (80.0, -12.0), "offset = 12.0"),
        ("synthesis-shaper", "E1", (250.0, 580.0), "ram_height = 580.0"),
        ("synthesis-shaper", "O1", (0.0, 320.0), "crank = "),
        ("synthesis-function", "C", (120.0, 0.0), "ground = 120.0"),
    ];
    for &(name, point, (x, y), written) in cases {
        let file = format!("{name}.toml");
        let text = std::fs::read_to_string(common::root().join("templates").join(&file)).unwrap();
        let mut s = Session::new(&text, &file).unwrap();
        let (before, design) = (s.frame(0).unwrap(), s.design_text().unwrap());
        s.reshape(point, mechdraw::geom::Point::new(x, y), 0, 1).unwrap_or_else(|e| panic!("{name} {point}: {e}"));
        assert!(s.scene_text().contains(written), "{name} {point}:\n{}", s.scene_text());
        // Every comment of the template is still there.
        assert_eq!(
            s.scene_text().matches('#').count(),
            text.matches('#').count() - usize::from(point == "C" && name.contains("rocker")),
            "{name}"
        );
        assert_ne!(s.frame(0).unwrap(), before, "{name} {point}: the construction is drawn again");
        assert_ne!(s.design_text().unwrap(), design, "{name} {point}: the design follows");
        // The design still meets the requirement by mechdraw's analysis (no failed check).
        assert!(s.warnings().iter().all(|w| !w.starts_with("check:")), "{name}: {:?}", s.warnings());
        let (gx, gy) = grip(&s, point);
        match point {
            "B2" => assert!((gy - y).abs() < 1e-9, "{name} {point}: the guide at the pointer's height ({gy})"),
            "E1" => assert!((gy - y).abs() < 1e-9, "{name} {point}: at the pointer's height ({gy})"),
            // The crank is written on the 0.1 grid: O1O3 = crank / sin(θ/2) within 0.05 / sin(θ/2).
            "O1" => assert!((gy - y).abs() < 0.2, "{name} {point}: at the pointer's height ({gy})"),
            "C" => assert!((gx - x).abs() < 1e-9 && gy.abs() < 1e-9, "{name} {point}: at ({gx}, {gy})"),
            _ => assert!((gx - x).abs() < 1e-9 && (gy - y).abs() < 1e-9, "{name} {point}: at ({gx}, {gy})"),
        }
    }
}

#[test]
fn dragging_a_positions_line_turns_it_and_a_point_without_a_field_is_refused() {
    let file = "synthesis-motion.toml";
    let text = std::fs::read_to_string(common::root().join("templates").join(file)).unwrap();
    let mut s = Session::new(&text, file).unwrap();
    let (ax, ay) = grip(&s, "P3");
    // The line's end dragged to 40° below the horizontal through P3.
    let r = 30.0;
    let a = (-40f64).to_radians();
    let (tx, ty) = (ax + r * libm::cos(a), ay + r * libm::sin(a));
    s.reshape("P3 line", mechdraw::geom::Point::new(tx, ty), 0, 3).unwrap();
    assert!(s.scene_text().contains("{ at = [100.0, 0.0], angle_deg = -40.0 }"), "{}", s.scene_text());
    let e = s.reshape("O1", mechdraw::geom::Point::new(0.0, 0.0), 0, 1).unwrap_err().to_string();
    assert!(e.contains("`O1` carries nothing") && e.contains("P1, P1 line"), "{e}");
    // A drag that would need a negative length is refused and changes nothing.
    let file = "synthesis-crank-rocker.toml";
    let text = std::fs::read_to_string(common::root().join("templates").join(file)).unwrap();
    let mut s = Session::new(&text, file).unwrap();
    let e = s.reshape("C", mechdraw::geom::Point::new(-5.0, 0.0), 0, 1).unwrap_err().to_string();
    assert!(e.contains("ground O1C would be -5.0"), "{e}");
    assert_eq!(s.scene_text(), text);
}
