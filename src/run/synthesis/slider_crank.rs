//! `task = "slider-crank"`: the offset slider-crank for H and K, its family over the offset
//! charted against γ_min, the design as a `linkage` scene, H and K by the analysis.

use serde_json::json;

use super::check;
use super::{Context, FamilyChart, Made, design, pt, serr, stroke_rows};
use crate::Error;
use crate::figure::synthesis::{deg, len, slider_crank as fig};
use crate::run::products::Diagram;
use crate::solve::synthesis::SynthesisError;
use crate::solve::synthesis::slider_crank::{Choice, Requirement, Synthesis, synthesise};

pub(super) fn made(cx: &Context, req: &Requirement) -> Result<Made, Error> {
    let field = |e: &SynthesisError| match e {
        SynthesisError::OutOfFamily { what: "the offset e", .. } => Some("offset".to_string()),
        SynthesisError::OutOfFamily { what: "the time ratio K", .. } => Some("time_ratio".to_string()),
        _ => None,
    };
    let syn = synthesise(req).map_err(serr(cx.file, field))?;
    let d = &syn.design;
    let u = cx.unit();
    let choice = match req.choice {
        Choice::Offset(e) => format!("chosen offset e = {} {u}", len(e)),
        Choice::BestTransmission => "the offset with the largest γ_min".into(),
    };
    let what = format!(
        "H = {}, K = {}; crank a = {}, rod b = {}, offset e = {}",
        len(d.stroke),
        len(req.time_ratio),
        len(d.a),
        len(d.b),
        len(d.e)
    );
    let text = design::slider_crank(&cx.design_name, cx.scene.units, &cx.header(&what), d, cx.scene.omega1);
    let rows = stroke_rows(cx, &text, req.stroke, req.time_ratio)?;
    let route = "linkage solver: the Assur groups over one crank turn, the slider's extremes refined where its speed along the guide changes sign (solve::stroke)".to_string();
    Ok(Made {
        picture: fig::construction(d, &choice, cx.units()),
        diagrams: vec![family_chart(&syn, u)],
        design: text,
        check: check::Check { rows, route },
        summary: json!({
            "requirement": {
                "stroke": req.stroke, "time_ratio": req.time_ratio,
                "choice": match req.choice { Choice::Offset(e) => json!({ "offset": e }), Choice::BestTransmission => json!("best transmission") },
            },
            "construction": {
                "theta_deg": d.theta.to_degrees(), "b1": pt(d.b1), "b2": pt(d.b2), "p": pt(d.p), "e": pt(d.e_point),
                "circle": { "centre": pt(d.centre), "radius": d.radius },
            },
            "design": { "crank": d.a, "rod": d.b, "offset": d.e, "o1": pt(d.o), "guide_y": -d.e },
            "quality": {
                "gamma_min_deg": d.gamma_min.to_degrees(),
                "defects": [],
                "working_stroke": if d.working_from_b1 { "B1 -> B2" } else { "B2 -> B1" },
            },
            "family": { "offset_max": syn.family.e_max, "best": { "offset": syn.family.best.0, "gamma_min_deg": syn.family.best.1.to_degrees() } },
        }),
        report: vec![
            format!("θ = {}; offset e = {} {u} (valid 0…{} {u})", deg(d.theta), len(d.e), len(syn.family.e_max)),
            format!("crank O1A = {} {u}, rod AB = {} {u}; γ_min = {}", len(d.a), len(d.b), deg(d.gamma_min)),
            format!("family: the best γ_min = {} at e = {} {u}", deg(syn.family.best.1), len(syn.family.best.0)),
        ],
        warnings: Vec::new(),
    })
}

/// γ_min over the offsets, the design and the best marked.
fn family_chart(syn: &Synthesis, unit: &str) -> Diagram {
    FamilyChart {
        title: "Offset slider-crank family: smallest transmission angle against the offset",
        x_label: format!("offset e [{unit}]"),
        samples: syn.family.samples.clone(),
        design: (syn.design.e, syn.design.gamma_min),
        best: syn.family.best,
        apart: 1e-6 * syn.design.stroke,
    }
    .diagram()
}
