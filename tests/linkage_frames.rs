//! The graph-analytical frames of any linkage (issue 15 §2, §3): force polygons per body
//! that close (each body's forces, the reactions from the Lagrange multipliers among them,
//! sum to zero: Newton's law body by body, an independent check of the reactions), the
//! closing side drawn equal to the body's last reaction, polygons drawn at the scales the
//! titles print (measured on the frame × printed scale = the solver's value), the
//! `[polygons]` table choosing points, and golden frames of the shaper with its polygons
//! and of the slider-crank with its force polygons.

mod common;

use mechdraw::draw::svg::{SvgOptions, to_string};
use mechdraw::draw::{Drawing, Shape};
use mechdraw::figure::linkage::forces::{body_forces, body_polygon, closure};
use mechdraw::figure::linkage::polygon::polygons_of;
use mechdraw::geom::Vector;
use mechdraw::run::{RunOptions, products};
use mechdraw::scene::linkage::LinkageScene;
use mechdraw::scene::{self, Scene};
use mechdraw::solve::linkage::{Anchor, Attach, Forces, Solver, State};

fn linkage(template: &str) -> LinkageScene {
    let loaded = scene::load(&common::root().join(template), &[]).unwrap();
    let Scene::Linkage(s) = loaded.scene else { panic!("not a linkage scene") };
    s
}

fn kinetostatics(s: &LinkageScene) -> (Vec<State>, Vec<Forces>) {
    let d = s.dynamics.as_ref().expect("a scene with forces");
    Solver::new(s.mechanism.clone()).unwrap().run_kinetostatics(&s.times, d).unwrap()
}

#[test]
fn every_body_force_polygon_closes_at_every_sample() {
    for template in ["templates/slider-crank.toml", "templates/shaper-forces.toml"] {
        let s = linkage(template);
        let d = s.dynamics.as_ref().unwrap();
        let (states, forces) = kinetostatics(&s);
        let mut worst: f64 = 0.0;
        for (st, f) in states.iter().zip(&forces) {
            for (b, bf) in body_forces(&s.mechanism, d, st, f).iter().enumerate() {
                // Every joint of the body contributes, plus its weight and inertia force.
                let size: f64 = bf.iter().map(|(_, nv)| nv.v.norm()).sum();
                let gap = closure(bf).norm() / size.max(1e-300);
                worst = worst.max(gap);
                assert!(gap <= 1e-9, "{template} t={} body {b}: Σ F = {:?} of {size} N", st.t, closure(bf));
                // The side that closes the drawn polygon is the body's last force itself.
                let poly = body_polygon(b, bf);
                let last = bf.iter().rev().find(|(_, nv)| nv.v.norm() > 1e-9 * size).unwrap();
                let drawn = poly.resultant(&last.1.name).unwrap();
                assert!((drawn - last.1.v).norm() <= 1e-9 * size, "{template} body {b} closing side");
            }
        }
        assert!(worst > 0.0 || template.contains("none"), "{template}: Σ F exactly zero everywhere is suspicious");
    }
}

#[test]
fn a_body_without_mass_or_load_balances_its_reactions_alone() {
    // The slider-crank's crank has no mass: its polygon is −RA and RO, equal and opposite.
    let s = linkage("templates/slider-crank.toml");
    let (states, forces) = kinetostatics(&s);
    let d = s.dynamics.as_ref().unwrap();
    let k = 30;
    let bf = &body_forces(&s.mechanism, d, &states[k], &forces[k])[0];
    let names: Vec<&str> = bf.iter().map(|(_, nv)| nv.name.as_str()).collect();
    assert_eq!(names, ["RO", "−RA"]);
    assert!((bf[0].1.v + bf[1].1.v).norm() <= 1e-9 * bf[0].1.v.norm());
}

/// The number printed after `key = ` in the text starting with `title`.
fn printed_scale(d: &Drawing, title: &str, key: &str) -> f64 {
    let text = d
        .entities
        .iter()
        // A text, or a scale caption as the paper states it.
        .find_map(|e| match e.shape.scale_text_in(None).unwrap_or_else(|| e.shape.clone()) {
            Shape::Text { value, .. } if value.starts_with(title) => Some(value),
            _ => None,
        })
        .unwrap_or_else(|| panic!("no title {title}"));
    let after = text.split(&format!("{key} = ")).nth(1).unwrap();
    after.split_whitespace().next().unwrap().parse().unwrap()
}

/// Arrows of a layer: (from, to).
fn arrows(d: &Drawing, layer: &str) -> Vec<(mechdraw::geom::Point, mechdraw::geom::Point)> {
    let l = d.layers.iter().position(|x| x.name == layer).unwrap();
    d.entities
        .iter()
        .filter(|e| e.layer == l)
        .filter_map(|e| match e.shape {
            Shape::Arrow { from, to, .. } => Some((from, to)),
            _ => None,
        })
        .collect()
}

#[test]
fn frames_draw_the_polygons_at_the_printed_scales() {
    let loaded = scene::load(&common::root().join("templates/slider-crank.toml"), &[]).unwrap();
    let Scene::Linkage(s) = &loaded.scene else { panic!() };
    let p = products(&loaded, &RunOptions::default()).unwrap();
    let mechdraw::run::products::Picture::Motion(anim) = &p.picture else { panic!("a linkage animates") };
    let (states, forces) = kinetostatics(s);
    let crank_pin = Anchor { body: Attach::Body(0), local: Vector::new(110.0, 0.0) };
    for k in [0, 30, 100, 250] {
        let d = anim.frame_of(&anim.pose(k));
        let paper = d.paper_mm_per_unit.unwrap();
        let k_v = printed_scale(&d, "Velocity polygon", "k_v");
        let k_a = printed_scale(&d, "Acceleration polygon", "k_a");
        // Each force figure has its own scale, in its caption: R_A is found in the dyad's.
        let k_f = printed_scale(&d, "Dyad 2–3 (RRP)", "k_f");
        // Some velocity arrow from the pole measures |v_A| at k_v, another |v_B| …
        let measured = |layer: &str, k: f64| -> Vec<f64> {
            arrows(&d, layer).iter().map(|(a, b)| (b - a).norm() * paper * k).collect()
        };
        let has = |got: &[f64], want: f64, what: &str| {
            assert!(got.iter().any(|g| (g - want).abs() <= 1e-9 * want.max(1e-9)), "{what} = {want}: {got:?}");
        };
        let st = &states[k];
        has(&measured("VELOCITY", k_v), st.velocity(crank_pin).norm(), "|v_A|");
        has(&measured("ACCELERATION", k_a), st.acceleration(crank_pin).norm(), "|a_A|");
        // The reaction at the crank pin in the dyad's polygon, at its k_f.
        let joint_a = s.mechanism.joints.iter().position(|j| j.name == "A").unwrap();
        has(&measured("FORCES", k_f), forces[k].reactions[joint_a].force.norm(), "|R_A|");
    }
}

#[test]
fn the_polygons_table_chooses_the_points() {
    let s = linkage("templates/shaper.toml");
    let states = Solver::new(s.mechanism.clone()).unwrap().run(&s.times[..3]).unwrap();
    let only = ["A".to_string(), "E".to_string()];
    let p = polygons_of(&s.mechanism, &states[2], Some(&only));
    let names: Vec<&str> = p.velocity.points.iter().map(|n| n.name.as_str()).collect();
    // A, E, and the rocker's point under A (the sliding velocity's start).
    assert_eq!(names, ["a", "e", "a3"]);
    // A scene naming an unknown point is refused with the field named, nothing written.
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(common::root().join("templates/shaper.toml")).unwrap()
        + "\n[polygons]\npoints = [\"A\", \"Q\"]\n";
    let file = dir.path().join("bad.toml");
    std::fs::write(&file, text).unwrap();
    let out = common::mechdraw().args(["run"]).arg(&file).arg("--out").arg(dir.path().join("out")).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("polygons.points[1]") && err.contains("`Q`"), "{err}");
    assert!(!dir.path().join("out").exists());
}

/// Frame `k` of a template's run against its golden PNG.
fn frame_golden(template: &str, k: usize, golden: &str) {
    let loaded = scene::load(&common::root().join(template), &[]).unwrap();
    let p = products(&loaded, &RunOptions::default()).unwrap();
    let mechdraw::run::products::Picture::Motion(anim) = &p.picture else { panic!("{template} animates") };
    let d = anim.frame_of(&anim.pose(k));
    common::assert_golden_png(golden, &to_string(&d, &SvgOptions::default()));
}

#[test]
fn shaper_polygons_frame_golden_png() {
    // t = 0.694 s, the return stroke: the ram fast, the Coriolis component k clear.
    frame_golden("templates/shaper.toml", 250, "linkage/shaper_polygons_250.png");
}

#[test]
fn slider_crank_forces_frame_golden_png() {
    frame_golden("templates/slider-crank.toml", 30, "linkage/slider_crank_forces_030.png");
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs poppler-utils (pdftotext): bash .ci/test, or cargo test --features system-tools"
)]
fn linkage_sheets_have_a_page_set_per_sample_at_measured_scales() {
    let over: Vec<mechdraw::scene::Override> = ["time.steps=12".parse().unwrap()].to_vec();
    let l = scene::load(&common::root().join("templates/slider-crank.toml"), &over).unwrap();
    let Scene::Linkage(s) = &l.scene else { panic!() };
    let tmp = tempfile::tempdir().unwrap();
    let opts = RunOptions {
        out_dir: Some(tmp.path().to_path_buf()),
        sheets: Some(mechdraw::figure::shared::sheet::Paper::A4),
        ..RunOptions::default()
    };
    let p = products(&l, &opts).unwrap();
    // The mechanism, the polygons and the forces of each of the 13 samples.
    assert_eq!(p.pages.len(), 39);
    let (states, forces) = kinetostatics(s);
    let crank_pin = Anchor { body: Attach::Body(0), local: Vector::new(110.0, 0.0) };
    for (k, set) in p.pages.chunks(3).enumerate() {
        let stems: Vec<&str> = set.iter().map(|g| g.stem.rsplit('-').next().unwrap()).collect();
        assert_eq!(stems, ["mechanism", "polygons", "forces"]);
        for page in set {
            assert_eq!(page.drawing.paper_mm_per_unit, Some(1.0));
        }
        // The page's own scales, in its panels' titles; measured in paper mm.
        let measured = |d: &Drawing, layer: &str, k: f64| -> Vec<f64> {
            arrows(d, layer).iter().map(|(a, b)| (b - a).norm() * k).collect()
        };
        let k_v = printed_scale(&set[1].drawing, "Velocity polygon", "k_v");
        let want = states[k].velocity(crank_pin).norm();
        assert!(
            measured(&set[1].drawing, "VELOCITY", k_v).iter().any(|g| (g - want).abs() <= 1e-9 * want),
            "{k}: |v_A|"
        );
        // R_A found in the RRP dyad's figure, at its own k_f.
        let k_f = printed_scale(&set[2].drawing, "Dyad 2–3 (RRP)", "k_f");
        let joint_a = s.mechanism.joints.iter().position(|j| j.name == "A").unwrap();
        let want = forces[k].reactions[joint_a].force.norm();
        assert!(measured(&set[2].drawing, "FORCES", k_f).iter().any(|g| (g - want).abs() <= 1e-9 * want), "{k}: |R_A|");
    }
    // The PDF: three pages per sample, its time and the sheet number on each.
    mechdraw::run::run(&l, &opts).unwrap();
    let pdf = tmp.path().join("slider-crank-sheets.pdf");
    let page = |n: usize| {
        let out = std::process::Command::new("pdftotext")
            .args(["-f", &n.to_string(), "-l", &n.to_string(), "-layout"])
            .arg(&pdf)
            .arg("-")
            .output();
        String::from_utf8_lossy(&out.expect("run pdftotext (poppler-utils)").stdout).to_string()
    };
    let t = states[3].t;
    let (mech, forces_page) = (page(10), page(12));
    for want in [format!("t = {t:.4} s"), "sheet 10 of 39".to_string(), "kl = ".into(), "φ1 = ".into(), "ω1 = ".into()]
    {
        assert!(mech.contains(&want), "page 10 lacks `{want}`:\n{mech}");
    }
    // The forces' rows (Me1 among them) are on the forces page since the mechanism page is
    // drawn at a 25 mm crank (issue 31).
    for want in ["sheet 12 of 39", "Crank 1 (driver)", "Dyad 2–3 (RRP)", "RA", "Me1"] {
        assert!(forces_page.contains(want), "page 12 lacks `{want}`:\n{forces_page}");
    }
}
