//! No two texts overlap in anything a run draws, for every template (issue 14's check
//! "label overlaps 0 over every template's frames, force and reaction names included"):
//! every animation frame, every still picture and sheet, the four-bar's printed pages. The
//! boxes are the letter placer's own measure (tests/common::text_boxes).

mod common;

use mechdraw::figure::shared::sheet::Paper;
use mechdraw::run::RunOptions;
use mechdraw::run::products::Picture;
use mechdraw::scene::{self, Override};

#[test]
fn no_two_texts_overlap_in_any_drawing_of_any_template() {
    let mut checked = 0;
    let mut found = Vec::new();
    let templates = common::template_paths();
    for t in &templates {
        let stem = t.file_stem().unwrap().to_string_lossy().to_string();
        let fourbar = stem.starts_with("fourbar-chebyshev");
        // The four-bar's printed pages too, at a 30° step to keep the test quick.
        let over: Vec<Override> = if fourbar { vec!["phi1_deg.step=30".parse().unwrap()] } else { Vec::new() };
        let loaded = scene::load(t, &over).unwrap();
        let opts = RunOptions { sheets: fourbar.then_some(Paper::A4), ..RunOptions::default() };
        let p = mechdraw::run::products(&loaded, &opts).unwrap();
        let mut drawings = Vec::new();
        match &p.picture {
            Picture::Still(d) => drawings.push(("picture".to_string(), d.clone())),
            Picture::Motion(a) => {
                for k in 0..a.len() {
                    drawings.push((format!("frame {k}"), a.frame_of(&a.pose(k))));
                }
            }
        }
        drawings.extend(p.sheets.iter().map(|s| (format!("sheet {}", s.suffix), s.drawing.clone())));
        drawings.extend(p.pages.iter().map(|g| (format!("page {}", g.stem), g.drawing.clone())));
        // A linkage's printed pages, at 24 samples to keep the test quick.
        if matches!(loaded.scene, scene::Scene::Linkage(_)) {
            let coarse = scene::load(t, &["time.steps=24".parse().unwrap()]).unwrap();
            let opts = RunOptions { sheets: Some(Paper::A4), ..RunOptions::default() };
            let pages = mechdraw::run::products(&coarse, &opts).unwrap().pages;
            assert_eq!(pages.len(), 25, "{stem}");
            drawings.extend(pages.into_iter().map(|g| (format!("page {}", g.stem), g.drawing)));
        }
        for (what, d) in &drawings {
            checked += 1;
            for (a, b) in common::overlapping_texts(d) {
                found.push(format!("{stem} {what}: {a:?} over {b:?}"));
            }
        }
    }
    assert!(checked > 1000, "{checked} drawings");
    let shown: Vec<&String> = found.iter().take(30).collect();
    assert!(found.is_empty(), "{} overlaps, e.g. {shown:#?}", found.len());
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
