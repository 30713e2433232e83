//! The chain drawing read as a student reads seed 001's figure (issue 14, item 8): every
//! feature labelled F_k at its coordinate, every dimension with a circle at its base (row B)
//! and an arrowhead at its end (row W's sign), and no dimension text crossed by a line or
//! covering another text. The expected coordinates are the hand-derived ones of
//! `chain_seed.rs`, not the solver's.

mod common;

use mechdraw::draw::{Drawing, HAlign, Shape, VAlign, parts};
use mechdraw::geom::Point;
use mechdraw::run::products::Picture;
use mechdraw::scene::{self, Override};

/// The chain drawing and JSON summary of a template, with `--set` overrides.
fn drawing(template: &str, sets: &[&str]) -> (Drawing, serde_json::Value) {
    let path = common::root().join("templates").join(template);
    let mut overrides: Vec<Override> = vec!["stackup.samples=0".parse().unwrap()];
    overrides.extend(sets.iter().map(|s| s.parse::<Override>().unwrap()));
    let loaded = scene::load(&path, &overrides).unwrap();
    let p = mechdraw::run::products(&loaded, &Default::default()).unwrap();
    match p.picture {
        Picture::Still(d) => (exploded(d), p.summary),
        Picture::Motion(_) => panic!("a chain is one drawing"),
    }
}

/// The drawing with each dimension broken into what the writers draw of it (its lines,
/// base circle, arrowheads and text, on its layer) and the scale caption as the paper
/// states it, as the checks below read it.
fn exploded(d: Drawing) -> Drawing {
    let style = d.dim_style;
    let entities = d
        .entities
        .iter()
        .flat_map(|e| {
            let shape = e.shape.scale_text_in(None).unwrap_or_else(|| e.shape.clone());
            mechdraw::draw::parts::explode_dimension(&shape, &style)
                .into_iter()
                .map(|shape| mechdraw::draw::Entity { shape, ..e.clone() })
        })
        .collect();
    Drawing { entities, ..d }
}

/// Matrix (2) with a redundant ninth dimension (17 from the end of 25), as chain_golden.rs.
const OVER: [&str; 2] = ["B=[0, 0, -38, -38, 260, -100, -100, 65, 25]", "W=[-38, 25, 80, 260, -100, 55, 65, 15, 17]"];

/// The three drawings checked: matrix (2), matrix (3) and matrix (2) over-dimensioned.
fn cases() -> Vec<(&'static str, Drawing, serde_json::Value)> {
    [
        ("matrix (2)", "chain-humienny-2.toml", &[][..]),
        ("matrix (3)", "chain-humienny-3.toml", &[]),
        ("matrix (2) + w9", "chain-humienny-2.toml", &OVER),
    ]
    .into_iter()
    .map(|(case, t, sets)| {
        let (d, s) = drawing(t, sets);
        (case, d, s)
    })
    .collect()
}

fn layer(d: &Drawing, name: &str) -> usize {
    d.layers.iter().position(|l| l.name == name).unwrap_or_else(|| panic!("no layer {name}"))
}

/// An axis-aligned box (min, max).
type Box2 = (Point, Point);

/// Estimated box of a text as the writers draw it: width [`parts::text_width`], from
/// [`parts::TEXT_DESCENT`] below the baseline to the cap height; unrotated or turned by 90°.
fn text_box(at: Point, height: f64, value: &str, halign: HAlign, valign: VAlign, rotation: f64) -> Box2 {
    let w = parts::text_width(value, height);
    let (x0, x1) = match halign {
        HAlign::Left => (0.0, w),
        HAlign::Center => (-0.5 * w, 0.5 * w),
        HAlign::Right => (-w, 0.0),
    };
    let base = match valign {
        VAlign::Baseline => 0.0,
        VAlign::Middle => -0.5 * height,
        VAlign::Top => -height,
    };
    let (y0, y1) = (base - parts::TEXT_DESCENT * height, base + height);
    if rotation == 0.0 {
        (Point::new(at.x + x0, at.y + y0), Point::new(at.x + x1, at.y + y1))
    } else {
        assert!((rotation - std::f64::consts::FRAC_PI_2).abs() < 1e-12, "only upright or quarter-turned text");
        // Turned counter-clockwise: along-text runs up, "up" runs left.
        (Point::new(at.x - y1, at.y + x0), Point::new(at.x - y0, at.y + x1))
    }
}

fn boxes_overlap(a: Box2, b: Box2) -> bool {
    a.0.x < b.1.x && b.0.x < a.1.x && a.0.y < b.1.y && b.0.y < a.1.y
}

/// Whether segment a–b passes through the interior of `bx` (Liang–Barsky).
fn segment_crosses(a: Point, b: Point, bx: Box2) -> bool {
    let d = b - a;
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [(-d.x, a.x - bx.0.x), (d.x, bx.1.x - a.x), (-d.y, a.y - bx.0.y), (d.y, bx.1.y - a.y)] {
        if p == 0.0 {
            if q <= 0.0 {
                return false;
            }
        } else if p < 0.0 {
            t0 = t0.max(q / p);
        } else {
            t1 = t1.min(q / p);
        }
    }
    t0 < t1
}

fn points_box(points: &[Point]) -> Box2 {
    let mut b = (points[0], points[0]);
    for p in points {
        b.0 = Point::new(b.0.x.min(p.x), b.0.y.min(p.y));
        b.1 = Point::new(b.1.x.max(p.x), b.1.y.max(p.y));
    }
    b
}

#[test]
fn no_dimension_text_is_crossed_by_a_line_or_covers_another_text() {
    for (case, d, _) in cases() {
        let dim_layers = ["DIMENSIONS", "REDUNDANT", "DEPENDENT"].map(|n| layer(&d, n));
        let texts: Vec<(usize, String, Box2)> = d
            .entities
            .iter()
            .enumerate()
            .filter_map(|(i, e)| match &e.shape {
                Shape::Text { at, height, value, halign, valign, rotation, .. } => {
                    Some((i, value.clone(), text_box(*at, *height, value, *halign, *valign, *rotation)))
                }
                _ => None,
            })
            .collect();
        let dim_texts: Vec<&(usize, String, Box2)> =
            texts.iter().filter(|(i, _, _)| dim_layers.contains(&d.entities[*i].layer)).collect();
        assert!(dim_texts.len() >= 12, "{case}: {} dimension texts", dim_texts.len());
        for (i, value, bx) in &dim_texts {
            for (j, e) in d.entities.iter().enumerate() {
                if j == *i {
                    continue;
                }
                let hit = match &e.shape {
                    Shape::Line { from, to } | Shape::Arrow { from, to, .. } => segment_crosses(*from, *to, *bx),
                    Shape::Circle { center, radius } => {
                        let r = Point::new(*radius, *radius).coords;
                        boxes_overlap(*bx, (center - r, center + r))
                    }
                    Shape::Filled { points } | Shape::Polyline { points, .. } => boxes_overlap(*bx, points_box(points)),
                    Shape::Text { .. } => {
                        let other = texts.iter().find(|(k, _, _)| *k == j).unwrap();
                        boxes_overlap(*bx, other.2)
                    }
                    other => panic!("{case}: unexpected {other:?} in the chain drawing"),
                };
                assert!(!hit, "{case}: \"{value}\" is crossed or covered by {:?}", e.shape);
            }
        }
    }
}

/// Hand-derived coordinate of the feature a matrix (2) value names (chain_seed.rs).
fn x2(value: f64) -> f64 {
    match value as i64 {
        0 => 0.0,
        -38 => -38.0,
        25 => 25.0,
        80 => 42.0,
        260 => 222.0,
        -100 => 122.0,
        55 => 177.0,
        65 => 187.0,
        15 => 202.0,
        17 => 42.0,
        v => panic!("no feature {v}"),
    }
}

#[test]
fn every_feature_label_sits_at_its_feature_and_f_names_run_along_the_axis() {
    for (case, d, summary) in cases() {
        let features = summary["features"].as_array().unwrap();
        assert_eq!(features.len(), 9, "{case}");
        let names = layer(&d, "FEATURE_NAMES");
        let labels: Vec<(Point, String)> = d
            .entities
            .iter()
            .filter(|e| e.layer == names)
            .filter_map(|e| match &e.shape {
                Shape::Text { at, value, .. } => Some((*at, value.clone())),
                _ => None,
            })
            .collect();
        assert_eq!(labels.len(), 9, "{case}");
        let mut xs = Vec::new();
        for k in 0..9 {
            let name = format!("F{k}");
            let f =
                features.iter().find(|f| f["label"] == name.as_str()).unwrap_or_else(|| panic!("{case}: no {name}"));
            let x = f["x"].as_f64().unwrap();
            let (at, text) = labels.iter().find(|(_, t)| t.starts_with(&format!("{name} "))).unwrap();
            assert_eq!(at.x, x, "{case}: {name} drawn at {} for x = {x}", at.x);
            assert_eq!(text, &format!("{name}  x = {x}"), "{case}");
            xs.push(x);
        }
        // F0 is the zero point; F1..F8 increase along the axis.
        assert_eq!(xs[0], 0.0, "{case}");
        assert!(xs[1..].windows(2).all(|w| w[0] < w[1]), "{case}: {xs:?}");
    }
    // Matrix (2) by hand: the features in axis order, the zero point apart.
    let (_, summary) = drawing("chain-humienny-2.toml", &[]);
    let by_label = |l: &str| {
        summary["features"].as_array().unwrap().iter().find(|f| f["label"] == l).unwrap()["x"].as_f64().unwrap()
    };
    let hand = [0.0, -38.0, 25.0, 42.0, 122.0, 177.0, 187.0, 202.0, 222.0];
    for (k, x) in hand.iter().enumerate() {
        assert_eq!(by_label(&format!("F{k}")), *x);
    }
}

/// Circle centres and arrowhead tips of the independent dimensions, by the height of their
/// dimension line.
fn marks(d: &Drawing, layer_name: &str) -> (Vec<Point>, Vec<Point>) {
    let l = layer(d, layer_name);
    let mut circles = Vec::new();
    let mut tips = Vec::new();
    for e in d.entities.iter().filter(|e| e.layer == l) {
        match &e.shape {
            Shape::Circle { center, .. } => circles.push(*center),
            Shape::Filled { points } => tips.push(points[0]),
            _ => {}
        }
    }
    (circles, tips)
}

#[test]
fn each_dimension_has_a_circle_at_its_base_and_an_arrow_at_its_end_as_rows_b_and_w_say() {
    // Matrix (2) as printed: row B the bases, row W the signed dimensions.
    let b = [0.0, 0.0, -38.0, -38.0, 260.0, -100.0, -100.0, 65.0];
    let w = [-38.0, 25.0, 80.0, 260.0, -100.0, 55.0, 65.0, 15.0];
    let (d, _) = drawing("chain-humienny-2.toml", &[]);
    let (circles, tips) = marks(&d, "DIMENSIONS");
    assert_eq!(circles.len(), 8);
    assert_eq!(tips.len(), 8, "one arrowhead per dimension, none at a base");
    for (bi, wi) in b.iter().zip(w) {
        let (base, end) = (x2(*bi), x2(*bi) + wi);
        // A circle at the base and, on the same dimension line, an arrowhead at the end.
        let found = circles.iter().any(|c| {
            (c.x - base).abs() < 1e-9 && tips.iter().any(|t| (t.x - end).abs() < 1e-9 && (t.y - c.y).abs() < 1e-9)
        });
        assert!(found, "w = {wi} from {bi}: no circle at x = {base} with an arrowhead at x = {end}");
    }
    // Dependent dimensions have no base: an arrowhead at each end, no circle.
    let (circles, tips) = marks(&d, "DEPENDENT");
    assert!(circles.is_empty());
    assert_eq!(tips.len(), 8);
}
