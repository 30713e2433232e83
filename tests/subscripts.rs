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

/// Every file of a run of template `name` at `positions` (all when `None`), without frames
/// when `frames` is false.
fn files_of(name: &str, positions: Option<&str>, frames: bool, sheets: bool) -> Vec<(String, Vec<u8>)> {
    let l = scene::load(&common::root().join(format!("templates/{name}.toml")), &[]).unwrap();
    let opts = RunOptions {
        positions: positions.map(|p| p.parse().unwrap()),
        no_frames: !frames,
        sheets: sheets.then_some(Paper::A4),
        ..RunOptions::default()
    };
    let p = mechdraw::run::products(&l, &opts).unwrap();
    bytes::to_files(&p, &WriteOptions::default()).unwrap()
}

/// The `<text>` bodies of every SVG whose name starts with `prefix`.
fn svg_texts_under(files: &[(String, Vec<u8>)], prefix: &str) -> Vec<String> {
    let found: Vec<String> = files
        .iter()
        .filter(|(n, _)| n.starts_with(prefix) && n.ends_with(".svg"))
        .flat_map(|(_, b)| svg_texts(std::str::from_utf8(b).unwrap()).into_iter().map(|(_, t)| t))
        .collect();
    assert!(!found.is_empty(), "no SVG text under {prefix}: {:?}", files.iter().map(|f| &f.0).collect::<Vec<_>>());
    found
}

/// A text's body with each subscript tspan written as `_{…}` (`M_{e1}`), other tspans'
/// texts as they are.
fn marked(body: &str) -> String {
    let mut out = String::new();
    let mut rest = body;
    while let Some(i) = rest.find("<tspan") {
        out.push_str(&rest[..i]);
        let open_end = rest[i..].find('>').map_or(rest.len(), |j| i + j + 1);
        let close = rest[open_end..].find("</tspan>").map_or(rest.len(), |j| open_end + j);
        // A subscript's tspan sets its smaller size; the base text after it only moves back.
        let content = &rest[open_end..close];
        if rest[i..open_end].contains("font-size") {
            out.push_str(&format!("_{{{content}}}"));
        } else {
            out.push_str(content);
        }
        rest = &rest[(close + "</tspan>".len()).min(rest.len())..];
    }
    out.push_str(rest);
    out
}

#[test]
fn the_tables_names_are_symbols_with_subscripts_and_a_users_load_as_typed() {
    // The frame's force panel: its Magnitudes list (R_A, …, M_e1), the load `gas` flat.
    let f = files(true);
    let frame: Vec<String> =
        svg_texts(text_of(&f, "frames/slider-crank/pos_000.svg")).into_iter().map(|t| marked(&t.1)).collect();
    assert!(frame.iter().any(|t| t == "M_{e1}"), "no M_e1 in the frame's table: {frame:?}");
    assert!(!frame.iter().any(|t| t == "Me1"), "a flat Me1 in the frame: {frame:?}");
    // The printed sheets' tables: kinematics (v_B …) and forces (F_i2, G_2, R…, M_e1).
    let sheets: Vec<String> = svg_texts_under(&f, "sheets/").iter().map(|t| marked(t)).collect();
    for want in ["M_{e1}", "F_{i2}", "G_{2}", "gas"] {
        assert!(sheets.iter().any(|t| t == want), "the sheets' tables lack {want}: {sheets:?}");
    }
    for flat in ["Me1", "Fi2", "G2", "g_{as}"] {
        assert!(!sheets.iter().any(|t| t == flat), "the sheets draw {flat}");
    }
    // A measured point's speed: v and the point's name as its subscript.
    assert!(sheets.iter().any(|t| t.starts_with("v_{") || t.starts_with("|v_{")), "{sheets:?}");
    // The four-bar's sheet table: R_An from the CSV's R_An, v_BA, ω_2, φ_2; a point's
    // coordinates (A) and the transmission angle ∠ABC flat.
    let f = files_of("fourbar-chebyshev", Some("90"), false, true);
    let sheets: Vec<String> = svg_texts_under(&f, "sheets/").iter().map(|t| marked(t)).collect();
    for want in ["R_{An}", "v_{BA}", "ω_{2}", "φ_{2}", "M_{e1}", "F_{i21}", "A", "∠ABC"] {
        assert!(sheets.iter().any(|t| t == want), "the four-bar's sheets lack {want}: {sheets:?}");
    }
    assert!(!sheets.iter().any(|t| t.contains('_') && !t.contains("_{")), "an underscore drawn: {sheets:?}");
}

#[test]
fn angle_dimensions_and_the_joukowski_line_have_subscripts_where_the_writer_can() {
    // The triad's φ1 = 75.77°: φ_1 in the SVG, `φ1` in the DXF (no `_`, no tspan).
    let f = files_of("triad-popa", None, false, false);
    let svg: Vec<String> = svg_texts_under(&f, "triad-popa").iter().map(|t| marked(t)).collect();
    assert!(svg.iter().any(|t| t == "φ_{1} = 75.77°"), "{svg:?}");
    let (_, dxf) = f.iter().find(|(n, _)| n == "triad-popa.dxf").unwrap();
    let dxf = String::from_utf8_lossy(dxf);
    assert!(dxf.lines().any(|l| l.contains("1 = 75.77") && !l.contains('_')), "the DXF lacks φ1 = 75.77°");
    assert!(!dxf.contains("_1 = 75.77") && !dxf.contains("tspan"));
    // Joukowski's lever: M_e1 = −Σ M_p(F_i) / ω_1 with its loads' names F_i21 in its table;
    // the DXF writes the line as marked up (`M_e1`, as the scale captions' `k_v`).
    let f = files_of("fourbar-chebyshev", None, false, false);
    let lever: Vec<String> =
        svg_texts(text_of(&f, "fourbar-chebyshev-joukowski.svg")).into_iter().map(|t| marked(&t.1)).collect();
    assert!(lever.iter().any(|t| t.starts_with("M_{e1} = −Σ M_{p}(F_{i}) / ω_{1} = ")), "{lever:?}");
    assert!(lever.iter().any(|t| t.starts_with("by the reactions: M_{e1} = ")), "{lever:?}");
    assert!(lever.iter().any(|t| t == "F_{i21}"), "{lever:?}");
    assert!(text_of(&f, "fourbar-chebyshev-joukowski.dxf").contains("M_e1 = "));
}

#[test]
fn the_reports_free_bodies_and_sketches_name_quantities_with_subscripts() {
    use mechdraw::draw::{RunKind, Shape};
    use mechdraw::run::positions::Positions;
    use mechdraw::run::report::{ReportOptions, report};
    let l = scene::load(&common::root().join("templates/slider-crank.toml"), &[]).unwrap();
    let r = report(&l, &ReportOptions { paper: Paper::A4, positions: Some(Positions::List(vec![0.0])) }).unwrap();
    // Every text of the report as (flat value, its subscripts).
    let texts: Vec<(String, Vec<String>)> = r
        .pages
        .iter()
        .flat_map(|p| p.drawing.entities.iter())
        .filter_map(|e| match &e.shape {
            Shape::Text { value, runs, .. } => Some((
                value.clone(),
                runs.split(value).filter(|(_, k)| *k == RunKind::Sub).map(|(s, _)| s.to_string()).collect(),
            )),
            _ => None,
        })
        .collect();
    let has = |value: &str, subs: &[&str]| texts.iter().any(|(v, s)| v == value && s == subs);
    // The driver's ω_1 on the sketches; the free bodies' F_i2, G_2, M_e1 = … N·mm.
    assert!(has("ω1", &["1"]), "no ω_1 drawn");
    assert!(has("Fi2", &["i2"]) && has("G2", &["2"]), "no F_i2, G_2 on the free bodies");
    assert!(texts.iter().any(|(v, s)| v.starts_with("Me1 = ") && s == &["e1"]), "no M_e1 = … on the free bodies");
    // The load `gas` as typed, wherever it is named.
    assert!(texts.iter().any(|(v, _)| v == "gas") && !texts.iter().any(|(v, s)| v == "gas" && !s.is_empty()));
    assert!(!texts.iter().any(|(v, s)| (v == "Fi2" || v == "ω1") && s.is_empty()), "a flat F_i2 or ω_1");
}

/// A DXF's bytes as read, its `\U+XXXX` escapes decoded.
fn dxf_plain(dxf: &[u8]) -> String {
    common::dxf_unescape(&String::from_utf8_lossy(dxf))
}

/// Whether `text` (an SVG text's body, subscripts marked `_{…}`) writes an angle's index
/// flat: `φ1`, `φ2`, `φ3` not as subscripts.
fn has_flat_phi(text: &str) -> bool {
    text.char_indices().any(|(i, c)| c == 'φ' && text[i + c.len_utf8()..].starts_with(|n: char| n.is_ascii_digit()))
}

#[test]
fn the_triads_caption_and_modes_lists_have_subscripts_flat_in_the_dxf() {
    let f = files_of("triad-popa", None, false, false);
    // Fig. 3's caption: the pattern method's start angle φ_1.
    let fig: Vec<String> = svg_texts(text_of(&f, "triad-popa.svg")).into_iter().map(|t| marked(&t.1)).collect();
    assert!(
        fig.iter().any(|t| t.starts_with("Pattern method: φ_{1} = 90.00° (dashed, red) → 75.77° in 4 iterations")),
        "{fig:?}"
    );
    // The modes sheet: each mode's φ_1, φ_2, φ_3, and the title's.
    let modes: Vec<String> = svg_texts(text_of(&f, "triad-popa-modes.svg")).into_iter().map(|t| marked(&t.1)).collect();
    let lists: Vec<&String> = modes.iter().filter(|t| t.starts_with("φ_{1} = ")).collect();
    assert_eq!(lists.len(), 8, "{modes:?}");
    assert!(lists.iter().all(|t| t.contains(", φ_{2} = ") && t.contains(", φ_{3} = ")), "{lists:?}");
    assert!(modes.iter().any(|t| t.ends_with("Fig. 3 draws mode 1.")), "{modes:?}");
    assert!(modes.iter().any(|t| t.starts_with("φ_{1}, φ_{2}, φ_{3}: directions")), "{modes:?}");
    // No angle's index left flat on either picture.
    for t in fig.iter().chain(&modes) {
        assert!(!has_flat_phi(t), "a flat φ index: {t}");
    }
    // The DXFs write the same texts flat: φ1, no `_`, no tspan.
    let fig_dxf = dxf_plain(&f.iter().find(|(n, _)| n == "triad-popa.dxf").unwrap().1);
    assert!(fig_dxf.contains("Pattern method: φ1 = 90.00° (dashed, red) → 75.77°"), "{fig_dxf}");
    let modes_dxf = dxf_plain(&f.iter().find(|(n, _)| n == "triad-popa-modes.dxf").unwrap().1);
    assert!(modes_dxf.contains("φ1 = 75.77°, φ2 = 102.23°, φ3 = 117.04°"), "mode 1's angles");
    assert!(modes_dxf.contains("Fig. 3 draws mode 1."));
    assert!(modes_dxf.contains("φ1, φ2, φ3: directions"));
    for dxf in [&fig_dxf, &modes_dxf] {
        assert!(!dxf.contains("φ_") && !dxf.contains("tspan"));
    }
}

#[test]
fn the_frames_position_titles_are_phi_1_in_the_svg_and_phi1_where_read() {
    // The four-bar's frame at 90°: φ_1 = 90° drawn with a subscript; its SVG read through
    // the tspans (as a browser's textContent reads it) says φ1 = 90°; the DXF's text, flat.
    let f = files_of("fourbar-chebyshev", Some("90"), true, false);
    let frame = text_of(&f, "frames/fourbar-chebyshev/pos_090.svg");
    let texts: Vec<String> = svg_texts(frame).into_iter().map(|t| marked(&t.1)).collect();
    assert!(texts.iter().any(|t| t == "φ_{1} = 90°"), "{texts:?}");
    assert!(!texts.iter().any(|t| has_flat_phi(t)), "{texts:?}");
    assert!(common::svg_plain(frame).contains("φ1 = 90°"));
    let dxf = dxf_plain(&f.iter().find(|(n, _)| n == "fourbar-chebyshev.dxf").unwrap().1);
    assert!(dxf.lines().any(|l| l.trim() == "φ1 = 90°"), "the DXF's position text");
    assert!(!dxf.contains("φ_1"));
    // The centres' and Joukowski's panels: φ_1 = 30°, Joukowski's lever   φ_1 = 135°.
    let centres: Vec<String> =
        svg_texts(text_of(&f, "fourbar-chebyshev-centres.svg")).into_iter().map(|t| marked(&t.1)).collect();
    assert!(centres.iter().any(|t| t == "φ_{1} = 30°") && !centres.iter().any(|t| has_flat_phi(t)), "{centres:?}");
    let lever: Vec<String> =
        svg_texts(text_of(&f, "fourbar-chebyshev-joukowski.svg")).into_iter().map(|t| marked(&t.1)).collect();
    assert!(lever.iter().any(|t| t.starts_with("Joukowski's lever   φ_{1} = ")), "{lever:?}");
    assert!(!lever.iter().any(|t| has_flat_phi(t)), "{lever:?}");
    let lever_dxf = dxf_plain(&f.iter().find(|(n, _)| n == "fourbar-chebyshev-joukowski.dxf").unwrap().1);
    assert!(lever_dxf.contains("Joukowski's lever   φ1 = ") && !lever_dxf.contains("φ_1"));
}

/// Every text of the report of template `name` at `positions` (a motion's; `None`: a scene
/// without one) as (flat value, its subscripts).
fn report_texts(name: &str, positions: Option<Vec<f64>>) -> Vec<(String, Vec<String>)> {
    use mechdraw::draw::{RunKind, Shape};
    use mechdraw::run::positions::Positions;
    use mechdraw::run::report::{ReportOptions, report};
    let l = scene::load(&common::root().join(format!("templates/{name}.toml")), &[]).unwrap();
    let r = report(&l, &ReportOptions { paper: Paper::A4, positions: positions.map(Positions::List) }).unwrap();
    r.pages
        .iter()
        .flat_map(|p| p.drawing.entities.iter())
        .filter_map(|e| match &e.shape {
            Shape::Text { value, runs, .. } => Some((
                value.clone(),
                runs.split(value).filter(|(_, k)| *k == RunKind::Sub).map(|(s, _)| s.to_string()).collect(),
            )),
            _ => None,
        })
        .collect()
}

/// Asserts that `texts` hold each (flat value, subscripts) of `want`.
fn assert_drawn(texts: &[(String, Vec<String>)], what: &str, want: &[(&str, &[&str])]) {
    for (value, subs) in want {
        assert!(texts.iter().any(|(v, s)| v == value && s == subs), "the {what} lack {value} with subscripts {subs:?}");
    }
}

#[test]
fn the_reports_tables_name_quantities_with_subscripts_and_points_and_users_names_flat() {
    // The four-bar's data: l_1, ω_1, ε_1, φ_1, m_21 …; the points O1, O1A flat.
    let t = report_texts("fourbar-chebyshev", Some(vec![90.0]));
    let four_bar: [(&str, &[&str]); 9] = [
        ("crank O1A = l1", &["1"]),
        ("ω1 (counter-clockwise +)", &["1"]),
        ("ε1", &["1"]),
        ("crank angles φ1", &["1"]),
        ("m21 bar AB", &["21"]),
        ("m3 rocker", &["3"]),
        ("F at M for φ1 ∈ [80°, 280°]", &["1"]),
        ("crank pivot O1", &[]),
        ("g", &[]),
    ];
    assert_drawn(&t, "four-bar's data", &four_bar);
    // The triad's: R_1, l_12, φ_1, and the iterations' header φ_1 [°], |R_3 − A3O3| [mm].
    let t = report_texts("triad-popa", None);
    let triad: [(&str, &[&str]); 7] = [
        ("R1 = O1A1", &["1"]),
        ("l12 = A1A2", &["12"]),
        ("pattern: start φ1", &["1"]),
        ("pattern: ε on |R3 − A3O3|", &["3"]),
        ("φ1 [°]", &["1"]),
        ("|R3 − A3O3| [mm]", &["3"]),
        ("pivot O2", &[]),
    ];
    assert_drawn(&t, "triad's tables", &triad);
    // The slider-crank's: m_2 and J_2 with the body's name as the scene writes it; the
    // user's load `gas` and every point's name flat.
    let t = report_texts("slider-crank", Some(vec![0.0]));
    let slider_crank: [(&str, &[&str]); 3] =
        [("m2 (rod)", &["2"]), ("J2 about its centroid", &["2"]), ("link 2 rod: AB", &[])];
    assert_drawn(&t, "slider-crank's data", &slider_crank);
    assert!(t.iter().any(|(v, s)| v.starts_with("load gas at B") && s.is_empty()), "the load's row");
}
