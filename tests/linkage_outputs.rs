//! `outputs` of a linkage scene (issue 16 §2): positions only computes no rate and draws
//! no polygon, its positions equal the full run's, and a measured rate that is not computed
//! is refused at its field.

mod common;

use mechdraw::run::products::Picture;
use mechdraw::run::{RunOptions, products};
use mechdraw::scene::{self, Scene};

/// The shaper with `outputs = [...]` and its measures cut to `measures`.
fn shaper(outputs: &str, measures: &str) -> String {
    let text = std::fs::read_to_string(common::root().join("templates/shaper.toml")).unwrap();
    let head = text.split("[[measure]]").next().unwrap();
    let head = head.replacen("time = {", &format!("outputs = {outputs}\ntime = {{"), 1);
    format!("{head}{measures}")
}

fn layers_with_arrows(d: &mechdraw::draw::Drawing) -> Vec<String> {
    let mut out: Vec<String> = d
        .entities
        .iter()
        .filter(|e| matches!(e.shape, mechdraw::draw::Shape::Arrow { .. }))
        .map(|e| d.layers[e.layer].name.clone())
        .collect();
    out.sort();
    out.dedup();
    out
}

#[test]
fn positions_only_solves_the_same_positions_and_draws_no_polygon() {
    let measures = "[[measure]]\npoint = \"ram.E\"\nquantities = [\"x\", \"y\"]\n";
    let dir = tempfile::tempdir().unwrap();
    let run = |outputs: &str| {
        let path = dir.path().join("shaper.toml");
        std::fs::write(&path, shaper(outputs, measures)).unwrap();
        let loaded = scene::load(&path, &[]).unwrap();
        let Scene::Linkage(s) = &loaded.scene else { panic!() };
        assert_eq!(s.outputs.velocity, outputs.contains("velocity"));
        products(&loaded, &RunOptions::default()).unwrap()
    };
    let only = run("[\"position\"]");
    let full = run("[\"position\", \"velocity\", \"acceleration\"]");
    assert_eq!(only.summary["outputs"], serde_json::json!(["position"]));
    assert_eq!(full.summary["outputs"], serde_json::json!(["position", "velocity", "acceleration"]));
    // The same positions (the same Assur route), to the last digit.
    let samples = |p: &mechdraw::run::Products| p.summary["samples"].as_array().unwrap().clone();
    for (a, b) in samples(&only).iter().zip(samples(&full).iter()) {
        assert_eq!(a["E.x"], b["E.x"]);
        assert_eq!(a["E.y"], b["E.y"]);
        let sliding = |x: &serde_json::Value| x.get("sliding").and_then(|v| v.as_object()).map_or(0, |m| m.len());
        assert_eq!(sliding(a), 0, "no sliding velocity without velocities");
        assert_eq!(sliding(b), 2, "the slide and the ram's guide");
    }
    // No polygon panel in the frames; the full run draws both.
    let arrows = |p: &mechdraw::run::Products| {
        let Picture::Motion(a) = &p.picture else { panic!() };
        layers_with_arrows(&a.frame_of(&a.pose(40)))
    };
    assert!(!arrows(&only).iter().any(|l| l == "VELOCITY" || l == "ACCELERATION"), "{:?}", arrows(&only));
    assert!(arrows(&full).iter().any(|l| l == "VELOCITY") && arrows(&full).iter().any(|l| l == "ACCELERATION"));
}

#[test]
fn a_rate_not_computed_is_refused_at_its_field() {
    let cases = [
        ("[\"position\"]", "quantities = [\"x\", \"vx\"]", "measure[0].quantities[1]", "\"velocity\""),
        ("[\"position\", \"velocity\"]", "quantities = [\"ax\"]", "measure[0].quantities[0]", "\"acceleration\""),
        ("[\"position\", \"acceleration\"]", "quantities = [\"x\"]", "outputs", "needs \"velocity\""),
        ("[\"position\", \"forces\"]", "quantities = [\"x\"]", "outputs", "masses or loads"),
        ("[\"speed\"]", "quantities = [\"x\"]", "outputs[0]", "not an output"),
        ("[]", "quantities = [\"x\"]", "outputs", "at least"),
    ];
    for (outputs, quantities, field, what) in cases {
        let text = shaper(outputs, &format!("[[measure]]\npoint = \"ram.E\"\n{quantities}\n"));
        let err = scene::parse(&text, "shaper.toml", &[]).unwrap_err().to_string();
        assert!(err.contains(field) && err.contains(what), "{outputs} {quantities}: {err}");
    }
}
