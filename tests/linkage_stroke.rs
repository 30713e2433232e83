//! Stroke H and time ratio K of a guided point, and the linkage diagrams as a textbook
//! draws them (issue 14, item 9), through the run's products: an offset slider-crank
//! against its closed form, a motion shorter than a turn, the diagrams' abscissa, names and
//! units.

#![allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the library calls"
)]

mod common;

use mechdraw::draw::Drawing;
use mechdraw::run::{self, Products, RunOptions};
use mechdraw::scene::{self, Loaded, Override};

/// Offset slider-crank, mm: crank O1A = R about O1 = (0, 0), rod AC = L, slider point C on
/// the line y = E_OFF; the crank turns once a second from φ1 = 0.
const R: f64 = 30.0;
const L: f64 = 100.0;
const E_OFF: f64 = 10.0;

fn slider_crank(extra: &str) -> String {
    let bx = R + (L * L - E_OFF * E_OFF).sqrt();
    let rod = E_OFF.atan2(bx - R).to_degrees();
    format!(
        r#"kind = "linkage"
name = "offset-slider-crank"
units = "mm"
time = {{ from = 0.0, to = 1.0, steps = 72 }}
[ground]
points = {{ O1 = [0.0, 0.0], G1 = [-50.0, {E_OFF}], G2 = [200.0, {E_OFF}] }}
[[body]]
name = "crank"
points = {{ O1 = [0.0, 0.0], A = [{R}, 0.0] }}
[[body]]
name = "rod"
points = {{ A = [0.0, 0.0], C = [{L}, 0.0] }}
at = [{R}, 0.0]
angle_deg = {rod}
[[body]]
name = "slider"
points = {{ C = [0.0, 0.0] }}
at = [{bx}, {E_OFF}]
[[joint]]
name = "O1"
revolute = ["ground.O1", "crank.O1"]
[[joint]]
name = "A"
revolute = ["crank.A", "rod.A"]
[[joint]]
name = "C"
revolute = ["rod.C", "slider.C"]
[[joint]]
name = "guide"
prismatic = {{ point = "slider.C", line = ["ground.G1", "ground.G2"] }}
[[driver]]
joint = "O1"
law = "2*pi*t"
[[measure]]
point = "slider.C"
quantities = ["x", "vx", "ax", "y"]
[[measure]]
body = "rod"
quantities = ["angle", "omega", "eps"]
{extra}
"#
    )
}

fn load(text: &str, set: &[&str]) -> Result<Loaded, scene::SceneError> {
    let over: Vec<Override> = set.iter().map(|s| s.parse().unwrap()).collect();
    scene::parse(text, "offset-slider-crank.toml", &over).map(|scene| Loaded {
        path: "offset-slider-crank.toml".into(),
        scene,
        text: text.to_string(),
    })
}

fn products(text: &str, set: &[&str]) -> Products {
    run::products(&load(text, set).unwrap(), &RunOptions::default()).unwrap()
}

fn num(v: &serde_json::Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

fn diagram<'a>(p: &'a Products, stem: &str) -> &'a Drawing {
    &p.diagrams.iter().find(|d| d.stem == stem).unwrap_or_else(|| panic!("no diagram {stem}")).drawing
}

/// The slider's extremes are where crank and rod are in line: C at √((L ± R)² − e²), the
/// crank at asin(e/(L + R)) (outer) and 180° + asin(e/(L − R)) (inner). So
/// H = √((L + R)² − e²) − √((L − R)² − e²), θ = asin(e/(L − R)) − asin(e/(L + R)), and with
/// the crank turning counter-clockwise the stroke from the outer to the inner extreme takes
/// 180° + θ of the turn: K = (180° + θ)/(180° − θ), the working stroke towards −x.
#[test]
fn offset_slider_crank_stroke_and_time_ratio_match_the_closed_form() {
    let p = products(&slider_crank(""), &[]);
    let s = &p.summary["strokes"]["C"];
    let h = ((L + R).powi(2) - E_OFF.powi(2)).sqrt() - ((L - R).powi(2) - E_OFF.powi(2)).sqrt();
    let (outer, inner) = ((E_OFF / (L + R)).asin().to_degrees(), 180.0 + (E_OFF / (L - R)).asin().to_degrees());
    let theta = inner - 180.0 - outer;
    let k = (180.0 + theta) / (180.0 - theta);
    eprintln!("offset slider-crank: H = {} (closed form {h}), K = {} (closed form {k})", s["H"], s["K"]);
    assert!((num(&s["H"]) - h).abs() <= 1e-9, "H {} vs {h}", s["H"]);
    assert!((num(&s["K"]) - k).abs() <= 1e-9, "K {} vs {k}", s["K"]);
    assert!((num(&s["start"]["driver_deg"]) - outer).abs() <= 1e-9, "{}", s["start"]);
    assert!((num(&s["end"]["driver_deg"]) - inner).abs() <= 1e-9, "{}", s["end"]);
    assert_eq!(s["direction"], serde_json::json!([-1.0, 0.0]));
    assert!((num(&s["working_time"]) + num(&s["return_time"]) - 1.0).abs() <= 1e-12);
    // The rod and the crank are not on a guide: one stroke record only.
    assert_eq!(p.summary["strokes"].as_object().unwrap().len(), 1);
}

/// Half a turn: H is the extent over the motion (from the outer extreme to where the
/// motion stops, C at −R + √(L² − e²) with the crank at 180°), K is not reported and the
/// JSON says why.
#[test]
fn less_than_a_turn_gives_the_stroke_over_the_motion_and_no_time_ratio() {
    let p = products(&slider_crank(""), &["time.to=0.5", "time.steps=36"]);
    let s = &p.summary["strokes"]["C"];
    let h = ((L + R).powi(2) - E_OFF.powi(2)).sqrt() - (-R + (L * L - E_OFF * E_OFF).sqrt());
    assert!((num(&s["H"]) - h).abs() <= 1e-9, "H {} vs {h}", s["H"]);
    assert!(s.get("K").is_none(), "{s}");
    assert_eq!(s["K_not_reported"], "the motion covers less than one turn of the driver");
    assert!(p.report.contains("K not reported: the motion covers less than one turn"), "{}", p.report);
    // Without K, s runs from the extreme at the guide's G1 end towards G2 (+x).
    assert_eq!(s["direction"], serde_json::json!([1.0, 0.0]));
}

/// The diagrams: against φ1 over the driver's range, textbook symbols and words, v and a in
/// m/s and m/s² from a mm scene, the guided point's displacement from its extreme; the
/// CSV's columns unchanged.
#[test]
fn diagrams_are_drawn_against_the_crank_angle_with_textbook_names_and_units() {
    let p = products(&slider_crank(""), &[]);
    let x = common::texts(diagram(&p, "C.x"));
    for want in ["Displacement of the slider point C", "sC [mm]", "φ1 [°]", "0", "360"] {
        assert!(x.iter().any(|t| t == want), "{want} not in {x:?}");
    }
    let v = common::texts(diagram(&p, "C.vx"));
    assert!(v.iter().any(|t| t == "Velocity of the slider point C") && v.iter().any(|t| t == "vC [m/s]"), "{v:?}");
    let a = common::texts(diagram(&p, "C.ax"));
    assert!(a.iter().any(|t| t == "Acceleration of the slider point C") && a.iter().any(|t| t == "aC [m/s²]"), "{a:?}");
    // y is across the guide: a coordinate diagram.
    assert!(common::texts(diagram(&p, "C.y")).iter().any(|t| t == "yC [mm]"));
    // The rod is body 2 (ψ2, ω2, ε2); the crank, which the driver turns, gives φ1.
    let rod = common::texts(diagram(&p, "rod.angle_deg"));
    assert!(rod.iter().any(|t| t == "ψ2 [°]") && rod.iter().any(|t| t == "Angle of the rod"), "{rod:?}");
    assert!(common::texts(diagram(&p, "rod.omega")).iter().any(|t| t == "ω2 [rad/s]"));
    assert!(common::texts(diagram(&p, "rod.eps")).iter().any(|t| t == "ε2 [rad/s²]"));
    // |v_C| ≤ ω·R·(1 + R/√(L² − …)) < 2π·30·1.5 mm/s ≈ 0.28 m/s: the ticks are in m/s, not
    // mm/s (no tick beyond 1).
    let ticks: Vec<f64> = v.iter().filter_map(|t| t.parse::<f64>().ok()).collect();
    let y_ticks: Vec<f64> = ticks.iter().copied().filter(|t| t.fract() != 0.0).collect();
    assert!(!y_ticks.is_empty() && y_ticks.iter().all(|t| t.abs() < 1.0), "{ticks:?}");
    // The CSV keeps its columns, in mm/s.
    let csv = String::from_utf8(p.tables[0].csv.to_bytes()).unwrap();
    assert_eq!(csv.lines().next().unwrap(), "t,C.x,C.vx,C.ax,C.y,rod.angle_deg,rod.omega,rod.eps");
}

/// `[diagrams] x = "t"` draws against time; `x = "angle"` without an angular driver is
/// refused naming the field; `symbol` sets the subscript.
#[test]
fn the_abscissa_and_the_symbols_are_chosen_in_the_scene() {
    let p = products(&slider_crank("[diagrams]\nx = \"t\""), &[]);
    assert!(common::texts(diagram(&p, "C.x")).iter().any(|t| t == "t [s]"));
    let with_symbol = slider_crank("").replace("point = \"slider.C\"\n", "point = \"slider.C\"\nsymbol = \"5\"\n");
    let p = products(&with_symbol, &[]);
    assert!(common::texts(diagram(&p, "C.x")).iter().any(|t| t == "s5 [mm]"));
    assert!(p.summary["strokes"]["C"]["H"].is_number());
    // Driven along the guide (a distance driver): no angle to draw against.
    let by_distance = slider_crank("[diagrams]\nx = \"angle\"")
        .replace("joint = \"O1\"\nlaw = \"2*pi*t\"", "joint = \"guide\"\nlaw = \"120 + 5*t\"");
    let e = load(&by_distance, &[]).unwrap_err().to_string();
    assert!(e.contains("diagrams.x") && e.contains("\"t\""), "{e}");
    // A crank that swings back and forth: drawn against t by default (against its angle the
    // curves would fold back), "angle" refused, no K.
    let swinging = slider_crank("").replace("law = \"2*pi*t\"", "law = \"sin(2*pi*t)\"");
    let p = products(&swinging, &[]);
    assert!(common::texts(diagram(&p, "C.x")).iter().any(|t| t == "t [s]"));
    assert_eq!(p.summary["strokes"]["C"]["K_not_reported"], "the driver turns back within the motion");
    let e = load(&swinging.replacen("[[measure]]", "[diagrams]\nx = \"angle\"\n[[measure]]", 1), &[])
        .unwrap_err()
        .to_string();
    assert!(e.contains("diagrams.x") && e.contains("turns back"), "{e}");
    let e = load(&slider_crank("[diagrams]\nx = \"phi\""), &[]).unwrap_err().to_string();
    assert!(e.contains("diagrams.x") && e.contains("unknown abscissa `phi`"), "{e}");
    let e = load(&slider_crank("").replace("point = \"slider.C\"\n", "point = \"slider.C\"\nsymbol = \"C 1\"\n"), &[])
        .unwrap_err()
        .to_string();
    assert!(e.contains("measure[0].symbol"), "{e}");
}
