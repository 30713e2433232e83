//! Every text of every drawing a run makes can be read (issue 31's check, after issue 14's
//! "label overlaps 0 over every template's frames"): for every template, in every animation
//! frame, still picture, extra sheet, diagram and printed page,
//! - no two texts overlap,
//! - no letter is crossed by a stroke of another element (a link, a vector, a hatch, a frame),
//! - no text leaves the panel it stands in,
//!
//! each text measured as the bundled DejaVu Sans draws it: its advances, from its deepest
//! descender to its highest glyph (tests/common::text_boxes, the letter placer's measure).

mod common;

use mechdraw::figure::shared::sheet::Paper;
use mechdraw::run::RunOptions;
use mechdraw::run::products::Picture;
use mechdraw::scene::{self, Override};

/// Every drawing of a template's run: (what, drawing).
fn drawings(t: &std::path::Path) -> Vec<(String, mechdraw::draw::Drawing)> {
    let stem = t.file_stem().unwrap().to_string_lossy().to_string();
    let fourbar = stem.starts_with("fourbar-chebyshev");
    // The four-bar's printed pages too, at a 30° step to keep the test quick.
    let over: Vec<Override> = if fourbar { vec!["phi1_deg.step=30".parse().unwrap()] } else { Vec::new() };
    let loaded = scene::load(t, &over).unwrap();
    let opts = RunOptions { sheets: fourbar.then_some(Paper::A4), ..RunOptions::default() };
    let p = mechdraw::run::products(&loaded, &opts).unwrap();
    let mut out = Vec::new();
    match &p.picture {
        Picture::Still(d) => out.push(("picture".to_string(), d.clone())),
        Picture::Motion(a) => {
            for k in 0..a.len() {
                out.push((format!("frame {k}"), a.frame_of(&a.pose(k))));
            }
        }
    }
    out.extend(p.sheets.iter().map(|s| (format!("sheet {}", s.suffix), s.drawing.clone())));
    out.extend(p.diagrams.iter().map(|g| (format!("diagram {}", g.stem), g.drawing.clone())));
    out.extend(p.pages.iter().map(|g| (format!("page {}", g.stem), g.drawing.clone())));
    // A linkage's printed pages, at 24 samples to keep the test quick.
    if matches!(loaded.scene, scene::Scene::Linkage(_)) {
        let coarse = scene::load(t, &["time.steps=24".parse().unwrap()]).unwrap();
        let opts = RunOptions { sheets: Some(Paper::A4), ..RunOptions::default() };
        let pages = mechdraw::run::products(&coarse, &opts).unwrap().pages;
        assert!(pages.len() >= 25, "{stem}: {} pages", pages.len());
        out.extend(pages.into_iter().map(|g| (format!("page {}", g.stem), g.drawing)));
    }
    out
}

#[test]
fn every_text_of_every_drawing_of_every_template_can_be_read() {
    let mut checked = 0;
    let (mut overlaps, mut crossed, mut outside) = (Vec::new(), Vec::new(), Vec::new());
    let mut counts = Vec::new();
    for t in &common::template_paths() {
        let stem = t.file_stem().unwrap().to_string_lossy().to_string();
        let (o0, c0, p0) = (overlaps.len(), crossed.len(), outside.len());
        for (what, d) in &drawings(t) {
            checked += 1;
            for (a, b) in common::overlapping_texts(d) {
                overlaps.push(format!("{stem} {what}: {a:?} over {b:?}"));
            }
            for (a, b) in common::crossed_texts(d) {
                crossed.push(format!("{stem} {what}: {a:?} crossed by a {b}"));
            }
            for (a, b) in common::texts_outside_their_panel(d) {
                outside.push(format!("{stem} {what}: {a:?} leaves its panel {b}"));
            }
        }
        counts.push(format!(
            "{stem}: {} overlaps, {} crossed, {} outside",
            overlaps.len() - o0,
            crossed.len() - c0,
            outside.len() - p0
        ));
    }
    eprintln!("{}", counts.join("\n"));
    // Every finding in target/labels_all.txt, to look at.
    let all: Vec<&String> = overlaps.iter().chain(&crossed).chain(&outside).collect();
    let list: String = all.iter().map(|s| format!("{s}\n")).collect::<String>();
    std::fs::write(common::root().join("target/labels_all.txt"), list).unwrap();
    assert!(checked > 1000, "{checked} drawings");
    let show = |v: &[String]| v.iter().take(25).cloned().collect::<Vec<_>>();
    assert!(
        overlaps.is_empty() && crossed.is_empty() && outside.is_empty(),
        "{} overlapping pairs, {} crossed texts, {} texts outside their panel; e.g.\n{:#?}\n{:#?}\n{:#?}",
        overlaps.len(),
        crossed.len(),
        outside.len(),
        show(&overlaps),
        show(&crossed),
        show(&outside)
    );
}

/// Every page of every template's report (`mechdraw report`, issue 33): no two texts overlap.
#[test]
fn no_two_texts_overlap_on_any_report_page() {
    use mechdraw::run::report::{ReportOptions, report};
    let mut found = Vec::new();
    let mut checked = 0;
    for t in &common::template_paths() {
        let stem = t.file_stem().unwrap().to_string_lossy().to_string();
        let loaded = scene::load(t, &[]).unwrap();
        // A synthesis scene has no report of its own: its design's is (tests/report.rs, bad input).
        if matches!(loaded.scene, scene::Scene::Synthesis(_)) {
            continue;
        }
        for paper in [Paper::A4, Paper::A3] {
            let r = report(&loaded, &ReportOptions { paper, positions: None }).unwrap();
            for p in &r.pages {
                checked += 1;
                for (a, b) in common::overlapping_texts(&p.drawing) {
                    found.push(format!("{stem} {} ({}): {a:?} over {b:?}", p.stem, paper.name()));
                }
            }
        }
    }
    assert!(checked > 50, "{checked} pages");
    let shown: Vec<&String> = found.iter().take(40).collect();
    assert!(found.is_empty(), "{} overlaps on report pages, e.g. {shown:#?}", found.len());
}

/// Every position page of every linkage and four-bar template's report, and every free-body
/// page: no force arrow drawn over the mechanism (tests/common::arrows_over_mechanism). The
/// letters' checks above do not see it: an arrow over a link crosses no letter (the shaper's
/// RA and R32 were drawn from A's centre over the slider's block and the rocker).
#[test]
fn no_force_is_drawn_over_the_mechanism_on_a_report_page() {
    use mechdraw::run::report::{ReportOptions, report};
    let mut found = Vec::new();
    let mut checked = 0;
    for t in &common::template_paths() {
        let stem = t.file_stem().unwrap().to_string_lossy().to_string();
        let loaded = scene::load(t, &[]).unwrap();
        if !matches!(loaded.scene, scene::Scene::Linkage(_) | scene::Scene::Fourbar(_)) {
            continue;
        }
        let r = report(&loaded, &ReportOptions::default()).unwrap();
        for p in &r.pages {
            checked += 1;
            for (a, b) in common::arrows_over_mechanism(&p.drawing) {
                found.push(format!("{stem} {}: {a} over {b}", p.stem));
            }
        }
    }
    assert!(checked > 50, "{checked} pages");
    // Known, left (issue 33's note): the four-bar at φ1 = 270°, where O1, A, B and M lie on
    // one vertical line and every placement of R_A crosses a link; the shaper's R05 at dead
    // position II, short, under the ram's block where the panel's edge leaves it no room
    // above. Any other is a new one.
    const KNOWN: [&str; 2] = ["fourbar-chebyshev 17-pos-270-1:", "shaper-forces 28-dead-2-4:"];
    let new: Vec<&String> = found.iter().filter(|f| !KNOWN.iter().any(|k| f.starts_with(k))).collect();
    let shown: Vec<&&String> = new.iter().take(40).collect();
    assert!(new.is_empty(), "{} forces over the mechanism on report pages, e.g. {shown:#?}", new.len());
}
