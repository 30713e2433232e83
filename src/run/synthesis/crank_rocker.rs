//! `task = "crank-rocker"`: the four-bar for ψ and K, its family over the ground length
//! charted against γ_min, the design as a `fourbar` scene, ψ and K by the analysis.

use serde_json::json;

use super::check::{self, Row, TOL_REL};
use super::design::{self, FourbarDesign};
use super::{Context, FamilyChart, Made, pt, serr};
use crate::Error;
use crate::figure::synthesis::{crank_rocker as fig, deg, len};
use crate::run::products::Diagram;
use crate::solve::fourbar::Geometry;
use crate::solve::synthesis::crank_rocker::{Choice, Circle, Design, Requirement, Synthesis, synthesise};
use crate::solve::synthesis::{SynthesisError, time_ratio};

pub(super) fn made(cx: &Context, req: &Requirement) -> Result<Made, Error> {
    let field = |e: &SynthesisError| match (e, req.choice) {
        (SynthesisError::OutOfFamily { .. }, Choice::Ground(_)) => Some("ground".to_string()),
        (SynthesisError::OutOfFamily { .. }, Choice::ExtremeToGround(_)) => Some("extreme_to_ground_deg".to_string()),
        _ => None,
    };
    let syn = synthesise(req).map_err(serr(cx.file, field))?;
    let d = &syn.design;
    let u = cx.unit();
    let choice = match req.choice {
        Choice::Ground(g) => format!("chosen ground O1C = {} {u}", len(g)),
        Choice::ExtremeToGround(a) => {
            format!("the ground line at {} to the rocker in an extreme ({} designs)", deg(a), 1 + syn.others.len())
        }
        Choice::BestTransmission => "the crank pivot with the largest γ_min".into(),
    };
    let picture = fig::construction(d, &choice, cx.units());
    let geometry = Geometry {
        o1: d.o1,
        c: d.pivot_c,
        l1: d.a,
        l_ab: d.b,
        l_bm: 0.5 * d.b,
        alpha: 0.0,
        l_bc: d.c,
        branch: d.branch,
    };
    let f = FourbarDesign { geometry, omega1: cx.scene.omega1, sweep_deg: (0.0, 359.0, 1.0) };
    let what = format!(
        "ψ = {}, K = {}; crank a = {}, coupler b = {}, rocker c = {}, ground d = {} (M is AB's middle)",
        deg(d.psi),
        len(req.time_ratio),
        len(d.a),
        len(d.b),
        len(d.c),
        len(d.d)
    );
    let text = design::fourbar(&cx.design_name, cx.scene.units, &cx.header(&what), &f);
    let parsed = cx.parse(&text)?;
    let g = check::fourbar_scene(&parsed).map_err(|e| cx.internal(e))?.spec.geometry;
    let (psi, k, _) = check::swing(&g).map_err(|e| cx.internal(e))?;
    let psi_deg = req.psi.to_degrees();
    let rows = vec![
        Row::new("ψ [°]", psi_deg, psi.to_degrees(), TOL_REL * psi_deg),
        Row::new("K", req.time_ratio, k, TOL_REL * req.time_ratio),
    ];
    let route = "fourbar solver: B by circle intersection at each crank angle, the rocker's extremes where ω3 = 0 (Newton on the exact rates)".to_string();
    Ok(Made {
        picture,
        diagrams: vec![family_chart(&syn, u)],
        design: text,
        check: check::Check { rows, route },
        summary: summary(req, &syn),
        report: report(&syn, u),
        warnings: Vec::new(),
    })
}

/// γ_min over the family, the design and the best marked.
fn family_chart(syn: &Synthesis, unit: &str) -> Diagram {
    FamilyChart {
        title: "Crank-rocker family: smallest transmission angle against the ground length",
        x_label: format!("O1C = d [{unit}]"),
        samples: syn.family.samples.iter().map(|(d, g)| (*d, g.unwrap_or(f64::NAN))).collect(),
        design: (syn.design.d, syn.design.gamma_min),
        best: syn.family.best,
        apart: 1e-6 * syn.design.c,
    }
    .diagram()
}

fn design_json(d: &Design) -> serde_json::Value {
    json!({
        "crank": d.a, "coupler": d.b, "rocker": d.c, "ground": d.d,
        "o1": pt(d.o1), "c": pt(d.pivot_c),
        "branch": d.branch,
        "gamma_min_deg": d.gamma_min.to_degrees(),
    })
}

fn summary(req: &Requirement, syn: &Synthesis) -> serde_json::Value {
    let d = &syn.design;
    let choice = match req.choice {
        Choice::Ground(g) => json!({ "ground": g }),
        Choice::ExtremeToGround(a) => json!({ "extreme_to_ground_deg": a.to_degrees() }),
        Choice::BestTransmission => json!("best transmission"),
    };
    json!({
        "requirement": { "psi_deg": req.psi.to_degrees(), "time_ratio": req.time_ratio, "rocker": req.rocker, "choice": choice },
        "construction": {
            "theta_deg": d.theta.to_degrees(),
            "b1": pt(d.b1), "b2": pt(d.b2), "p": pt(d.p), "e": pt(d.e),
            "circle": { "centre": pt(d.centre), "radius": d.radius, "side": d.circle },
            "forbidden": d.forbidden.map(|(f, g)| json!([pt(f), pt(g)])),
        },
        "design": design_json(d),
        "quality": {
            "class": d.class,
            "gamma_min_deg": d.gamma_min.to_degrees(),
            "defects": [],
            "working_stroke": if d.working_from_b1 { "B1 -> B2" } else { "B2 -> B1" },
        },
        "others": syn.others.iter().map(design_json).collect::<Vec<_>>(),
        "family": {
            "valid_ground": syn.family.valid,
            "best": { "ground": syn.family.best.0, "gamma_min_deg": syn.family.best.1.to_degrees() },
        },
    })
}

fn report(syn: &Synthesis, u: &str) -> Vec<String> {
    let d = &syn.design;
    let mut lines = vec![
        format!(
            "θ = {}; crank pivot on the circle k {} (radius {} {u})",
            deg(d.theta),
            match d.circle {
                Circle::Far => "on the far side of B1B2 from C (d > c)",
                Circle::Near => "on C's side of B1B2 (d < c)",
            },
            len(d.radius)
        ),
        format!(
            "crank O1A = {} {u}, coupler AB = {} {u}, rocker CB = {} {u}, ground O1C = {} {u}",
            len(d.a),
            len(d.b),
            len(d.c),
            len(d.d)
        ),
        format!(
            "{}; γ_min = {}; K = {} by construction",
            d.class.describe(),
            deg(d.gamma_min),
            len(time_ratio(d.theta))
        ),
    ];
    for o in &syn.others {
        lines.push(format!(
            "also possible: ground {} {u}, crank {} {u}, coupler {} {u}, γ_min {}",
            len(o.d),
            len(o.a),
            len(o.b),
            deg(o.gamma_min)
        ));
    }
    lines.push(format!(
        "family: d in {}; the best γ_min = {} at d = {} {u}",
        syn.family.valid.iter().map(|(a, b)| format!("{}…{}", len(*a), len(*b))).collect::<Vec<_>>().join(", "),
        deg(syn.family.best.1),
        len(syn.family.best.0)
    ));
    lines
}
