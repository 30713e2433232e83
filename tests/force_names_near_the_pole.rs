//! The names around a force polygon's pole stand apart (issue 31: the four-bar's F_i21,
//! R_An, G_22 and f crowded near the pole at φ1 = 90°, 200°, 270°, though not overlapping):
//! on every frame of fourbar-chebyshev and every forces page of its A4 sheets, the
//! smallest gap between the box of a name near a pole (within [`NEAR_MM`]) and the box of
//! any other name is at least [`LEAST_GAP_MM`] on paper. (A cluster of short vectors away
//! from the pole — G_21, G_22 at the end of a long R_An — is not covered: placing those
//! larger too pushed other names onto leaders, tests/labels_all.rs.)

mod common;

use mechdraw::draw::{Drawing, Shape};
use mechdraw::figure::shared::sheet::Paper;
use mechdraw::geom::Point;
use mechdraw::run::RunOptions;
use mechdraw::scene::{self, Override};

/// The least gap between two names near a pole, paper mm.
const LEAST_GAP_MM: f64 = 0.5;
/// How near a pole a name counts as "near" (its box's distance to the pole), paper mm.
/// (Before the crowd rule: 19 of the 72 drawings had two such names under 0.5 mm apart,
/// the closest 0.02 mm; after it the closest are 0.73 mm apart.)
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
