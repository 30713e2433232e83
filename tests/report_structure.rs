//! The report's structure page (issue 31, a teacher's review): the mechanism and each
//! group drawn at the finest drafting scale their panel holds, the printed k_l measuring
//! the drawn links to the scene's lengths, each link's circled number at its own link and
//! on no line, every text readable, and no framed cell left empty (the page's panels and
//! its title block tile the border's inside).
//!
//! Everything is read back from the page as drawn (its panels' frames, their titles, the
//! title block's scales, the joints' circles, the circled numbers) and held against the
//! scene's mechanism solved at the report's first position (the Assur solver run over the
//! scene's times, as the report runs it).

mod common;

use mechdraw::draw::{Drawing, Shape};
use mechdraw::figure::linkage::LinkageFigure;
use mechdraw::figure::report::page::panel_area;
use mechdraw::figure::report::sketch::{self, Sketch};
use mechdraw::figure::report::structure::{group_caption, group_sketch};
use mechdraw::figure::shared::labels::CIRCLE_RADIUS;
use mechdraw::figure::shared::sheet::Paper;
use mechdraw::figure::shared::vocab::DRAFTING_MANTISSAS;
use mechdraw::geom::{Point, Vector};
use mechdraw::run::report::{ReportOptions, report};
use mechdraw::scene::{self, Scene};
use mechdraw::solve::linkage::{AssurSolver, Attach, JointKind, Structure, place};

/// Least share of its panel (the frame less its title band and margins) a drawing's extent
/// takes in the direction that limits its scale. The drafting scales step by at most 2
/// (5 → 10), so a drawing at the finest scale its panel holds fills at least half of what
/// is left after the room kept for symbols and letters.
const LEAST_SHARE: f64 = 0.4;

/// Farthest a link's number's centre may be from its link, in letter heights.
const NUMBER_REACH: f64 = 4.0;

/// Relative tolerance of a measured length.
const MEASURE: f64 = 1e-9;

/// A framed panel of the page: its frame and its title.
#[derive(Debug, Clone)]
struct Panel {
    min: Point,
    max: Point,
    title: String,
}

impl Panel {
    fn inside(&self, p: Point) -> bool {
        p.x > self.min.x && p.x < self.max.x && p.y > self.min.y && p.y < self.max.y
    }
    fn bounds(&self) -> mechdraw::draw::Bounds {
        mechdraw::draw::Bounds { min: self.min, max: self.max }
    }
}

fn layer(d: &Drawing, e: &mechdraw::draw::Entity) -> String {
    d.layers[e.layer].name.clone()
}

/// The rectangles framed on the sheet's layer, with `width` (0 for panels, 0.5 for the
/// border and the title block).
fn rectangles(d: &Drawing, width: f64) -> Vec<(Point, Point)> {
    d.entities
        .iter()
        .filter(|e| layer(d, e) == "SHEET")
        .filter_map(|e| match &e.shape {
            Shape::Polyline { points, closed: true, width: w } if points.len() == 4 && *w == width => {
                let min = points.iter().fold(points[0], |m, p| Point::new(m.x.min(p.x), m.y.min(p.y)));
                let max = points.iter().fold(points[0], |m, p| Point::new(m.x.max(p.x), m.y.max(p.y)));
                Some((min, max))
            }
            _ => None,
        })
        .collect()
}

/// The page's panels: each frame with the text in its title band (left, at its top).
fn panels(d: &Drawing, text: f64) -> Vec<Panel> {
    rectangles(d, 0.0)
        .into_iter()
        .map(|(min, max)| {
            let title = d
                .entities
                .iter()
                .filter_map(|e| match &e.shape {
                    Shape::Text { at, value, .. }
                        if layer(d, e) == "SHEET"
                            && at.x > min.x
                            && at.x < min.x + text
                            && at.y < max.y
                            && at.y > max.y - 2.2 * text =>
                    {
                        Some(value.clone())
                    }
                    _ => None,
                })
                .next()
                .unwrap_or_default();
            Panel { min, max, title }
        })
        .collect()
}

/// The number printed after `key` (`k_l = `) in `text`.
fn number_after(text: &str, key: &str) -> Option<f64> {
    let rest = &text[text.find(key)? + key.len()..];
    rest.chars().take_while(|c| c.is_ascii_digit() || *c == '.').collect::<String>().parse().ok()
}

/// The title block's two scales: the mechanism's k_l and the groups'.
fn printed_scales(d: &Drawing) -> (f64, f64) {
    let texts: Vec<&String> = d
        .entities
        .iter()
        .filter_map(|e| match &e.shape {
            Shape::Text { value, .. } => Some(value),
            _ => None,
        })
        .collect();
    let groups = texts.iter().find_map(|t| t.strip_prefix("groups: ").and_then(|r| number_after(r, "k_l = ")));
    let mech = texts.iter().find(|t| t.starts_with("k_l = ")).and_then(|t| number_after(t, "k_l = "));
    (mech.expect("the title block's k_l"), groups.expect("the title block's groups' k_l"))
}

/// The next finer drafting scale than `k` (model units per mm).
fn finer(k: f64) -> f64 {
    let mut best = 0.0f64;
    let mut decade = 1e-12;
    while decade < 1e12 {
        for m in DRAFTING_MANTISSAS {
            let v = m * decade;
            if v < k * (1.0 - 1e-9) {
                best = best.max(v);
            }
        }
        decade *= 10.0;
    }
    best
}

fn distance_to_segment(p: Point, a: Point, b: Point) -> f64 {
    let ab = b - a;
    let t = if ab.norm_squared() > 0.0 { ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0) } else { 0.0 };
    (p - (a + ab * t)).norm()
}

/// Every stroke of the mechanism's layer inside `panel`, as segments.
fn strokes(d: &Drawing, panel: &Panel) -> Vec<(Point, Point)> {
    let mut out = Vec::new();
    for e in d.entities.iter().filter(|e| layer(d, e) == "MECHANISM") {
        match &e.shape {
            Shape::Line { from, to } | Shape::Arrow { from, to, .. } => out.push((*from, *to)),
            Shape::Polyline { points, closed, .. } => {
                out.extend(points.windows(2).map(|w| (w[0], w[1])));
                if *closed {
                    out.push((points[points.len() - 1], points[0]));
                }
            }
            Shape::Filled { points } => {
                out.extend((0..points.len()).map(|k| (points[k], points[(k + 1) % points.len()])))
            }
            _ => {}
        }
    }
    out.retain(|(a, b)| panel.inside(*a) || panel.inside(*b));
    out
}

/// The circles of `radius` on the mechanism's layer inside `panel`.
fn circles(d: &Drawing, panel: &Panel, radius: f64) -> Vec<Point> {
    d.entities
        .iter()
        .filter(|e| layer(d, e) == "MECHANISM")
        .filter_map(|e| match e.shape {
            Shape::Circle { center, radius: r } if (r - radius).abs() <= 1e-9 * radius && panel.inside(center) => {
                Some(center)
            }
            _ => None,
        })
        .collect()
}

/// The circled numbers inside `panel`: (number, centre).
fn numbers(d: &Drawing, panel: &Panel, text: f64) -> Vec<(usize, Point)> {
    let rings = circles(d, panel, CIRCLE_RADIUS * text);
    d.entities
        .iter()
        .filter_map(|e| match &e.shape {
            Shape::Text { at, value, .. } if rings.iter().any(|c| (c - at).norm() < 1e-9) => {
                value.parse().ok().map(|n| (n, *at))
            }
            _ => None,
        })
        .collect()
}

/// What one drawing panel shows: its title's start, the bodies and the joints drawn.
struct Shown {
    caption: String,
    sketch: Sketch,
    bodies: Vec<usize>,
    joints: Vec<usize>,
}

/// The circled numbers of `panel` on `d`: every link of `bodies` once, each within
/// NUMBER_REACH letters of its own link (`mech` at `q`, drawn at `origin + p / k`), nearer it
/// than any other (a bar's, a plate's: a block, a one-point body, sits on the links through
/// its point and is only held to its reach), its circle on no line and off every joint
/// (`joints`, the drawn joint circles).
fn check_numbers(
    d: &Drawing,
    panel: &Panel,
    (mech, q): (&mechdraw::solve::linkage::Mechanism, &[f64]),
    bodies: &[usize],
    (origin, k): (Vector, f64),
    joints: &[Point],
    what: &str,
) {
    let s = Paper::A4.sizes();
    let circled = numbers(d, panel, s.text);
    let mut seen: Vec<usize> = circled.iter().map(|(n, _)| *n).filter(|n| *n > 0).collect();
    seen.sort_unstable();
    let mut wanted: Vec<usize> = bodies.iter().map(|b| b + 1).collect();
    wanted.sort_unstable();
    assert_eq!(seen, wanted, "{what}: the links' numbers");
    let link = |b: usize| -> Vec<(Point, Point)> {
        let pts: Vec<Point> = mech.bodies[b]
            .points
            .iter()
            .map(|(_, v)| Point::from(origin + place(q, Attach::Body(b), *v).coords / k))
            .collect();
        if pts.len() == 1 { vec![(pts[0], pts[0])] } else { pts.windows(2).map(|w| (w[0], w[1])).collect() }
    };
    let from_link =
        |c: Point, b: usize| link(b).iter().map(|(a, e)| distance_to_segment(c, *a, *e)).fold(f64::INFINITY, f64::min);
    let lines = strokes(d, panel);
    let r = CIRCLE_RADIUS * s.text;
    for (n, c) in circled.iter().filter(|(n, _)| *n > 0) {
        let own = from_link(*c, n - 1);
        assert!(own <= NUMBER_REACH * s.text, "{what}: ({n}) is {own:.1} mm from its link");
        let block = mech.bodies[n - 1].points.len() == 1;
        for &b in bodies.iter().filter(|&&b| b != n - 1 && !block) {
            let other = from_link(*c, b);
            assert!(own < other, "{what}: ({n}) nearer link {} ({other:.1} mm) than its own ({own:.1} mm)", b + 1);
        }
        for (a, e) in &lines {
            let gap = distance_to_segment(*c, *a, *e);
            assert!(gap >= r - 1e-9, "{what}: ({n}) on a line ({gap:.2} mm from {a:?}–{e:?})");
        }
        for j in joints {
            assert!((j - c).norm() >= r + s.joint, "{what}: ({n}) over the joint at {j:?}");
        }
    }
}

/// The origin that puts the pins (`pins`, model) on `drawn` joint circles at `k`: model
/// point p at `origin + p / k` (paper mm).
fn drawn_origin(drawn: &[Point], pins: &[Point], k: f64, what: &str) -> Vector {
    let on = |o: Vector, p: Point| drawn.iter().any(|c| (c.coords - (o + p.coords / k)).norm() <= 1e-6);
    drawn
        .iter()
        .map(|c| c.coords - pins[0].coords / k)
        .find(|o| pins.iter().all(|p| on(*o, *p)))
        .unwrap_or_else(|| panic!("{what}: the joints are not drawn at k_l = {k}"))
}

/// The revolute joints' points of `mech` at `q` (model): where its joint circles are drawn.
fn pins_of(mech: &mechdraw::solve::linkage::Mechanism, joints: &[usize], q: &[f64]) -> Vec<Point> {
    joints
        .iter()
        .filter_map(|&j| match mech.joints[j].kind {
            JointKind::Revolute { a, .. } => Some(place(q, a.body, a.local)),
            JointKind::Prismatic { .. } => None,
        })
        .collect()
}

/// Every linkage template, loaded, with its name.
fn linkages() -> Vec<(String, scene::Loaded)> {
    common::template_paths()
        .into_iter()
        .map(|t| (t.file_stem().unwrap().to_string_lossy().to_string(), scene::load(&t, &[]).unwrap()))
        .filter(|(_, l)| matches!(l.scene, Scene::Linkage(_)))
        .collect()
}

#[test]
fn the_kinematic_diagrams_numbers_sit_at_their_own_links() {
    let paper = Paper::A4;
    let s = paper.sizes();
    let mut checked = 0;
    for (name, loaded) in linkages() {
        let Scene::Linkage(sc) = &loaded.scene else { continue };
        let mech = &sc.mechanism;
        let q0 = AssurSolver::new(mech.clone()).unwrap().run_positions(&sc.times).unwrap().swap_remove(0);
        let r = report(&loaded, &ReportOptions { paper, positions: None }).unwrap();
        let page = r.pages.iter().find(|p| p.stem.ends_with("kinematic")).expect("a kinematic page");
        let d = &page.drawing;
        let panel = panels(d, s.text)
            .into_iter()
            .find(|p| p.title.starts_with("Kinematic diagram"))
            .unwrap_or_else(|| panic!("{name}: no kinematic diagram's panel"));
        let k = number_after(&panel.title, "k_l = ").expect("the diagram's k_l");
        let drawn = circles(d, &panel, s.joint);
        let all: Vec<usize> = (0..mech.joints.len()).collect();
        let what = format!("{name}: kinematic diagram");
        let origin = drawn_origin(&drawn, &pins_of(mech, &all, &q0), k, &what);
        let bodies: Vec<usize> = (0..mech.bodies.len()).collect();
        check_numbers(d, &panel, (mech, &q0), &bodies, (origin, k), &drawn, &what);
        checked += 1;
    }
    assert!(checked >= 4, "{checked} kinematic diagrams");
}

#[test]
fn each_structure_drawing_is_at_the_finest_scale_its_panel_holds_and_measures_true() {
    let paper = Paper::A4;
    let s = paper.sizes();
    let room = sketch::room(s);
    let mut checked = 0;
    for (name, loaded) in linkages() {
        let Scene::Linkage(sc) = &loaded.scene else { continue };
        let mech = &sc.mechanism;
        let motion = AssurSolver::new(mech.clone()).unwrap().run_positions(&sc.times).unwrap();
        let q0 = motion[0].clone();
        let refs: Vec<&[f64]> = motion.iter().map(Vec::as_slice).collect();
        let structure = Structure::of(mech, Some(&q0));
        let figure = LinkageFigure::new(mech, |a| sc.point_name(a), Vec::new());
        let whole = Sketch { figure, names: Vec::new(), driver: None, loads: Vec::new() };
        let r = report(&loaded, &ReportOptions { paper, positions: None }).unwrap();
        let page = r.pages.iter().find(|p| p.stem.ends_with("structure")).expect("a structure page");
        let d = &page.drawing;
        let (k_mech, k_groups) = printed_scales(d);
        let all_panels = panels(d, s.text);
        let mut shown = vec![Shown {
            caption: "The mechanism, links numbered".into(),
            sketch: whole.clone(),
            bodies: (0..mech.bodies.len()).collect(),
            joints: (0..mech.joints.len()).collect(),
        }];
        for g in &structure.groups {
            shown.push(Shown {
                caption: group_caption(g),
                sketch: group_sketch(&whole, mech, g),
                bodies: g.group.bodies.clone(),
                joints: g.group.joints.clone(),
            });
        }
        let mut groups_full = false;
        for (i, sh) in shown.iter().enumerate() {
            let k = if i == 0 { k_mech } else { k_groups };
            let what = format!("{name}: {}", sh.caption);
            let panel = all_panels
                .iter()
                .find(|p| p.title.starts_with(&sh.caption))
                .unwrap_or_else(|| panic!("{what}: no panel so titled in {:?}", all_panels));
            // The caption and its scale apart (` · `), when the scale is in it.
            if panel.title.contains("k_l") {
                assert!(panel.title.contains(" · k_l = "), "{what}: {}", panel.title);
                assert_eq!(number_after(&panel.title, "k_l = "), Some(k), "{what}");
            }
            // The pins where the printed k_l puts them: the origin from one, every other
            // on a drawn joint circle, and every link's length on the page × k_l the
            // scene's.
            let drawn = circles(d, panel, s.joint);
            let pins = pins_of(mech, &sh.joints, &q0);
            assert!(!pins.is_empty() || sh.joints.is_empty(), "{what}");
            let on =
                |o: Vector, p: Point| drawn.iter().copied().find(|c| (c.coords - (o + p.coords / k)).norm() <= 1e-6);
            let origin = drawn_origin(&drawn, &pins, k, &what);
            for (a, pa) in pins.iter().enumerate() {
                for pb in &pins[a + 1..] {
                    let model = (pb - pa).norm();
                    let paper_len = (on(origin, *pb).unwrap() - on(origin, *pa).unwrap()).norm();
                    assert!(
                        (paper_len * k - model).abs() <= MEASURE * model.max(1e-300),
                        "{what}: {paper_len} × {k} ≠ {model}"
                    );
                }
            }
            // The scale: the drawing fits its panel leaving the room for its symbols and
            // letters, fills at least LEAST_SHARE of it, and would not fit at the next
            // finer drafting scale (the groups: one of them would not).
            let (lo, hi) = sh.sketch.extent_with_guides(&q0, &refs, s).unwrap();
            let area = panel_area(panel.bounds(), true, s);
            let size = (hi - lo) / k;
            let inner = Vector::new(area.width(), area.height()) - 2.0 * room;
            assert!(size.x <= inner.x + 1e-9 && size.y <= inner.y + 1e-9, "{what}: {size:?} in {inner:?}");
            let bigger = size * (k / finer(k));
            let full = bigger.x > inner.x || bigger.y > inner.y;
            if i == 0 {
                assert!(full, "{what}: at k_l = {} it would still fit ({bigger:?} in {inner:?})", finer(k));
                let share = (size.x / area.width()).max(size.y / area.height());
                assert!(share >= LEAST_SHARE, "{what}: fills {share:.2} of its panel");
            } else {
                groups_full |= full;
            }
            check_numbers(d, panel, (mech, &q0), &sh.bodies, (origin, k), &drawn, &what);
            checked += 1;
        }
        assert!(
            groups_full,
            "{name}: the groups' k_l = {k_groups}: every group would still fit at {}",
            finer(k_groups)
        );
    }
    assert!(checked >= 12, "{checked} drawings");
}

#[test]
fn no_framed_cell_of_a_structure_page_is_empty_and_the_panels_tile_the_page() {
    let mut seen = 0;
    for t in common::template_paths() {
        let loaded = scene::load(&t, &[]).unwrap();
        if matches!(loaded.scene, Scene::Synthesis(_) | Scene::Chain(_)) {
            continue;
        }
        let name = t.file_stem().unwrap().to_string_lossy().to_string();
        for paper in [Paper::A4, Paper::A3] {
            let s = paper.sizes();
            let r = report(&loaded, &ReportOptions { paper, positions: None }).unwrap();
            let Some(page) = r.pages.iter().find(|p| p.stem.ends_with("structure")) else { continue };
            let d = &page.drawing;
            let ps = panels(d, s.text);
            assert!(ps.len() >= 3, "{name}: {} panels", ps.len());
            for p in &ps {
                assert!(!p.title.is_empty(), "{name}: an untitled panel at {:?}", p.min);
                // Besides its title, something drawn or written inside it.
                let inside = d
                    .entities
                    .iter()
                    .filter(|e| match &e.shape {
                        Shape::Text { at, value, .. } => p.inside(*at) && *value != p.title,
                        Shape::Circle { center, .. } => p.inside(*center),
                        Shape::Line { from, to } => p.inside(*from) && p.inside(*to),
                        Shape::Polyline { points, closed: false, .. } => points.iter().all(|x| p.inside(*x)),
                        _ => false,
                    })
                    .count();
                assert!(inside >= 3, "{name} ({}): the panel {:?} holds {inside} things", paper.name(), p.title);
            }
            // Every text readable (tests/labels_all.rs's measures): none over another,
            // none crossed by a line, none out of its panel.
            let unread: Vec<String> = common::overlapping_texts(d)
                .into_iter()
                .chain(common::crossed_texts(d))
                .chain(common::texts_outside_their_panel(d))
                .map(|(a, b)| format!("{a:?} / {b}"))
                .collect();
            assert!(unread.is_empty(), "{name} ({}): {unread:#?}", paper.name());
            // The panels and the title block tile the border's inside: no blank area.
            let thick = rectangles(d, 0.5);
            let area = |(a, b): (Point, Point)| (b.x - a.x) * (b.y - a.y);
            let border = thick.iter().copied().max_by(|x, y| area(*x).total_cmp(&area(*y))).unwrap();
            let title = thick.iter().copied().min_by(|x, y| area(*x).total_cmp(&area(*y))).unwrap();
            let covered: f64 = ps.iter().map(|p| area((p.min, p.max))).sum::<f64>() + area(title);
            assert!(
                (covered - area(border)).abs() <= 1e-6 * area(border),
                "{name} ({}): panels and title block cover {covered:.1} of {:.1} mm²",
                paper.name(),
                area(border)
            );
            for (i, a) in ps.iter().enumerate() {
                for b in &ps[..i] {
                    let w = a.max.x.min(b.max.x) - a.min.x.max(b.min.x);
                    let h = a.max.y.min(b.max.y) - a.min.y.max(b.min.y);
                    assert!(w <= 1e-9 || h <= 1e-9, "{name}: {:?} and {:?} overlap", a.title, b.title);
                }
            }
            seen += 1;
        }
    }
    assert!(seen >= 10, "{seen} structure pages");
}
