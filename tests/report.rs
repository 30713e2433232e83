//! `mechdraw report` (issue 33): the structural analysis against the solver, the report's
//! pages (their count, the scales printed on each position's pages measured on the drawn
//! vectors against the report's table, the diagrams' marks at the chosen positions read
//! back through the diagrams' own axes), the files written, and bad input refused with
//! nothing written.

mod common;

use std::path::Path;

use mechdraw::draw::{Drawing, Shape};
use mechdraw::figure::shared::sheet::Paper;
use mechdraw::geom::Point;
use mechdraw::run::positions::Positions;
use mechdraw::run::report::{Report, ReportOptions, report};
use mechdraw::scene::{self, Scene};
use mechdraw::solve::linkage::{AssurSolver, Structure};

fn template(name: &str) -> std::path::PathBuf {
    common::root().join("templates").join(format!("{name}.toml"))
}

fn report_of(name: &str, positions: Option<Vec<f64>>) -> Report {
    let loaded = scene::load(&template(name), &[]).unwrap();
    report(&loaded, &ReportOptions { paper: Paper::A4, positions: positions.map(Positions::List) }).unwrap()
}

#[test]
fn every_linkage_template_has_mobility_one_and_the_solvers_groups() {
    let mut seen = 0;
    for t in common::template_paths() {
        let loaded = scene::load(&t, &[]).unwrap();
        let Scene::Linkage(s) = &loaded.scene else { continue };
        let mech = &s.mechanism;
        let q: Vec<f64> = mech.bodies.iter().flat_map(|b| [b.at.x, b.at.y, b.angle]).collect();
        let st = Structure::of(mech, Some(&q));
        let name = t.display();
        assert_eq!(st.mobility.formula, 1, "{name}: {}", st.mobility.worked());
        assert_eq!(st.mobility.actual, Some(1), "{name}: the joints' rank at the placement");
        assert_eq!(st.drivers, 1, "{name}");
        // The groups are the solver's, in its order.
        let solver = AssurSolver::new(mech.clone()).unwrap();
        let solver_groups: Vec<_> = solver.groups().cloned().collect();
        let ours: Vec<_> = st.groups.iter().map(|g| g.group.clone()).collect();
        assert_eq!(ours, solver_groups, "{name}");
        // Every Assur group has no mobility of its own; the driver has its one.
        for g in &st.groups {
            assert_eq!(g.mobility, if g.is_driver() { 1 } else { 0 }, "{name}: {:?}", g.group);
            assert_eq!(g.order, g.outer.len());
            assert!(g.class >= if g.is_driver() { 1 } else { 2 });
        }
        seen += 1;
    }
    assert!(seen >= 4, "{seen} linkage templates");
}

#[test]
fn the_known_mechanisms_have_their_textbook_structure() {
    let formula = |name: &str| {
        let r = report_of(name, Some(vec![0.0]));
        let kind = &r.summary["kind"];
        let groups: Vec<String> = kind["groups"]
            .as_array()
            .unwrap()
            .iter()
            .map(|g| format!("{}:{}:{}", g["kind"].as_str().unwrap(), g["class"], g["order"]))
            .collect();
        (kind["mobility"].as_i64().unwrap(), groups.join(" "))
    };
    // The four-bar: the crank with the frame, one RRR dyad.
    assert_eq!(formula("fourbar-chebyshev"), (1, "driven (angle):1:1 RRR:2:2".into()));
    // The shaper: the crank, the inverted slider (RPR: block on the rocker), the ram's RRP.
    assert_eq!(formula("shaper-forces"), (1, "driven (angle):1:1 RPR:2:2 RRP:2:2".into()));
    assert_eq!(formula("slider-crank"), (1, "driven (angle):1:1 RRP:2:2".into()));
    // Seed 000's triad carried by a crank: a class III group of order 3.
    assert_eq!(formula("triad-driven"), (1, "driven (angle):1:1 triad:3:3".into()));
}

/// The pages of the PDF file `pdf`, by poppler.
fn pdf_pages(pdf: &Path) -> usize {
    let out = std::process::Command::new("pdfinfo").arg(pdf).output().expect("pdfinfo (poppler-utils)");
    let text = String::from_utf8_lossy(&out.stdout);
    text.lines().find_map(|l| l.strip_prefix("Pages:")).map(|v| v.trim().parse().unwrap()).unwrap()
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs poppler-utils (pdfinfo): bash .ci/test, or cargo test --features system-tools"
)]
fn the_report_has_a_page_per_part_asked_for_and_says_so_in_its_files() {
    let dir = common::root().join("target/test-report/count");
    let _ = std::fs::remove_dir_all(&dir);
    let out = common::mechdraw()
        .args(["report", "templates/shaper-forces.toml", "--positions", "0.25,0,0.5", "--quiet", "--out"])
        .arg(&dir)
        .current_dir(common::root())
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    // Parts: title, structure, kinematic diagram, plan; for each position asked for the
    // printed sheets `run --sheets` draws of one position and the groups' free-body page;
    // the run's diagrams four to a page.
    let loaded = scene::load(&template("shaper-forces"), &[]).unwrap();
    let diagrams = mechdraw::run::products(&loaded, &Default::default()).unwrap().diagrams.len();
    let one = common::root().join("target/test-report/count-one");
    let _ = std::fs::remove_dir_all(&one);
    let ok = common::mechdraw()
        .args([
            "run",
            "templates/shaper-forces.toml",
            "--no-frames",
            "--quiet",
            "--sheets",
            "a4",
            "--positions",
            "0.25",
        ])
        .arg("--out")
        .arg(&one)
        .current_dir(common::root())
        .status()
        .unwrap();
    assert!(ok.success());
    let per_position = pdf_pages(&one.join("shaper-forces-sheets.pdf")) + 1;
    let expected = 4 + 3 * per_position + diagrams.div_ceil(4);
    assert_eq!(pdf_pages(&dir.join("shaper-forces-report.pdf")), expected);
    let svgs = std::fs::read_dir(dir.join("report/shaper-forces")).unwrap().count();
    assert_eq!(svgs, expected, "an SVG per page");
    let csv = std::fs::read_to_string(dir.join("shaper-forces-report.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(rows.len(), 1 + 3, "{csv}");
    assert!(rows[0].starts_with("position,t,E.x,"), "{}", rows[0]);
    // The positions in the order asked for, each the run's own row.
    let run_dir = common::root().join("target/test-report/count-run");
    let _ = std::fs::remove_dir_all(&run_dir);
    let ok = common::mechdraw()
        .args(["run", "templates/shaper-forces.toml", "--no-frames", "--quiet", "--out"])
        .arg(&run_dir)
        .current_dir(common::root())
        .status()
        .unwrap();
    assert!(ok.success());
    let run_csv = std::fs::read_to_string(run_dir.join("shaper-forces.csv")).unwrap();
    let run_rows: Vec<&str> = run_csv.lines().collect();
    for (row, sample) in rows[1..].iter().zip([90, 0, 180]) {
        let ours = row.split_once(',').unwrap().1;
        assert_eq!(ours, run_rows[1 + sample], "t = {sample}/360 s");
    }
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("shaper-forces-report.json")).unwrap()).unwrap();
    assert_eq!(json["pages"].as_u64(), Some(expected as u64));
    // `every=Δ` as `run --positions` reads it: the four-bar every 90° is four positions.
    let r = {
        let loaded = scene::load(&template("fourbar-chebyshev"), &[]).unwrap();
        report(&loaded, &ReportOptions { paper: Paper::A4, positions: Some("every=90".parse().unwrap()) }).unwrap()
    };
    let drives: Vec<f64> =
        r.summary["kind"]["positions"].as_array().unwrap().iter().map(|p| p["phi1_deg"].as_f64().unwrap()).collect();
    assert_eq!(drives, [0.0, 90.0, 180.0, 270.0], "{}", r.summary["kind"]["positions"]);
    let _ = std::fs::remove_dir_all(dir.parent().unwrap());
}

/// The numbers printed after `k_<name> = ` on a page (every occurrence; e.g. `k_v = 0.02
/// (m/s)/mm` gives 0.02).
fn printed_scales(d: &Drawing, name: &str) -> Vec<f64> {
    let key = format!("k_{name} = ");
    let mut out = Vec::new();
    for e in &d.entities {
        if let Shape::Text { value, .. } = &e.shape {
            let mut rest = value.as_str();
            while let Some(i) = rest.find(&key) {
                rest = &rest[i + key.len()..];
                let num: String =
                    rest.chars().take_while(|c| c.is_ascii_digit() || *c == '.' || *c == 'e' || *c == '-').collect();
                if let Ok(v) = num.parse::<f64>() {
                    out.push(v);
                }
            }
        }
    }
    out.sort_by(f64::total_cmp);
    out.dedup();
    out
}

/// The lengths of the arrows drawn on layer `layer`, paper mm.
fn arrows(d: &Drawing, layer: &str) -> Vec<f64> {
    d.entities
        .iter()
        .filter(|e| d.layers[e.layer].name == layer)
        .filter_map(|e| match &e.shape {
            Shape::Arrow { from, to, .. } => Some((to - from).norm()),
            _ => None,
        })
        .collect()
}

/// Whether some arrow on `layer` of `pages`, times some `k` printed on the same page,
/// measures `value` to 1e-9.
fn measured(pages: &[&Drawing], layer: &str, k: &str, value: f64) -> bool {
    pages.iter().any(|d| {
        let ks = printed_scales(d, k);
        arrows(d, layer).iter().any(|len| ks.iter().any(|k| ((len * k) - value).abs() <= 1e-9 * value.abs()))
    })
}

/// The report's table: header and rows of numbers (the first column, the position's mark,
/// as text).
fn table(r: &Report) -> (Vec<String>, Vec<(String, Vec<f64>)>) {
    let text = String::from_utf8(r.table.as_ref().unwrap().to_bytes()).unwrap();
    let mut lines = text.lines();
    let header: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| {
            let mut cells = l.split(',');
            let mark = cells.next().unwrap().to_string();
            (mark, cells.map(|c| c.parse::<f64>().unwrap_or(f64::NAN)).collect())
        })
        .collect();
    (header, rows)
}

/// The pages of each chosen position, in order (by the part titles).
fn position_pages(r: &Report) -> Vec<Vec<&Drawing>> {
    let mut out = Vec::new();
    for (i, (title, first)) in r.parts.iter().enumerate() {
        if !title.starts_with("Position ") {
            continue;
        }
        let next = r.parts.get(i + 1).map_or(r.pages.len() + 1, |p| p.1);
        out.push((*first..next).map(|n| &r.pages[n - 1].drawing).collect());
    }
    out
}

/// The page of part `title` (its first).
fn part_page<'a>(r: &'a Report, title: &str) -> &'a Drawing {
    let first = r.parts.iter().find(|(t, _)| t == title).unwrap_or_else(|| panic!("no part {title}")).1;
    &r.pages[first - 1].drawing
}

#[test]
fn the_kinematic_diagram_and_every_positions_mechanism_share_one_drafting_scale() {
    // The same drawing at the same scale: a teacher compares the kinematic diagram with the
    // mechanism of each position page. The shaper's diagram alone fits at 4 mm/mm, its
    // position pages (the whole motion and the table) need 5: both are drawn at 5.
    for (name, expected) in [("shaper-forces", Some(5.0)), ("slider-crank", None), ("fourbar-chebyshev", None)] {
        let r = report_of(name, None);
        let kin = printed_scales(part_page(&r, "Kinematic diagram"), "l");
        assert_eq!(kin.len(), 1, "{name}: one k_l on the kinematic diagram: {kin:?}");
        if let Some(k) = expected {
            assert_eq!(kin[0], k, "{name}");
        }
        for pages in position_pages(&r) {
            let on_mechanism = printed_scales(pages[0], "l");
            assert_eq!(on_mechanism, kin, "{name}: the position's mechanism page against the kinematic diagram");
        }
    }
}

#[test]
fn the_four_bars_printed_scales_measure_its_vectors_to_the_table() {
    let r = report_of("fourbar-chebyshev", None);
    let (header, rows) = table(&r);
    let col = |name: &str| header.iter().position(|h| h == name).unwrap() - 1;
    let pages = position_pages(&r);
    assert_eq!(pages.len(), rows.len(), "a set of pages per row of the table");
    // Four evenly spaced and the rocker's two extremes, the folded one at 270°: on a sample.
    assert_eq!(rows.len(), 5, "{rows:?}");
    for ((mark, row), pages) in rows.iter().zip(&pages) {
        // A velocity at rounding level (v_BA = 6e-17 m/s where ω2 = 0) is not drawn.
        let largest = ["vA_mag", "vM_mag", "vBA_mag"].iter().map(|v| row[col(v)]).fold(0.0, f64::max);
        for v in ["vA_mag", "vM_mag", "vBA_mag"] {
            let value = row[col(v)];
            assert!(
                value < 1e-9 * largest || measured(pages, "VELOCITY", "v", value),
                "position {mark}: {v} = {value}"
            );
        }
        for a in ["aA_mag", "aB_mag", "aM_mag"] {
            let value = row[col(a)];
            assert!(measured(pages, "ACCELERATION", "a", value), "position {mark}: {a} = {value}");
        }
        for f in ["R_A_mag", "R_B_mag", "R_C_mag", "R_O_mag"] {
            let value = row[col(f)];
            assert!(measured(pages, "FORCES", "f", value), "position {mark}: {f} = {value}");
        }
    }
}

#[test]
fn the_linkages_printed_scales_measure_their_vectors_to_the_table() {
    for (name, point) in [("shaper-forces", "E"), ("slider-crank", "B")] {
        let r = report_of(name, None);
        let (header, rows) = table(&r);
        let col = |name: &str| header.iter().position(|h| h == name).unwrap_or_else(|| panic!("{name}")) - 1;
        let pages = position_pages(&r);
        assert_eq!(pages.len(), rows.len(), "{name}");
        let loaded = scene::load(&template(name), &[]).unwrap();
        let Scene::Linkage(s) = &loaded.scene else { panic!() };
        for ((mark, row), pages) in rows.iter().zip(&pages) {
            // The guided point moves along x: |v| = |vx|, |a| = |ax|.
            let v = row[col(&format!("{point}.vx"))].abs();
            assert!(v < 1e-9 || measured(pages, "VELOCITY", "v", v), "{name} position {mark}: v = {v}");
            let a = row[col(&format!("{point}.ax"))].abs();
            assert!(a < 1e-9 || measured(pages, "ACCELERATION", "a", a), "{name} position {mark}: a = {a}");
            // Every joint's reaction.
            for j in &s.mechanism.joints {
                let (fx, fy) = (row[col(&format!("{}.Fx", j.name))], row[col(&format!("{}.Fy", j.name))]);
                let value = libm::hypot(fx, fy);
                assert!(
                    value < 1e-9 || measured(pages, "FORCES", "f", value),
                    "{name} position {mark}: R_{} = {value}",
                    j.name
                );
            }
        }
    }
}

/// Numbers written under a plot's frame (its abscissa's tick labels) with where they stand:
/// (paper x, value).
fn x_ticks(d: &Drawing, frame: (Point, Point)) -> Vec<(f64, f64)> {
    d.entities
        .iter()
        .filter(|e| d.layers[e.layer].name == "PLOT_TEXT")
        .filter_map(|e| match &e.shape {
            Shape::Text { at, value, rotation, .. } if *rotation == 0.0 => Some((*at, value.parse::<f64>().ok()?)),
            _ => None,
        })
        .filter(|(at, _)| {
            at.y < frame.0.y && at.y > frame.0.y - 10.0 && at.x >= frame.0.x - 1.0 && at.x <= frame.1.x + 1.0
        })
        .map(|(at, v)| (at.x, v))
        .collect()
}

/// The plot frames of a diagrams page (PLOT_FRAME's closed rectangles).
fn plot_frames(d: &Drawing) -> Vec<(Point, Point)> {
    d.entities
        .iter()
        .filter(|e| d.layers[e.layer].name == "PLOT_FRAME")
        .filter_map(|e| match &e.shape {
            Shape::Polyline { points, closed: true, .. } if points.len() == 4 => {
                let lo = points.iter().fold(points[0], |m, p| Point::new(m.x.min(p.x), m.y.min(p.y)));
                let hi = points.iter().fold(points[0], |m, p| Point::new(m.x.max(p.x), m.y.max(p.y)));
                Some((lo, hi))
            }
            _ => None,
        })
        .collect()
}

/// The distance from `p` to the nearest curve drawn on PLOT_DATA inside `frame`.
fn to_curve(d: &Drawing, frame: (Point, Point), p: Point) -> f64 {
    let mut best = f64::INFINITY;
    for e in d.entities.iter().filter(|e| d.layers[e.layer].name == "PLOT_DATA") {
        if let Shape::Polyline { points, .. } = &e.shape {
            if !points.iter().all(|q| q.x >= frame.0.x - 1e-6 && q.x <= frame.1.x + 1e-6) {
                continue;
            }
            for w in points.windows(2) {
                best = best.min(mechdraw::figure::shared::vocab::distance_to_segment(p, w[0], w[1]));
            }
        }
    }
    best
}

#[test]
fn the_diagrams_mark_the_chosen_positions_on_their_curves() {
    // The abscissa of the diagrams: φ1 in degrees (the four-bar's drive; the linkages'
    // angular drivers: the shaper's 2πt, the slider-crank's 320 rpm).
    type Abscissa = fn(f64) -> f64;
    let cases: [(&str, Abscissa); 3] =
        [("fourbar-chebyshev", |phi| phi), ("shaper-forces", |t| 360.0 * t), ("slider-crank", |t| 1920.0 * t)];
    for (name, abscissa) in cases {
        let r = report_of(name, None);
        // (abscissa, whether it is a sample: a vertex of the drawn curve, else a dead position
        // solved between two samples, under a chord of the curve).
        let positions: Vec<(f64, bool)> = r.summary["kind"]["positions"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| {
                let x = abscissa(p.get("phi1_deg").or(p.get("t")).and_then(|v| v.as_f64()).unwrap());
                (x, p["mark"].as_str().unwrap().parse::<usize>().is_ok())
            })
            .collect();
        let diagram_pages: Vec<&Drawing> =
            r.pages.iter().filter(|p| p.stem.contains("-diagrams")).map(|p| &p.drawing).collect();
        assert!(!diagram_pages.is_empty());
        let mut marks_checked = 0;
        for d in diagram_pages {
            for frame in plot_frames(d) {
                let ticks = x_ticks(d, frame);
                assert!(ticks.len() >= 3, "{name}: {ticks:?}");
                // value = a + b·x through the first and last tick.
                let ((x0, v0), (x1, v1)) = (ticks[0], ticks[ticks.len() - 1]);
                let b = (v1 - v0) / (x1 - x0);
                let value = |x: f64| v0 + b * (x - x0);
                let rings: Vec<Point> = d
                    .entities
                    .iter()
                    .filter(|e| d.layers[e.layer].name == "MARKS")
                    .filter_map(|e| match &e.shape {
                        Shape::Circle { center, .. } => Some(*center),
                        _ => None,
                    })
                    .filter(|c| {
                        c.x >= frame.0.x - 1e-6
                            && c.x <= frame.1.x + 1e-6
                            && c.y >= frame.0.y - 1e-6
                            && c.y <= frame.1.y + 1e-6
                    })
                    .collect();
                assert_eq!(rings.len(), positions.len(), "{name}: a mark per chosen position");
                for (c, (want, sample)) in rings.iter().zip(&positions) {
                    let got = value(c.x);
                    let span = (v1 - v0).abs();
                    assert!((got - want).abs() <= 1e-6 * span, "{name}: a mark at {got}, the position at {want}");
                    // On a vertex of the curve; a dead position under its chord (a sample
                    // every 0.44 mm of abscissa: the chord is within a few tenths of the curve).
                    let tol = if *sample { 1e-6 } else { 0.3 };
                    let off = to_curve(d, frame, *c);
                    assert!(off < tol, "{name}: the mark at {got} is {off} mm off the curve");
                    marks_checked += 1;
                }
            }
        }
        assert!(marks_checked >= 4 * positions.len(), "{name}: {marks_checked}");
    }
}

/// Runs `mechdraw report` with `args` into a fresh directory: (exit code, stderr, files).
fn refused(args: &[&str]) -> (i32, String, usize) {
    let dir = common::root().join(format!("target/test-report/bad-{}", args.join("_").replace(['/', '.', ','], "-")));
    let _ = std::fs::remove_dir_all(&dir);
    let out = common::mechdraw()
        .arg("report")
        .args(args)
        .arg("--out")
        .arg(&dir)
        .current_dir(common::root())
        .output()
        .unwrap();
    let files = if dir.exists() { std::fs::read_dir(&dir).unwrap().count() } else { 0 };
    let _ = std::fs::remove_dir_all(&dir);
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stderr).into_owned(), files)
}

#[test]
fn bad_input_is_refused_by_name_and_nothing_is_written() {
    for (args, says) in [
        (
            vec!["templates/fourbar-chebyshev.toml", "--positions", "400"],
            vec!["--positions", "400°", "outside the motion", "from 0° to 359°"],
        ),
        (vec!["templates/fourbar-chebyshev.toml", "--positions", "30,60,30"], vec!["--positions", "30", "twice"]),
        (
            vec!["templates/fourbar-chebyshev.toml", "--positions", "30,30.0000000001"],
            vec!["--positions", "30°", "twice"],
        ),
        (vec!["templates/fourbar-chebyshev.toml", "--positions", "every=7.5"], vec!["--positions", "multiple", "step"]),
        (
            vec!["templates/fourbar-chebyshev.toml", "--positions", "45.5"],
            vec!["--positions", "not a position of the run", "nearest"],
        ),
        (
            vec!["templates/shaper-forces.toml", "--positions", "1.5"],
            vec!["--positions", "1.5 s", "outside the motion", "time t"],
        ),
        (vec!["templates/shaper-forces.toml", "--positions", ""], vec!["--positions", "empty"]),
        (vec!["templates/shaper-forces.toml", "--positions", "0,,1"], vec!["--positions", "empty item"]),
        (vec!["templates/shaper-forces.toml", "--positions", "0,abc"], vec!["--positions", "`abc` is not a number"]),
        (vec!["templates/fourbar-chebyshev.toml", "--positions", "nan"], vec!["--positions", "not a finite number"]),
        (vec!["templates/fourbar-chebyshev.toml", "--positions", " , "], vec!["--positions", "empty item"]),
        (
            vec!["templates/chain-humienny-2.toml", "--positions", "1"],
            vec!["--positions", "chain scene", "leave out --positions"],
        ),
        (vec!["templates/fourbar-chebyshev.toml", "--paper", "A5"], vec!["--paper", "A5", "a4", "a3"]),
        (vec!["templates/shaper-forces.toml", "--paper", "letter"], vec!["--paper", "letter", "a4", "a3"]),
        (vec!["templates/triad-popa.toml", "--positions", "0"], vec!["--positions", "triad"]),
        (vec!["templates/synthesis-crank-rocker.toml"], vec!["synthesis scene", "-design.toml", "mechdraw report"]),
    ] {
        let (code, err, files) = refused(&args);
        assert_eq!(code, 2, "{args:?}: {err}");
        for s in says {
            assert!(err.contains(s), "{args:?}: `{s}` not in: {err}");
        }
        assert_eq!(files, 0, "{args:?}: nothing written");
    }
}

#[test]
fn the_live_pages_report_is_the_command_lines() {
    let dir = common::root().join("target/test-report/web");
    let _ = std::fs::remove_dir_all(&dir);
    let ok = common::mechdraw()
        .args([
            "report",
            "templates/slider-crank.toml",
            "--paper",
            "a3",
            "--positions",
            "0,0.046875",
            "--quiet",
            "--out",
        ])
        .arg(&dir)
        .current_dir(common::root())
        .status()
        .unwrap();
    assert!(ok.success());
    let text = std::fs::read_to_string(template("slider-crank")).unwrap();
    let session = mechdraw::web::Session::new(&text, "templates/slider-crank.toml").unwrap();
    let files = session.report("a3", "0,0.046875").unwrap().files;
    let mut on_disk = Vec::new();
    common::read_tree(&dir, Path::new(""), &mut on_disk);
    on_disk.sort();
    let mut ours = files.clone();
    ours.sort();
    assert_eq!(
        ours.iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>(),
        on_disk.iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>()
    );
    for ((n, a), (_, b)) in ours.iter().zip(&on_disk) {
        assert!(a == b, "{n} differs");
    }
    // The page's errors are the command line's.
    let e = session.report("letter", "").unwrap_err().to_string();
    assert!(e.contains("--paper") && e.contains("a4"), "{e}");
    let e = session.report("a4", "5").unwrap_err().to_string();
    assert!(e.contains("--positions") && e.contains("outside the motion"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Headless Chromium (Debian's `chromium`), the browser the page tests use.
fn chromium() -> &'static str {
    ["chromium", "chromium-browser"]
        .into_iter()
        .find(|c| std::process::Command::new(c).arg("--version").output().is_ok_and(|o| o.status.success()))
        .expect("chromium not found: this test prints the page's report as a browser does (apt-get install chromium)")
}

/// Page `page`'s words (poppler's `pdftotext`), sorted.
fn pdf_words(pdf: &Path, page: usize) -> Vec<String> {
    let p = page.to_string();
    let out = std::process::Command::new("pdftotext").args(["-f", &p, "-l", &p]).arg(pdf).arg("-").output().unwrap();
    let mut w: Vec<String> = String::from_utf8_lossy(&out.stdout).split_whitespace().map(String::from).collect();
    w.sort();
    w
}

/// The size of the PDF's first page, pt (pdfinfo).
fn pdf_page_size(pdf: &Path) -> (f64, f64) {
    let out = std::process::Command::new("pdfinfo").arg(pdf).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    let line = text.lines().find_map(|l| l.strip_prefix("Page size:")).unwrap().to_string();
    let v: Vec<f64> = line.split_whitespace().filter_map(|t| t.parse().ok()).collect();
    (v[0], v[1])
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and poppler-utils (pdfinfo, pdftotext): bash .ci/test, or cargo test --features system-tools"
)]
fn the_live_pages_report_prints_as_the_command_lines_pdf() {
    // The page's download: every page in one HTML document to print (the module has no PDF
    // writer), then the PDF where the build has one, the table and the JSON.
    let text = std::fs::read_to_string(template("fourbar-chebyshev")).unwrap();
    let session = mechdraw::web::Session::new(&text, "templates/fourbar-chebyshev.toml").unwrap();
    let offered = session.report_download("a3", "0,90").unwrap().files;
    let names: Vec<&str> = offered.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(
        names,
        [
            "fourbar-chebyshev-report.html",
            "fourbar-chebyshev-report.pdf",
            "fourbar-chebyshev-report.csv",
            "fourbar-chebyshev-report.json"
        ]
    );
    // The document holds every page's SVG of the report, in order.
    let html = std::str::from_utf8(&offered[0].1).unwrap();
    let whole = session.report("a3", "0,90").unwrap().files;
    let svgs: Vec<&[u8]> = whole.iter().filter(|(n, _)| n.ends_with(".svg")).map(|(_, b)| b.as_slice()).collect();
    let mut at = 0;
    for s in &svgs {
        let s = std::str::from_utf8(s).unwrap().trim();
        at += html[at..].find(s).expect("every page's SVG in the document, in order") + s.len();
    }
    // Printed by a browser (Chromium's print to PDF, as Print → Save as PDF does): a sheet per
    // page on the report's paper, each sheet with the words of the command line's PDF page.
    let dir = tempfile::tempdir().unwrap();
    let doc = dir.path().join("report.html");
    std::fs::write(&doc, html).unwrap();
    let ours = dir.path().join("ours.pdf");
    std::fs::write(&ours, &offered[1].1).unwrap();
    let printed = dir.path().join("printed.pdf");
    let profile = tempfile::tempdir().unwrap();
    let out = std::process::Command::new(chromium())
        .args(["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--no-pdf-header-footer"])
        .arg(format!("--user-data-dir={}", profile.path().display()))
        .arg(format!("--print-to-pdf={}", printed.display()))
        .arg(format!("file://{}", doc.display()))
        .output()
        .unwrap();
    assert!(printed.is_file(), "chromium printed nothing:\n{}", String::from_utf8_lossy(&out.stderr));
    let n = pdf_pages(&ours);
    assert_eq!(n, svgs.len());
    assert_eq!(pdf_pages(&printed), n, "a printed sheet per page");
    let ((w, h), (w0, h0)) = (pdf_page_size(&printed), pdf_page_size(&ours));
    // A3 landscape, 420 × 297 mm = 1190.55 × 841.89 pt; Chromium rounds the sheet to its
    // pixels (1/96 in = 0.75 pt), the drawing is not scaled.
    assert!(
        (w - w0).abs() < 0.75 && (h - h0).abs() < 0.75 && (w0 - 1190.55).abs() < 0.1,
        "{w} × {h} pt, ours {w0} × {h0}"
    );
    for page in 1..=n {
        assert_eq!(pdf_words(&printed, page), pdf_words(&ours, page), "page {page}'s words");
        // Printed at 100 %: the words that are once on the page start where the PDF's do
        // (the median x to 0.5 pt: a sheet scaled by 1 % would move them by pt; a centred or
        // right-aligned text moves by the difference of the browser's and our width of it;
        // y within the two fonts' different ascents, which set a box's top).
        let (a, b) = (word_boxes(&printed, page), word_boxes(&ours, page));
        let mut dx = Vec::new();
        for (word, at) in &a {
            let (Some(there), 1, 1) = (
                b.iter().find(|(v, _)| v == word),
                a.iter().filter(|(v, _)| v == word).count(),
                b.iter().filter(|(v, _)| v == word).count(),
            ) else {
                continue;
            };
            dx.push((at.0 - there.1.0).abs());
            assert!((at.1 - there.1.1).abs() < 5.0, "page {page} {word}: {at:?} printed, {:?} ours", there.1);
        }
        dx.sort_by(f64::total_cmp);
        let compared = dx.len();
        assert!(compared > 10, "page {page}: {compared} words compared");
        assert!(dx[compared / 2] < 0.5, "page {page}: the words' x moved by {} pt (median)", dx[compared / 2]);
    }
}

/// Page `page`'s words with where each starts (poppler's `pdftotext -bbox`: x from the left,
/// y of the top from the top, pt).
fn word_boxes(pdf: &Path, page: usize) -> Vec<(String, (f64, f64))> {
    let p = page.to_string();
    let out =
        std::process::Command::new("pdftotext").args(["-bbox", "-f", &p, "-l", &p]).arg(pdf).arg("-").output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    let attr = |l: &str, k: &str| -> f64 {
        let i = l.find(&format!("{k}=\"")).unwrap() + k.len() + 2;
        l[i..].split('"').next().unwrap().parse().unwrap()
    };
    text.lines()
        .filter(|l| l.trim_start().starts_with("<word "))
        .map(|l| {
            let word = l.split('>').nth(1).unwrap_or("").split('<').next().unwrap_or("").to_string();
            (word, (attr(l, "xMin"), attr(l, "yMin")))
        })
        .collect()
}

/// `s` holds a number in e-notation (`1.3e-10`, `2.777e0`, `5E+3`).
fn e_notation(s: &str) -> bool {
    let b = s.as_bytes();
    (1..b.len()).any(|i| {
        (b[i] == b'e' || b[i] == b'E') && b[i - 1].is_ascii_digit() && {
            let rest = &b[i + 1..];
            let rest = rest.strip_prefix(b"-").or_else(|| rest.strip_prefix(b"+")).unwrap_or(rest);
            rest.first().is_some_and(u8::is_ascii_digit)
        }
    })
}

#[test]
fn no_report_page_writes_a_number_in_e_notation_or_not_a_number() {
    assert!(e_notation("|R| = 1.32e-10 mm") && e_notation("2.777e0") && !e_notation("the 3 ends") && !e_notation("e2"));
    let mut found = Vec::new();
    for t in common::template_paths() {
        let loaded = scene::load(&t, &[]).unwrap();
        // A synthesis scene has no report of its own: its design's is (tests/report.rs, bad input).
        if matches!(loaded.scene, scene::Scene::Synthesis(_)) {
            continue;
        }
        let r = report(&loaded, &ReportOptions::default()).unwrap();
        for p in &r.pages {
            for b in common::text_boxes(&p.drawing) {
                let v = &b.value;
                // A law or a load as the scene writes it (`-2.5e6*(1 - t/0.09375)`) is quoted.
                let quoted = v.contains('*');
                if (e_notation(v) && !quoted) || v.contains("NaN") || v.contains("inf") {
                    found.push(format!("{} {}: {v}", r.name, p.stem));
                }
            }
        }
    }
    assert!(found.is_empty(), "{found:#?}");
}

/// A parallelogram four-bar with a third crank between its coupler and the ground: the
/// classical redundant (passive) link.
const PARALLELOGRAM: &str = r#"
kind = "linkage"
name = "parallelogram"
units = "SI"
time = { from = 0.0, to = 0.1, steps = 10 }
[ground]
points = { O1 = [0.0, 0.0], C = [0.08, 0.0], D = [0.04, 0.0] }
[[body]]
name = "crank"
points = { O1 = [0.0, 0.0], A = [0.0, 0.04] }
[[body]]
name = "coupler"
points = { A = [0.0, 0.0], B = [0.08, 0.0], E = [0.04, 0.0] }
at = [0.0, 0.04]
[[body]]
name = "rocker"
points = { C = [0.0, 0.0], B = [0.0, 0.04] }
at = [0.08, 0.0]
[[body]]
name = "extra"
points = { D = [0.0, 0.0], E = [0.0, 0.04] }
at = [0.04, 0.0]
[[joint]]
revolute = ["ground.O1", "crank.O1"]
[[joint]]
revolute = ["crank.A", "coupler.A"]
[[joint]]
revolute = ["coupler.B", "rocker.B"]
[[joint]]
revolute = ["ground.C", "rocker.C"]
[[joint]]
revolute = ["ground.D", "extra.D"]
[[joint]]
revolute = ["coupler.E", "extra.E"]
[[driver]]
body = "crank"
law = "10*t"
"#;

#[test]
fn a_redundant_link_gets_its_structure_with_the_formulas_value_the_solvers_and_why_they_differ() {
    // M = 3·4 − 2·6 − 0 = 0 by the formula; at the placement the joints' rank is 11 (the
    // third crank repeats one equation of the parallelogram), so they leave 12 − 11 = 1
    // degree of freedom, the one the driver takes. `mechdraw run` refuses it (the solver
    // needs independent joints); the report draws its title page, its structure and its
    // kinematic diagram (3 pages), says why the two mobilities differ and why it stops.
    let dir = common::root().join("target/test-report/redundant");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("parallelogram.toml");
    std::fs::write(&scene, PARALLELOGRAM).unwrap();
    // `run` still refuses it, pointing at the report.
    let o = common::mechdraw().arg("run").arg(&scene).arg("--out").arg(dir.join("run")).output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    for s in
        ["0 degrees of freedom", "3 × 4 bodies − 2 × 6 joints", "leave 1", "12 − 11", "redundant", "mechdraw report"]
    {
        assert!(err.contains(s), "`{s}` not in: {err}");
    }
    assert!(!dir.join("run").exists(), "nothing written");
    // The report: exit 0, three pages.
    let out = dir.join("out");
    let o = common::mechdraw().arg("report").arg(&scene).arg("--out").arg(&out).output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert!(err.contains("redundant link") && err.contains("3 pages"), "{err}");
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("parallelogram-report.json")).unwrap()).unwrap();
    assert_eq!(json["kind"]["mobility"], 0, "{json}");
    assert_eq!(json["kind"]["mobility_at_placement"], 1, "{json}");
    assert_eq!(json["kind"]["redundant"], 1, "{json}");
    assert_eq!(json["pages"], 3, "{json}");
    let svgs: Vec<String> = std::fs::read_dir(out.join("report/parallelogram"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    let mut svgs = svgs;
    svgs.sort();
    assert_eq!(svgs, ["01-title.svg", "02-structure.svg", "03-kinematic.svg"]);
    assert!(out.join("parallelogram-report.pdf").is_file());
    // The structure page, through the library: the counts, both mobilities, the passive link.
    let parsed =
        scene::parse_with(PARALLELOGRAM, "parallelogram.toml", &[], scene::linkage::Redundancy::Accepted).unwrap();
    assert!(scene::parse(PARALLELOGRAM, "parallelogram.toml", &[]).is_err(), "refused by default");
    let loaded = scene::Loaded { path: scene.clone(), scene: parsed, text: PARALLELOGRAM.into() };
    let r = report(&loaded, &ReportOptions::default()).unwrap();
    assert_eq!(r.pages.len(), 3);
    // The words as read, whatever the panel's width wraps where.
    let text = common::texts(&r.pages[1].drawing).join(" ").split_whitespace().collect::<Vec<_>>().join(" ");
    for s in [
        "n = 4 moving links",
        "p₅ = 6 lower pairs",
        "M = 3·4 − 2·6 − 0 = 0",
        "leave 1 degree of freedom",
        "12 − 11",
        "repeat others",
        "stops at the structure",
        "passive link (4)",
        "W = 3·1 − 2·2 = −1",
        "I(0,1) → II(2,3) → passive(4)",
    ] {
        assert!(text.contains(s), "`{s}` not on the structure page: {text}");
    }
    // `--positions` has nothing to choose from: refused, nothing written.
    let out2 = dir.join("out2");
    let o = common::mechdraw()
        .args(["report", scene.to_str().unwrap(), "--positions", "0", "--out", out2.to_str().unwrap()])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("--positions") && err.contains("redundant link"), "{err}");
    assert!(!out2.exists(), "nothing written");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The arrows drawn on layer `layer` of `d`, as vectors (paper mm).
fn arrow_vectors(d: &Drawing, layer: &str) -> Vec<(f64, f64)> {
    d.entities
        .iter()
        .filter(|e| d.layers[e.layer].name == layer)
        .filter_map(|e| match &e.shape {
            Shape::Arrow { from, to, .. } => Some((to.x - from.x, to.y - from.y)),
            _ => None,
        })
        .collect()
}

#[test]
fn the_free_body_figures_draw_every_reaction_of_the_table_to_their_printed_k_f() {
    for name in ["shaper-forces", "slider-crank"] {
        let r = report_of(name, None);
        let (header, rows) = table(&r);
        let col = |name: &str| header.iter().position(|h| h == name).unwrap_or_else(|| panic!("{name}")) - 1;
        let loaded = scene::load(&template(name), &[]).unwrap();
        let Scene::Linkage(s) = &loaded.scene else { panic!() };
        let st = Structure::of(&s.mechanism, None);
        // A joint between two links of one group has no arrow (its reactions cancel there).
        let inside = |j: &mechdraw::solve::linkage::Joint| {
            let bodies = match j.kind {
                mechdraw::solve::linkage::JointKind::Revolute { a, b } => [a.body, b.body],
                mechdraw::solve::linkage::JointKind::Prismatic { point, q1, .. } => [q1.body, point.body],
            };
            st.groups.iter().any(|g| {
                bodies
                    .iter()
                    .all(|x| matches!(x, mechdraw::solve::linkage::Attach::Body(i) if g.group.bodies.contains(i)))
            })
        };
        let pages = position_pages(&r);
        assert_eq!(pages.len(), rows.len());
        let mut checked = 0;
        for ((mark, row), pages) in rows.iter().zip(&pages) {
            let fb = pages.last().unwrap();
            let ks = printed_scales(fb, "F");
            assert_eq!(ks.len().min(1), 1, "{name} position {mark}: k_F printed");
            let arrows = arrow_vectors(fb, "FORCES");
            for j in s.mechanism.joints.iter().filter(|j| !inside(j)) {
                let (fx, fy) = (row[col(&format!("{}.Fx", j.name))], row[col(&format!("{}.Fy", j.name))]);
                let value = libm::hypot(fx, fy);
                if value < 1e-9 {
                    continue;
                }
                // The reaction on either of its links: +R or −R, componentwise to 1e-9.
                let found = arrows.iter().any(|(x, y)| {
                    ks.iter().any(|k| {
                        [1.0, -1.0].iter().any(|sg| libm::hypot(sg * x * k - fx, sg * y * k - fy) <= 1e-9 * value)
                    })
                });
                assert!(found, "{name} position {mark}: R_{} = ({fx}, {fy}) not drawn at a printed k_F", j.name);
                checked += 1;
            }
        }
        assert!(checked >= 2 * rows.len(), "{name}: {checked} reactions checked");
    }
}

#[test]
fn the_four_bars_free_body_figures_draw_its_reactions_to_their_printed_k_f() {
    let r = report_of("fourbar-chebyshev", None);
    let (header, rows) = table(&r);
    let col = |name: &str| header.iter().position(|h| h == name).unwrap_or_else(|| panic!("{name}")) - 1;
    let pages = position_pages(&r);
    assert_eq!(pages.len(), rows.len());
    for ((mark, row), pages) in rows.iter().zip(&pages) {
        let fb = pages.last().unwrap();
        let ks = printed_scales(fb, "F");
        assert!(!ks.is_empty(), "position {mark}: k_F printed");
        let arrows = arrow_vectors(fb, "FORCES");
        // R_B is inside the dyad: not drawn. R_A on both groups (−R_A on the crank).
        for (reaction, signs) in [("R_A", &[1.0, -1.0][..]), ("R_C", &[1.0][..]), ("R_O", &[1.0][..])] {
            let (fx, fy) = (row[col(&format!("{reaction}_x"))], row[col(&format!("{reaction}_y"))]);
            let value = libm::hypot(fx, fy);
            for sg in signs {
                let found = arrows
                    .iter()
                    .any(|(x, y)| ks.iter().any(|k| libm::hypot(x * k - sg * fx, y * k - sg * fy) <= 1e-9 * value));
                assert!(found, "position {mark}: {sg}·{reaction} = ({fx}, {fy}) not drawn at a printed k_F {ks:?}");
            }
        }
    }
}

#[test]
fn each_groups_free_body_is_in_equilibrium_with_its_couples() {
    use mechdraw::figure::linkage::forces::body_forces;
    use mechdraw::figure::report::freebody::{body_couples, group_loads};
    for name in ["shaper-forces", "slider-crank"] {
        let loaded = scene::load(&template(name), &[]).unwrap();
        let Scene::Linkage(s) = &loaded.scene else { panic!() };
        let dynamics = s.dynamics.as_ref().unwrap();
        let mut solver = mechdraw::solve::linkage::Solver::new(s.mechanism.clone()).unwrap();
        let (states, forces) = solver.run_kinetostatics(&s.times, dynamics).unwrap();
        let st = Structure::of(&s.mechanism, Some(&states[0].q));
        let m = dynamics.length_unit_m;
        for k in (0..states.len()).step_by(states.len() / 7 + 1) {
            let bf = body_forces(&s.mechanism, dynamics, &states[k], &forces[k]);
            let bc = body_couples(&s.mechanism, dynamics, &states[k], &forces[k]);
            for g in &st.groups {
                let loads = group_loads(&s.mechanism, g, &bf, &bc);
                let (mut sx, mut sy, mut sm, mut scale) = (0.0, 0.0, 0.0, 0.0f64);
                for (p, nv) in &loads.forces {
                    sx += nv.v.x;
                    sy += nv.v.y;
                    // About the origin, N·m.
                    let mz = m * (p.x * nv.v.y - p.y * nv.v.x);
                    sm += mz;
                    scale = scale.max(nv.v.norm()).max(mz.abs());
                }
                for c in &loads.couples {
                    sm += c.value;
                    scale = scale.max(c.value.abs());
                }
                assert!(
                    libm::hypot(sx, sy) <= 1e-9 * scale && sm.abs() <= 1e-9 * scale,
                    "{name} sample {k} {:?}: ΣF = ({sx}, {sy}), ΣM = {sm} (scale {scale})",
                    g.group.bodies
                );
            }
        }
    }
}

/// No text of a report is cut: a caption too long for its panel's title puts the rest on
/// lines under it (the triad's modes page cut its angles, `φ3 117.0…`, before 28 Nov 2026).
#[test]
fn no_text_of_a_report_is_cut() {
    for name in ["triad-popa", "fourbar-chebyshev", "shaper-forces", "chain-humienny-2"] {
        let r = report_of(name, None);
        for (i, p) in r.pages.iter().enumerate() {
            for t in common::texts(&p.drawing) {
                assert!(!t.ends_with('…'), "{name} page {}: \"{t}\" is cut", i + 1);
            }
        }
    }
    // The modes' angles are all there, in each mode's title or on lines under it (its
    // panel wide enough for the whole caption since the page takes a 3 × 3 grid).
    let r = report_of("triad-popa", None);
    let texts: Vec<String> = r.pages.iter().flat_map(|p| common::texts(&p.drawing)).collect();
    assert!(texts.iter().any(|t| t.starts_with("Mode 1 · ccw")), "{texts:?}");
    assert!(texts.iter().any(|t| t.contains("φ1 75.77° φ2 102.23° φ3 117.04°")), "{texts:?}");
}
