//! What a LibreCAD user sees of our DXF (issue 13): `librecad dxf2pdf` of the triad and chain
//! templates gives a real page (larger than 100 mm both ways), and the page shows the triad's
//! angular dimensions φ2 = 102.23° and φ3 = 117.04° (these numbers appear nowhere else in
//! the drawing: LibreCAD draws them only if it draws the DIMENSION) and the chain's "±0.1"
//! tolerances; and that no text runs off LibreCAD's page (its font is wider than ours).
//!
//! LibreCAD draws text as strokes, so `pdftotext` finds nothing: the page is read back with
//! tesseract. An angular dimension's text is drawn along its arc, so each one is cropped
//! from the page around the arc's middle (the DIMENSION's point 16; LibreCAD prints the
//! limits at 1:1 in mm), turned level, thresholded (the light grey construction lines go)
//! and thickened before OCR. Needs `librecad`, `pdfinfo`/`pdftoppm` (poppler-utils),
//! `tesseract` and ImageMagick's `convert`; `.ci/test` installs them.

mod common;

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Millimetres per PDF point.
const MM_PER_PT: f64 = 25.4 / 72.0;
/// The smallest page side accepted, mm.
const MIN_PAGE_MM: f64 = 100.0;
/// Resolution of the angular-dimension crops: the triad's dimension text, 0.85 × 3.5 mm on
/// paper at k_l = 2 mm/mm, is 6 mm high in model space (LibreCAD prints it 1:1), about
/// 95 px at 400 dpi (the 4.1 mm text of the older size table was read at 600 dpi).
const CROP_DPI: f64 = 400.0;
/// Half the side of a crop around an angular dimension's text, mm.
const CROP_HALF_MM: f64 = 26.0;
/// Resolution of the chain's whole page: its 7 mm dimension text (3.5 mm on paper at
/// k_l = 2 mm/mm) is then about 77 px high.
const PAGE_DPI: u32 = 280;

fn on_path(tool: &str) -> bool {
    std::env::var_os("PATH").is_some_and(|p| std::env::split_paths(&p).any(|d| d.join(tool).is_file()))
}

fn require_tools() {
    let missing: Vec<&str> =
        ["librecad", "pdfinfo", "pdftoppm", "tesseract", "convert"].into_iter().filter(|t| !on_path(t)).collect();
    assert!(
        missing.is_empty(),
        "missing {missing:?}: install Debian's librecad, poppler-utils, tesseract-ocr and imagemagick (bash .ci/test does)"
    );
}

fn out_dir(name: &str) -> PathBuf {
    let d = common::root().join("target/test-out/dxf_librecad").join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(d.join("home")).unwrap();
    d
}

/// `mechdraw run templates/<scene>.toml` into `dir`, with extra options; the DXF's path.
fn write_dxf(scene: &str, dir: &Path, extra: &[&str]) -> PathBuf {
    let status = Command::new(env!("CARGO_BIN_EXE_mechdraw"))
        .arg("run")
        .arg(common::root().join("templates").join(format!("{scene}.toml")))
        .args(["--out", dir.to_str().unwrap(), "--no-frames", "-q"])
        .args(extra)
        .status()
        .expect("run mechdraw");
    assert!(status.success(), "mechdraw run {scene} failed");
    dir.join(format!("{scene}.dxf"))
}

/// `librecad dxf2pdf` of `dxf` (headless, its settings in `dir/home`); the PDF's path.
fn dxf2pdf(dxf: &Path, dir: &Path) -> PathBuf {
    let home = dir.join("home");
    let out = Command::new("librecad")
        .args(["dxf2pdf", "-t", dir.to_str().unwrap(), dxf.to_str().unwrap()])
        .env("QT_QPA_PLATFORM", "offscreen")
        .env("HOME", &home)
        .env("XDG_CONFIG_HOME", home.join(".config"))
        .env("XDG_RUNTIME_DIR", &home)
        .output()
        .expect("run librecad dxf2pdf");
    let pdf = dir.join(dxf.with_extension("pdf").file_name().unwrap());
    assert!(
        out.status.success() && pdf.is_file(),
        "librecad dxf2pdf {} failed: {}{}",
        dxf.display(),
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    pdf
}

/// The page size in mm (`pdfinfo`).
fn page_mm(pdf: &Path) -> (f64, f64) {
    let out = Command::new("pdfinfo").arg(pdf).output().expect("run pdfinfo");
    let text = String::from_utf8_lossy(&out.stdout);
    let line = text.lines().find(|l| l.starts_with("Page size:")).expect("pdfinfo prints the page size");
    let nums: Vec<f64> = line.split_whitespace().filter_map(|w| w.parse().ok()).collect();
    assert!(nums.len() >= 2, "page size line {line:?}");
    (nums[0] * MM_PER_PT, nums[1] * MM_PER_PT)
}

/// The DXF as (group code, value) pairs.
fn pairs(dxf: &Path) -> Vec<(i32, String)> {
    let text = String::from_utf8_lossy(&std::fs::read(dxf).unwrap()).into_owned();
    let lines: Vec<&str> = text.lines().collect();
    lines.chunks_exact(2).map(|c| (c[0].trim().parse().unwrap_or(-1), c[1].trim().to_string())).collect()
}

/// A header point variable (x, y).
fn header_point(p: &[(i32, String)], name: &str) -> (f64, f64) {
    let i = p.iter().position(|(c, v)| *c == 9 && v == name).unwrap_or_else(|| panic!("no {name}"));
    (p[i + 1].1.parse().unwrap(), p[i + 2].1.parse().unwrap())
}

/// The DIMENSION entities of the ENTITIES section, each as its first value per group code.
fn dimensions(p: &[(i32, String)]) -> Vec<HashMap<i32, String>> {
    let start = p.iter().position(|(c, v)| *c == 2 && v == "ENTITIES").expect("ENTITIES section");
    let mut dims = Vec::new();
    let mut current: Option<HashMap<i32, String>> = None;
    for (c, v) in &p[start..] {
        if *c == 0 {
            dims.extend(current.take());
            current = (v == "DIMENSION").then(HashMap::new);
        } else if let Some(d) = current.as_mut() {
            d.entry(*c).or_insert_with(|| v.clone());
        }
    }
    dims
}

/// tesseract's reading of an image after the clean-up that makes LibreCAD's thin strokes
/// readable: `turn` degrees clockwise, grey (construction lines) to white, strokes
/// thickened by `thicken` pixels. Returns the text.
fn ocr(image: &Path, turn: f64, thicken: u32) -> String {
    let clean = image.with_file_name(format!(
        "{}.t{}.k{thicken}.png",
        image.file_stem().unwrap().to_string_lossy(),
        turn.round()
    ));
    let status = Command::new("convert")
        .arg(image)
        .args(["-background", "white", "-rotate", &format!("{turn}"), "-flatten", "-threshold", "60%"])
        .args(["-morphology", "Erode", &format!("Disk:{thicken}")])
        .arg(&clean)
        .status()
        .expect("run convert");
    assert!(status.success(), "convert failed on {}", image.display());
    let out = Command::new("tesseract").arg(&clean).args(["stdout", "--psm", "11"]).output().expect("run tesseract");
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// OCR of the page around each angular DIMENSION whose text contains one of `wanted`;
/// returns (text, what OCR read) for each.
fn angular_texts_read(dxf: &Path, pdf: &Path, wanted: &[&str]) -> Vec<(String, String)> {
    let p = pairs(dxf);
    let (x0, _) = header_point(&p, "$PLIMMIN");
    let (_, y1) = header_point(&p, "$PLIMMAX");
    let px_per_mm = CROP_DPI / 25.4;
    let num = |d: &HashMap<i32, String>, c: i32| d.get(&c).and_then(|v| v.parse::<f64>().ok()).unwrap_or(f64::NAN);
    let mut found = Vec::new();
    for (k, d) in dimensions(&p).iter().enumerate() {
        let text = d.get(&1).cloned().unwrap_or_default();
        let flags: i32 = d.get(&70).and_then(|v| v.parse().ok()).unwrap_or(0);
        if flags & 7 != 2 || !wanted.iter().any(|w| text.contains(w)) {
            continue;
        }
        // 2-line angular: 13 the vertex, 16 on the arc; LibreCAD writes the text along the
        // arc at its middle, level when turned by (bisector − 90°) clockwise.
        let (vx, vy, ax, ay) = (num(d, 13), num(d, 23), num(d, 16), num(d, 26));
        let turn = (ay - vy).atan2(ax - vx).to_degrees() - 90.0;
        let side = (2.0 * CROP_HALF_MM * px_per_mm).round() as i64;
        let left = ((ax - CROP_HALF_MM - x0) * px_per_mm).round() as i64;
        let top = ((y1 - ay - CROP_HALF_MM) * px_per_mm).round() as i64;
        let base = pdf.with_file_name(format!("angular{k}"));
        let status = Command::new("pdftoppm")
            .args(["-gray", "-png", "-singlefile", "-r", &format!("{CROP_DPI}")])
            .args(["-x", &left.to_string(), "-y", &top.to_string(), "-W", &side.to_string(), "-H", &side.to_string()])
            .arg(pdf)
            .arg(&base)
            .status()
            .expect("run pdftoppm");
        assert!(status.success());
        let image = base.with_extension("png");
        let read: String = [2, 1].iter().map(|&t| ocr(&image, turn, t)).collect::<Vec<_>>().join(" | ");
        found.push((text, read));
    }
    found
}

#[test]
fn librecad_draws_the_triads_angular_dimensions_on_a_real_page() {
    require_tools();
    for version in ["R12", "R2000", "R2007"] {
        let dir = out_dir(&format!("triad-{version}"));
        let dxf = write_dxf("triad-popa", &dir, &["--dxf-version", version]);
        let pdf = dxf2pdf(&dxf, &dir);
        let (w, h) = page_mm(&pdf);
        assert!(w > MIN_PAGE_MM && h > MIN_PAGE_MM, "{version}: page {w:.0} × {h:.0} mm");
        let wanted = ["102.23", "117.04"];
        let read = angular_texts_read(&dxf, &pdf, &wanted);
        assert_eq!(read.len(), 2, "{version}: the two angular dimensions are 2-line DIMENSIONs");
        for (text, ocr) in &read {
            // The dimension text names its angle ("φ2 = 102.23°"): the number is what OCR must read.
            let digits = wanted.iter().find(|w| text.contains(*w)).expect("selected by its number");
            assert!(ocr.contains(digits), "{version}: {digits} not on LibreCAD's page; OCR read {ocr:?}");
        }
    }
}

#[test]
fn librecad_draws_the_chains_tolerances_on_a_real_page() {
    require_tools();
    let dir = out_dir("chain");
    let dxf = write_dxf("chain-humienny-2", &dir, &[]);
    let pdf = dxf2pdf(&dxf, &dir);
    let (w, h) = page_mm(&pdf);
    assert!(w > MIN_PAGE_MM && h > MIN_PAGE_MM, "page {w:.0} × {h:.0} mm");
    let base = dir.join("page");
    let status = Command::new("pdftoppm")
        .args(["-gray", "-png", "-singlefile", "-r", &PAGE_DPI.to_string()])
        .arg(&pdf)
        .arg(&base)
        .status()
        .expect("run pdftoppm");
    assert!(status.success());
    let read = ocr(&base.with_extension("png"), 0.0, 2);
    // The chain's eight "N ±0.1" dimensions; OCR reads ± as + and misses one now and then.
    let wanted = ["38", "25", "80", "260", "100", "55", "65", "15"];
    let words: Vec<&str> = read.split_whitespace().collect();
    let seen: Vec<&str> = wanted
        .iter()
        .copied()
        .filter(|n| words.windows(2).any(|w| w[0] == *n && (w[1] == "±0.1" || w[1] == "+0.1")))
        .collect();
    assert!(seen.len() >= 5, "only {seen:?} of {wanted:?} read with ±0.1 on LibreCAD's page; OCR read {read:?}");
}

/// The page as an 8-bit grey image (`pdftoppm -gray`, PGM): (width, height, pixels row by row).
fn page_grey(pdf: &Path, dpi: u32) -> (usize, usize, Vec<u8>) {
    let out = Command::new("pdftoppm")
        .args(["-gray", "-singlefile", "-r", &dpi.to_string()])
        .arg(pdf)
        .output()
        .expect("run pdftoppm");
    assert!(out.status.success(), "pdftoppm {} failed", pdf.display());
    // "P5", width, height, maxval, each followed by one whitespace, then the pixels.
    let bytes = out.stdout;
    let mut fields = Vec::new();
    let mut i = 0;
    while fields.len() < 4 {
        while bytes[i].is_ascii_whitespace() {
            i += 1;
        }
        let start = i;
        while !bytes[i].is_ascii_whitespace() {
            i += 1;
        }
        fields.push(String::from_utf8_lossy(&bytes[start..i]).into_owned());
    }
    assert_eq!(fields[0], "P5", "pdftoppm -gray writes a binary PGM");
    let (w, h): (usize, usize) = (fields[1].parse().unwrap(), fields[2].parse().unwrap());
    let pixels = bytes[i + 1..].to_vec();
    assert_eq!(pixels.len(), w * h, "one byte a pixel");
    (w, h, pixels)
}

/// LibreCAD prints the limits as the page, and draws text in its own font (wider than the
/// DejaVu Sans the drawing's bounds assume): every caption and title must still be on the
/// page. Checked on the page itself: nothing is drawn within 3 mm of its edges (the
/// triad's first caption line ran off the right edge when the limits held the bounds alone).
#[test]
fn librecad_pages_hold_every_text() {
    require_tools();
    const DPI: u32 = 50;
    const EDGE_MM: f64 = 3.0;
    let dir = out_dir("margins");
    // One run writes both: the triad's drawing and its modes sheet.
    write_dxf("triad-popa", &dir, &[]);
    for stem in ["triad-popa", "triad-popa-modes"] {
        let pdf = dxf2pdf(&dir.join(format!("{stem}.dxf")), &dir);
        let (w, h, px) = page_grey(&pdf, DPI);
        let edge = (EDGE_MM / 25.4 * DPI as f64).ceil() as usize;
        let inked: Vec<(usize, usize)> = (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .filter(|&(x, y)| (x < edge || x + edge >= w || y < edge || y + edge >= h) && px[y * w + x] < 200)
            .collect();
        assert!(
            inked.is_empty(),
            "{stem}: LibreCAD draws within {EDGE_MM} mm of the page's edge ({} px of a {w} × {h} page, e.g. {:?})",
            inked.len(),
            &inked[..inked.len().min(5)]
        );
        // And the page holds a drawing: something is drawn.
        assert!(px.iter().filter(|&&v| v < 200).count() > 1000, "{stem}: an empty page");
    }
}
