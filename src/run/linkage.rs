//! The linkage pipeline: assemble at the first time, step through the time range keeping
//! the assembly mode, measure the asked quantities, draw every position, and write the
//! DXF (a layer per position), SVG frames with the HTML viewer, diagrams, CSV and JSON.
//! With `--drag`, the dragged configuration is written instead of the motion.

use std::collections::BTreeMap;

use serde::Serialize;

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
    let samples = states
        .iter()
        .enumerate()
        .map(|(k, s)| Sample {
            t: s.t,
            values: cols.iter().map(|c| (c.name.clone(), c.values[k])).collect(),
            near_singular: s.near_singular.is_some().then_some(true),
        })
        .collect();
    let extremes = cols
        .iter()
        .map(|c| {
            let (mut kmin, mut kmax) = (0, 0);
            for (k, v) in c.values.iter().enumerate() {
                if *v < c.values[kmin] {
                    kmin = k;
                }
                if *v > c.values[kmax] {
                    kmax = k;
                }
            }
            let e = Extremes { min: c.values[kmin], t_min: states[kmin].t, max: c.values[kmax], t_max: states[kmax].t };
            (c.name.clone(), e)
        })
        .collect();
    let mech = &scene.mechanism;
    let summary = products::summary_value(
        &MotionSummary {
            kind: "linkage",
            name: &scene.name,
            units: scene.units.length(),
            bodies: mech.bodies.len(),
            joints: mech.joints.len(),
            drivers: mech.drivers.len(),
            positions: states.len(),
            t_from: scene.times[0],
            t_to: scene.times[scene.times.len() - 1],
            max_residual,
            newton_iterations_max: max_iter,
            newton_iterations_mean: mean_iter,
            columns: cols.iter().map(|c| c.name.as_str()).collect(),
            extremes,
            near_singular: near_singular
                .iter()
                .map(|n| NearSingularRecord {
                    t: n.t,
                    drivers: &n.drivers,
                    constraints: &n.constraints,
                    pivot: n.pivot,
                })
                .collect(),
            samples,
        },
        &scene.name,
    )?;
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
    let figure = figure_of(scene);
    let spans = fig::guide_spans(&figure, &motion, &style);
    let base = fig::frame_base(&figure, &motion, &style);
    // The window: the paths and the mechanism at every position.
    let mut all = base.clone();
    for q in &motion {
        all.append(&fig::frame_moving(&figure, q, &spans, &style));
    }
    let window = all.bounds().unwrap_or(crate::draw::Bounds { min: Point::new(0.0, 0.0), max: Point::new(1.0, 1.0) });
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
    let pose = move |k: usize| fig::frame_moving(&figure, &qs[k], &spans, &style);
    Ok(Products {
        name: scene.name.clone(),
        picture: Picture::Motion(Animation::new(scene.name.clone(), base, window, names, labels, pose)),
        positions: Some(PositionsSource { field: "time.steps", advice: "use fewer steps" }),
        sheets: Vec::new(),
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
        records.push(DragRecord {
            request: spec,
            target: [target.x, target.y],
            reached: [reached.x, reached.y],
            distance: (reached - target).norm(),
        });
    }
    let mech = &scene.mechanism;
    let bodies = mech
        .bodies
        .iter()
        .enumerate()
        .map(|(i, b)| BodyRecord {
            name: &b.name,
            x: state.q[3 * i],
            y: state.q[3 * i + 1],
            angle_deg: deg(state.q[3 * i + 2]),
            points: b
                .points
                .iter()
                .map(|(n, v)| {
                    let p = crate::solve::linkage::place(&state.q, crate::solve::linkage::Attach::Body(i), *v);
                    (n.as_str(), [p.x, p.y])
                })
                .collect(),
        })
        .collect();
    let units = scene.units.length();
    let report = records
        .iter()
        .map(|r| {
            format!(
                "drag {:?}: reached ({:.6}, {:.6}) (distance {:.6} {units})",
                r.request, r.reached[0], r.reached[1], r.distance
            )
        })
        .collect::<Vec<_>>()
        .join("\n");
    let summary = products::summary_value(
        &DragSummary {
            kind: "linkage",
            name: &scene.name,
            units,
            t: t0,
            drag: records,
            max_residual: state.residual,
            bodies,
        },
        &scene.name,
    )?;
    let style = Style::for_length(mech.length_scale);
    let motion = [state.q.as_slice()];
    let figure = figure_of(scene);
    let spans = fig::guide_spans(&figure, &motion, &style);
    let mut d = fig::new_drawing(&style);
    let layer = d.layer("DRAG", Aci::BLACK, LineType::Continuous);
    fig::mechanism(&mut d, layer, &figure, &state.q, &spans, &style);
    Ok(Products {
        name: scene.name.clone(),
        picture: Picture::Still(d),
        positions: None,
        sheets: Vec::new(),
        diagrams: Vec::new(),
        tables: Vec::new(),
        summary,
        report,
        warnings: Vec::new(),
    })
}

/// The figure-side description of a linkage scene: the solver's bodies and joints, the
/// scene's point names (a revolute joint is named by its second point's name, else its
/// first's, else the joint's name), and the measured points as the traced paths.
pub fn figure_of(scene: &LinkageScene) -> fig::LinkageFigure {
    let traced = scene
        .measures
        .iter()
        .filter_map(|m| match m.target {
            MeasureTarget::Point(a) => Some(a),
            MeasureTarget::Body(_) => None,
        })
        .collect();
    fig::LinkageFigure::new(&scene.mechanism, |a| scene.point_name(a), traced)
}

/// One sample of the JSON summary: t, every measured column, and a flag at near-singular
/// steps.
#[derive(Debug, Serialize)]
struct Sample {
    t: f64,
    #[serde(flatten)]
    values: BTreeMap<String, f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    near_singular: Option<bool>,
}

/// Smallest and largest value of a column, with their times.
#[derive(Debug, Serialize)]
struct Extremes {
    min: f64,
    t_min: f64,
    max: f64,
    t_max: f64,
}

/// A near-singular step (see `NearSingular`).
#[derive(Debug, Serialize)]
struct NearSingularRecord<'a> {
    t: f64,
    drivers: &'a str,
    constraints: &'a str,
    pivot: f64,
}

/// The JSON summary of a motion (docs/linkage.md).
#[derive(Debug, Serialize)]
struct MotionSummary<'a> {
    kind: &'static str,
    name: &'a str,
    units: &'static str,
    bodies: usize,
    joints: usize,
    drivers: usize,
    positions: usize,
    t_from: f64,
    t_to: f64,
    max_residual: f64,
    newton_iterations_max: usize,
    newton_iterations_mean: f64,
    columns: Vec<&'a str>,
    extremes: BTreeMap<String, Extremes>,
    near_singular: Vec<NearSingularRecord<'a>>,
    samples: Vec<Sample>,
}

/// One `--drag` request and where the point went.
#[derive(Debug, Serialize)]
struct DragRecord<'a> {
    request: &'a str,
    target: [f64; 2],
    reached: [f64; 2],
    distance: f64,
}

/// A body's pose after dragging, with its named points (global).
#[derive(Debug, Serialize)]
struct BodyRecord<'a> {
    name: &'a str,
    x: f64,
    y: f64,
    angle_deg: f64,
    points: BTreeMap<&'a str, [f64; 2]>,
}

/// The JSON summary of a `--drag` run.
#[derive(Debug, Serialize)]
struct DragSummary<'a> {
    kind: &'static str,
    name: &'a str,
    units: &'static str,
    t: f64,
    drag: Vec<DragRecord<'a>>,
    max_residual: f64,
    bodies: Vec<BodyRecord<'a>>,
}
