//! Printed sheets (`--sheets a4|a3`, issue 14 item 3, issue 31), checked on the template
//! four-bar every 30° (12 positions): the PDF has a set of three pages per position (the
//! mechanism, the polygons, the forces) and each page carries its φ1 and what it shows (read
//! back with poppler's `pdftotext`); every sheet SVG is 297 × 210 mm (420 × 297); every
//! polygon fills at least half of its panel's area, measured on the sheet's drawing; the
//! value table's numbers are the solver's (the JSON records') to the printed digits; a
//! length measured on a sheet times the scale printed in its panel is the value (k_v × mm =
//! |v|); every panel has a scale bar as long as its value; the files on disk are the
//! in-memory bytes; golden PNGs of the three pages at φ1 = 90°.

#![allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the library calls"
)]

mod common;

use mechdraw::figure::shared::sheet::read_number;
use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

use mechdraw::draw::{Bounds, Drawing, Shape};
use mechdraw::figure::shared::sheet::{Panel, Paper};
use mechdraw::geom::Point;
use mechdraw::run::RunOptions;
use mechdraw::run::bytes::{self, WriteOptions};
use mechdraw::run::products::Products;
use mechdraw::scene::{self, Override};

const NAME: &str = "fourbar-chebyshev";

fn loaded(step: &str) -> scene::Loaded {
    let over: Vec<Override> = [format!("phi1_deg.step={step}")].iter().map(|s| s.parse().unwrap()).collect();
    scene::load(&common::root().join("templates/fourbar-chebyshev.toml"), &over).unwrap()
}

fn products(paper: Paper) -> (scene::Loaded, Products) {
    let l = loaded("30");
    let p = mechdraw::run::products(&l, &RunOptions { sheets: Some(paper), ..RunOptions::default() }).unwrap();
    (l, p)
}

/// The pages of one kind (`mechanism`, `polygons`, `forces`), in order.
fn pages_of<'a>(p: &'a Products, kind: &str) -> Vec<&'a mechdraw::run::products::Page> {
    p.pages.iter().filter(|g| g.stem.ends_with(&format!("-{kind}"))).collect()
}

/// Crank angles of the run, degrees, as the JSON records give them.
fn angles(p: &Products) -> Vec<f64> {
    p.summary["positions"].as_array().unwrap().iter().map(|r| r["phi1_deg"].as_f64().unwrap()).collect()
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs poppler-utils (pdfinfo, pdftotext): bash .ci/test, or cargo test --features system-tools"
)]
fn the_pdf_has_a_page_per_position_each_with_its_crank_angle() {
    let l = loaded("30");
    let tmp = tempfile::tempdir().unwrap();
    let opts = RunOptions { out_dir: Some(tmp.path().to_path_buf()), sheets: Some(Paper::A4), ..RunOptions::default() };
    let outcome = mechdraw::run::run(&l, &opts).unwrap();
    let pdf = tmp.path().join(format!("{NAME}-sheets.pdf"));
    assert!(outcome.written.contains(&pdf), "{pdf:?} not written");
    let info = Command::new("pdfinfo").arg(&pdf).output().expect("run pdfinfo (poppler-utils)");
    let info = String::from_utf8_lossy(&info.stdout);
    let field = |k: &str| info.lines().find_map(|l| l.strip_prefix(k)).map(str::trim).unwrap_or("").to_string();
    assert_eq!(field("Pages:"), "36", "{info}");
    // True size: 297 × 210 mm is 841.89 × 595.276 pt.
    assert!(field("Page size:").starts_with("841.89 x 595.276 pts"), "{info}");
    let products = mechdraw::run::products(&l, &opts).unwrap();
    for (i, deg) in angles(&products).iter().enumerate() {
        for (j, shows) in [
            // The text as drawn: k_l (a subscript l) reads `kl` (tests/subscripts.rs).
            &["kl = 0.0015 m/mm", "ω1 = 20 rad/s", "Me1", "forces kf = "][..],
            &["Velocity polygon", "kv = ", "Acceleration polygon", "ka = "][..],
            &["Dyad 2–3", "Crank 1", "kf = "][..],
        ]
        .iter()
        .enumerate()
        {
            let page = (3 * i + j + 1).to_string();
            let out = Command::new("pdftotext")
                .args(["-f", &page, "-l", &page, "-layout"])
                .arg(&pdf)
                .arg("-")
                .output()
                .expect("run pdftotext (poppler-utils)");
            let text = String::from_utf8_lossy(&out.stdout);
            let want = format!("φ1 = {}°", deg.round() as i64);
            assert!(text.contains(&want), "page {page} lacks `{want}`:\n{text}");
            assert!(text.contains(&format!("sheet {page} of 36")), "page {page}:\n{text}");
            for k in *shows {
                assert!(text.contains(k), "page {page} lacks `{k}`:\n{text}");
            }
        }
    }
}

#[test]
fn sheet_svgs_are_true_size_paper() {
    for (paper, w, h) in [(Paper::A4, 297, 210), (Paper::A3, 420, 297)] {
        let (_, p) = products(paper);
        let files = bytes::to_files(&p, &WriteOptions::default()).unwrap();
        let sheets: Vec<&(String, Vec<u8>)> = files.iter().filter(|(n, _)| n.starts_with("sheets/")).collect();
        assert_eq!(sheets.len(), 36);
        assert_eq!(sheets[9].0, format!("sheets/{NAME}/pos_090-mechanism.svg"));
        for (n, b) in sheets {
            let s = std::str::from_utf8(b).unwrap();
            let head = &s[..s.find('>').unwrap()];
            assert!(head.contains(&format!(r#"width="{w}mm""#)), "{n}: {head}");
            assert!(head.contains(&format!(r#"height="{h}mm""#)), "{n}: {head}");
            assert!(head.contains(&format!(r#"viewBox="0 -{h} {w} {h}""#)), "{n}: {head}");
        }
    }
}

/// The SHEET layer's panel frames (thin closed rectangles) of a page.
fn panel_frames(d: &Drawing) -> Vec<Bounds> {
    let sheet = d.layers.iter().position(|l| l.name == "SHEET").unwrap();
    d.entities
        .iter()
        .filter(|e| e.layer == sheet)
        .filter_map(|e| match &e.shape {
            Shape::Polyline { points, closed: true, width } if *width == 0.0 && points.len() == 4 => {
                let xs = points.iter().map(|p| p.x);
                let ys = points.iter().map(|p| p.y);
                Some(Bounds {
                    min: Point::new(xs.clone().fold(f64::INFINITY, f64::min), ys.clone().fold(f64::INFINITY, f64::min)),
                    max: Point::new(xs.fold(f64::NEG_INFINITY, f64::max), ys.fold(f64::NEG_INFINITY, f64::max)),
                })
            }
            _ => None,
        })
        .collect()
}

/// The box of the lines and arrows (not the letters) on `layer`.
fn drawn_extent(d: &Drawing, layer: &str) -> Option<Bounds> {
    let l = d.layers.iter().position(|x| x.name == layer)?;
    let mut pts = Vec::new();
    for e in d.entities.iter().filter(|e| e.layer == l) {
        match &e.shape {
            Shape::Arrow { from, to, .. } | Shape::Line { from, to } => pts.extend([*from, *to]),
            Shape::Polyline { points, .. } => pts.extend(points.iter().copied()),
            _ => {}
        }
    }
    let first = *pts.first()?;
    Some(pts.iter().fold(Bounds { min: first, max: first }, |b, p| Bounds {
        min: Point::new(b.min.x.min(p.x), b.min.y.min(p.y)),
        max: Point::new(b.max.x.max(p.x), b.max.y.max(p.y)),
    }))
}

#[test]
fn every_polygon_fills_at_least_half_of_its_panel_less_its_letters() {
    for paper in [Paper::A4, Paper::A3] {
        let (_, p) = products(paper);
        assert_eq!(p.pages.len(), 36);
        let mut fills = Vec::new();
        for page in pages_of(&p, "polygons") {
            let frames = panel_frames(&page.drawing);
            assert_eq!(frames.len(), 2, "{}: the two polygons' panels", page.stem);
            for layer in ["VELOCITY", "ACCELERATION"] {
                let e = drawn_extent(&page.drawing, layer).unwrap_or_else(|| panic!("{}: no {layer}", page.stem));
                let mid = Point::new((e.min.x + e.max.x) / 2.0, (e.min.y + e.max.y) / 2.0);
                let frame = frames
                    .iter()
                    .find(|f| mid.x > f.min.x && mid.x < f.max.x && mid.y > f.min.y && mid.y < f.max.y)
                    .unwrap_or_else(|| panic!("{}: {layer} is in no panel", page.stem));
                let area = Panel::of_outline(*frame, paper.sizes()).area;
                // Fitted to the area less room for the letters at its outer points.
                let room = 2.0 * mechdraw::figure::shared::sheet_pages::LETTER_ROOM * paper.sizes().text;
                let (w, h) =
                    ((area.width() - room).max(0.5 * area.width()), (area.height() - room).max(0.5 * area.height()));
                let fill = (e.width() / w).max(e.height() / h);
                // At least half; at most the whole area (plus an arrowhead's half width).
                assert!(fill >= 0.5, "{} {}: {layer} fills {fill:.3} of its panel", paper.name(), page.stem);
                let slack = 0.5 * paper.sizes().head;
                assert!(
                    e.min.x >= area.min.x - slack
                        && e.max.x <= area.max.x + slack
                        && e.min.y >= area.min.y - slack
                        && e.max.y <= area.max.y + slack,
                    "{} {}: {layer} {e:?} leaves its area {area:?}",
                    paper.name(),
                    page.stem
                );
                fills.push(fill);
            }
        }
        let mean = fills.iter().sum::<f64>() / fills.len() as f64;
        eprintln!(
            "{}: polygon fills {:.2}…{:.2}, mean {mean:.2}",
            paper.name(),
            fills.iter().cloned().fold(1.0, f64::min),
            fills.iter().cloned().fold(0.0, f64::max)
        );
        assert!((0.55..0.85).contains(&mean), "about two thirds on average: {mean}");
    }
}

/// The table's rows on a page: name → the other cells, read from the SHEET layer's texts
/// (cells of one row share their baseline).
fn table_rows(d: &Drawing) -> BTreeMap<String, Vec<String>> {
    let sheet = d.layers.iter().position(|l| l.name == "SHEET").unwrap();
    let mut rows: BTreeMap<i64, Vec<(f64, String)>> = BTreeMap::new();
    for e in d.entities.iter().filter(|e| e.layer == sheet) {
        if let Shape::Text { at, value, .. } = &e.shape {
            rows.entry((at.y * 1000.0).round() as i64).or_default().push((at.x, value.clone()));
        }
    }
    rows.into_values()
        .filter_map(|mut cells| {
            cells.sort_by(|a, b| a.0.total_cmp(&b.0));
            let mut it = cells.into_iter().map(|c| c.1);
            let name = it.next()?;
            Some((name, it.collect()))
        })
        .collect()
}

/// `printed` equals `value` to its printed digits (half a unit in the last place).
fn agrees(printed: &str, value: f64) -> bool {
    let p: f64 = read_number(printed).unwrap_or_else(|| panic!("not a number: {printed}"));
    let (mantissa, exp) = printed.split_once('e').map_or((printed, 0), |(m, e)| (m, e.parse::<i32>().unwrap()));
    let decimals = mantissa.split_once('.').map_or(0, |(_, d)| d.len()) as i32;
    (p - value).abs() <= 0.5 * 10f64.powi(exp - decimals) * (1.0 + 1e-9)
}

#[test]
fn the_value_table_is_the_solvers() {
    let (_, p) = products(Paper::A4);
    let records = p.summary["positions"].as_array().unwrap();
    let mut checked = 0;
    for (page, rec) in pages_of(&p, "mechanism").into_iter().zip(records) {
        let rows = table_rows(&page.drawing);
        let scalar = |row: &str, key: &str| {
            let cells = &rows[row];
            let v = rec[key].as_f64().unwrap();
            assert!(agrees(cells[2].as_str(), v), "{}: {row} printed {} for {v}", page.stem, cells[2]);
        };
        scalar("φ1", "phi1_deg");
        scalar("ω2", "omega2");
        scalar("ε3", "eps3");
        scalar("Me1", "Me1");
        checked += 4;
        for (row, key) in [("A", "A"), ("M", "M"), ("vB", "vB"), ("aM", "aM"), ("RA", "R_A"), ("RO", "R_O")] {
            let cells = &rows[row];
            let v = rec[key].as_array().unwrap();
            for c in 0..2 {
                let want = v[c].as_f64().unwrap();
                assert!(agrees(&cells[c], want), "{}: {row}[{c}] printed {} for {want}", page.stem, cells[c]);
            }
            if let Some(mag) = rec.get(format!("{key}_mag")) {
                assert!(agrees(&cells[2], mag.as_f64().unwrap()), "{}: |{row}| printed {}", page.stem, cells[2]);
            }
            checked += 1;
        }
        assert_eq!(rows["RB"].last().map(String::as_str), Some("N"));
        assert_eq!(rows["Me1"].last().map(String::as_str), Some("N·m"));
    }
    assert_eq!(checked, 12 * 10);
}

#[test]
fn files_on_disk_are_the_in_memory_bytes_with_sheets() {
    let l = loaded("60");
    let tmp = tempfile::tempdir().unwrap();
    let opts = RunOptions { out_dir: Some(tmp.path().to_path_buf()), sheets: Some(Paper::A3), ..RunOptions::default() };
    let outcome = mechdraw::run::run(&l, &opts).unwrap();
    let memory = bytes::to_files(&mechdraw::run::products(&l, &opts).unwrap(), &WriteOptions::default()).unwrap();
    let mut disk = Vec::new();
    common::read_tree(tmp.path(), Path::new(""), &mut disk);
    common::take_live_page(&mut disk, NAME);
    disk.sort();
    let mut mem = memory.clone();
    mem.sort();
    assert_eq!(disk.len(), mem.len());
    for ((dn, db), (mn, mb)) in disk.iter().zip(&mem) {
        assert_eq!(dn, mn);
        assert!(db == mb, "{dn} differs between disk and memory");
    }
    let written: Vec<String> = outcome
        .written
        .iter()
        .map(|p| p.strip_prefix(tmp.path()).unwrap().to_string_lossy().replace('\\', "/"))
        .collect();
    let page = format!("{NAME}.html");
    let order: Vec<&str> = memory.iter().map(|(n, _)| n.as_str()).chain([page.as_str()]).collect();
    assert_eq!(written, order);
    assert!(
        order.contains(&format!("{NAME}-sheets.pdf").as_str())
            && order.contains(&format!("sheets/{NAME}/pos_120-mechanism.svg").as_str())
            && order.contains(&format!("sheets/{NAME}/pos_120-polygons.svg").as_str())
            && order.contains(&format!("sheets/{NAME}/pos_120-forces.svg").as_str())
    );
}

#[test]
fn chain_and_triad_scenes_have_no_sheets() {
    let l = scene::load(&common::root().join("templates/chain-humienny-2.toml"), &[]).unwrap();
    let err =
        mechdraw::run::products(&l, &RunOptions { sheets: Some(Paper::A4), ..RunOptions::default() }).unwrap_err();
    assert!(err.to_string().contains("--sheets"), "{err}");
    assert_eq!(err.exit_code(), 2);
}

/// The A4 page `kind` at φ1 = 90° against its golden PNG.
fn golden_page(kind: &str) {
    let (_, p) = products(Paper::A4);
    let stem = format!("pos_090-{kind}");
    let page = p.pages.iter().find(|pg| pg.stem == stem).unwrap();
    let files = bytes::to_files(&p, &WriteOptions::default()).unwrap();
    let svg = &files.iter().find(|(n, _)| *n == format!("sheets/{NAME}/{stem}.svg")).unwrap().1;
    assert_eq!(page.window, Paper::A4.bounds());
    common::assert_golden_png(&format!("fourbar/sheet_a4_090_{kind}.png"), std::str::from_utf8(svg).unwrap());
}

#[test]
fn golden_mechanism_sheet_at_90_degrees() {
    golden_page("mechanism");
}

#[test]
fn golden_polygons_sheet_at_90_degrees() {
    golden_page("polygons");
}

#[test]
fn golden_forces_sheet_at_90_degrees() {
    golden_page("forces");
}

/// The scale printed in the title of the panel named `title` (`k_v = 0.02 (m/s)/mm` → 0.02).
fn printed_scale(d: &Drawing, title: &str) -> f64 {
    d.entities
        .iter()
        .find_map(|e| match &e.shape {
            Shape::Text { value, .. } if value.starts_with(title) => {
                let after = value.split(" = ").nth(1)?;
                after.split(' ').next()?.parse().ok()
            }
            _ => None,
        })
        .unwrap_or_else(|| panic!("no panel titled {title}"))
}

/// The longest arrow drawn from the pole on `layer`, paper mm.
fn longest_from_pole(d: &Drawing, layer: &str) -> f64 {
    let l = d.layers.iter().position(|x| x.name == layer).unwrap();
    let on: Vec<&Shape> = d.entities.iter().filter(|e| e.layer == l).map(|e| &e.shape).collect();
    // The pole: the point most arrows start from (the layer's circles are the pole and the
    // centroid images' marks, so a circle alone does not tell it).
    let tails: Vec<Point> = on
        .iter()
        .filter_map(|s| match s {
            Shape::Arrow { from, .. } => Some(*from),
            _ => None,
        })
        .collect();
    let starting_at = |p: &Point| tails.iter().filter(|q| (**q - *p).norm() < 1e-9).count();
    let pole = *tails.iter().max_by_key(|p| starting_at(p)).unwrap();
    on.iter()
        .filter_map(|s| match s {
            Shape::Arrow { from, to, .. } if (*from - pole).norm() < 1e-9 => Some((*to - *from).norm()),
            _ => None,
        })
        .fold(0.0, f64::max)
}

#[test]
fn a_length_measured_on_the_sheet_times_its_printed_scale_is_the_value() {
    let (_, p) = products(Paper::A4);
    let records = p.summary["positions"].as_array().unwrap();
    for (page, rec) in pages_of(&p, "polygons").into_iter().zip(records) {
        let d = &page.drawing;
        let largest =
            |keys: [&str; 3]| keys.iter().map(|k| rec[format!("{k}_mag")].as_f64().unwrap()).fold(0.0, f64::max);
        let k_v = printed_scale(d, "Velocity polygon");
        let v = largest(["vA", "vB", "vM"]);
        assert!((longest_from_pole(d, "VELOCITY") * k_v - v).abs() < 1e-9 * v, "{}: k_v × mm ≠ |v|", page.stem);
        let k_a = printed_scale(d, "Acceleration polygon");
        let a = largest(["aA", "aB", "aM"]);
        assert!((longest_from_pole(d, "ACCELERATION") * k_a - a).abs() < 1e-9 * a, "{}: k_a × mm ≠ |a|", page.stem);
    }
}

#[test]
fn every_panel_of_every_page_has_a_scale_bar_whose_length_is_its_value() {
    let (_, p) = products(Paper::A4);
    for page in &p.pages {
        let d = &page.drawing;
        let dims = d.layers.iter().position(|x| x.name == "DIMENSIONS").unwrap();
        let texts: Vec<(Point, &str)> = d
            .entities
            .iter()
            .filter(|e| e.layer == dims)
            .filter_map(|e| match &e.shape {
                Shape::Text { at, value, .. } => Some((*at, value.as_str())),
                _ => None,
            })
            .collect();
        // A bar is its "0" and its label (value and unit) level with it.
        let zeros: Vec<Point> = texts.iter().filter(|(_, v)| *v == "0").map(|(at, _)| *at).collect();
        let panels: &[(&str, &str, &str)] = match page.stem.rsplit('-').next().unwrap() {
            "mechanism" => &[("Mechanism", "k_l", " m")],
            "polygons" => &[("Velocity polygon", "k_v", " m/s"), ("Acceleration polygon", "k_a", " m/s²")],
            _ => &[("Dyad 2–3", "k_f", " N"), ("Crank 1", "k_f", " N")],
        };
        assert_eq!(zeros.len(), panels.len(), "{}: one bar per panel", page.stem);
        let all: Vec<&str> = d
            .entities
            .iter()
            .filter_map(|e| match &e.shape {
                Shape::Text { value, .. } => Some(value.as_str()),
                _ => None,
            })
            .collect();
        for (title, symbol, unit) in panels {
            let heading =
                all.iter().find(|t| t.starts_with(title)).unwrap_or_else(|| panic!("{}: no {title}", page.stem));
            let k: f64 =
                heading.split(&format!("{symbol} = ")).nth(1).unwrap().split(' ').next().unwrap().parse().unwrap();
            // The bar's label on the level of a "0".
            let length = texts
                .iter()
                .filter(|(at, v)| v.ends_with(unit) && v.split(' ').count() == 2 && zeros.iter().any(|z| (z.y - at.y).abs() < 1e-9))
                .filter_map(|(_, v)| v.split(' ').next()?.parse::<f64>().ok())
                .map(|value| value / k)
                .find(|length| {
                    d.entities.iter().any(|e| {
                        e.layer == dims
                            && matches!(e.shape, Shape::Line { from, to } if ((to - from).norm() - length).abs() < 1e-9 && (to.y - from.y).abs() < 1e-12)
                    })
                });
            assert!(length.is_some(), "{}: no {title} bar at {symbol} = {k}", page.stem);
        }
    }
}
