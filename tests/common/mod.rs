//! Shared test harness: golden files (text and images), the ezdxf audit, the binary.
//!
//! Golden files live in `golden/`; `UPDATE_GOLDEN=1 cargo test` re-blesses them (look at
//! every re-blessed file before committing it: golden/README.md). A mismatch writes the
//! actual output (and for images a diff) under `target/golden-mismatch/`.

#![allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the library calls"
)]
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::Command;

pub mod tolerance;

/// Channel tolerance of the image comparison: a pixel differs when any channel differs
/// by more than this (as in resvg's own tests).
pub const PIXEL_CHANNEL_TOL: u8 = 1;
/// Fraction of pixels allowed to differ (anti-aliasing noise between machines): 2e-5, about
/// 20 pixels of an 800 × 1100 picture. Every golden renders with 0 differing pixels on the
/// machine that blessed them (28 Nov 2026); the earlier 1e-3 (≈ 1100 pixels) let a stale
/// golden pass whose only change was one subscript's underscore (244 pixels, e5afd67).
pub const PIXEL_FRACTION_TOL: f64 = 2e-5;
/// Width at which golden SVGs are rasterised.
pub const GOLDEN_WIDTH_PX: u32 = 800;

/// The repository root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// An SVG's text as read: the `<tspan …>` and `</tspan>` tags of subscripts taken out, so
/// that R_A reads `RA` and `k_v = 1` reads `kv = 1` (as the PDF's text does).
pub fn svg_plain(svg: &str) -> String {
    let mut out = String::with_capacity(svg.len());
    let mut rest = svg;
    while let Some(i) = [rest.find("<tspan"), rest.find("</tspan>")].into_iter().flatten().min() {
        out.push_str(&rest[..i]);
        let end = rest[i..].find('>').map_or(rest.len(), |j| i + j + 1);
        rest = &rest[end..];
    }
    out.push_str(rest);
    out
}

/// A DXF text as read: its `\U+XXXX` escapes (how R12 and R2000 write φ, °, →, −)
/// decoded; an escape that is not one stays as written.
#[allow(dead_code)]
pub fn dxf_unescape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    let mut rest = s;
    while let Some(i) = rest.find("\\U+") {
        out.push_str(&rest[..i]);
        match rest.get(i + 3..i + 7).and_then(|h| u32::from_str_radix(h, 16).ok()).and_then(char::from_u32) {
            Some(c) => {
                out.push(c);
                rest = &rest[i + 7..];
            }
            None => {
                out.push_str("\\U+");
                rest = &rest[i + 3..];
            }
        }
    }
    out.push_str(rest);
    out
}

fn update() -> bool {
    std::env::var_os("UPDATE_GOLDEN").is_some_and(|v| v == "1")
}

fn mismatch_dir() -> PathBuf {
    let d = root().join("target/golden-mismatch");
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Compares `actual` text with `golden/<name>` (line ends normalised).
pub fn assert_golden_text(name: &str, actual: &str) {
    let actual = actual.replace("\r\n", "\n");
    let path = root().join("golden").join(name);
    if update() {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, &actual).unwrap();
        eprintln!("re-blessed {}", path.display());
        return;
    }
    let expected = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| {
            panic!("golden file {} missing ({e}); run with UPDATE_GOLDEN=1 and look at it", path.display())
        })
        .replace("\r\n", "\n");
    if expected != actual {
        let out = mismatch_dir().join(name.replace('/', "_"));
        std::fs::write(&out, &actual).unwrap();
        let (i, (e, a)) = expected
            .lines()
            .zip(actual.lines())
            .enumerate()
            .find(|(_, (e, a))| e != a)
            .unwrap_or((expected.lines().count().min(actual.lines().count()), ("<end>", "<end>")));
        panic!(
            "{name} differs from its golden file at line {}:\n  golden: {e}\n  actual: {a}\nactual written to {}",
            i + 1,
            out.display()
        );
    }
}

/// Rasterises `svg` at [`GOLDEN_WIDTH_PX`] with the bundled font and compares it with
/// `golden/<name>` (a PNG) pixel by pixel.
pub fn assert_golden_png(name: &str, svg: &str) {
    use mechdraw::draw::raster;
    let actual = raster::render(svg, GOLDEN_WIDTH_PX).expect("rasterise");
    let path = root().join("golden").join(name);
    if update() {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        actual.save_png(&path).unwrap();
        eprintln!("re-blessed {}", path.display());
        return;
    }
    let expected = resvg::tiny_skia::Pixmap::load_png(&path).unwrap_or_else(|e| {
        panic!("golden image {} missing or unreadable ({e}); run with UPDATE_GOLDEN=1 and look at it", path.display())
    });
    let stem = name.replace('/', "_");
    if (expected.width(), expected.height()) != (actual.width(), actual.height()) {
        let out = mismatch_dir().join(format!("{stem}.actual.png"));
        actual.save_png(&out).unwrap();
        panic!(
            "{name}: size {}×{} differs from golden {}×{}; actual written to {}",
            actual.width(),
            actual.height(),
            expected.width(),
            expected.height(),
            out.display()
        );
    }
    let mut diff = resvg::tiny_skia::Pixmap::new(actual.width(), actual.height()).unwrap();
    let mut differing = 0usize;
    for ((e, a), d) in expected.pixels().iter().zip(actual.pixels()).zip(diff.pixels_mut()) {
        let (e, a) = (e.demultiply(), a.demultiply());
        let delta = [
            e.red().abs_diff(a.red()),
            e.green().abs_diff(a.green()),
            e.blue().abs_diff(a.blue()),
            e.alpha().abs_diff(a.alpha()),
        ];
        *d = if delta.iter().any(|&c| c > PIXEL_CHANNEL_TOL) {
            differing += 1;
            resvg::tiny_skia::PremultipliedColorU8::from_rgba(255, 0, 0, 255).unwrap()
        } else {
            resvg::tiny_skia::PremultipliedColorU8::from_rgba(255, 255, 255, 255).unwrap()
        };
    }
    let fraction = differing as f64 / (actual.width() * actual.height()) as f64;
    if fraction > PIXEL_FRACTION_TOL {
        let a = mismatch_dir().join(format!("{stem}.actual.png"));
        let d = mismatch_dir().join(format!("{stem}.diff.png"));
        actual.save_png(&a).unwrap();
        diff.save_png(&d).unwrap();
        panic!(
            "{name}: {differing} pixels ({:.3} %) differ by more than {PIXEL_CHANNEL_TOL} in a channel (allowed {:.3} %); see {} and {}",
            100.0 * fraction,
            100.0 * PIXEL_FRACTION_TOL,
            a.display(),
            d.display()
        );
    }
}

/// The Python interpreter that has ezdxf: `$MECHDRAW_PYTHON`, else the venv that
/// `.ci/test` creates (`target/venv`).
pub fn python() -> PathBuf {
    if let Some(p) = std::env::var_os("MECHDRAW_PYTHON") {
        return PathBuf::from(p);
    }
    root().join("target/venv/bin/python")
}

/// Audits DXF files with ezdxf (recover + audit): fails on any error or any fix, and on a
/// DIMENSION whose geometry block is missing. Needs the venv from `.ci/test`.
pub fn assert_ezdxf_clean(files: &[&Path]) {
    let py = python();
    assert!(
        py.exists(),
        "{} not found: run `bash .ci/test` once (it creates target/venv with ezdxf) or set MECHDRAW_PYTHON",
        py.display()
    );
    let out =
        Command::new(&py).arg(root().join("tests/ezdxf_audit.py")).args(files).output().expect("run the ezdxf audit");
    let text = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "ezdxf audit failed:\n{text}");
}

/// The mechdraw binary under test.
pub fn mechdraw() -> Command {
    Command::new(env!("CARGO_BIN_EXE_mechdraw"))
}

/// `a` and `b` agree to `rel` relative to the larger magnitude (or `floor`).
pub fn rel_close(a: f64, b: f64, rel: f64, floor: f64) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs()).max(floor)
}

/// The triad of seed 000 (Popa & Popa): O1(15, 30) R1 = 50, O2(90, 20) R2 = 60,
/// O3(150, 40) R3 = 84, l12 = 50, l23 = 50, l13 = 92 — the paper's published data.
pub fn seed_triad() -> mechdraw::solve::triad::Triad {
    use mechdraw::geom::Point;
    mechdraw::solve::triad::Triad::new(
        [Point::new(15.0, 30.0), Point::new(90.0, 20.0), Point::new(150.0, 40.0)],
        [50.0, 60.0, 84.0],
        50.0,
        50.0,
        92.0,
    )
    .expect("the seed's triad is valid")
}

/// A text of a drawing with its box as the font draws it (the bundled DejaVu Sans's advances,
/// from its deepest descender to its highest glyph: `mechdraw::draw::text_corners`, the
/// letter placer's measure), or, for a circled link number, its circle's square.
#[derive(Debug, Clone)]
pub struct TextBox {
    pub layer: String,
    pub value: String,
    pub at: mechdraw::geom::Point,
    pub halign: mechdraw::draw::HAlign,
    /// Lower-left and upper-right of the axis-aligned box holding it (turned with a turned
    /// text).
    pub min: mechdraw::geom::Point,
    pub max: mechdraw::geom::Point,
    /// Its rotation (radians) and its box in its own frame (unturned, from `at`): for
    /// strokes crossing it.
    pub rotation: f64,
    pub local: (mechdraw::geom::Vector, mechdraw::geom::Vector),
    /// Whether it is a circled link number (its box is its circle's square).
    pub circled: bool,
}

/// Every shape of `d` as drawn, with its layer: dimensions exploded into their parts.
pub fn drawn_shapes(d: &mechdraw::draw::Drawing) -> Vec<(String, mechdraw::draw::Shape)> {
    use mechdraw::draw::{Shape, parts};
    let mut out = Vec::new();
    for e in &d.entities {
        let layer = d.layers[e.layer].name.clone();
        match &e.shape {
            dim @ (Shape::AngularDimension { .. } | Shape::LinearDimension { .. }) => {
                out.extend(parts::explode_dimension(dim, &d.dim_style).into_iter().map(|s| (layer.clone(), s)))
            }
            // A scale caption as the paper states it.
            caption @ Shape::ScaleText { .. } => out.extend(caption.scale_text_in(None).map(|t| (layer, t))),
            other => out.push((layer, other.clone())),
        }
    }
    out
}

/// Every text of `d` with its box.
pub fn text_boxes(d: &mechdraw::draw::Drawing) -> Vec<TextBox> {
    use mechdraw::draw::Shape;
    use mechdraw::figure::shared::labels::CIRCLE_RADIUS;
    use mechdraw::geom::{Point, Vector};
    let shapes = drawn_shapes(d);
    let circles: Vec<(Point, f64)> = shapes
        .iter()
        .filter_map(|(_, s)| match s {
            Shape::Circle { center, radius } => Some((*center, *radius)),
            _ => None,
        })
        .collect();
    shapes
        .iter()
        .filter_map(|(layer, shape)| {
            let Shape::Text { at, height, value, halign, rotation, .. } = shape else { return None };
            let corners = mechdraw::draw::text_corners(shape)?;
            let (sin, cos) = rotation.sin_cos();
            let back = |p: Point| {
                let v = p - *at;
                Vector::new(cos * v.x + sin * v.y, -sin * v.x + cos * v.y)
            };
            let mut local = (back(corners[0]), back(corners[2]));
            let mut min = corners.iter().fold(corners[0], |m, c| Point::new(m.x.min(c.x), m.y.min(c.y)));
            let mut max = corners.iter().fold(corners[0], |m, c| Point::new(m.x.max(c.x), m.y.max(c.y)));
            let r = CIRCLE_RADIUS * height;
            let circled = circles.iter().any(|(c, cr)| *c == *at && (cr - r).abs() < 1e-12 * r);
            if circled {
                (min, max) = (*at - Vector::new(r, r), *at + Vector::new(r, r));
                local = (Vector::new(-r, -r), Vector::new(r, r));
            }
            Some(TextBox {
                layer: layer.clone(),
                value: value.clone(),
                at: *at,
                halign: *halign,
                min,
                max,
                rotation: *rotation,
                local,
                circled,
            })
        })
        .collect()
}

/// The pairs of texts of `d` whose boxes overlap (empty texts aside).
pub fn overlapping_texts(d: &mechdraw::draw::Drawing) -> Vec<(String, String)> {
    let t: Vec<TextBox> = text_boxes(d).into_iter().filter(|t| !t.value.trim().is_empty()).collect();
    let mut out = Vec::new();
    for (i, a) in t.iter().enumerate() {
        for b in &t[..i] {
            if boxes_overlap(a, b) {
                out.push((a.value.clone(), b.value.clone()));
            }
        }
    }
    out
}

/// Whether the boxes of two texts overlap.
pub fn boxes_overlap(a: &TextBox, b: &TextBox) -> bool {
    a.min.x < b.max.x && b.min.x < a.max.x && a.min.y < b.max.y && b.min.y < a.max.y
}

/// A stroke of a drawing: a straight piece of a line drawn `width` wide.
#[derive(Debug, Clone, Copy)]
pub struct Stroke {
    pub from: mechdraw::geom::Point,
    pub to: mechdraw::geom::Point,
    pub width: f64,
}

/// Every stroke of a shape as straight pieces (circles and arcs at 1° chords, the sides of
/// filled shapes and of arrowheads), none for a text.
pub fn strokes_of(shape: &mechdraw::draw::Shape) -> Vec<Stroke> {
    use mechdraw::draw::{Shape, parts};
    use mechdraw::geom::{Point, Vector};
    let seg = |from: Point, to: Point, width: f64| Stroke { from, to, width };
    let ring = |c: Point, r: f64, start: f64, sweep: f64| {
        // Chords of 2.5° at most: 0.02 % of the radius from the arc.
        let n = ((sweep.abs().to_degrees() / 2.5).ceil() as usize).max(1);
        let at = |k: usize| {
            let a = start + sweep * k as f64 / n as f64;
            c + Vector::new(a.cos(), a.sin()) * r
        };
        (0..n).map(|k| seg(at(k), at(k + 1), 0.0)).collect::<Vec<_>>()
    };
    let closed = |pts: &[Point], width: f64| {
        (0..pts.len()).map(|i| seg(pts[i], pts[(i + 1) % pts.len()], width)).collect::<Vec<_>>()
    };
    match shape {
        Shape::Circle { center, radius } => ring(*center, *radius, 0.0, std::f64::consts::TAU),
        Shape::Arc { center, radius, start, end } => ring(*center, *radius, *start, parts::arc_sweep(*start, *end)),
        Shape::Line { from, to } => vec![seg(*from, *to, 0.0)],
        Shape::Polyline { points, closed: c, width } => {
            if *c && points.len() > 2 {
                closed(points, *width)
            } else {
                points.windows(2).map(|w| seg(w[0], w[1], *width)).collect()
            }
        }
        Shape::Filled { points } => closed(points, 0.0),
        Shape::Arrow { from, to, head } => match parts::arrow(*from, *to, *head) {
            Some((base, tri)) => {
                let mut out = vec![seg(*from, base, 0.0)];
                out.extend(closed(&tri, 0.0));
                out
            }
            None => vec![seg(*from, *to, 0.0)],
        },
        _ => Vec::new(),
    }
}

/// The distance between the segment a–b and the box lo–hi (0 when they meet).
pub fn segment_box_distance(
    a: mechdraw::geom::Vector,
    b: mechdraw::geom::Vector,
    lo: mechdraw::geom::Vector,
    hi: mechdraw::geom::Vector,
) -> f64 {
    use mechdraw::geom::Vector;
    if segment_crosses_box(a, b, lo, hi) {
        return 0.0;
    }
    let to_segment = |p: Vector| {
        let ab = b - a;
        let t = if ab.norm_squared() > 0.0 { ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0) } else { 0.0 };
        (p - (a + ab * t)).norm()
    };
    let to_box = |p: Vector| (Vector::new(p.x.clamp(lo.x, hi.x), p.y.clamp(lo.y, hi.y)) - p).norm();
    let corners = [lo, Vector::new(hi.x, lo.y), hi, Vector::new(lo.x, hi.y)];
    corners.iter().map(|c| to_segment(*c)).chain([to_box(a), to_box(b)]).fold(f64::INFINITY, f64::min)
}

/// Whether the segment a–b passes through the interior of the box lo–hi (Liang–Barsky).
pub fn segment_crosses_box(
    a: mechdraw::geom::Vector,
    b: mechdraw::geom::Vector,
    lo: mechdraw::geom::Vector,
    hi: mechdraw::geom::Vector,
) -> bool {
    let d = b - a;
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [(-d.x, a.x - lo.x), (d.x, hi.x - a.x), (-d.y, a.y - lo.y), (d.y, hi.y - a.y)] {
        if p == 0.0 {
            if q <= 0.0 {
                return false;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    t0 < t1
}

/// The texts of `d` crossed by a stroke of another element: (text, what crosses it). A stroke
/// crosses a text when it passes through the inside of its box (shrunk by a millionth of the
/// text's height, so that a leader ending on the box's edge does not count) or, drawn wide,
/// comes nearer to the box than half its width; a circled number's own circle does not
/// count.
pub fn crossed_texts(d: &mechdraw::draw::Drawing) -> Vec<(String, String)> {
    use mechdraw::draw::Shape;
    use mechdraw::geom::{Point, Vector};
    /// What a shape strokes: a full circle (tested exactly), or straight pieces.
    enum Ink {
        Circle(Point, f64),
        Pieces(Vec<Stroke>),
    }
    let shapes = drawn_shapes(d);
    // Each shape's strokes with their bounding box (grown by the widest stroke's half).
    let inks: Vec<(String, Ink, Point, Point)> = shapes
        .iter()
        .filter(|(_, s)| !matches!(s, Shape::Text { .. }))
        .filter_map(|(layer, s)| {
            let what = match s {
                Shape::Circle { .. } => "circle",
                Shape::Arc { .. } => "arc",
                Shape::Line { .. } => "line",
                Shape::Polyline { .. } => "polyline",
                Shape::Filled { .. } => "filled shape",
                Shape::Arrow { .. } => "arrow",
                _ => "dimension",
            };
            let (ink, lo, hi) = match s {
                Shape::Circle { center, radius } => {
                    let r = Vector::new(*radius, *radius);
                    (Ink::Circle(*center, *radius), center - r, center + r)
                }
                _ => {
                    let pieces = strokes_of(s);
                    let first = pieces.first()?;
                    let grow = pieces.iter().map(|p| 0.5 * p.width).fold(0.0, f64::max);
                    let (mut lo, mut hi) = (first.from, first.from);
                    for p in &pieces {
                        for q in [p.from, p.to] {
                            lo = Point::new(lo.x.min(q.x), lo.y.min(q.y));
                            hi = Point::new(hi.x.max(q.x), hi.y.max(q.y));
                        }
                    }
                    let g = Vector::new(grow, grow);
                    (Ink::Pieces(pieces), lo - g, hi + g)
                }
            };
            Some((format!("{what} on {layer}"), ink, lo, hi))
        })
        .collect();
    let mut out = Vec::new();
    for t in text_boxes(d).iter().filter(|t| !t.value.trim().is_empty()) {
        let h = (t.local.1.y - t.local.0.y).abs().max(1e-300);
        let (sin, cos) = t.rotation.sin_cos();
        let local = |p: Point| {
            let v = p - t.at;
            Vector::new(cos * v.x + sin * v.y, -sin * v.x + cos * v.y)
        };
        for (what, ink, lo, hi) in &inks {
            if lo.x >= t.max.x || hi.x <= t.min.x || lo.y >= t.max.y || hi.y <= t.min.y {
                continue;
            }
            let eps = 1e-6 * h;
            let hit = match ink {
                Ink::Circle(c, r) => {
                    if t.circled && *c == t.at {
                        continue;
                    }
                    // The circle passes through the box's inside: the box's nearest point is
                    // inside the circle and its farthest corner outside.
                    let (c, (bl, bh)) = (local(*c), (t.local.0, t.local.1));
                    let near = Vector::new(c.x.clamp(bl.x, bh.x), c.y.clamp(bl.y, bh.y));
                    let far = Vector::new(
                        if c.x - bl.x > bh.x - c.x { bl.x } else { bh.x },
                        if c.y - bl.y > bh.y - c.y { bl.y } else { bh.y },
                    );
                    (near - c).norm() < *r - eps && (far - c).norm() > *r + eps
                }
                Ink::Pieces(pieces) => pieces.iter().any(|s| {
                    let (a, b) = (local(s.from), local(s.to));
                    let (lo, hi) = (t.local.0, t.local.1);
                    // Through the box, or (a wide stroke) nearer to it than half its width.
                    let g = Vector::new(eps, eps);
                    segment_crosses_box(a, b, lo + g, hi - g)
                        || (s.width > 0.0 && segment_box_distance(a, b, lo, hi) < 0.5 * s.width - eps)
                }),
            };
            if hit {
                out.push((t.value.clone(), what.clone()));
            }
        }
    }
    out
}

/// The panels of a drawing: the rectangles drawn as closed four-point polylines on a layer
/// named `SHEET` or `PANELS` (a sheet's border, title block and panel frames; a frame's
/// panels).
pub fn panels(d: &mechdraw::draw::Drawing) -> Vec<(mechdraw::geom::Point, mechdraw::geom::Point)> {
    use mechdraw::draw::Shape;
    use mechdraw::geom::Point;
    d.entities
        .iter()
        .filter(|e| matches!(d.layers[e.layer].name.as_str(), "SHEET" | "PANELS"))
        .filter_map(|e| match &e.shape {
            Shape::Polyline { points, closed: true, .. } if points.len() == 4 => {
                let min = points.iter().fold(points[0], |m, p| Point::new(m.x.min(p.x), m.y.min(p.y)));
                let max = points.iter().fold(points[0], |m, p| Point::new(m.x.max(p.x), m.y.max(p.y)));
                // Axis-aligned rectangles only.
                points
                    .iter()
                    .all(|p| (p.x == min.x || p.x == max.x) && (p.y == min.y || p.y == max.y))
                    .then_some((min, max))
            }
            _ => None,
        })
        .collect()
}

/// The texts of `d` that leave the panel their insertion point is in (the smallest panel
/// holding it): (text, the panel's corners).
pub fn texts_outside_their_panel(d: &mechdraw::draw::Drawing) -> Vec<(String, String)> {
    let panels = panels(d);
    let mut out = Vec::new();
    for t in text_boxes(d).iter().filter(|t| !t.value.trim().is_empty()) {
        let inside = |(lo, hi): &(mechdraw::geom::Point, mechdraw::geom::Point), p: mechdraw::geom::Point| {
            p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y
        };
        let home = panels
            .iter()
            .filter(|p| inside(p, t.at))
            .min_by(|a, b| ((a.1 - a.0).x * (a.1 - a.0).y).total_cmp(&((b.1 - b.0).x * (b.1 - b.0).y)));
        if let Some(p) = home
            && !(inside(p, t.min) && inside(p, t.max))
        {
            out.push((t.value.clone(), format!("{:.1},{:.1}–{:.1},{:.1}", p.0.x, p.0.y, p.1.x, p.1.y)));
        }
    }
    out
}

/// Every file under `dir` (from `rel`), with `/`-separated paths relative to `dir`, pushed
/// onto `into` with its bytes.
#[allow(dead_code)]
pub fn read_tree(dir: &Path, rel: &Path, into: &mut Vec<(String, Vec<u8>)>) {
    for e in std::fs::read_dir(dir.join(rel)).unwrap() {
        let e = e.unwrap();
        let r = rel.join(e.file_name());
        if e.path().is_dir() {
            read_tree(dir, &r, into);
        } else {
            into.push((r.to_string_lossy().replace('\\', "/"), std::fs::read(e.path()).unwrap()));
        }
    }
}

/// The bundled templates (`templates/*.toml`), sorted by path.
#[allow(dead_code)]
pub fn template_paths() -> Vec<PathBuf> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(root().join("templates"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    paths.sort();
    paths
}

/// Every template with the `--set` overrides that make it run in seconds (fewer positions
/// and samples): (path, overrides).
#[allow(dead_code)]
pub fn reduced_templates() -> Vec<(std::path::PathBuf, Vec<String>)> {
    let paths = template_paths();
    assert!(paths.len() >= 9, "templates missing");
    paths
        .into_iter()
        .map(|path| {
            let text = std::fs::read_to_string(&path).unwrap();
            let kind = text.lines().find_map(|l| l.strip_prefix("kind = ")).unwrap().trim_matches('"').to_string();
            let mut set = match kind.as_str() {
                "fourbar" => vec!["phi1_deg.step=30".to_string()],
                "linkage" => vec!["time.steps=12".to_string()],
                "chain" => vec!["stackup.samples=20000".to_string()],
                _ => vec![],
            };
            if text.lines().any(|l| l.trim() == "[tolerances]") {
                set.push("tolerances.settings.samples=2000".to_string());
            }
            (path, set)
        })
        .collect()
}

/// The scene file's text with the overrides written into it (what a page's fields do).
#[allow(dead_code)]
pub fn text_with(path: &Path, set: &[String]) -> String {
    let mut table: toml::Table = std::fs::read_to_string(path).unwrap().parse().unwrap();
    for s in set {
        s.parse::<mechdraw::scene::Override>().unwrap().apply(&mut table).unwrap();
    }
    toml::to_string(&table).unwrap()
}

/// Takes the live page `<name>.html` out of `files` (a run's files on disk: the command line
/// writes it, the in-memory products have no page) and returns it, checking that it is the
/// live page: the module inside it and the scene's text.
#[allow(dead_code)]
pub fn take_live_page(files: &mut Vec<(String, Vec<u8>)>, name: &str) -> String {
    let file = format!("{name}.html");
    let i = files.iter().position(|(n, _)| *n == file).unwrap_or_else(|| panic!("no {file} written"));
    let page = String::from_utf8(files.remove(i).1).expect("the page is UTF-8");
    assert!(page.contains("mod.initSync") && page.contains("const FILE = "), "{file}: not the live page");
    assert!(page.contains("window.MECHDRAW_WASM = \"") && page.len() > 300_000, "{file}: the module is missing");
    page
}

/// Every text of a drawing, in drawing order.
pub fn texts(d: &mechdraw::draw::Drawing) -> Vec<String> {
    d.entities
        .iter()
        .filter_map(|e| match &e.shape {
            mechdraw::draw::Shape::Text { value, .. } => Some(value.clone()),
            _ => None,
        })
        .collect()
}

/// The force arrows of `d` (layer `FORCES`) drawn over the mechanism (layer `MECHANISM`):
/// (the arrow's name-less description, what it crosses). An arrow's shaft crosses a stroke of
/// the mechanism — a link, a slider's block, a guide, a joint's circle, the ground symbol, not
/// the ω arc —
/// farther from its tail than the largest joint circle's radius (a force drawn from a joint
/// leaves its circle; one at a link's centroid starts on the link): a reaction drawn from a
/// slider's centre over its block and its guide's link is one (the shaper's R32 at A was).
pub fn arrows_over_mechanism(d: &mechdraw::draw::Drawing) -> Vec<(String, String)> {
    use mechdraw::draw::Shape;
    use mechdraw::geom::Point;
    let shapes = drawn_shapes(d);
    let radius = shapes
        .iter()
        .filter(|(l, _)| l == "MECHANISM")
        .filter_map(|(_, s)| match s {
            Shape::Circle { radius, .. } => Some(*radius),
            _ => None,
        })
        .fold(0.0, f64::max);
    let reach = 1.05 * radius + 1e-9;
    // The links, guides, blocks, joints and ground symbols; not the driver's ω arc with its
    // head (an annotation drawn round the pivot after the forces, on the same layer).
    let mech: Vec<Stroke> = shapes
        .iter()
        .filter(|(l, s)| l == "MECHANISM" && !matches!(s, Shape::Arc { .. } | Shape::Filled { .. }))
        .flat_map(|(_, s)| strokes_of(s))
        .collect();
    let cross = |a: mechdraw::geom::Vector, b: mechdraw::geom::Vector| a.x * b.y - a.y * b.x;
    let mut out = Vec::new();
    for (_, s) in shapes.iter().filter(|(l, _)| l == "FORCES") {
        let Shape::Arrow { from, .. } = s else { continue };
        let Some(shaft) = strokes_of(s).into_iter().next() else { continue };
        let (a, u) = (shaft.from, shaft.to - shaft.from);
        for m in &mech {
            let w = m.to - m.from;
            let den = cross(u, w);
            if den.abs() <= 1e-12 * u.norm() * w.norm() {
                continue;
            }
            let dd = m.from - a;
            let (t, k) = (cross(dd, w) / den, cross(dd, u) / den);
            if (0.0..=1.0).contains(&t) && (0.0..=1.0).contains(&k) {
                let x: Point = a + u * t;
                if (x - from).norm() > reach {
                    out.push((
                        format!("arrow from ({:.1}, {:.1})", from.x, from.y),
                        format!("a mechanism stroke at ({:.1}, {:.1})", x.x, x.y),
                    ));
                    break;
                }
            }
        }
    }
    out
}
