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

/// Channel tolerance of the image comparison: a pixel differs when any channel differs
/// by more than this (as in resvg's own tests).
pub const PIXEL_CHANNEL_TOL: u8 = 1;
/// Fraction of pixels allowed to differ (anti-aliasing noise between CPUs).
pub const PIXEL_FRACTION_TOL: f64 = 0.001;
/// Width at which golden SVGs are rasterised.
pub const GOLDEN_WIDTH_PX: u32 = 800;

/// The repository root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
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

/// A text of a drawing as the letter placer measures it: its layer, its value and its box
/// (label width by one cap height, from its alignment, turned with the text; a circled link
/// number's circle).
#[derive(Debug, Clone)]
pub struct TextBox {
    pub layer: String,
    pub value: String,
    pub at: mechdraw::geom::Point,
    pub halign: mechdraw::draw::HAlign,
    pub min: mechdraw::geom::Point,
    pub max: mechdraw::geom::Point,
}

/// Every text of `d` with its box.
pub fn text_boxes(d: &mechdraw::draw::Drawing) -> Vec<TextBox> {
    use mechdraw::draw::{HAlign, Shape, VAlign};
    use mechdraw::figure::shared::labels::{CIRCLE_RADIUS, label_width};
    use mechdraw::geom::{Point, Vector};
    let circles: Vec<(Point, f64)> = d
        .entities
        .iter()
        .filter_map(|e| match e.shape {
            Shape::Circle { center, radius } => Some((center, radius)),
            _ => None,
        })
        .collect();
    d.entities
        .iter()
        // A scale caption as the paper states it.
        .map(|e| (e, e.shape.scale_text_in(None)))
        .filter_map(|(e, caption)| match caption.as_ref().unwrap_or(&e.shape) {
            Shape::Text { at, height, value, halign, valign, rotation } => {
                let (h, w) = (*height, label_width(value, *height));
                let x0 = match halign {
                    HAlign::Left => at.x,
                    HAlign::Center => at.x - 0.5 * w,
                    HAlign::Right => at.x - w,
                };
                let y0 = match valign {
                    VAlign::Baseline => at.y,
                    VAlign::Middle => at.y - 0.5 * h,
                    VAlign::Top => at.y - h,
                };
                let (mut min, mut max) = (Point::new(x0, y0), Point::new(x0 + w, y0 + h));
                let r = CIRCLE_RADIUS * h;
                if circles.iter().any(|(c, cr)| *c == *at && (cr - r).abs() < 1e-12 * r) {
                    (min, max) = (*at - Vector::new(r, r), *at + Vector::new(r, r));
                }
                // A rotated text: the box of its rotated corners (about its insertion point).
                if *rotation != 0.0 {
                    let (sin, cos) = rotation.sin_cos();
                    let turn = |p: Point| {
                        let v = p - *at;
                        *at + Vector::new(cos * v.x - sin * v.y, sin * v.x + cos * v.y)
                    };
                    let corners = [min, Point::new(max.x, min.y), max, Point::new(min.x, max.y)].map(turn);
                    min = corners.iter().fold(corners[0], |m, c| Point::new(m.x.min(c.x), m.y.min(c.y)));
                    max = corners.iter().fold(corners[0], |m, c| Point::new(m.x.max(c.x), m.y.max(c.y)));
                }
                let layer = d.layers[e.layer].name.clone();
                Some(TextBox { layer, value: value.clone(), at: *at, halign: *halign, min, max })
            }
            _ => None,
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
