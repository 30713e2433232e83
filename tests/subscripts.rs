//! Subscripts (issue 31, typography): a vector's name is drawn as its quantity's symbol with
//! the rest as a subscript (R_A, F_i2, ω_1, k_v) in the SVG, PNG and PDF, and written flat in
//! the DXF (`RA`, `k_v`). Checked on the slider-crank template at t = 0: the frame's SVG
//! draws `RA` as `R<tspan dy font-size>A</tspan>` at 0.7 × the size, 0.25 em lower; a user's
//! load (`gas`) stays as written; the DXF's texts are flat; the PDF's text reads back as the
//! letters drawn (`RA`, `kv = `, `φ1 = `: poppler's `pdftotext`).

mod common;

use mechdraw::draw::font::{SUB_SHIFT_EM, SUB_SIZE};
use mechdraw::figure::shared::sheet::Paper;
use mechdraw::run::RunOptions;
use mechdraw::run::bytes::{self, WriteOptions};
use mechdraw::scene;

fn files(sheets: bool) -> Vec<(String, Vec<u8>)> {
    let l = scene::load(&common::root().join("templates/slider-crank.toml"), &[]).unwrap();
    let opts = RunOptions {
        positions: Some("0".parse().unwrap()),
        sheets: sheets.then_some(Paper::A4),
        ..RunOptions::default()
    };
    let p = mechdraw::run::products(&l, &opts).unwrap();
    bytes::to_files(&p, &WriteOptions::default()).unwrap()
}

fn text_of<'a>(files: &'a [(String, Vec<u8>)], name: &str) -> &'a str {
    let (_, b) = files.iter().find(|(n, _)| n == name).unwrap_or_else(|| panic!("no {name}"));
    std::str::from_utf8(b).unwrap()
}

/// The `<text …>` elements' contents (between `>` and `</text>`), each with its font size.
fn svg_texts(svg: &str) -> Vec<(f64, String)> {
    svg.split("<text ")
        .skip(1)
        .map(|t| {
            let size = t.split("font-size=\"").nth(1).and_then(|r| r.split('"').next()).unwrap().parse().unwrap();
            let body = &t[t.find('>').unwrap() + 1..t.find("</text>").unwrap()];
            (size, body.trim().to_string())
        })
        .collect()
}

#[test]
fn a_vector_name_is_a_symbol_and_a_subscript_tspan_in_the_svg_and_flat_in_the_dxf() {
    let f = files(false);
    let svg = text_of(&f, "frames/slider-crank/pos_000.svg");
    let texts = svg_texts(svg);
    // R_A: R at the text's size, A in a tspan 0.7 × as large, lowered by 0.25 em.
    let (size, body) = texts
        .iter()
        .find(|(_, b)| b.starts_with("R<tspan") && b.contains(">A</tspan>"))
        .unwrap_or_else(|| panic!("no R_A among {texts:?}"));
    let attr = |name: &str| -> f64 {
        body.split(&format!("{name}=\"")).nth(1).and_then(|r| r.split('"').next()).unwrap().parse().unwrap()
    };
    assert!((attr("font-size") - SUB_SIZE * size).abs() < 1e-5 * size, "{body}");
    assert!((attr("dy") - SUB_SHIFT_EM * size).abs() < 1e-5 * size, "{body}");
    // ω_1 and the inertia forces F_i2 alike; the caption's k_v without its `_`.
    for (base, sub) in [("ω", "1"), ("F", "i2"), ("k", "v")] {
        let tspan = format!(">{sub}</tspan>");
        assert!(texts.iter().any(|(_, b)| b.contains(&format!("{base}<tspan")) && b.contains(&tspan)), "{base}_{sub}");
    }
    assert!(!svg.contains("k_v"), "the `_` is drawn in the SVG");
    assert!(!text_of(&f, "slider-crank.dxf").contains("k<"), "a tspan in the DXF");
    // The user's load `gas` is a name as written, not g_as.
    assert!(texts.iter().any(|(_, b)| b == "gas"), "{texts:?}");
    // The DXF writes every text flat.
    let dxf = text_of(&f, "slider-crank.dxf");
    let values: Vec<&str> = dxf.lines().map(str::trim).collect();
    for want in ["RA", "−RA", "gas"] {
        let want = want.replace('−', "\\U+2212");
        assert!(values.contains(&want.as_str()), "the DXF lacks the text {want}");
    }
    assert!(!dxf.contains("tspan"));
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs poppler-utils (pdftotext): bash .ci/test, or cargo test --features system-tools"
)]
fn the_pdfs_text_reads_flat_as_the_dxf_writes_it() {
    let dir = tempfile::tempdir().unwrap();
    let f = files(true);
    let (_, pdf) = f.iter().find(|(n, _)| n.ends_with("-sheets.pdf")).unwrap();
    let path = dir.path().join("sheets.pdf");
    std::fs::write(&path, pdf).unwrap();
    let out = std::process::Command::new("pdftotext").arg(&path).arg("-").output().expect("run pdftotext");
    let text = String::from_utf8_lossy(&out.stdout);
    // Drawn R_A, φ_1, k_v; read back as the letters drawn: RA, φ1, kv (no `_`).
    let words: Vec<&str> = text.split_whitespace().collect();
    for want in ["RA", "−RA", "R03", "Fi2", "φ1", "ω1", "kv", "kl", "kf", "gas"] {
        assert!(words.contains(&want), "the PDF's text lacks `{want}`:\n{text}");
    }
}
