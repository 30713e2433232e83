//! `task = "motion"`: the four-bar through two or three coupler positions, its defects, the
//! design as a `fourbar` scene, each position by the analysis at its crank angle.

use serde_json::json;

use super::check::{self, Row, TOL_POSE};
use super::design::{self, FourbarDesign};
use super::{Context, Made, pt, serr};
use crate::Error;
use crate::figure::synthesis::{deg, len, motion as fig};
use crate::geom::wrap_pi;
use crate::solve::fourbar::Geometry;
use crate::solve::synthesis::motion::{Design, Requirement, synthesise};

pub(super) fn made(cx: &Context, req: &Requirement) -> Result<Made, Error> {
    let d = synthesise(req).map_err(serr(cx.file, |_| None))?;
    let u = cx.unit();
    let omega = if d.ccw == Some(false) { -cx.scene.omega1.abs() } else { cx.scene.omega1.abs() };
    let geometry = Geometry {
        o1: d.o_a,
        c: d.o_b,
        l1: d.l_in,
        l_ab: d.l_ab,
        l_bm: d.l_bp,
        alpha: d.alpha,
        l_bc: d.l_out,
        branch: d.sides[0],
    };
    let f = FourbarDesign { geometry, omega1: omega, sweep_deg: (0.0, 359.0, 1.0) };
    let what = format!(
        "{} positions of the coupler point M (P) and line; crank {}, coupler {}, rocker {}, ground {}",
        d.poses.len(),
        len(d.l_in),
        len(d.l_ab),
        len(d.l_out),
        len(d.ground)
    );
    let text = design::fourbar(&cx.design_name, cx.scene.units, &cx.header(&what), &f);
    let parsed = cx.parse(&text)?;
    let g = check::fourbar_scene(&parsed).map_err(|e| cx.internal(e))?.spec.geometry;
    let size = d.l_in.max(d.l_ab).max(d.l_out).max(d.ground);
    let mut rows = Vec::new();
    for (i, pose) in d.poses.iter().enumerate() {
        let (m, ab, _) = check::coupler(&g, d.input[i]).map_err(|e| cx.internal(e))?;
        let n = i + 1;
        rows.push(Row::new(format!("P{n} x [{u}]"), pose.at.x, m.x, TOL_POSE * size));
        rows.push(Row::new(format!("P{n} y [{u}]"), pose.at.y, m.y, TOL_POSE * size));
        let angle = pose.angle + wrap_pi(ab + d.line_offset - pose.angle);
        rows.push(Row::new(
            format!("line {n} [°]"),
            pose.angle.to_degrees(),
            angle.to_degrees(),
            TOL_POSE.to_degrees(),
        ));
    }
    let route = "fourbar solver: M and the coupler's direction by circle intersection at each position's crank angle, on the design's assembly mode".to_string();
    Ok(Made {
        picture: fig::construction(&d, cx.units()),
        diagrams: Vec::new(),
        design: text,
        check: check::Check { rows, route },
        summary: summary(req, &d),
        report: report(&d, u),
        warnings: d.defects.iter().map(|x| x.describe()).collect(),
    })
}

fn summary(req: &Requirement, d: &Design) -> serde_json::Value {
    json!({
        "requirement": {
            "positions": req.poses.iter().map(|p| json!({ "at": pt(p.at), "angle_deg": p.angle.to_degrees() })).collect::<Vec<_>>(),
            "a1": pt(req.a1), "b1": pt(req.b1),
            "bisector_distance": if req.poses.len() == 2 { Some(req.bisector_distance) } else { None },
            "crank": req.crank, "turning": req.turning,
        },
        "construction": {
            "a": d.a.iter().copied().map(pt).collect::<Vec<_>>(),
            "b": d.b.iter().copied().map(pt).collect::<Vec<_>>(),
        },
        "design": {
            "o1": pt(d.o_a), "c": pt(d.o_b), "crank": d.l_in, "coupler": d.l_ab, "rocker": d.l_out, "ground": d.ground,
            "l_bm": d.l_bp, "alpha_deg": d.alpha.to_degrees(),
            "crank_deg": d.input.iter().map(|a| a.to_degrees()).collect::<Vec<_>>(),
            "sides": d.sides,
            "turns_ccw": d.ccw,
        },
        "quality": {
            "class": d.class,
            "gamma_min_deg": d.gamma_min.map(f64::to_degrees),
            "defects": d.defects,
        },
    })
}

fn report(d: &Design, u: &str) -> Vec<String> {
    let mut lines = vec![
        format!("fixed pivots O1 ({}, {}) {u}, C ({}, {}) {u}", len(d.o_a.x), len(d.o_a.y), len(d.o_b.x), len(d.o_b.y)),
        format!(
            "crank O1A = {} {u}, coupler AB = {} {u}, rocker CB = {} {u}, ground = {} {u}; crank at {}",
            len(d.l_in),
            len(d.l_ab),
            len(d.l_out),
            len(d.ground),
            d.input.iter().map(|a| deg(*a)).collect::<Vec<_>>().join(", ")
        ),
        format!("{}{}", d.class.describe(), d.gamma_min.map_or(String::new(), |g| format!("; γ_min = {}", deg(g)))),
    ];
    if d.defects.is_empty() {
        lines.push("no branch, order or crank defect".into());
    }
    lines.extend(d.defects.iter().map(|x| x.describe()));
    lines
}
