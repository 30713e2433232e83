//! The linkage pipeline: assemble at the first time, step through the time range keeping
//! the assembly mode, measure the asked quantities, draw every position, and write the
//! DXF (a layer per position), SVG frames with the HTML viewer, diagrams, CSV and JSON.
//! With `--drag`, the dragged configuration is written instead of the motion.

use serde_json::{Map, Value, json};

use super::products::{self, Picture, PositionsSource, Products};
use super::solve_err;
use crate::Error;
use crate::draw::{Aci, LineType};
use crate::figure::animation::Animation;
use crate::figure::linkage::{self as fig, Style};
use crate::figure::plot::{Diagram, Series, diagram};
use crate::geom::{Point, deg};
use crate::report::Csv;
use crate::scene::linkage::{LinkageScene, MeasureTarget, Quantity};
use crate::solve::linkage::{Anchor, LinkageError, NEAR_SINGULAR_PIVOT_REL, NearSingular, Solver, State};

/// One measured column: its name, unit and values over the motion.
#[derive(Debug, Clone)]
pub struct Column {
    /// `E.x`, `rocker.omega`, …
    pub name: String,
    /// Unit for diagram labels.
    pub unit: String,
    /// Description for diagram titles.
    pub title: String,
    /// One value per sample.
    pub values: Vec<f64>,
}

/// The value of one quantity at one state.
pub fn quantity(state: &State, target: MeasureTarget, q: Quantity) -> f64 {
    match target {
        MeasureTarget::Point(a) => {
            let p = state.point(a);
            let v = state.velocity(a);
            let acc = state.acceleration(a);
            match q {
                Quantity::X => p.x,
                Quantity::Y => p.y,
                Quantity::Vx => v.x,
                Quantity::Vy => v.y,
                Quantity::Ax => acc.x,
                Quantity::Ay => acc.y,
                Quantity::V => v.norm(),
                Quantity::A => acc.norm(),
                _ => f64::NAN,
            }
        }
        MeasureTarget::Body(b) => {
            let (phi, w, e) = state.angular(b);
            match q {
                Quantity::Angle => deg(phi),
                Quantity::Omega => w,
                Quantity::Eps => e,
                _ => f64::NAN,
            }
        }
    }
}

/// The measured columns of a scene over `states`.
pub fn columns(scene: &LinkageScene, states: &[State]) -> Vec<Column> {
    let lu = scene.units.length();
    let mut out = Vec::new();
    for m in &scene.measures {
        for &q in &m.quantities {
            let (unit, what) = match q {
                Quantity::X => (lu.to_string(), "x"),
                Quantity::Y => (lu.to_string(), "y"),
                Quantity::Vx => (format!("{lu}/s"), "x-velocity"),
                Quantity::Vy => (format!("{lu}/s"), "y-velocity"),
                Quantity::V => (format!("{lu}/s"), "speed"),
                Quantity::Ax => (format!("{lu}/s²"), "x-acceleration"),
                Quantity::Ay => (format!("{lu}/s²"), "y-acceleration"),
                Quantity::A => (format!("{lu}/s²"), "acceleration magnitude"),
                Quantity::Angle => ("°".to_string(), "angle"),
                Quantity::Omega => ("rad/s".to_string(), "angular velocity"),
                Quantity::Eps => ("rad/s²".to_string(), "angular acceleration"),
            };
            let owner = match m.target {
                MeasureTarget::Point(_) => "point",
                MeasureTarget::Body(_) => "body",
            };
            out.push(Column {
                name: format!("{}.{}", m.label, q.column()),
                unit,
                title: format!("{what} of {owner} {}", m.label),
                values: states.iter().map(|s| quantity(s, m.target, q)).collect(),
            });
        }
    }
    out
}

/// The warning line for a step solved near a singular position.
fn near_singular_warning(n: &NearSingular) -> String {
    format!(
        "near-singular position at t = {} s ({}): the constraint Jacobian is nearly singular (smallest relative pivot \
         {:.1e} < {:.0e}), a dead point; involved: {}; the position is kept, velocities and accelerations there are \
         unreliable (JSON: near_singular)",
        n.t, n.drivers, n.pivot, NEAR_SINGULAR_PIVOT_REL, n.constraints
    )
}

/// Parses `BODY.POINT=x,y`.
fn parse_drag(scene: &LinkageScene, spec: &str) -> Result<(Anchor, Point), Error> {
    let bad = |message: String| Error::Option { option: format!("--drag {spec}"), message };
    let Some((point, xy)) = spec.split_once('=') else {
        return Err(bad("expected BODY.POINT=x,y, e.g. crank.A=10,20".into()));
    };
    let anchor = scene.anchor(point.trim()).map_err(bad)?;
    let parts: Vec<&str> = xy.split(',').collect();
    let nums: Vec<f64> = parts.iter().filter_map(|s| s.trim().parse::<f64>().ok()).collect();
    if parts.len() != 2 || nums.len() != 2 || !nums.iter().all(|v| v.is_finite()) {
        return Err(bad(format!("`{xy}` is not a target x,y of two finite numbers, e.g. 10,20")));
    }
    Ok((anchor, Point::new(nums[0], nums[1])))
}

pub(super) fn products(scene: &LinkageScene, file: &str, drag: &[String]) -> Result<Products, Error> {
    let serr = solve_err(file);
    let mut solver = match Solver::new(scene.mechanism.clone()) {
        Ok(s) => s,
        Err(e) => return Err(serr(e.into())),
    };
    if !drag.is_empty() {
        return drag_products(scene, file, drag, solver);
    }
    let states = solver.run(&scene.times).map_err(|e| solve_err(file)(e.into()))?;
    let cols = columns(scene, &states);
    let max_residual = states.iter().map(|s| s.residual).fold(0.0, f64::max);
    let max_iter = states.iter().skip(1).map(|s| s.iterations).max().unwrap_or(0);
    let mean_iter = if states.len() > 1 {
        states.iter().skip(1).map(|s| s.iterations as f64).sum::<f64>() / (states.len() - 1) as f64
    } else {
        0.0
    };
    let mut warnings = Vec::new();
    if scene.measures.is_empty() {
        warnings.push("no [[measure]] in the scene: the CSV and the diagrams have no quantity columns".to_string());
    }
    let near_singular: Vec<&NearSingular> = states.iter().filter_map(|s| s.near_singular.as_ref()).collect();
    warnings.extend(near_singular.iter().map(|n| near_singular_warning(n)));
    for c in &cols {
        if c.values.iter().any(|v| !v.is_finite()) {
            return Err(serr(
                LinkageError::InvalidModel { what: format!("measured column {} is not finite", c.name) }.into(),
            ));
        }
    }

    // JSON summary.
    let mut samples = Vec::with_capacity(states.len());
    for (k, s) in states.iter().enumerate() {
        let mut rec = Map::new();
        rec.insert("t".into(), json!(s.t));
        for c in &cols {
            rec.insert(c.name.clone(), json!(c.values[k]));
        }
        if s.near_singular.is_some() {
            rec.insert("near_singular".into(), json!(true));
        }
        samples.push(Value::Object(rec));
    }
    let mut extremes = Map::new();
    for c in &cols {
        let (mut kmin, mut kmax) = (0, 0);
        for (k, v) in c.values.iter().enumerate() {
            if *v < c.values[kmin] {
                kmin = k;
            }
            if *v > c.values[kmax] {
                kmax = k;
            }
        }
        extremes.insert(
            c.name.clone(),
            json!({"min": c.values[kmin], "t_min": states[kmin].t, "max": c.values[kmax], "t_max": states[kmax].t}),
        );
    }
    let mech = &scene.mechanism;
    let summary = json!({
        "kind": "linkage",
        "name": scene.name,
        "units": scene.units.length(),
        "bodies": mech.bodies.len(),
        "joints": mech.joints.len(),
        "drivers": mech.drivers.len(),
        "positions": states.len(),
        "t_from": scene.times[0],
        "t_to": scene.times[scene.times.len() - 1],
        "max_residual": max_residual,
        "newton_iterations_max": max_iter,
        "newton_iterations_mean": mean_iter,
        "columns": cols.iter().map(|c| c.name.clone()).collect::<Vec<_>>(),
        "extremes": extremes,
        "near_singular": near_singular
            .iter()
            .map(|n| json!({"t": n.t, "drivers": n.drivers, "constraints": n.constraints, "pivot": n.pivot}))
            .collect::<Vec<_>>(),
        "samples": samples,
    });
    let report = format!(
        "linkage {}: {} bodies, {} joints, {} driver(s); {} positions, t = {}..{} s; max residual {:.1e} (relative); \
         Newton iterations per step ≤ {} (mean {:.2})",
        scene.name,
        mech.bodies.len(),
        mech.joints.len(),
        mech.drivers.len(),
        states.len(),
        scene.times[0],
        scene.times[scene.times.len() - 1],
        max_residual,
        max_iter,
        mean_iter
    );

    let style = Style::for_length(mech.length_scale);
    let motion: Vec<&[f64]> = states.iter().map(|s| s.q.as_slice()).collect();
    let spans = fig::guide_spans(scene, &motion, &style);
    let base = fig::frame_base(scene, &motion, &style);
    let window = fig::all_positions(scene, &motion, &spans, &style).bounds().or_else(|| base.bounds());
    let window = window.unwrap_or(crate::draw::Bounds { min: Point::new(0.0, 0.0), max: Point::new(1.0, 1.0) });
    let names = (0..states.len()).map(|k| format!("POS_{k:03}")).collect();
    let labels = states.iter().map(|s| format!("t = {:.4} s", s.t)).collect();

    // Diagrams, one per measured column.
    let t: Vec<f64> = states.iter().map(|s| s.t).collect();
    let diagrams = cols
        .iter()
        .map(|c| products::Diagram {
            stem: c.name.clone(),
            drawing: diagram(&Diagram {
                title: format!("{} — {}", c.name, c.title),
                x_label: "t [s]".into(),
                y_label: format!("{} [{}]", c.name, c.unit),
                series: vec![Series { label: c.name.clone(), x: t.clone(), y: c.values.clone() }],
            }),
        })
        .collect();

    // CSV.
    let mut csv = Csv::new(std::iter::once("t".to_string()).chain(cols.iter().map(|c| c.name.clone())));
    for (k, s) in states.iter().enumerate() {
        csv.row(std::iter::once(s.t).chain(cols.iter().map(|c| c.values[k])));
    }

    let qs: Vec<Vec<f64>> = states.into_iter().map(|s| s.q).collect();
    let owned = scene.clone();
    let pose = move |k: usize| fig::frame_moving(&owned, &qs[k], &spans, &style);
    Ok(Products {
        name: scene.name.clone(),
        picture: Picture::Motion(Animation::new(scene.name.clone(), base, window, names, labels, pose)),
        positions: Some(PositionsSource { field: "time.steps", advice: "use fewer steps" }),
        diagrams,
        tables: vec![products::Table { suffix: String::new(), csv }],
        summary,
        report,
        warnings,
    })
}

fn drag_products(scene: &LinkageScene, file: &str, drag: &[String], mut solver: Solver) -> Result<Products, Error> {
    let requests: Vec<(Anchor, Point)> = drag.iter().map(|s| parse_drag(scene, s)).collect::<Result<_, _>>()?;
    let t0 = scene.times[0];
    let mut state = solver.assemble(t0).map_err(|e| solve_err(file)(e.into()))?;
    let mut records = Vec::new();
    for ((anchor, target), spec) in requests.iter().zip(drag) {
        state = solver.drag(&state, *anchor, *target).map_err(|e| solve_err(file)(e.into()))?;
        let reached = state.point(*anchor);
        records.push(json!({
            "request": spec,
            "target": crate::report::point(*target),
            "reached": crate::report::point(reached),
            "distance": (reached - target).norm(),
        }));
    }
    let mech = &scene.mechanism;
    let bodies: Vec<Value> = mech
        .bodies
        .iter()
        .enumerate()
        .map(|(i, b)| {
            let points: Map<String, Value> = b
                .points
                .iter()
                .map(|(n, v)| (n.clone(), crate::report::point(crate::solve::linkage::place(&state.q, crate::solve::linkage::Attach::Body(i), *v))))
                .collect();
            json!({"name": b.name, "x": state.q[3 * i], "y": state.q[3 * i + 1], "angle_deg": deg(state.q[3 * i + 2]), "points": points})
        })
        .collect();
    let summary = json!({
        "kind": "linkage",
        "name": scene.name,
        "units": scene.units.length(),
        "t": t0,
        "drag": records,
        "max_residual": state.residual,
        "bodies": bodies,
    });
    let report = records
        .iter()
        .map(|r| {
            format!(
                "drag {}: reached {} (distance {:.6} {})",
                r["request"],
                r["reached"],
                r["distance"],
                scene.units.length()
            )
        })
        .collect::<Vec<_>>()
        .join("\n");
    let style = Style::for_length(mech.length_scale);
    let motion = [state.q.as_slice()];
    let spans = fig::guide_spans(scene, &motion, &style);
    let mut d = fig::new_drawing(&style);
    let layer = d.layer("DRAG", Aci::BLACK, LineType::Continuous);
    fig::mechanism(&mut d, layer, scene, &state.q, &spans, &style);
    Ok(Products {
        name: scene.name.clone(),
        picture: Picture::Still(d),
        positions: None,
        diagrams: Vec::new(),
        tables: Vec::new(),
        summary,
        report,
        warnings: Vec::new(),
    })
}
