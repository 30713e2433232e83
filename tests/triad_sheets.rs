//! The triad's two drawings (issue 14, item 7), measured on the drawings themselves:
//! Fig. 3 shows the drawn mode alone (the seed's wide polyline, the approximate triangle,
//! three angular dimensions, letters clear of each other, of the dimension texts and of
//! every line); the modes sheet has one panel per mode whose triangle, measured in the
//! panel, satisfies the triad's six equations and whose printed φ1, φ2, φ3 are the
//! measured directions and the solver's (the JSON summary), the drawn mode marked once.

#![allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the library calls"
)]

mod common;

use mechdraw::draw::parts::explode_dimension;
use mechdraw::draw::{Drawing, Entity, HAlign, Shape, VAlign};
use mechdraw::figure::shared::labels::TextBox;
use mechdraw::geom::Point;
use mechdraw::run::RunOptions;
use mechdraw::run::products::Products;
use serde_json::Value;

const O: [(f64, f64); 3] = [(15.0, 30.0), (90.0, 20.0), (150.0, 40.0)];
const R: [f64; 3] = [50.0, 60.0, 84.0];
/// l12, l23, l13 of the template.
const SIDES: [f64; 3] = [50.0, 50.0, 92.0];

fn products() -> Products {
    let loaded = mechdraw::scene::load(&common::root().join("templates/triad-popa.toml"), &[]).unwrap();
    mechdraw::run::products(&loaded, &RunOptions::default()).unwrap()
}

fn layer<'a>(d: &'a Drawing, name: &str) -> impl Iterator<Item = &'a Entity> + 'a {
    let i = d.layers.iter().position(|l| l.name == name).unwrap_or_else(|| panic!("no layer {name}"));
    d.entities.iter().filter(move |e| e.layer == i)
}

fn texts(d: &Drawing) -> Vec<(Point, String)> {
    d.entities
        .iter()
        .filter_map(|e| match &e.shape {
            Shape::Text { at, value, .. } => Some((*at, value.clone())),
            _ => None,
        })
        .collect()
}

/// `Mode 3 · clockwise` → 3.
fn mode_number(text: &str) -> Option<usize> {
    let rest = text.strip_prefix("Mode ")?;
    // `Mode 1 · counter-clockwise` (the DXF writes the separator `·` as a comma).
    rest.split([' ', ',']).next()?.parse().ok()
}

/// `φ1 = 75.77°, φ2 = …, φ3 = …` → the three angles, degrees.
fn angles(text: &str) -> Option<[f64; 3]> {
    let v: Vec<f64> = text
        .split(", ")
        .map(|part| part.split(" = ").nth(1).and_then(|x| x.trim_end_matches('°').parse().ok()))
        .collect::<Option<_>>()?;
    v.try_into().ok()
}

fn dist(a: Point, b: Point) -> f64 {
    (a - b).norm()
}

fn signed_area(a: [Point; 3]) -> f64 {
    0.5 * ((a[1] - a[0]).x * (a[2] - a[0]).y - (a[1] - a[0]).y * (a[2] - a[0]).x)
}

#[test]
fn modes_sheet_has_one_panel_per_mode_with_the_solvers_angles() {
    let p = products();
    let solutions = p.summary["solutions"].as_array().unwrap().clone();
    let primary = p.summary["primary"].as_u64().unwrap() as usize;
    assert_eq!(solutions.len(), 8, "the template has 8 assembly modes");
    assert_eq!(p.sheets.len(), 1);
    assert_eq!(p.sheets[0].suffix, "modes");
    let d = &p.sheets[0].drawing;

    // Panels: closed rectangles on PANELS, one per mode.
    let panels: Vec<(Point, Point)> = layer(d, "PANELS")
        .map(|e| match &e.shape {
            Shape::Polyline { points, closed: true, .. } if points.len() == 4 => {
                let xs = points.iter().map(|p| p.x);
                let ys = points.iter().map(|p| p.y);
                (
                    Point::new(xs.clone().fold(f64::INFINITY, f64::min), ys.clone().fold(f64::INFINITY, f64::min)),
                    Point::new(xs.fold(f64::NEG_INFINITY, f64::max), ys.fold(f64::NEG_INFINITY, f64::max)),
                )
            }
            s => panic!("not a panel frame: {s:?}"),
        })
        .collect();
    assert_eq!(panels.len(), solutions.len(), "one panel per mode");
    let inside = |q: Point, (lo, hi): (Point, Point)| lo.x < q.x && q.x < hi.x && lo.y < q.y && q.y < hi.y;

    // Mode numbers: each of 1..=8 exactly once, in its own panel; the drawn one marked.
    let all = texts(d);
    let mut numbers: Vec<usize> = all.iter().filter_map(|(_, t)| mode_number(t)).collect();
    numbers.sort();
    assert_eq!(numbers, (1..=solutions.len()).collect::<Vec<_>>());
    let marked: Vec<usize> =
        all.iter().filter(|(_, t)| t.contains("· in Fig. 3")).filter_map(|(_, t)| mode_number(t)).collect();
    assert_eq!(marked, [primary + 1]);

    let circles: Vec<(Point, f64)> = layer(d, "CONSTRUCTION")
        .filter_map(|e| match e.shape {
            Shape::Circle { center, radius } => Some((center, radius)),
            _ => None,
        })
        .collect();
    let triangles: Vec<[Point; 3]> = layer(d, "MECHANISM")
        .filter_map(|e| match &e.shape {
            Shape::Polyline { points, closed: true, .. } if points.len() == 3 && e.color.is_none() => {
                // The triangle (closed, three vertices); ground symbols' triangles are thin
                // and come with their pivot's circle, the triangle is the wide one.
                Some([points[0], points[1], points[2]])
            }
            _ => None,
        })
        .filter(|t| (dist(t[0], t[1]) - SIDES[0]).abs() < 1e-6)
        .collect();
    assert_eq!(triangles.len(), solutions.len(), "one triangle per panel");

    for panel in &panels {
        let heading = all.iter().find(|(at, t)| inside(*at, *panel) && mode_number(t).is_some()).unwrap();
        let n = mode_number(&heading.1).unwrap();
        let sol: &Value = &solutions[n - 1];
        let printed = all.iter().find_map(|(at, t)| if inside(*at, *panel) { angles(t) } else { None }).unwrap();
        // The solver's angles, as printed (two decimals).
        for i in 0..3 {
            let solver = sol[format!("phi{}_deg", i + 1)].as_f64().unwrap();
            assert!((printed[i] - solver).abs() <= 0.005 + 1e-9, "mode {n}: φ{} {} vs {solver}", i + 1, printed[i]);
        }
        // Measured in the panel: the pivots are the circles' centres (the template's,
        // shifted by the panel's offset), the triangle's vertices lie on the circles, its
        // sides are the triad's, its sense is the heading's, and the directions O_i → A_i are
        // the printed angles.
        let c: Vec<&(Point, f64)> = circles.iter().filter(|(o, _)| inside(*o, *panel)).collect();
        assert_eq!(c.len(), 3, "mode {n}: three circles");
        let shift = c[0].0 - Point::new(O[0].0, O[0].1);
        for i in 0..3 {
            assert!(dist(c[i].0, Point::new(O[i].0, O[i].1) + shift) < 1e-9);
            assert!((c[i].1 - R[i]).abs() < 1e-12);
        }
        let a = *triangles.iter().find(|t| inside(t[0], *panel)).unwrap();
        for i in 0..3 {
            assert!((dist(a[i], c[i].0) - R[i]).abs() < 1e-9, "mode {n}: A{} off its circle", i + 1);
            let dir = (a[i] - c[i].0).y.atan2((a[i] - c[i].0).x).to_degrees().rem_euclid(360.0);
            assert!((dir - printed[i]).abs() <= 0.005 + 1e-9, "mode {n}: φ{} measured {dir}", i + 1);
        }
        assert!((dist(a[0], a[1]) - SIDES[0]).abs() < 1e-9);
        assert!((dist(a[1], a[2]) - SIDES[1]).abs() < 1e-9);
        assert!((dist(a[0], a[2]) - SIDES[2]).abs() < 1e-9);
        let sense = if signed_area(a) > 0.0 { "counter-clockwise" } else { "clockwise" };
        assert!(heading.1.contains(&format!("· {sense}")), "mode {n}: {} is {sense}", heading.1);
        assert_eq!(sol["orientation"], if sense == "clockwise" { "cw" } else { "ccw" });
    }

    // The same count through ezdxf, the independent reader.
    let tmp = tempfile::tempdir().unwrap();
    let files = mechdraw::run::bytes::to_files(&p, &mechdraw::run::bytes::WriteOptions::default()).unwrap();
    let (_, dxf) = files.iter().find(|(n, _)| n == "triad-popa-modes.dxf").unwrap();
    let path = tmp.path().join("modes.dxf");
    std::fs::write(&path, dxf).unwrap();
    let out = std::process::Command::new(common::python())
        .arg(common::root().join("tests/ezdxf_inspect.py"))
        .arg(&path)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let inspected: Value = serde_json::from_slice(&out.stdout).unwrap();
    let mut in_dxf: Vec<usize> = inspected["texts"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|t| mode_number(t["plain"].as_str().unwrap()))
        .collect();
    in_dxf.sort();
    assert_eq!(in_dxf, (1..=solutions.len()).collect::<Vec<_>>());
    common::assert_ezdxf_clean(&[&path]);
}

/// Segments of everything drawn as a line in `d` (circles and arcs as 3.75° chords).
fn line_segments(d: &Drawing) -> Vec<(Point, Point)> {
    let mut out = Vec::new();
    let arc = |out: &mut Vec<(Point, Point)>, c: Point, r: f64, a0: f64, sweep: f64| {
        let n = ((sweep / std::f64::consts::TAU * 96.0).ceil() as usize).max(1);
        let at = |k: usize| {
            let a = a0 + sweep * k as f64 / n as f64;
            Point::new(c.x + r * a.cos(), c.y + r * a.sin())
        };
        for k in 0..n {
            out.push((at(k), at(k + 1)));
        }
    };
    for e in &d.entities {
        let parts = match &e.shape {
            s @ Shape::AngularDimension { .. } => explode_dimension(s, &d.dim_style),
            s => vec![s.clone()],
        };
        for s in parts {
            match s {
                Shape::Line { from, to } => out.push((from, to)),
                Shape::Polyline { points, closed, .. } => {
                    out.extend(points.windows(2).map(|w| (w[0], w[1])));
                    if closed {
                        out.push((points[points.len() - 1], points[0]));
                    }
                }
                // Joint circles are the letters' own points: their clearance is the placer's.
                Shape::Circle { center, radius } if radius > 10.0 => {
                    arc(&mut out, center, radius, 0.0, std::f64::consts::TAU)
                }
                Shape::Arc { center, radius, start, end } => {
                    arc(&mut out, center, radius, start, (end - start).rem_euclid(std::f64::consts::TAU))
                }
                _ => {}
            }
        }
    }
    out
}

#[test]
fn fig3_is_the_drawn_mode_alone_with_letters_clear() {
    let p = products();
    let mechdraw::run::products::Picture::Still(d) = &p.picture else { panic!("a still picture") };
    let names: Vec<&str> = d.layers.iter().map(|l| l.name.as_str()).collect();
    assert!(!names.contains(&"MODES"), "no other modes on Fig. 3: {names:?}");

    // The exact triangle: the seed's PLine W 0.5, closed, the drawn mode's vertices.
    let sol = &p.summary["solutions"][p.summary["primary"].as_u64().unwrap() as usize];
    let vertex = |k: &str| Point::new(sol[k][0].as_f64().unwrap(), sol[k][1].as_f64().unwrap());
    let exact = [vertex("A1"), vertex("A2"), vertex("A3")];
    let wide: Vec<&Vec<Point>> = layer(d, "MECHANISM")
        .filter_map(|e| match &e.shape {
            Shape::Polyline { points, closed: true, width } if points.len() == 3 && *width == 0.5 => Some(points),
            _ => None,
        })
        .collect();
    assert_eq!(wide.len(), 1);
    for (p, q) in wide[0].iter().zip(exact) {
        assert!(dist(*p, q) < 1e-12);
    }
    // Three links O_iA_i, as wide.
    let links = layer(d, "MECHANISM")
        .filter(|e| matches!(&e.shape, Shape::Polyline { points, closed: false, width } if points.len() == 2 && *width == 0.5))
        .count();
    assert_eq!(links, 3);
    // The approximate triangle, dashed red: its own layer, one closed polyline.
    assert_eq!(layer(d, "APPROXIMATE").count(), 1);
    // Three angular dimensions, the seed's 75.77° and the analytic 102.23°, 117.04°.
    let dims: Vec<String> = layer(d, "DIMENSIONS")
        .filter_map(|e| match &e.shape {
            Shape::AngularDimension { text, .. } => Some(text.clone()),
            _ => None,
        })
        .collect();
    assert_eq!(dims, ["φ1 = 75.77°", "φ2 = 102.23°", "φ3 = 117.04°"]);

    // The letters: six, clear of each other, of the dimension texts and of every line.
    let letters: Vec<TextBox> = layer(d, "TEXT")
        .filter_map(|e| match &e.shape {
            Shape::Text { at, height, value, halign: HAlign::Center, valign: VAlign::Middle, .. } => {
                Some(TextBox::centred(*at, value, *height))
            }
            _ => None,
        })
        .collect();
    assert_eq!(letters.len(), 6, "O1, O2, O3, A1, A2, A3");
    let dim_texts: Vec<TextBox> = layer(d, "DIMENSIONS")
        .flat_map(|e| explode_dimension(&e.shape, &d.dim_style))
        .filter_map(|s| match s {
            Shape::Text { at, height, value, .. } => Some(TextBox::centred(at, &value, height)),
            _ => None,
        })
        .collect();
    let lines = line_segments(d);
    for (i, b) in letters.iter().enumerate() {
        for o in letters.iter().take(i).chain(&dim_texts) {
            assert!(!b.overlaps(o), "letter {b:?} overlaps {o:?}");
        }
        for (u, v) in &lines {
            assert!(!b.crosses(*u, *v), "letter {b:?} crosses {u:?}–{v:?}");
        }
    }
}

/// The drafting scales (GOST 2.302's mantissas 1, 1.5, 2, 2.5, 4, 5 × 10ᵏ) finer than `k`,
/// the nearest first.
fn finer_drafting_scale(k: f64) -> f64 {
    let mut all: Vec<f64> = (-3..=3)
        .flat_map(|e| [1.0, 1.5, 2.0, 2.5, 4.0, 5.0].map(|m| m * 10f64.powi(e)))
        .filter(|s| *s < k * (1.0 - 1e-9))
        .collect();
    all.sort_by(f64::total_cmp);
    *all.last().unwrap()
}

/// The modes sheet is laid out on A3 (issue 31, fig): its SVG no larger than the page; every
/// sketch (the three circles, measured on the sheet) centred in its cell under the cell's
/// texts and filling most of it; the printed k_l the sheet's own scale, measuring the
/// pivots' distances to the scene's (1e-9); and the next finer drafting scale would hold the
/// sketches in no grid of the page (so the printed one is the largest the page allows).
#[test]
fn modes_sheet_draws_its_sketches_as_large_as_its_a3_page_allows() {
    use mechdraw::figure::triad::{MODES_PAD_MM, modes_area};
    use mechdraw::geom::Vector;
    let p = products();
    let d = &p.sheets[0].drawing;
    let mm = d.paper_mm_per_unit.expect("drawn on paper");
    // The printed k_l (model mm per paper mm): the sheet's own scale.
    let k_text = d
        .entities
        .iter()
        .filter_map(|e| e.shape.scale_text_in(Some(mm)))
        .find_map(|s| match s {
            Shape::Text { value, .. } => value.strip_prefix("k_l = ").map(str::to_string),
            _ => None,
        })
        .expect("k_l printed");
    let k_l: f64 = k_text.trim_end_matches(" mm/mm").parse().unwrap();
    assert_eq!(k_text, format!("{k_l} mm/mm"));
    assert!((k_l * mm - 1.0).abs() < 1e-12, "printed k_l {k_l}, drawn at {} mm per mm", mm);
    assert_eq!(k_l, 2.5, "the template at 2.5 mm/mm (5 before)");

    // The SVG's page: no larger than A3, either way round.
    let files = mechdraw::run::bytes::to_files(&p, &mechdraw::run::bytes::WriteOptions::default()).unwrap();
    let (_, svg) = files.iter().find(|(n, _)| n == "triad-popa-modes.svg").unwrap();
    let svg = String::from_utf8(svg.clone()).unwrap();
    let attr = |name: &str| -> f64 {
        let at = svg.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
        svg[at..].split("mm\"").next().unwrap().parse().unwrap()
    };
    let (w, h) = (attr("width"), attr("height"));
    assert!(w.min(h) <= 297.0 + 1e-6 && w.max(h) <= 420.0 + 1e-6, "{w} × {h} mm is larger than A3");

    let panels: Vec<(Point, Point)> = common::panels(d);
    let circles: Vec<(Point, f64)> = layer(d, "CONSTRUCTION")
        .filter_map(|e| match e.shape {
            Shape::Circle { center, radius } => Some((center, radius)),
            _ => None,
        })
        .collect();
    let all = texts(d);
    let inside = |q: Point, (lo, hi): (Point, Point)| lo.x < q.x && q.x < hi.x && lo.y < q.y && q.y < hi.y;
    let scene_o = O.map(|(x, y)| Point::new(x, y));
    let mut header = 0.0f64;
    let mut sketch_paper = Vector::zeros();
    for panel in &panels {
        let c: Vec<&(Point, f64)> = circles.iter().filter(|(o, _)| inside(*o, *panel)).collect();
        assert_eq!(c.len(), 3);
        // Measured on paper × k_l: the scene's distances between the pivots.
        for (i, j) in [(0, 1), (1, 2), (0, 2)] {
            let on_paper = dist(c[i].0, c[j].0) * mm;
            assert!((on_paper * k_l - dist(scene_o[i], scene_o[j])).abs() < 1e-9);
        }
        let lo = c
            .iter()
            .fold(Point::new(f64::INFINITY, f64::INFINITY), |m, (o, r)| Point::new(m.x.min(o.x - r), m.y.min(o.y - r)));
        let hi = c.iter().fold(Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY), |m, (o, r)| {
            Point::new(m.x.max(o.x + r), m.y.max(o.y + r))
        });
        let cell = (panel.1 - panel.0) * mm;
        let sketch = (hi - lo) * mm;
        sketch_paper = sketch;
        // The cell's texts: its heading and angles line, above the sketch.
        let lowest_text = all
            .iter()
            .filter(|(at, t)| inside(*at, *panel) && (mode_number(t).is_some() || angles(t).is_some()))
            .map(|(at, _)| at.y)
            .fold(f64::INFINITY, f64::min);
        assert!(lowest_text.is_finite());
        assert!(hi.y < lowest_text, "the sketch under its cell's texts");
        header = header.max((panel.1.y - lowest_text) * mm);
        // Centred across the cell.
        assert!(((lo.x + hi.x) - (panel.0.x + panel.1.x)).abs() * mm < 1e-9, "centred across");
        // Most of the cell: 80 % of its width, 70 % of its height, 60 % of its area.
        let (sw, sh) = (sketch.x / cell.x, sketch.y / cell.y);
        assert!(sw >= 0.8 && sh >= 0.7 && sw * sh >= 0.6, "sketch {sketch:?} in a cell {cell:?}");
    }
    // The next finer drafting scale: the sketch (its circles alone) would fit no cell of any
    // grid of the page's room under the caption block as this sheet draws it (its gaps, its
    // cells' texts and padding), the page either way round.
    let finer = finer_drafting_scale(k_l);
    let at_finer = sketch_paper * k_l / finer;
    let top = all.iter().map(|(at, _)| at.y).fold(f64::NEG_INFINITY, f64::max);
    let grid_top = panels.iter().map(|p| p.1.y).fold(f64::NEG_INFINITY, f64::max);
    let caption = (top - grid_top) * mm;
    let gap = panels
        .iter()
        .flat_map(|a| panels.iter().map(move |b| b.0.x - a.1.x))
        .filter(|g| *g > 0.0)
        .fold(f64::INFINITY, f64::min)
        * mm;
    let n = panels.len();
    for page in [Vector::new(420.0, 297.0), Vector::new(297.0, 420.0)] {
        let room = modes_area(page);
        for columns in 1..=n {
            let rows = n.div_ceil(columns);
            let cell_w = (room.x - (columns - 1) as f64 * gap) / columns as f64 - 2.0 * MODES_PAD_MM;
            let cell_h = (room.y - caption - rows as f64 * gap) / rows as f64 - header - MODES_PAD_MM;
            assert!(
                at_finer.x > cell_w || at_finer.y > cell_h,
                "at k_l = {finer} the sketch {at_finer:?} fits a {columns} × {rows} grid ({cell_w} × {cell_h})"
            );
        }
    }
}

/// The modes sheet's joints are named (O1 … A3 in every cell) and its texts are readable:
/// none overlaps another, none is crossed by a line, none leaves its cell (measured in the
/// bundled font, as tests/labels_all.rs does).
#[test]
fn modes_sheet_names_every_joint_readably() {
    let p = products();
    let d = &p.sheets[0].drawing;
    let panels = common::panels(d);
    let inside = |q: Point, (lo, hi): (Point, Point)| lo.x < q.x && q.x < hi.x && lo.y < q.y && q.y < hi.y;
    let all = texts(d);
    for panel in &panels {
        let mut names: Vec<&str> =
            all.iter().filter(|(at, t)| inside(*at, *panel) && t.len() == 2).map(|(_, t)| t.as_str()).collect();
        names.sort();
        assert_eq!(names, ["A1", "A2", "A3", "O1", "O2", "O3"]);
    }
    assert_eq!(common::overlapping_texts(d), Vec::<(String, String)>::new());
    assert_eq!(common::crossed_texts(d), Vec::<(String, String)>::new());
    assert_eq!(common::texts_outside_their_panel(d), Vec::<(String, String)>::new());
    // No two names closer than the force figures' name gap.
    let height = mechdraw::figure::shared::vocab::PAPER_TEXT_MM / d.paper_mm_per_unit.unwrap();
    let (gap, a, b) = closest_labels(d).unwrap();
    assert!(gap >= mechdraw::figure::shared::forces::NAME_GAP * height, "{a} and {b} {gap} apart");
}

/// The least box-to-box distance between the labels of `d` (the texts a placer put beside
/// points: `O1` … `A3` and the circled link numbers), with the pair.
fn closest_labels(d: &Drawing) -> Option<(f64, String, String)> {
    let boxes: Vec<common::TextBox> = common::text_boxes(d)
        .into_iter()
        .filter(|t| {
            let v = t.value.as_str();
            v.chars().all(|c| c.is_ascii_digit()) || (v.len() == 2 && (v.starts_with('O') || v.starts_with('A')))
        })
        .collect();
    let mut best: Option<(f64, String, String)> = None;
    for (i, a) in boxes.iter().enumerate() {
        for b in &boxes[..i] {
            let dx = (b.min.x - a.max.x).max(a.min.x - b.max.x).max(0.0);
            let dy = (b.min.y - a.max.y).max(a.min.y - b.max.y).max(0.0);
            let g = dx.hypot(dy);
            if best.as_ref().is_none_or(|(x, ..)| g < *x) {
                best = Some((g, a.value.clone(), b.value.clone()));
            }
        }
    }
    best
}

/// The report's modes page (issue 31, fig): the grid of the finest drafting scale (3 × 3
/// at k_l = 4 mm/mm on A4 for the template, 4 × 2 at 5 before), every sketch's joints named
/// and its links numbered, no two of those labels closer than the force figures' name gap
/// (⓪ touched ① in modes 4 and 7 before), and none overlapping, crossed or out of its panel.
#[test]
fn reports_modes_page_is_as_large_as_a4_allows_with_its_labels_apart() {
    use mechdraw::figure::shared::forces::NAME_GAP;
    use mechdraw::figure::shared::sheet::Paper;
    use mechdraw::run::report::{ReportOptions, report};
    let loaded = mechdraw::scene::load(&common::root().join("templates/triad-popa.toml"), &[]).unwrap();
    let r = report(&loaded, &ReportOptions { paper: Paper::A4, positions: None }).unwrap();
    let first = r.parts.iter().find(|(t, _)| t == "Assembly modes").unwrap().1;
    let d = &r.pages[first - 1].drawing;
    let all = texts(d);
    assert!(all.iter().any(|(_, t)| t == "k_l = 4 mm/mm"), "{all:?}");
    // The printed k_l measures true: each mode's triangle, measured on the page × 4, has the
    // triad's sides (1e-9).
    let mut sides_ok = 0;
    for e in layer(d, "MECHANISM") {
        if let Shape::Polyline { points, closed: true, .. } = &e.shape
            && points.len() == 3
        {
            let mut sides =
                [dist(points[0], points[1]), dist(points[1], points[2]), dist(points[0], points[2])].map(|l| l * 4.0);
            sides.sort_by(f64::total_cmp);
            if (sides[2] - SIDES[2]).abs() < 1e-9 {
                assert!((sides[0] - SIDES[0]).abs() < 1e-9 && (sides[1] - SIDES[1]).abs() < 1e-9, "{sides:?}");
                sides_ok += 1;
            }
        }
    }
    assert_eq!(sides_ok, 8, "eight triangles measuring the triad's sides at the printed k_l");
    // Eight mode panels, each with its six names and its numbers 1 … 4.
    let headings: Vec<Point> = all.iter().filter(|(_, t)| t.starts_with("Mode ")).map(|(at, _)| *at).collect();
    assert_eq!(headings.len(), 8);
    let columns = {
        let mut xs: Vec<f64> = headings.iter().map(|p| (p.x * 1e6).round()).collect();
        xs.sort_by(f64::total_cmp);
        xs.dedup();
        xs.len()
    };
    assert_eq!(columns, 3, "a 3 × 3 grid");
    for name in ["O1", "O2", "O3", "A1", "A2", "A3", "0", "1", "2", "3", "4"] {
        assert_eq!(all.iter().filter(|(_, t)| t == name).count(), 8, "{name} once a mode");
    }
    let text_height = d
        .entities
        .iter()
        .find_map(|e| match &e.shape {
            Shape::Text { value, height, .. } if value == "O1" => Some(*height),
            _ => None,
        })
        .unwrap();
    let (gap, a, b) = closest_labels(d).unwrap();
    assert!(gap >= NAME_GAP * text_height, "{a} and {b} {gap} mm apart");
    assert_eq!(common::overlapping_texts(d), Vec::<(String, String)>::new());
    assert_eq!(common::crossed_texts(d), Vec::<(String, String)>::new());
    assert_eq!(common::texts_outside_their_panel(d), Vec::<(String, String)>::new());
}
