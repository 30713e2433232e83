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

#![allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the library calls"
)]

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
/// Half the side of a crop around an angular dimension's text, mm: room for the whole of
/// `φ1 = 234.39°` (12 characters of LibreCAD's font at the triad's 6 mm, 65 mm), which LibreCAD
/// writes level over the arc of a part of 170°.
const CROP_HALF_MM: f64 = 40.0;
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
        // Three thicknesses: thin strokes of LibreCAD's `8` read as `6` until thickened by 3 px.
        let read: String = [2, 1, 3].iter().map(|&t| ocr(&image, turn, t)).collect::<Vec<_>>().join(" | ");
        found.push((text, read));
    }
    found
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs LibreCAD, poppler-utils, tesseract and ImageMagick: bash .ci/test, or cargo test --features system-tools"
)]
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

/// At `mode = 3` all three angles are 180° or more (234.39°, 204.96°, 183.94°): LibreCAD
/// draws no angular DIMENSION that large, so each is written as two 2-line halves, the
/// first with the text (issue 29). Before, LibreCAD's page had none of the three.
#[test]
fn librecad_draws_the_triads_angles_of_180_degrees_and_more() {
    require_tools();
    for version in ["R12", "R2007"] {
        let dir = out_dir(&format!("triad-mode3-{version}"));
        let dxf = write_dxf("triad-popa", &dir, &["--set", "mode=3", "--dxf-version", version]);
        let pdf = dxf2pdf(&dxf, &dir);
        let wanted = ["234.39", "204.96", "183.94"];
        let read = angular_texts_read(&dxf, &pdf, &wanted);
        assert_eq!(read.len(), 3, "{version}: each angle's first half carries its text");
        for (text, ocr) in &read {
            let digits = wanted.iter().find(|w| text.contains(*w)).expect("selected by its number");
            assert!(reads_number(ocr, digits), "{version}: {digits} not on LibreCAD's page; OCR read {ocr:?}");
        }
    }
}

/// Whether OCR read the number `wanted` (`234.39`): its digits in order with nothing between
/// them but a decimal point or a space (OCR loses the thin point of LibreCAD's font now and
/// then, reading `234 39`); a misread digit is a miss.
fn reads_number(ocr: &str, wanted: &str) -> bool {
    let squeeze = |s: &str| s.chars().filter(|c| *c != '.' && *c != ' ').collect::<String>();
    squeeze(ocr).contains(&squeeze(wanted))
}

/// The chain with `--dxf-dimensions exploded`, the encoding docs/dxf.md gives LibreCAD users
/// for the chain: its dimensions as drawn (seed 001's circles and arrows, each text where the
/// chain placed it). As DIMENSION entities LibreCAD redraws them with two arrowheads and
/// centres each text on its line, where the short ones overlap their neighbours.
#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs LibreCAD, poppler-utils, tesseract and ImageMagick: bash .ci/test, or cargo test --features system-tools"
)]
fn librecad_draws_the_chains_tolerances_on_a_real_page() {
    require_tools();
    let dir = out_dir("chain");
    let dxf = write_dxf("chain-humienny-2", &dir, &["--dxf-dimensions", "exploded"]);
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
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs LibreCAD, poppler-utils, tesseract and ImageMagick: bash .ci/test, or cargo test --features system-tools"
)]
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

/// LibreCAD 2.2's stroke font for our text style, read from LibreCAD's own font file: the
/// independent width model of the tests below (LibreCAD draws a glyph 9 font units per text
/// height, each glyph at the previous one's right edge plus the letter spacing, a space
/// the word spacing; a character the font lacks as a stand-in about a letter wide).
struct StrokeFont {
    /// Each glyph's (left, right) edge, font units from its origin.
    glyphs: HashMap<char, (f64, f64)>,
    letter_spacing: f64,
    word_spacing: f64,
}

/// The font file of the DXF's text style (`AZOMIX`) as Debian's librecad installs it.
const AZOMIX_LFF: &str = "/usr/share/librecad/fonts/azomix.lff";

impl StrokeFont {
    fn read(path: &str) -> StrokeFont {
        let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e} (Debian's librecad)"));
        let header = |name: &str| -> f64 {
            text.lines()
                .find_map(|l| l.strip_prefix('#').and_then(|l| l.trim().strip_prefix(name)))
                .and_then(|v| v.trim_start_matches(':').trim().parse().ok())
                .unwrap_or_else(|| panic!("{path}: no {name}"))
        };
        // "[0041] A" then strokes "x,y;x,y;..." (a value may carry a bulge "A..."), or
        // "C0041" (another glyph's strokes).
        let mut strokes: HashMap<u32, Vec<String>> = HashMap::new();
        let mut current: Option<u32> = None;
        for line in text.lines() {
            if let Some(rest) = line.strip_prefix('[') {
                current = rest.get(..rest.find(']').unwrap_or(0)).and_then(|h| u32::from_str_radix(h, 16).ok());
                continue;
            }
            if let (Some(c), false) = (current, line.is_empty() || line.starts_with('#')) {
                strokes.entry(c).or_default().push(line.to_string());
            }
        }
        fn edges(c: u32, strokes: &HashMap<u32, Vec<String>>, depth: usize) -> Option<(f64, f64)> {
            let mut e: Option<(f64, f64)> = None;
            let mut add = |lo: f64, hi: f64| e = Some(e.map_or((lo, hi), |(a, b)| (a.min(lo), b.max(hi))));
            for l in strokes.get(&c)? {
                if let Some(code) = l.strip_prefix('C') {
                    let sub = u32::from_str_radix(code.get(..4).unwrap_or(""), 16).ok();
                    if let Some((lo, hi)) = sub.filter(|_| depth < 4).and_then(|s| edges(s, strokes, depth + 1)) {
                        add(lo, hi);
                    }
                    continue;
                }
                for x in l.split(';').filter_map(|p| p.split(',').next()?.trim().parse::<f64>().ok()) {
                    add(x, x);
                }
            }
            e
        }
        let glyphs = strokes.keys().filter_map(|&c| Some((char::from_u32(c)?, edges(c, &strokes, 0)?))).collect();
        StrokeFont { glyphs, letter_spacing: header("LetterSpacing"), word_spacing: header("WordSpacing") }
    }

    /// The ink of a left-aligned text `height` high, from its insertion point: (left, right).
    fn ink(&self, text: &str, height: f64) -> (f64, f64) {
        let (mut pos, mut left, mut right) = (0.0, f64::INFINITY, f64::NEG_INFINITY);
        for c in text.chars() {
            if c == ' ' {
                pos += self.word_spacing;
                continue;
            }
            // A missing glyph: LibreCAD's stand-in, taken as wide as a capital W.
            let (l, r) = self.glyphs.get(&c).or_else(|| self.glyphs.get(&'W')).copied().unwrap_or((0.0, 9.0));
            left = left.min(pos + l);
            right = right.max(pos + r);
            pos += r + self.letter_spacing;
        }
        (left * height / 9.0, right * height / 9.0)
    }
}

/// A level TEXT of the DXF: layer, where it is aligned, height, text (escapes decoded),
/// horizontal alignment (72: 0 left, 1 centre, 2 right), width factor (41).
#[derive(Debug, Clone)]
struct DxfText {
    layer: String,
    at: (f64, f64),
    height: f64,
    text: String,
    halign: i32,
    width: f64,
}

/// Every level TEXT of the ENTITIES section.
fn level_texts(p: &[(i32, String)]) -> Vec<DxfText> {
    let start = p.iter().position(|(c, v)| *c == 2 && v == "ENTITIES").expect("ENTITIES section");
    let mut out = Vec::new();
    let mut current: Option<HashMap<i32, String>> = None;
    let mut finish = |t: HashMap<i32, String>| {
        let num = |c: i32| t.get(&c).and_then(|v| v.parse::<f64>().ok());
        let halign = num(72).unwrap_or(0.0) as i32;
        let aligned = halign != 0 || num(73).unwrap_or(0.0) != 0.0;
        let at = if aligned { (num(11), num(21)) } else { (num(10), num(20)) };
        if let ((Some(x), Some(y)), Some(h)) = (at, num(40))
            && num(50).unwrap_or(0.0) == 0.0
        {
            out.push(DxfText {
                layer: t.get(&8).cloned().unwrap_or_default(),
                at: (x, y),
                height: h,
                text: common::dxf_unescape(t.get(&1).map_or("", String::as_str)),
                halign,
                width: num(41).unwrap_or(1.0),
            });
        }
    };
    for (c, v) in &p[start..] {
        if *c == 0 {
            if let Some(t) = current.take() {
                finish(t);
            }
            current = (v == "TEXT").then(HashMap::new);
        } else if let Some(t) = current.as_mut() {
            t.entry(*c).or_insert_with(|| v.clone());
        }
    }
    out
}

/// The ink of a text as LibreCAD lays it out: (left, right), model units. LibreCAD moves a
/// centred or right-aligned text by its ink's width, so its ink starts where a left-aligned
/// one's would, that far to the left; it narrows glyphs and spacing by the width factor.
fn librecad_ink(font: &StrokeFont, t: &DxfText) -> (f64, f64) {
    let (l, r) = font.ink(&t.text, t.height);
    let (l, r) = (l * t.width, r * t.width);
    let shift = match t.halign {
        1 => -0.5 * (r - l),
        2 => -(r - l),
        _ => 0.0,
    };
    (t.at.0 + l + shift, t.at.0 + r + shift)
}

/// The closed POLYLINEs of `layer` as boxes (min x, min y, max x, max y).
fn layer_boxes(p: &[(i32, String)], layer: &str) -> Vec<(f64, f64, f64, f64)> {
    let start = p.iter().position(|(c, v)| *c == 2 && v == "ENTITIES").expect("ENTITIES section");
    let mut boxes = Vec::new();
    let mut i = start;
    while i < p.len() {
        if p[i] == (0, "POLYLINE".to_string())
            && p[i + 1..].iter().take_while(|(c, _)| *c != 0).any(|(c, v)| *c == 8 && v == layer)
        {
            let (mut x0, mut y0, mut x1, mut y1) = (f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY);
            i += 1;
            while i < p.len() && p[i] != (0, "SEQEND".to_string()) {
                let (c, v) = &p[i];
                if let Ok(x) = v.parse::<f64>() {
                    if *c == 10 && p[..i].iter().rev().find(|(c, _)| *c == 0).is_some_and(|(_, v)| v == "VERTEX") {
                        (x0, x1) = (x0.min(x), x1.max(x));
                    } else if *c == 20 && p[..i].iter().rev().find(|(c, _)| *c == 0).is_some_and(|(_, v)| v == "VERTEX")
                    {
                        (y0, y1) = (y0.min(x), y1.max(x));
                    }
                }
                i += 1;
            }
            boxes.push((x0, y0, x1, y1));
        }
        i += 1;
    }
    boxes
}

/// The triad's modes sheet in LibreCAD: each mode's heading, angles and joint names stay in their cell
/// (the first heading, "Mode 1 · counter-clockwise · drawn in Fig. 3", ran 41 mm into the
/// second cell when the cells were as wide as the DejaVu widths of the SVG). Checked twice:
/// on LibreCAD's page, where the gaps between the cells hold no ink at all, and with
/// LibreCAD's own font file, every text's ink inside its cell; the font model is held to the
/// page (a heading measured on the page within 1 mm of the model).
#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs LibreCAD, poppler-utils, tesseract and ImageMagick: bash .ci/test, or cargo test --features system-tools"
)]
fn librecad_keeps_each_modes_text_in_its_cell() {
    require_tools();
    const DPI: u32 = 50;
    let dir = out_dir("modes-cells");
    write_dxf("triad-popa", &dir, &[]);
    let dxf = dir.join("triad-popa-modes.dxf");
    let pdf = dxf2pdf(&dxf, &dir);
    let p = pairs(&dxf);
    let (x_min, _) = header_point(&p, "$PLIMMIN");
    let (_, y_max) = header_point(&p, "$PLIMMAX");
    let cells = layer_boxes(&p, "PANELS");
    assert_eq!(cells.len(), 8, "the eight modes' cells: {cells:?}");
    let (w, h, px) = page_grey(&pdf, DPI);
    let px_per_mm = DPI as f64 / 25.4;
    let col = |x: f64| ((x - x_min) * px_per_mm).round() as i64;
    let row = |y: f64| ((y_max - y) * px_per_mm).round() as i64;
    let inked = |x: i64, y: i64| {
        x >= 0 && y >= 0 && (x as usize) < w && (y as usize) < h && px[y as usize * w + x as usize] < 200
    };
    // The gap between two cells side by side: nothing is drawn there.
    for a in &cells {
        for b in &cells {
            if (a.3 - b.3).abs() > 1e-6 || b.0 <= a.2 {
                continue;
            }
            let (x0, x1) = (col(a.2) + 2, col(b.0) - 2);
            let (y0, y1) = (row(a.3) + 2, row(a.1) - 2);
            assert!(x1 > x0 + 5, "a gap of {} px between the cells", x1 - x0);
            let ink: Vec<(i64, i64)> =
                (y0..=y1).flat_map(|y| (x0..=x1).map(move |x| (x, y))).filter(|&(x, y)| inked(x, y)).collect();
            assert!(
                ink.is_empty(),
                "LibreCAD draws in the gap between the cells at x {:.0}..{:.0} ({} px, e.g. {:?}): a text runs out of its cell",
                a.2,
                b.0,
                ink.len(),
                &ink[..ink.len().min(5)]
            );
        }
    }
    // Every text's ink by LibreCAD's font inside the cell that holds its insertion point.
    let font = StrokeFont::read(AZOMIX_LFF);
    let texts = level_texts(&p);
    let mut checked = 0;
    for t in &texts {
        let Some(cell) = cells.iter().find(|c| c.0 <= t.at.0 && t.at.0 <= c.2 && c.1 <= t.at.1 && t.at.1 <= c.3) else {
            continue;
        };
        let (l, r) = librecad_ink(&font, t);
        assert!(
            l >= cell.0 && r <= cell.2,
            "{:?}: LibreCAD's ink {l:.1}..{r:.1} leaves its cell {:.1}..{:.1}",
            t.text,
            cell.0,
            cell.2
        );
        checked += 1;
    }
    assert_eq!(checked, 64, "a heading, an angles line and six joint names in each of the eight cells");
    // The model against the page: the second cell's angles line (every glyph in the font),
    // measured between the cell's borders.
    let t = texts.iter().find(|t| t.text.starts_with("φ1 = 84.04°")).expect("mode 2's angles");
    let cell = cells.iter().find(|c| c.0 <= t.at.0 && t.at.0 <= c.2 && c.1 <= t.at.1 && t.at.1 <= c.3).unwrap();
    let (l, r) = librecad_ink(&font, t);
    let (y0, y1) = (row(t.at.1 + 1.1 * t.height), row(t.at.1 - 0.3 * t.height));
    let columns: Vec<i64> = (col(cell.0) + 2..=col(cell.2) - 2).filter(|&x| (y0..=y1).any(|y| inked(x, y))).collect();
    assert!(!columns.is_empty(), "{:?} not on LibreCAD's page", t.text);
    let (first, last) = (columns[0] as f64 / px_per_mm + x_min, *columns.last().unwrap() as f64 / px_per_mm + x_min);
    let tol = 0.05 * t.height + 1.0 / px_per_mm;
    assert!(
        (first - l).abs() < tol && (last - r).abs() < tol,
        "LibreCAD draws {:?} at {first:.1}..{last:.1}, the font model says {l:.1}..{r:.1}",
        t.text
    );
}

/// The frames in LibreCAD: the panels' titles, the position's text beside the mechanism's
/// title and the force figures' captions stay at least a text height apart as LibreCAD's
/// font draws them (the four-bar's "Acceleration polygon   k_a = 2.5 (m/s²)/mm" ran to
/// within 0.75 heights of "Force polygons", out of its panel, and the driven triad's
/// "Mechanism   k_l = 2 mm/mm" over its "t = 0.0000 s", when the panels were as wide as
/// the DejaVu widths of the SVG). Checked at every position, with LibreCAD's own font file.
#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs LibreCAD, poppler-utils, tesseract and ImageMagick: bash .ci/test, or cargo test --features system-tools"
)]
fn librecad_keeps_panel_titles_apart() {
    require_tools();
    let font = StrokeFont::read(AZOMIX_LFF);
    for scene in ["fourbar-chebyshev", "triad-driven"] {
        let dir = out_dir(&format!("titles-{scene}"));
        let p = pairs(&write_dxf(scene, &dir, &[]));
        let texts = level_texts(&p);
        // The rows of the titles and captions (on DIMENSIONS), and with them every text on
        // their baselines (the position's text is on its position's layer).
        let titles: Vec<&DxfText> = texts.iter().filter(|t| t.layer == "DIMENSIONS").collect();
        let mut positions: Vec<&str> =
            texts.iter().filter(|t| t.layer.starts_with("POS_")).map(|t| t.layer.as_str()).collect();
        positions.sort_unstable();
        positions.dedup();
        assert!(positions.len() > 100, "{scene}: one layer per position");
        let mut rows = 0;
        for pos in &positions {
            for base in titles.iter().map(|t| (t.at.1, t.height)) {
                let mut row: Vec<(f64, f64, &str)> = texts
                    .iter()
                    .filter(|t| {
                        (t.layer == "DIMENSIONS" || t.layer == *pos)
                            && (t.at.1 - base.0).abs() < 1e-9
                            && t.height == base.1
                    })
                    .map(|t| {
                        let (l, r) = librecad_ink(&font, t);
                        (l, r, t.text.as_str())
                    })
                    .collect();
                row.sort_by(|a, b| a.0.total_cmp(&b.0));
                for w in row.windows(2) {
                    assert!(
                        w[1].0 - w[0].1 >= base.1,
                        "{scene}, {pos}: LibreCAD draws {:?} {:.1} text heights from {:?}",
                        w[0].2,
                        (w[1].0 - w[0].1) / base.1,
                        w[1].2
                    );
                }
                rows += 1;
            }
        }
        assert!(rows > 0, "{scene}: no title rows");
    }
}

/// The writer's table of LibreCAD's glyphs (`draw::dxf::librecad::glyph`, what the width
/// factors and the centring of single characters are computed from) is LibreCAD's own font
/// file, character by character; the characters it says the font lacks are not in it.
#[test]
fn the_writers_glyph_table_is_librecads_font() {
    use mechdraw::draw::dxf::librecad::{advance, glyph};
    let font = StrokeFont::read(AZOMIX_LFF);
    assert_eq!((font.letter_spacing, font.word_spacing), (1.0, 6.75));
    let listed =
        (0x21u32..0x7f).filter_map(char::from_u32).chain("°±²³′″µ×÷−≈≤≥≡→←↑↓∞√ΣΔΩαβγδεθλμπρστφωψΦΨΓΛΘΠ".chars());
    let mut checked = 0;
    for c in listed {
        let ours = glyph(c).unwrap_or_else(|| panic!("{c:?} missing from the writer's table"));
        let lff = font.glyphs.get(&c).copied().unwrap_or_else(|| panic!("{c:?} missing from {AZOMIX_LFF}"));
        assert!(
            (ours.0 - lff.0).abs() < 1e-9 && (ours.1 - lff.1).abs() < 1e-9,
            "{c:?}: ours {ours:?}, LibreCAD's {lff:?}"
        );
        assert!((advance(c) - (lff.1 + font.letter_spacing)).abs() < 1e-9, "{c:?}");
        checked += 1;
    }
    assert!(checked > 130);
    for c in ['·', '–', '—'] {
        assert!(glyph(c).is_none() && !font.glyphs.contains_key(&c), "{c:?}");
    }
}

/// Text laid out for DejaVu Sans (every layout's measure) stays in its box in LibreCAD: the
/// writer gives each TEXT the width factor that keeps LibreCAD's wider glyphs inside it, so
/// nothing a figure keeps clear of the box is touched there (issue 29: the chain's
/// "38 ±0.1" ran onto the F1 extension line, force names merged, "RBgas"); and every
/// character written is one LibreCAD's font has (`·` and `–` were drawn as a stand-in).
/// Checked on every level TEXT of the triad, the chain, the four-bar and the slider-crank,
/// with LibreCAD's own font file.
#[test]
fn every_text_stays_in_its_box_in_librecads_font() {
    let font = StrokeFont::read(AZOMIX_LFF);
    let mut checked = 0;
    for (scene, extra) in [
        ("triad-popa", &["--dxf-dimensions", "exploded"][..]),
        ("chain-humienny-2", &["--dxf-dimensions", "exploded"][..]),
        ("fourbar-chebyshev", &["--positions", "0,90,180,270"][..]),
        ("slider-crank", &["--positions", "0,0.05,0.1"][..]),
    ] {
        let dir = out_dir(&format!("boxes-{scene}"));
        let dxf = write_dxf(scene, &dir, extra);
        for t in level_texts(&pairs(&dxf)) {
            for c in t.text.chars().filter(|c| *c != ' ') {
                assert!(font.glyphs.contains_key(&c), "{scene}: {:?} has {c:?}, which LibreCAD's font lacks", t.text);
            }
            if t.text.chars().count() < 2 {
                // A single centred character is written left-aligned, centred between
                // LibreCAD's glyph and DejaVu's (unit tests of `librecad::text_fit`).
                continue;
            }
            let w = mechdraw::draw::parts::text_width(&t.text, t.height);
            let (l, r) = librecad_ink(&font, &t);
            let x = t.at.0;
            let (lo, hi) = match t.halign {
                1 => (x - 0.5 * w, x + 0.5 * w),
                2 => (x - w, x),
                _ => (x, x + w),
            };
            let tol = 0.02 * t.height;
            // A right-aligned text ends its first glyph's left edge past its point in LibreCAD
            // (it centres and right-aligns by ink): within half a height.
            let hi = if t.halign == 2 { hi + 0.5 * t.height } else { hi };
            assert!(
                l >= lo - tol && r <= hi + tol,
                "{scene}: LibreCAD draws {:?} (on {}) at {l:.2}..{r:.2}, its box is {lo:.2}..{hi:.2}",
                t.text,
                t.layer
            );
            checked += 1;
        }
    }
    assert!(checked > 200, "{checked} texts");
}
