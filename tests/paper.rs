//! Paper is real (issue 14 item 2): every SVG a run writes is sized in millimetres with its
//! viewBox in paper millimetres, so that a length measured on the printed page times the
//! printed scale is the value; and librsvg (rsvg-convert, which drew every letter of a
//! metre-sized frame as a black box) and resvg render the four-bar frame's text (read back
//! by tesseract).
//!
//! The measuring test reads only what a student with a ruler has: the frame SVG (lengths
//! in viewBox millimetres) and the scales printed in the panel titles; the values it
//! compares with come from the run's JSON summary.

#![allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the library calls"
)]

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

fn out_dir(name: &str) -> PathBuf {
    let d = common::root().join("target/test-out/paper").join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// `mechdraw run templates/<scene>.toml --out dir -q` plus `extra`; its stdout.
fn run(scene: &str, dir: &Path, extra: &[&str]) -> String {
    let out = common::mechdraw()
        .arg("run")
        .arg(common::root().join("templates").join(format!("{scene}.toml")))
        .args(["--out", dir.to_str().unwrap(), "-q"])
        .args(extra)
        .output()
        .expect("run mechdraw");
    assert!(out.status.success(), "mechdraw run {scene}: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap()
}

/// Every file under `dir` ending in `.svg`.
fn svgs(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            out.extend(svgs(&p));
        } else if p.extension().is_some_and(|x| x == "svg") {
            out.push(p);
        }
    }
    out
}

/// The value of attribute `name` in the tag `tag` (e.g. `<svg ...>`).
fn attr<'a>(tag: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let start = tag.find(&key)? + key.len();
    Some(&tag[start..start + tag[start..].find('"')?])
}

/// Every element `<name …>` of `svg` (its opening tag), with the text up to its close when
/// it has content (`<text …>…</text>`).
fn elements<'a>(svg: &'a str, name: &str) -> Vec<&'a str> {
    let open = format!("<{name} ");
    let mut out = Vec::new();
    let mut rest = svg;
    while let Some(i) = rest.find(&open) {
        let s = &rest[i..];
        let end = s.find('>').unwrap() + 1;
        let end = if name == "text" { s.find("</text>").unwrap() } else { end };
        out.push(&s[..end]);
        rest = &s[end..];
    }
    out
}

/// The `<g class="layer-NAME">` groups' contents of `svg`, concatenated.
fn layer<'a>(svg: &'a str, name: &str) -> Vec<&'a str> {
    let open = format!("<g class=\"layer-{name}\"");
    let mut out = Vec::new();
    let mut rest = svg;
    while let Some(i) = rest.find(&open) {
        let s = &rest[i..];
        let end = s.find("</g>").unwrap();
        out.push(&s[..end]);
        rest = &s[end..];
    }
    out
}

fn num(tag: &str, name: &str) -> f64 {
    attr(tag, name).unwrap_or_else(|| panic!("no {name} in {tag}")).parse().unwrap()
}

/// The page of an SVG: (width mm, height mm, viewBox).
fn page(svg: &str) -> (f64, f64, [f64; 4]) {
    let head = &svg[svg.find("<svg").expect("an <svg> element")..];
    let head = &head[..head.find('>').unwrap()];
    let mm = |name: &str| -> f64 {
        let v = attr(head, name).unwrap_or_else(|| panic!("no {name}: {head}"));
        v.strip_suffix("mm").unwrap_or_else(|| panic!("{name}=\"{v}\" is not in mm")).parse().unwrap()
    };
    let vb: Vec<f64> = attr(head, "viewBox").unwrap().split(' ').map(|x| x.parse().unwrap()).collect();
    (mm("width"), mm("height"), [vb[0], vb[1], vb[2], vb[3]])
}

#[test]
fn every_svg_of_every_template_is_sized_in_mm_with_a_viewbox_of_the_same_size() {
    let mut templates: Vec<String> = std::fs::read_dir(common::root().join("templates"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    templates.sort();
    assert!(templates.len() >= 7, "{templates:?}");
    let mut checked = 0;
    for t in &templates {
        let dir = out_dir(&format!("all/{t}"));
        run(t, &dir, &[]);
        for f in svgs(&dir) {
            let svg = std::fs::read_to_string(&f).unwrap();
            let (w, h, vb) = page(&svg);
            assert!(w > 10.0 && h > 10.0 && w < 1200.0 && h < 1200.0, "{}: {w} × {h} mm", f.display());
            // The viewBox is in paper mm: as large as the page.
            assert!(
                (vb[2] - w).abs() < 1e-9 && (vb[3] - h).abs() < 1e-9,
                "{}: viewBox {vb:?}, page {w} × {h}",
                f.display()
            );
            // Every drawing of a mechanism or a chain (not the diagrams) prints its k_l;
            // Joukowski's lever (a velocity polygon turned, no lengths) its k_v.
            let diagram = f.components().any(|c| c.as_os_str() == "diagrams");
            let lever = f.to_string_lossy().ends_with("-joukowski.svg");
            // (k_l drawn with a subscript l: `kl = ` once its tspans are read through.)
            let scale = if lever { "kv = " } else { "kl = " };
            assert!(diagram || common::svg_plain(&svg).contains(scale), "{}: no {scale} printed", f.display());
            checked += 1;
        }
    }
    assert!(checked > 360, "{checked}");
}

/// The scale printed after `key = ` in one of the texts, e.g. `k_v = 0.01 (m/s)/mm` → 0.01.
fn printed_scale(texts: &[&str], key: &str) -> f64 {
    let t = texts.iter().find_map(|t| t.split(&format!("{key} = ")).nth(1)).unwrap_or_else(|| panic!("no {key}"));
    t.split(' ').next().unwrap().parse().unwrap()
}

#[test]
fn a_length_measured_on_the_page_times_the_printed_scale_is_the_value() {
    let dir = out_dir("measure");
    let json: serde_json::Value = serde_json::from_str(&run("fourbar-chebyshev", &dir, &["--json"])).unwrap();
    let svg = std::fs::read_to_string(dir.join("frames/fourbar-chebyshev/pos_090.svg")).unwrap();
    // k_l and k_v are drawn with subscripts: read through their tspans (`kl = `).
    let svg = common::svg_plain(&svg);
    let texts: Vec<&str> = elements(&svg, "text").into_iter().map(|t| t[t.find('>').unwrap() + 1..].trim()).collect();
    assert!(texts.contains(&"φ1 = 90°"), "not the 90° frame");
    let (k_l, k_v) = (printed_scale(&texts, "kl"), printed_scale(&texts, "kv"));
    let pos = &json["positions"][90];
    assert_eq!(pos["phi1_deg"].as_f64(), Some(90.0));

    // O1C: the centres of the two ground pivots' circles (O1 at the origin, C on its right
    // on the ground line, same radius) on layer MECHANISM.
    let circles: Vec<(f64, f64, f64)> = layer(&svg, "MECHANISM")
        .iter()
        .flat_map(|g| elements(g, "circle"))
        .map(|c| (num(c, "cx"), num(c, "cy"), num(c, "r")))
        .collect();
    let o1 = circles.iter().find(|c| c.0 == 0.0 && c.1 == 0.0).expect("O1 at the origin");
    let c = circles.iter().find(|c| c.0 > 0.0 && c.1 == 0.0 && c.2 == o1.2).expect("C on the ground line");
    let o1c = (c.0 - o1.0).hypot(c.1 - o1.1) * k_l;
    assert!((o1c - 0.08).abs() < 1e-6 * 0.08, "O1C measured {o1c} m");

    // pa: the velocity polygon's pole p (its small circle), and the arrow from it whose
    // direction is v_A's; the tip is the arrowhead's vertex farthest from the pole.
    let vel = layer(&svg, "VELOCITY");
    let pole = vel.iter().flat_map(|g| elements(g, "circle")).next().expect("the pole p");
    let (px, py) = (num(pole, "cx"), num(pole, "cy"));
    let va = &pos["vA"];
    let (vax, vay) = (va[0].as_f64().unwrap(), va[1].as_f64().unwrap());
    let va_mag = pos["vA_mag"].as_f64().unwrap();
    let heads: Vec<Vec<(f64, f64)>> = vel
        .iter()
        .flat_map(|g| elements(g, "polygon"))
        .filter(|p| attr(p, "stroke") == Some("none"))
        .map(|p| {
            attr(p, "points")
                .unwrap()
                .split(' ')
                .map(|xy| {
                    let (x, y) = xy.split_once(',').unwrap();
                    (x.parse().unwrap(), y.parse().unwrap())
                })
                .collect()
        })
        .collect();
    let mut found = None;
    for head in &heads {
        let tip = head
            .iter()
            .cloned()
            .fold((px, py), |a, b| if (b.0 - px).hypot(b.1 - py) > (a.0 - px).hypot(a.1 - py) { b } else { a });
        // SVG's y points down.
        let (dx, dy) = (tip.0 - px, -(tip.1 - py));
        let len = dx.hypot(dy);
        if len > 0.0 && (dx / len - vax / va_mag).abs() < 1e-4 && (dy / len - vay / va_mag).abs() < 1e-4 {
            found = Some(len * k_v);
        }
    }
    let measured = found.expect("the arrow pa");
    assert!((measured - va_mag).abs() < 1e-6 * va_mag, "|pa| · k_v = {measured}, |v_A| = {va_mag}");
    // The JSON states the same scales: k_l for the run, k_v this frame's.
    assert_eq!(json["scales"]["k_l"]["value"].as_f64(), Some(k_l));
    assert_eq!(pos["scales"]["k_v"].as_f64(), Some(k_v));
}

/// The words tesseract reads in the PNG `png`.
fn ocr(png: &Path) -> String {
    let out = Command::new("tesseract").arg(png).arg("stdout").output().expect("run tesseract");
    assert!(out.status.success(), "tesseract: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8_lossy(&out.stdout).into_owned()
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs rsvg-convert (librsvg2-bin) and tesseract: bash .ci/test, or cargo test --features system-tools"
)]
fn librsvg_and_resvg_render_the_four_bar_frames_text() {
    let missing: Vec<&str> = ["rsvg-convert", "tesseract"]
        .into_iter()
        .filter(|t| {
            !Command::new("sh").args(["-c", &format!("command -v {t}")]).output().is_ok_and(|o| o.status.success())
        })
        .collect();
    assert!(
        missing.is_empty(),
        "missing {missing:?}: install Debian's librsvg2-bin and tesseract-ocr (bash .ci/test does)"
    );
    let dir = out_dir("librsvg");
    run("fourbar-chebyshev", &dir, &[]);
    let svg = dir.join("frames/fourbar-chebyshev/pos_090.svg");
    let png = dir.join("pos_090.png");
    // 200 dpi: 3.5 mm letters are about 28 px high.
    let out = Command::new("rsvg-convert")
        .args(["--dpi-x", "200", "--dpi-y", "200", "--background-color", "white", "-o"])
        .arg(&png)
        .arg(&svg)
        .output()
        .expect("run rsvg-convert");
    assert!(out.status.success(), "rsvg-convert: {}", String::from_utf8_lossy(&out.stderr));
    let text = ocr(&png);
    // k_v's subscript v is too small for tesseract (it reads `k,`): its unit instead.
    for word in ["Mechanism", "Velocity", "(m/s)/mm"] {
        assert!(text.contains(word), "{word} not read from librsvg's render:\n{text}");
    }
    // The same frame through resvg (the library's rasteriser, with the bundled font), at
    // the same 200 dpi.
    let frame = std::fs::read_to_string(&svg).unwrap();
    let (w_mm, _, _) = page(&frame);
    let px = (w_mm / 25.4 * 200.0).round() as u32;
    let png = dir.join("pos_090_resvg.png");
    std::fs::write(&png, mechdraw::draw::raster::to_png(&frame, px).unwrap()).unwrap();
    let text = ocr(&png);
    for word in ["Mechanism", "Velocity", "(m/s)/mm"] {
        assert!(text.contains(word), "{word} not read from resvg's render:\n{text}");
    }
}
