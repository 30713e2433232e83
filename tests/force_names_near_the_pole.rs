//! The names of a force figure stand apart (issue 31: the four-bar's F_i21, R_An, G_22 and
//! f crowded near the pole at φ1 = 90°, 200°, 270°; G_21 and G_22 0.04 mm apart at the end
//! of a long R_An at φ1 = 80°, though not overlapping): on every frame of fourbar-chebyshev
//! and every forces page of its A4 sheets, the smallest gap between the box of a name near
//! a pole (within [`NEAR_MM`]) and the box of any other name is at least [`LEAST_GAP_MM`] on
//! paper; and any two names of one figure, anywhere, are at least [`LEAST_GAP_MM`] apart,
//! on those drawings and on every linkage template's A4 forces pages.

mod common;

use mechdraw::draw::{Drawing, HAlign, Shape};
use mechdraw::figure::shared::sheet::Paper;
use mechdraw::geom::Point;
use mechdraw::run::RunOptions;
use mechdraw::scene::{self, Override};

/// The least gap between two names near a pole, paper mm.
const LEAST_GAP_MM: f64 = 0.5;
/// How near a pole a name counts as "near" (its box's distance to the pole), paper mm.
/// (Before the crowd rule: 19 of the 72 drawings had two such names under 0.5 mm apart,
/// the closest 0.02 mm; after it the closest were 0.73 mm apart, 1.22 mm with the names'
/// gap, `forces::NAME_GAP`.)
const NEAR_MM: f64 = 8.0;

/// The distance between two boxes (0 when they overlap).
fn box_gap(a: &common::TextBox, b: &common::TextBox) -> f64 {
    let dx = (a.min.x - b.max.x).max(b.min.x - a.max.x).max(0.0);
    let dy = (a.min.y - b.max.y).max(b.min.y - a.max.y).max(0.0);
    libm::hypot(dx, dy)
}

/// The distance from `p` to a box.
fn to_box(p: Point, b: &common::TextBox) -> f64 {
    let dx = (b.min.x - p.x).max(p.x - b.max.x).max(0.0);
    let dy = (b.min.y - p.y).max(p.y - b.max.y).max(0.0);
    libm::hypot(dx, dy)
}

/// The smallest gap (paper mm) between a name near a pole of `d` and another name, with the
/// two names.
fn crowding(d: &Drawing) -> Option<(f64, String, String)> {
    let mm = d.paper_mm_per_unit.unwrap_or(1.0);
    let frc = d.layers.iter().position(|l| l.name == "FORCES")?;
    let poles: Vec<Point> = d
        .entities
        .iter()
        .filter(|e| e.layer == frc)
        .filter_map(|e| match e.shape {
            Shape::Circle { center, .. } => Some(center),
            _ => None,
        })
        .collect();
    let names: Vec<common::TextBox> =
        common::text_boxes(d).into_iter().filter(|t| t.layer == "FORCES" && !t.value.trim().is_empty()).collect();
    let near = |t: &common::TextBox| poles.iter().any(|p| to_box(*p, t) * mm <= NEAR_MM);
    let mut worst: Option<(f64, String, String)> = None;
    for (i, a) in names.iter().enumerate() {
        for b in names.iter().skip(i + 1) {
            if !(near(a) || near(b)) {
                continue;
            }
            let g = box_gap(a, b) * mm;
            if worst.as_ref().is_none_or(|w| g < w.0) {
                worst = Some((g, a.value.clone(), b.value.clone()));
            }
        }
    }
    worst
}

#[test]
fn names_near_the_four_bars_force_poles_stand_apart() {
    let t = common::root().join("templates/fourbar-chebyshev.toml");
    let over: Vec<Override> = vec!["phi1_deg.step=10".parse().unwrap()];
    let loaded = scene::load(&t, &over).unwrap();
    let p = mechdraw::run::products(&loaded, &RunOptions { sheets: Some(Paper::A4), ..RunOptions::default() }).unwrap();
    let mut found = Vec::new();
    let mechdraw::run::products::Picture::Motion(anim) = &p.picture else { panic!("a motion") };
    let mut drawings: Vec<(String, Drawing)> =
        (0..anim.len()).map(|k| (format!("frame {k}"), anim.frame_of(&anim.pose(k)))).collect();
    drawings
        .extend(p.pages.iter().filter(|g| g.stem.ends_with("-forces")).map(|g| (g.stem.clone(), g.drawing.clone())));
    let mut all = Vec::new();
    for (what, d) in &drawings {
        if let Some((g, a, b)) = crowding(d) {
            all.push(g);
            if g < LEAST_GAP_MM {
                found.push(format!("{what}: {a:?} and {b:?} {g:.2} mm apart"));
            }
        }
    }
    // Every frame and every forces page has names near a pole (36 positions each).
    assert!(all.len() >= 72, "{} drawings with names near a pole", all.len());
    all.sort_by(f64::total_cmp);
    eprintln!("smallest gaps: {:?}", &all[..all.len().min(10)]);
    assert!(found.is_empty(), "{} crowded:\n{}", found.len(), found.join("\n"));
}

/// The smallest gap (paper mm) between two names of one figure of `d` (two centred names on
/// the `FORCES` layer in the same panel, or anywhere on a drawing without panels: not the
/// rows of a frame's Magnitudes list), with them.
fn closest_names(d: &Drawing) -> Option<(f64, String, String)> {
    let mm = d.paper_mm_per_unit.unwrap_or(1.0);
    let names: Vec<common::TextBox> = common::text_boxes(d)
        .into_iter()
        .filter(|t| t.layer == "FORCES" && t.halign == HAlign::Center && !t.value.trim().is_empty())
        .collect();
    let panels = common::panels(d);
    // The smallest panel holding a name's anchor: its figure's.
    let panel_of = |p: Point| {
        panels
            .iter()
            .enumerate()
            .filter(|(_, (lo, hi))| p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y)
            .min_by(|a, b| {
                let area = |(lo, hi): &(Point, Point)| (hi.x - lo.x) * (hi.y - lo.y);
                area(a.1).total_cmp(&area(b.1))
            })
            .map(|(i, _)| i)
    };
    let mut worst: Option<(f64, String, String)> = None;
    for (i, a) in names.iter().enumerate() {
        for b in names.iter().skip(i + 1) {
            if panel_of(a.at) != panel_of(b.at) {
                continue;
            }
            let g = box_gap(a, b) * mm;
            if worst.as_ref().is_none_or(|w| g < w.0) {
                worst = Some((g, a.value.clone(), b.value.clone()));
            }
        }
    }
    worst
}

/// The drawings of `loaded` whose force names are checked: its A4 forces pages, and, with
/// `frames`, every frame of its animation.
fn force_drawings(loaded: &scene::Loaded, frames: bool) -> Vec<(String, Drawing)> {
    let p = mechdraw::run::products(loaded, &RunOptions { sheets: Some(Paper::A4), ..RunOptions::default() }).unwrap();
    let mut out = Vec::new();
    if frames {
        let mechdraw::run::products::Picture::Motion(anim) = &p.picture else { panic!("a motion") };
        out.extend((0..anim.len()).map(|k| (format!("frame {k}"), anim.frame_of(&anim.pose(k)))));
    }
    out.extend(p.pages.iter().filter(|g| g.stem.ends_with("-forces")).map(|g| (g.stem.clone(), g.drawing.clone())));
    out
}

/// (Before the names' gap, `forces::NAME_GAP`: 202 of these drawings had two names of
/// one figure under 0.5 mm apart, the closest 0.001 mm; with it the closest are 0.55 mm.)
#[test]
fn any_two_names_of_a_force_figure_stand_apart() {
    let mut found = Vec::new();
    let mut all = Vec::new();
    let mut check = |what: &str, drawings: &[(String, Drawing)]| {
        for (stem, d) in drawings {
            if let Some((g, a, b)) = closest_names(d) {
                all.push(g);
                if g < LEAST_GAP_MM {
                    found.push(format!("{what} {stem}: {a:?} and {b:?} {g:.2} mm apart"));
                }
            }
        }
    };
    let t = common::root().join("templates/fourbar-chebyshev.toml");
    let over: Vec<Override> = vec!["phi1_deg.step=10".parse().unwrap()];
    check("fourbar-chebyshev", &force_drawings(&scene::load(&t, &over).unwrap(), true));
    let mut linkages = 0;
    for t in common::template_paths() {
        if !std::fs::read_to_string(&t).unwrap().contains("kind = \"linkage\"") {
            continue;
        }
        let stem = t.file_stem().unwrap().to_string_lossy().to_string();
        let drawings = force_drawings(&scene::load(&t, &[]).unwrap(), false);
        linkages += usize::from(!drawings.is_empty());
        check(&stem, &drawings);
    }
    assert!(linkages >= 2, "{linkages} linkage templates with forces pages");
    assert!(all.len() >= 72 + 361, "{} drawings with force names", all.len());
    all.sort_by(f64::total_cmp);
    eprintln!("smallest gaps: {:?}", &all[..all.len().min(10)]);
    assert!(found.is_empty(), "{} crowded:\n{}", found.len(), found.join("\n"));
}
