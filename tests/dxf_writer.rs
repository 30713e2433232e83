//! The DXF writer checked with an independent reader (ezdxf: recover + audit, then a read
//! back of counts, layers, line type pattern, dimension measurements, widths and text),
//! plus the golden DXF and the golden PNG (SVG writer) of one sample drawing.

#![allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the library calls"
)]

mod common;

use std::f64::consts::PI;
use std::path::PathBuf;
use std::process::Command;

use mechdraw::draw::dxf::{self, Dimensions, DxfOptions, DxfVersion};
use mechdraw::draw::{Aci, DimStyle, Drawing, Entity, HAlign, LineType, LinearMarks, Runs, Shape, VAlign, svg};
use mechdraw::geom::{Point, Vector};
use serde_json::Value;

fn p(x: f64, y: f64) -> Point {
    Point::new(x, y)
}

/// A four-bar-like sketch that uses every shape kind, every text alignment, entity colours,
/// the dashed line type (by layer and by entity) and four dimensions (an angular one over
/// 180°, a rotated linear one, one whose text is turned).
fn sample_drawing() -> Drawing {
    let mut d = Drawing::new(DimStyle { text_height: 2.5, arrow_size: 2.5 });
    let frame = d.layer("FRAME", Aci::BLACK, LineType::Continuous);
    let links = d.layer("LINKS", Aci::BLUE, LineType::Continuous);
    let constr = d.layer("CONSTRUCTION", Aci::RED, LineType::Dashed);
    let dims = d.layer("DIMENSIONS", Aci::GREEN, LineType::Continuous);
    let text = d.layer("TEXT", Aci::MAGENTA, LineType::Continuous);
    let vectors = d.layer("VECTORS", Aci::ORANGE, LineType::Continuous);

    let (a0, b0, a, b) = (p(10.0, 10.0), p(70.0, 10.0), p(25.0, 35.0), p(65.0, 45.0));
    // Origin marker with a centred label exactly at (0, 0).
    d.add(frame, Shape::Line { from: p(-4.0, 0.0), to: p(4.0, 0.0) });
    d.add(frame, Shape::Line { from: p(0.0, -4.0), to: p(0.0, 4.0) });
    d.add(
        text,
        Shape::Text {
            at: p(0.0, 0.0),
            height: 1.5,
            value: "O".into(),
            runs: Runs::flat(),
            halign: HAlign::Center,
            valign: VAlign::Middle,
            rotation: 0.0,
        },
    );
    // Ground: hatched filled triangles and a quad under each fixed joint.
    for g in [a0, b0] {
        d.add(frame, Shape::Filled { points: vec![g, g + Vector::new(-3.0, -5.0), g + Vector::new(3.0, -5.0)] });
        d.add(
            frame,
            Shape::Filled {
                points: vec![
                    g + Vector::new(-6.0, -5.0),
                    g + Vector::new(6.0, -5.0),
                    g + Vector::new(6.0, -6.0),
                    g + Vector::new(-6.0, -6.0),
                ],
            },
        );
    }
    // A convex pentagon (more than four vertices: written as a fan of SOLIDs).
    d.add_colored(
        frame,
        Aci(140),
        Shape::Filled { points: vec![p(125.0, 20.0), p(130.0, 24.0), p(128.0, 30.0), p(122.0, 30.0), p(120.0, 24.0)] },
    );
    // Links: a wide open polyline and a closed triangle (coupler) of zero width.
    d.add(links, Shape::Polyline { points: vec![a0, a, b, b0], closed: false, width: 0.8 });
    d.add(links, Shape::Polyline { points: vec![a, b, p(50.0, 60.0)], closed: true, width: 0.0 });
    for j in [a0, b0, a, b] {
        d.add(links, Shape::Circle { center: j, radius: 1.5 });
    }
    // Construction: the circle of A about A0 (dashed by layer), an arc wrapping through 0°,
    // and a dashed line on a continuous layer (dashed by entity).
    let ra = (a - a0).norm();
    d.add(constr, Shape::Arc { center: a0, radius: ra, start: 20f64.to_radians(), end: 150f64.to_radians() });
    d.add(constr, Shape::Arc { center: b0, radius: 12.0, start: 300f64.to_radians(), end: 40f64.to_radians() });
    d.push(Entity {
        layer: links,
        color: Some(Aci::DARK_GREY),
        linetype: Some(LineType::Dashed),
        shape: Shape::Line { from: a0, to: b },
    });
    // Velocity of B and a short vector whose head is shortened.
    d.add(vectors, Shape::Arrow { from: b, to: p(80.0, 60.0), head: 3.0 });
    d.add_colored(vectors, Aci::RED, Shape::Arrow { from: a, to: p(27.0, 36.0), head: 3.0 });
    // Every alignment, with Greek letters, degrees and primes.
    let words = ["φ1", "ω2 = 12.5 rad/s", "ε3 ≈ π/2", "30′", "45°"];
    let mut k = 0;
    for (iv, valign) in [VAlign::Baseline, VAlign::Middle, VAlign::Top].into_iter().enumerate() {
        for (ih, halign) in [HAlign::Left, HAlign::Center, HAlign::Right].into_iter().enumerate() {
            let at = p(100.0 + 25.0 * ih as f64, 60.0 - 8.0 * iv as f64);
            d.add(frame, Shape::Circle { center: at, radius: 0.3 });
            d.add(
                text,
                Shape::Text {
                    at,
                    height: 2.0,
                    value: words[k % words.len()].into(),
                    runs: Runs::flat(),
                    halign,
                    valign,
                    rotation: 0.0,
                },
            );
            k += 1;
        }
    }
    d.add(
        text,
        Shape::Text {
            at: p(95.0, 10.0),
            height: 2.5,
            value: "rotated 30°".into(),
            runs: Runs::flat(),
            halign: HAlign::Left,
            valign: VAlign::Baseline,
            rotation: 30f64.to_radians(),
        },
    );
    d.text(text, p(a.x - 6.0, a.y + 2.0), 3.0, "A");
    d.text(text, p(b.x + 2.0, b.y + 2.0), 3.0, "B");
    // Dimensions: φ1 at A0, the 250° reflex angle at B0, A0B0 horizontal, AB rotated along
    // the link, B0B vertical, and one measured at 200° (text turned to stay readable).
    let phi1 = (a - a0).y.atan2((a - a0).x).to_degrees();
    d.add(
        dims,
        Shape::AngularDimension {
            vertex: a0,
            first: p(30.0, 10.0),
            second: a,
            radius: 14.0,
            text: format!("φ1 = {phi1:.2}°"),
            runs: Default::default(),
        },
    );
    d.add(
        dims,
        Shape::AngularDimension {
            vertex: b0,
            first: b0 + Vector::new(-10.0, 0.0),
            second: b,
            radius: 8.0,
            text: "reflex".into(),
            runs: Default::default(),
        },
    );
    d.add(
        dims,
        Shape::LinearDimension {
            p1: a0,
            p2: b0,
            line_at: p(40.0, -12.0),
            angle: 0.0,
            text: "60".into(),
            marks: LinearMarks::default(),
        },
    );
    let ab = b - a;
    d.add_colored(
        dims,
        Aci::BLUE,
        Shape::LinearDimension {
            p1: a,
            p2: b,
            line_at: a + Vector::new(-ab.y, ab.x).normalize() * 8.0,
            angle: ab.y.atan2(ab.x),
            text: format!("{:.2}", ab.norm()),
            marks: LinearMarks::default(),
        },
    );
    d.add(
        dims,
        Shape::LinearDimension {
            p1: b0,
            p2: b,
            line_at: p(90.0, 30.0),
            angle: PI / 2.0,
            text: "35".into(),
            marks: LinearMarks::default(),
        },
    );
    d.add(
        dims,
        Shape::LinearDimension {
            p1: a,
            p2: p(50.0, 60.0),
            line_at: p(30.0, 60.0),
            angle: 200f64.to_radians(),
            text: "~".into(),
            marks: LinearMarks::default(),
        },
    );
    d
}

/// The sample drawing plus 360 layers `POS_000` … `POS_359` (one marker each), as a
/// position-per-degree animation would write.
fn many_layers_drawing() -> Drawing {
    let mut d = sample_drawing();
    for i in 0..360 {
        let color = Aci((i % 255 + 1) as u8);
        let l = d.layer(&format!("POS_{i:03}"), color, LineType::Continuous);
        let a = (i as f64).to_radians();
        d.add(l, Shape::Circle { center: p(40.0 + 30.0 * a.cos(), 30.0 + 30.0 * a.sin()), radius: 0.4 });
    }
    d
}

fn out_dir() -> PathBuf {
    let d = common::root().join("target/test-out/dxf_writer");
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn write_dxf(name: &str, d: &Drawing) -> PathBuf {
    let path = out_dir().join(name);
    let bytes = dxf::to_bytes(d, &DxfOptions::default()).expect("DXF written");
    std::fs::write(&path, bytes).unwrap();
    path
}

fn inspect(path: &std::path::Path) -> Value {
    let out = Command::new(common::python())
        .arg(common::root().join("tests/ezdxf_inspect.py"))
        .arg(path)
        .output()
        .expect("run ezdxf_inspect.py");
    assert!(out.status.success(), "ezdxf_inspect failed: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("inspect JSON")
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

#[test]
fn sample_drawing_audits_clean_and_reads_back() {
    let d = many_layers_drawing();
    let path = write_dxf("many_layers.dxf", &d);
    common::assert_ezdxf_clean(&[&path]);
    let info = inspect(&path);
    assert_eq!(info["version"], "AC1009");

    // Entity counts, counted by hand from sample_drawing().
    let counts = &info["counts"];
    let n = |t: &str| counts[t].as_u64().unwrap_or(0);
    // Circles: 4 joints + 9 alignment markers + 360 POS markers.
    assert_eq!(n("CIRCLE"), 4 + 9 + 360);
    // Arcs: two construction arcs.
    assert_eq!(n("ARC"), 2);
    // Lines: origin cross (2) + dashed A0–B + two arrow shafts.
    assert_eq!(n("LINE"), 2 + 1 + 2);
    // SOLIDs: 2 triangles + 2 quads + pentagon fan (3) + 2 arrowheads.
    assert_eq!(n("SOLID"), 2 + 2 + 3 + 2);
    assert_eq!(n("POLYLINE"), 2);
    assert_eq!(n("TEXT"), 1 + 9 + 1 + 2);
    // Six dimensions, the reflex angle as two halves.
    assert_eq!(n("DIMENSION"), 7);

    // Layers with their colours and line types.
    // (ezdxf adds its own "Defpoints" layer to every document it loads.)
    let layers = info["layers"].as_object().unwrap();
    assert_eq!(layers.keys().filter(|k| *k != "Defpoints").count(), d.layers.len());
    for l in &d.layers {
        let got = &layers[&l.name];
        assert_eq!(got[0].as_i64().unwrap(), l.color.0 as i64, "colour of {}", l.name);
        let lt = if l.linetype == LineType::Dashed { "DASHED" } else { "CONTINUOUS" };
        assert_eq!(got[1].as_str().unwrap(), lt, "line type of {}", l.name);
    }

    // The DASHED pattern: two elements, dash positive, gap negative, total = |dash| + |gap|,
    // and a dash a sensible fraction (0.5–5 %) of the drawing's extent.
    let pat: Vec<f64> = info["linetypes"]["DASHED"].as_array().unwrap().iter().filter_map(|v| v.as_f64()).collect();
    // ezdxf stores [72 alignment, 73 count, 40 total, 49 dash, 49 gap].
    let (count, total, dash, gap) = (pat[pat.len() - 4], pat[pat.len() - 3], pat[pat.len() - 2], pat[pat.len() - 1]);
    assert_eq!(count, 2.0);
    assert!(dash > 0.0 && gap < 0.0);
    assert!(close(total, dash - gap, 1e-12));
    let b = d.bounds().unwrap();
    let extent = b.width().max(b.height());
    assert!(dash > 0.005 * extent && dash < 0.05 * extent, "dash {dash} for extent {extent}");

    // Entity colour overrides and line type overrides.
    let ents = info["entities"].as_array().unwrap();
    assert!(ents.iter().any(|e| e["type"] == "LINE" && e["color"] == 8 && e["linetype"] == "DASHED"));
    assert!(ents.iter().any(|e| e["type"] == "SOLID" && e["color"] == 140));
    assert!(ents.iter().filter(|e| e["type"] == "CIRCLE").all(|e| e["color"] == 256), "circles are BYLAYER");

    // Polylines: width 0.8 at every vertex, open; the triangle closed; vertices on the
    // polyline's layer.
    let polys = info["polylines"].as_array().unwrap();
    assert_eq!(polys[0]["closed"], false);
    for w in polys[0]["widths"].as_array().unwrap() {
        assert_eq!(w[0].as_f64().unwrap(), 0.8);
        assert_eq!(w[1].as_f64().unwrap(), 0.8);
    }
    assert_eq!(polys[0]["points"].as_array().unwrap().len(), 4);
    assert_eq!(polys[1]["closed"], true);
    for poly in polys {
        for l in poly["vertex_layers"].as_array().unwrap() {
            assert_eq!(l, &poly["layer"]);
        }
    }

    // Text: every value round-trips (Greek letters, °, ′, ≈); justified text is placed at
    // its alignment point, including the one at the origin; the width factor keeps
    // LibreCAD's wider font in the text's box, and a centred single character is written
    // left-aligned where it is centred between LibreCAD's glyph and DejaVu's
    // (`librecad::text_fit`, whose unit tests hold both to those rules).
    let texts = info["texts"].as_array().unwrap();
    let expected: Vec<(&str, Point, u8, u8, f64, f64)> = d
        .entities
        .iter()
        .filter_map(|e| match &e.shape {
            Shape::Text { at, height, value, halign, valign, rotation, .. } => {
                Some((value, *at, *height, *halign, *valign, *rotation))
            }
            _ => None,
        })
        .map(|(value, at, height, halign, valign, rotation)| {
            let fit = dxf::librecad::text_fit(at, height, value, halign, valign, rotation);
            (value.as_str(), fit.at, fit.halign, fit.valign, rotation, fit.width)
        })
        .map(|(value, at, halign, valign, rotation, width)| {
            (
                value,
                at,
                match halign {
                    HAlign::Left => 0,
                    HAlign::Center => 1,
                    HAlign::Right => 2,
                },
                match valign {
                    VAlign::Baseline => 0,
                    VAlign::Middle => 2,
                    VAlign::Top => 3,
                },
                rotation.to_degrees(),
                width,
            )
        })
        .collect();
    assert_eq!(texts.len(), expected.len());
    assert!(expected.iter().any(|e| e.5 < 1.0), "some text is narrowed for LibreCAD");
    for (t, (value, at, h, v, rot, width)) in texts.iter().zip(&expected) {
        assert_eq!(t["text"].as_str().unwrap(), *value);
        assert_eq!(t["width"].as_f64().unwrap(), *width, "{value}: width factor");
        assert_eq!(t["halign"].as_u64().unwrap(), *h as u64, "{value}");
        assert_eq!(t["valign"].as_u64().unwrap(), *v as u64, "{value}");
        let pl = t["placement"].as_array().unwrap();
        assert!(
            close(pl[0].as_f64().unwrap(), at.x, 1e-9) && close(pl[1].as_f64().unwrap(), at.y, 1e-9),
            "{value}: {pl:?}"
        );
        assert!(close(t["rotation"].as_f64().unwrap(), *rot, 1e-9), "{value}");
        // The insertion point (10/20) is where the text starts (left end of the baseline,
        // from the estimated width), for readers that ignore the alignment.
        let height = t["height"].as_f64().unwrap();
        let width = mechdraw::draw::parts::text_width(value, height);
        let along = [0.0, 0.5, 1.0][*h as usize] * width;
        let up = match v {
            2 => 0.5 * height,
            3 => height,
            _ => 0.0,
        };
        let r = rot.to_radians();
        let start = (at.x - along * r.cos() + up * r.sin(), at.y - along * r.sin() - up * r.cos());
        let ins = t["insert"].as_array().unwrap();
        assert!(
            close(ins[0].as_f64().unwrap(), start.0, 1e-9) && close(ins[1].as_f64().unwrap(), start.1, 1e-9),
            "{value}: insertion point {ins:?}, expected {start:?}"
        );
    }

    // Dimensions: measurements equal the true angle or distance computed here from the
    // coordinates; the drawing's text is the override; each has its own *D block with
    // arrowheads and the same text. An angle of 180° or more is two 2-line halves (LibreCAD
    // draws no larger angular dimension), the first with the text and one arrowhead, the
    // second with no text (a space) and the other arrowhead.
    let dims = info["dimensions"].as_array().unwrap();
    // (dimension type, true value, text, arrowheads and texts in its block)
    let truth: Vec<(u64, f64, String, u64, u64)> = d
        .entities
        .iter()
        .flat_map(|e| match &e.shape {
            Shape::AngularDimension { vertex, first, second, text, .. } => {
                let a1 = (first - vertex).y.atan2((first - vertex).x).to_degrees();
                let a2 = (second - vertex).y.atan2((second - vertex).x).to_degrees();
                let sweep = (a2 - a1).rem_euclid(360.0);
                if sweep < 180.0 {
                    vec![(2, sweep, text.clone(), 2, 1)]
                } else {
                    // The part with the text 170° (its text well away from both rays), the
                    // rest at least 10°; over 340°, halves.
                    let first = (0.5 * sweep).max(170f64.min(sweep - 10.0));
                    vec![(2, first, text.clone(), 1, 1), (2, sweep - first, " ".to_string(), 1, 0)]
                }
            }
            Shape::LinearDimension { p1, p2, angle, text, .. } => {
                let u = Vector::new(angle.cos(), angle.sin());
                vec![(0, (p2 - p1).dot(&u).abs(), text.clone(), 2, 1)]
            }
            _ => Vec::new(),
        })
        .collect();
    assert_eq!(dims.len(), truth.len());
    let mut names = std::collections::HashSet::new();
    for (dim, (kind, value, text, heads, texts)) in dims.iter().zip(&truth) {
        assert_eq!(dim["dimtype"].as_u64().unwrap() & 0x0F, *kind);
        let m = dim["measurement"].as_f64().unwrap();
        assert!(close(m, *value, 1e-9), "measurement {m} vs true {value} ({text})");
        assert_eq!(dim["text"].as_str().unwrap(), text);
        let block = dim["block"].as_str().unwrap();
        assert!(block.starts_with("*D") && names.insert(block.to_string()), "block {block}");
        let content = &dim["block_content"];
        assert_eq!(content["SOLID"].as_u64(), Some(*heads), "{block}: arrowheads");
        assert_eq!(content["TEXT"].as_u64().unwrap_or(0), *texts, "{block}: texts");
        if *texts > 0 {
            assert_eq!(dim["block_texts"][0].as_str().unwrap(), text);
        }
    }
    // The reflex angle is over 180°: two parts.
    assert!(truth.iter().any(|(_, _, t, ..)| t == " "));

    // Header: dimension sizes and extents.
    assert_eq!(info["header"]["$DIMTXT"].as_f64(), Some(d.dim_style.text_height));
    assert_eq!(info["header"]["$DIMASZ"].as_f64(), Some(d.dim_style.arrow_size));
    assert!(close(info["extmin"][0].as_f64().unwrap(), b.min.x, 1e-9));
    assert!(close(info["extmax"][1].as_f64().unwrap(), b.max.y, 1e-9));
    assert!(info["limmin"][0].as_f64().unwrap() < b.min.x && info["limmax"][1].as_f64().unwrap() > b.max.y);
}

#[test]
fn r2000_audits_clean_too() {
    let path = out_dir().join("many_layers_r2000.dxf");
    let bytes =
        dxf::to_bytes(&many_layers_drawing(), &DxfOptions { version: DxfVersion::R2000, ..DxfOptions::default() })
            .unwrap();
    std::fs::write(&path, bytes).unwrap();
    common::assert_ezdxf_clean(&[&path]);
    let info = inspect(&path);
    assert_eq!(info["version"], "AC1015");
    // Six dimensions, the reflex one (the second) as two halves.
    assert_eq!(info["counts"]["DIMENSION"].as_u64(), Some(7));
    let m = |k: usize| info["dimensions"][k]["measurement"].as_f64().unwrap();
    assert!(m(1) < 180.0 && m(2) < 180.0 && m(1) + m(2) > 180.0);
}

/// Every version with every dimension encoding audits clean (0 errors, 0 fixes) and reads
/// back: the dimensions as DIMENSIONs or as their parts, the text style, the units.
#[test]
fn every_version_and_dimension_encoding_audits_clean() {
    let d = many_layers_drawing();
    let mut paths = Vec::new();
    for version in DxfVersion::ALL {
        for dimensions in [Dimensions::Entities, Dimensions::Exploded] {
            let opts = DxfOptions { version, dimensions, ..DxfOptions::default() };
            let path = out_dir().join(format!("many_layers_{}_{}.dxf", version.name(), dimensions.name()));
            std::fs::write(&path, dxf::to_bytes(&d, &opts).unwrap()).unwrap();
            paths.push((path, version, dimensions));
        }
    }
    common::assert_ezdxf_clean(&paths.iter().map(|(p, ..)| p.as_path()).collect::<Vec<_>>());
    let dims = d
        .entities
        .iter()
        .filter(|e| matches!(e.shape, Shape::AngularDimension { .. } | Shape::LinearDimension { .. }))
        .count() as u64;
    // An angle of 180° or more is written as two DIMENSIONs.
    let reflex = d
        .entities
        .iter()
        .filter(|e| match &e.shape {
            Shape::AngularDimension { vertex, first, second, .. } => {
                let (u, v) = (first - vertex, second - vertex);
                (v.y.atan2(v.x) - u.y.atan2(u.x)).rem_euclid(2.0 * PI) >= PI
            }
            _ => false,
        })
        .count() as u64;
    assert_eq!(reflex, 1, "the sample has one reflex angle");
    for (path, version, dimensions) in &paths {
        let info = inspect(path);
        let what = format!("{} {}", version.name(), dimensions.name());
        let expected = match version {
            DxfVersion::R12 => "AC1009",
            DxfVersion::R2000 => "AC1015",
            DxfVersion::R2007 => "AC1021",
        };
        assert_eq!(info["version"], expected, "{what}");
        let n = |t: &str| info["counts"][t].as_u64().unwrap_or(0);
        // Exploded: each dimension's block content (lines, an arc, 2 SOLIDs, a TEXT) in
        // model space instead of the DIMENSION.
        match dimensions {
            Dimensions::Entities => assert_eq!((n("DIMENSION"), n("TEXT")), (dims + reflex, 13), "{what}"),
            Dimensions::Exploded => {
                assert_eq!((n("DIMENSION"), n("TEXT"), n("SOLID")), (0, 13 + dims, 9 + 2 * dims), "{what}");
                // Every filled shape (5) and arrowhead (2 arrows, 2 a dimension) outlined
                // by a closed POLYLINE of width 0 as well (FreeCAD drops SOLID), besides the
                // two links.
                assert_eq!(n("POLYLINE"), 2 + 5 + 2 + 2 * dims, "{what}");
            }
        }
        // Every text in the AZOMIX style, the one LibreCAD draws Greek letters in.
        assert_eq!(info["header"]["$TEXTSTYLE"], dxf::TEXT_STYLE, "{what}");
        assert_eq!(info["styles"][dxf::TEXT_STYLE], dxf::TEXT_FONT_FILE, "{what}");
        for t in info["texts"].as_array().unwrap() {
            assert_eq!(t["style"], dxf::TEXT_STYLE, "{what}");
        }
        // Greek letters read back whatever the encoding (escapes, or UTF-8 in R2007).
        assert!(info["texts"].as_array().unwrap().iter().any(|t| t["text"] == "ε3 ≈ π/2"), "{what}");
        // Millimetres stated where the version has the variables (R2000+).
        if *version != DxfVersion::R12 {
            assert_eq!(info["header"]["$INSUNITS"].as_i64(), Some(4), "{what}: $INSUNITS = mm");
            assert_eq!(info["header"]["$MEASUREMENT"].as_i64(), Some(1), "{what}: metric");
            assert_eq!(info["header"]["$DIMTXSTY"], dxf::TEXT_STYLE, "{what}");
        }
    }
}

/// A drawing in metres written with 1000 mm per unit: every coordinate, length and text
/// height × 1000 (read back by ezdxf), dimension measurements in mm, the limits a real sheet.
#[test]
fn metres_are_written_as_millimetres() {
    let mut d = Drawing::new(DimStyle { text_height: 0.004, arrow_size: 0.003 });
    let l = d.layer("LINKS", Aci::BLUE, LineType::Continuous);
    d.add(l, Shape::Polyline { points: vec![p(0.0, 0.0), p(0.04, 0.03)], closed: false, width: 0.001 });
    d.add(l, Shape::Circle { center: p(0.08, 0.0), radius: 0.002 });
    d.text(l, p(0.01, 0.05), 0.005, "B");
    d.add(
        l,
        Shape::LinearDimension {
            p1: p(0.0, 0.0),
            p2: p(0.08, 0.0),
            line_at: p(0.0, -0.02),
            angle: 0.0,
            text: "80".into(),
            marks: LinearMarks::default(),
        },
    );
    let opts = DxfOptions { mm_per_unit: 1000.0, ..DxfOptions::default() };
    let path = out_dir().join("metres.dxf");
    std::fs::write(&path, dxf::to_bytes(&d, &opts).unwrap()).unwrap();
    common::assert_ezdxf_clean(&[&path]);
    let info = inspect(&path);
    let poly = &info["polylines"][0];
    assert_eq!(poly["points"][1][0].as_f64(), Some(40.0));
    assert_eq!(poly["points"][1][1].as_f64(), Some(30.0));
    assert!(close(poly["widths"][0][0].as_f64().unwrap(), 1.0, 1e-12));
    assert!(close(info["texts"][0]["height"].as_f64().unwrap(), 5.0, 1e-12));
    assert!(close(info["dimensions"][0]["measurement"].as_f64().unwrap(), 80.0, 1e-9));
    assert!(close(info["header"]["$DIMTXT"].as_f64().unwrap(), 4.0, 1e-12));
    assert!(close(info["extmax"][0].as_f64().unwrap(), 82.0, 1e-9), "the circle's right edge");
    // The sheet: at least A4 landscape about the drawing.
    let (lmin, lmax) = (&info["limmin"], &info["limmax"]);
    let w = lmax[0].as_f64().unwrap() - lmin[0].as_f64().unwrap();
    let h = lmax[1].as_f64().unwrap() - lmin[1].as_f64().unwrap();
    assert!(close(w, 297.0, 1e-9) && close(h, 210.0, 1e-9), "sheet {w} × {h}");
    // The same drawing scaled by hand and written at 1 mm per unit gives the same file.
    let by_hand = Drawing {
        entities: d
            .entities
            .iter()
            .map(|e| {
                let mut e = e.clone();
                let k = |q: &mut Point| *q = Point::from(q.coords * 1000.0);
                match &mut e.shape {
                    Shape::Polyline { points, width, .. } => {
                        points.iter_mut().for_each(k);
                        *width *= 1000.0;
                    }
                    Shape::Circle { center, radius } => {
                        k(center);
                        *radius *= 1000.0;
                    }
                    Shape::Text { at, height, .. } => {
                        k(at);
                        *height *= 1000.0;
                    }
                    Shape::LinearDimension { p1, p2, line_at, .. } => {
                        k(p1);
                        k(p2);
                        k(line_at);
                    }
                    other => panic!("not in this drawing: {other:?}"),
                }
                e
            })
            .collect(),
        dim_style: DimStyle { text_height: 4.0, arrow_size: 3.0 },
        ..d.clone()
    };
    assert_eq!(dxf::to_bytes(&by_hand, &DxfOptions::default()).unwrap(), dxf::to_bytes(&d, &opts).unwrap());
}

#[test]
fn empty_drawing_audits_clean() {
    let d = Drawing::new(DimStyle { text_height: 2.5, arrow_size: 2.5 });
    let mut paths = Vec::new();
    for (name, version) in [("empty_r12.dxf", DxfVersion::R12), ("empty_r2000.dxf", DxfVersion::R2000)] {
        let path = out_dir().join(name);
        std::fs::write(&path, dxf::to_bytes(&d, &DxfOptions { version, ..DxfOptions::default() }).unwrap()).unwrap();
        paths.push(path);
    }
    common::assert_ezdxf_clean(&paths.iter().map(|p| p.as_path()).collect::<Vec<_>>());
}

#[test]
fn golden_sample_dxf() {
    let bytes = dxf::to_bytes(&sample_drawing(), &DxfOptions::default()).unwrap();
    let path = write_dxf("draw_sample.dxf", &sample_drawing());
    common::assert_ezdxf_clean(&[&path]);
    common::assert_golden_text("draw_sample.dxf", std::str::from_utf8(&bytes).expect("ASCII DXF"));
}

#[test]
fn golden_sample_png() {
    let svg = svg::to_string(&sample_drawing(), &svg::SvgOptions::default());
    std::fs::write(out_dir().join("draw_sample.svg"), &svg).unwrap();
    common::assert_golden_png("draw_sample.png", &svg);
}

/// The DXF drawing a run writes for a template (a motion: every position on its own
/// layer), built through the products seam as `mechdraw run` builds it.
fn template_drawing(template: &str) -> Drawing {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("templates/{template}.toml"));
    let loaded = mechdraw::scene::load(&path, &[]).expect("template loads");
    mechdraw::run::products(&loaded, &Default::default()).expect("solves").picture.drawing()
}

/// The hand-written R12 path gives the crate path's bytes for real drawings (the triad,
/// chain and three-position four-bar files are also pinned by their golden tests).
#[test]
fn fast_r12_path_equals_the_crate_path_on_real_drawings() {
    // The four-bar is in metres: written at 1000 mm per unit, as `run` writes it.
    for (name, d, mm_per_unit) in [
        ("sample", sample_drawing(), 1.0),
        ("fourbar animation", template_drawing("fourbar-chebyshev"), 1000.0),
        ("shaper positions", template_drawing("shaper"), 1.0),
    ] {
        for dimensions in [Dimensions::Entities, Dimensions::Exploded] {
            let opts = DxfOptions { dimensions, mm_per_unit, ..DxfOptions::default() };
            let fast = dxf::to_bytes(&d, &opts).unwrap();
            let reference = dxf::to_bytes_via_crate(&d, &opts).unwrap();
            assert!(fast.len() > 1000, "{name}");
            assert!(fast == reference, "{name}, {opts:?}: the fast R12 bytes differ from the crate path's");
        }
    }
}
