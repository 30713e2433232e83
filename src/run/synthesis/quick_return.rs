//! `task = "quick-return"`: the shaper for H and K, the design as a `linkage` scene laid out
//! as `templates/shaper.toml`, H and K by the analysis.

use serde_json::json;

use super::check;
use super::{Context, Made, design, pt, serr, stroke_rows};
use crate::Error;
use crate::figure::synthesis::{deg, len, quick_return as fig};
use crate::solve::synthesis::SynthesisError;
use crate::solve::synthesis::quick_return::{Requirement, Size, synthesise};

pub(super) fn made(cx: &Context, req: &Requirement) -> Result<Made, Error> {
    let field = |e: &SynthesisError| match e {
        SynthesisError::OutOfFamily { what: "the link BE", .. } => Some("link".to_string()),
        _ => None,
    };
    let d = synthesise(req).map_err(serr(cx.file, field))?;
    let u = cx.unit();
    let what = format!(
        "H = {}, K = {}; crank {}, O1O3 {}, rocker {}, link {}, ram guide at {}",
        len(d.stroke),
        len(req.time_ratio),
        len(d.crank),
        len(d.ground),
        len(d.rocker),
        len(d.link),
        len(d.ram_height)
    );
    let text = design::shaper(&cx.design_name, cx.scene.units, &cx.header(&what), &d, cx.scene.omega1);
    let rows = stroke_rows(cx, &text, req.stroke, req.time_ratio)?;
    let route = "linkage solver: the Assur groups over one crank turn, the ram's extremes refined where its speed along the guide changes sign (solve::stroke)".to_string();
    let mut warnings = Vec::new();
    if d.block_reach > d.rocker {
        warnings.push(format!(
            "the block reaches {} {u} from O3 (d + r), beyond the rocker O3B = {} {u}: the slot must run past B",
            len(d.block_reach),
            len(d.rocker)
        ));
    }
    Ok(Made {
        picture: fig::construction(&d, cx.units()),
        diagrams: Vec::new(),
        design: text,
        check: check::Check { rows, route },
        summary: json!({
            "requirement": {
                "stroke": req.stroke, "time_ratio": req.time_ratio,
                "crank": match req.size { Size::Crank(r) => Some(r), Size::Ground(_) => None },
                "ground": match req.size { Size::Ground(g) => Some(g), Size::Crank(_) => None },
                "link": req.link, "ram_height": req.ram_height,
            },
            "construction": {
                "theta_deg": d.theta.to_degrees(),
                "a": [pt(d.a[0]), pt(d.a[1])], "b": [pt(d.b[0]), pt(d.b[1])], "e": [pt(d.e[0]), pt(d.e[1])],
            },
            "design": {
                "crank": d.crank, "ground": d.ground, "rocker": d.rocker, "link": d.link, "ram_height": d.ram_height,
                "o1": pt(d.o1), "o3": pt(d.o3),
            },
            "quality": {
                "gamma_min_deg": d.gamma_min.to_degrees(),
                "block_reach": d.block_reach,
                "defects": if d.block_reach > d.rocker { vec!["slot shorter than the block's reach"] } else { vec![] },
            },
        }),
        report: vec![
            format!("θ = {} (the rocker's swing); sin(θ/2) = r/d", deg(d.theta)),
            format!(
                "crank O1A = {} {u}, O1O3 = {} {u}, rocker O3B = {} {u}, link BE = {} {u}, ram guide at {} {u}",
                len(d.crank),
                len(d.ground),
                len(d.rocker),
                len(d.link),
                len(d.ram_height)
            ),
            format!("smallest transmission angle at E: {}", deg(d.gamma_min)),
        ],
        warnings,
    })
}
