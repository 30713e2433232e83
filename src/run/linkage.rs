//! The linkage pipeline: assemble at the first time, step through the time range keeping
//! the assembly mode, measure the asked quantities, draw every position, and write the
//! DXF (a layer per position), SVG frames with the HTML viewer, diagrams, CSV and JSON.
//! With `--drag`, the dragged configuration is written instead of the motion.

use rayon::prelude::*;
use serde_json::{Map, Value, json};

use super::output::Output;
use super::{Outcome, RunOptions, solve_err};
use crate::Error;
use crate::draw::svg::{self, SvgOptions, to_string as svg_string};
use crate::draw::viewer::{Frame, html};
use crate::draw::{Aci, Drawing, LineType};
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

fn export(what: &str) -> impl FnOnce(String) -> Error + '_ {
    move |message| Error::Export { what: what.to_string(), message }
}

fn dxf_bytes(d: &Drawing, opts: &crate::draw::dxf::DxfOptions) -> Result<Vec<u8>, Error> {
    crate::draw::dxf::to_bytes(d, opts).map_err(|e| export("DXF")(e.to_string()))
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

pub(super) fn run(scene: &LinkageScene, file: &str, opts: &RunOptions) -> Result<Outcome, Error> {
    let serr = solve_err(file);
    let mut solver = match Solver::new(scene.mechanism.clone()) {
        Ok(s) => s,
        Err(e) => return Err(serr(e.into())),
    };
    if !opts.drag.is_empty() {
        return run_drag(scene, file, opts, solver);
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

    let Some(dir) = &opts.out_dir else {
        return Ok(Outcome { summary, report, warnings, written: Vec::new() });
    };
    super::check_drawn(file, "time.steps", states.len(), "use fewer steps")?;
    let mut out = Output::new(dir)?;
    let style = Style::for_length(mech.length_scale);
    let motion: Vec<&[f64]> = states.iter().map(|s| s.q.as_slice()).collect();
    let spans = fig::guide_spans(scene, &motion, &style);

    // DXF: every position on its own layer, the paths on TRAJECTORY.
    let all = fig::all_positions(scene, &motion, &spans, &style);
    out.write(format!("{}.dxf", scene.name), dxf_bytes(&all, &opts.dxf_for(scene.units))?)?;
    let window = all.bounds();

    // The first position with the paths, as the scene's picture.
    let frame_drawing = |q: &[f64]| fig::frame(scene, &motion, q, &spans, &style);
    let svg_opts = SvgOptions { window, ..SvgOptions::default() };
    out.write(format!("{}.svg", scene.name), svg_string(&frame_drawing(motion[0]), &svg_opts))?;

    if !opts.no_frames {
        // The paths are written once; each frame is its mechanism appended to them.
        let base_svg = svg_string(&fig::frame_base(scene, &motion, &style), &svg_opts);
        let frames: Vec<Frame> = states
            .par_iter()
            .map(|s| {
                let moving = svg_string(&fig::frame_moving(scene, &s.q, &spans, &style), &svg_opts);
                let svg =
                    svg::splice(&base_svg, &moving).unwrap_or_else(|| svg_string(&frame_drawing(&s.q), &svg_opts));
                Frame { label: format!("t = {:.4} s", s.t), svg }
            })
            .collect();
        let files: Vec<(std::path::PathBuf, &[u8])> = frames
            .iter()
            .enumerate()
            .map(|(k, f)| (format!("frames/{}/pos_{k:03}.svg", scene.name).into(), f.svg.as_bytes()))
            .collect();
        out.write_many(&files)?;
        out.write(format!("{}.html", scene.name), html(&scene.name, &frames))?;
    }

    // Diagrams, one per measured column.
    let t: Vec<f64> = states.iter().map(|s| s.t).collect();
    for c in &cols {
        let d = diagram(&Diagram {
            title: format!("{} — {}", c.name, c.title),
            x_label: "t [s]".into(),
            y_label: format!("{} [{}]", c.name, c.unit),
            series: vec![Series { label: c.name.clone(), x: t.clone(), y: c.values.clone() }],
        });
        let svg = svg_string(&d, &SvgOptions::default());
        if opts.png {
            let png = crate::draw::raster::to_png(&svg, 1000).map_err(|e| export("PNG")(e.to_string()))?;
            out.write(format!("diagrams/{}/{}.png", scene.name, c.name), png)?;
        }
        out.write(format!("diagrams/{}/{}.svg", scene.name, c.name), svg)?;
    }

    // CSV.
    let mut csv = Csv::new(std::iter::once("t".to_string()).chain(cols.iter().map(|c| c.name.clone())));
    for (k, s) in states.iter().enumerate() {
        csv.row(std::iter::once(s.t).chain(cols.iter().map(|c| c.values[k])));
    }
    out.write(format!("{}.csv", scene.name), csv.to_bytes())?;
    out.write(format!("{}.json", scene.name), serde_json::to_vec_pretty(&summary).unwrap_or_default())?;
    let written = out.commit()?;
    Ok(Outcome { summary, report, warnings, written })
}

fn run_drag(scene: &LinkageScene, file: &str, opts: &RunOptions, mut solver: Solver) -> Result<Outcome, Error> {
    let requests: Vec<(Anchor, Point)> = opts.drag.iter().map(|s| parse_drag(scene, s)).collect::<Result<_, _>>()?;
    let t0 = scene.times[0];
    let mut state = solver.assemble(t0).map_err(|e| solve_err(file)(e.into()))?;
    let mut records = Vec::new();
    for ((anchor, target), spec) in requests.iter().zip(&opts.drag) {
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
    let Some(dir) = &opts.out_dir else {
        return Ok(Outcome { summary, report, warnings: Vec::new(), written: Vec::new() });
    };
    let mut out = Output::new(dir)?;
    let style = Style::for_length(mech.length_scale);
    let motion = [state.q.as_slice()];
    let spans = fig::guide_spans(scene, &motion, &style);
    let mut d = fig::new_drawing(&style);
    let layer = d.layer("DRAG", Aci::BLACK, LineType::Continuous);
    fig::mechanism(&mut d, layer, scene, &state.q, &spans, &style);
    out.write(format!("{}.dxf", scene.name), dxf_bytes(&d, &opts.dxf_for(scene.units))?)?;
    out.write(format!("{}.svg", scene.name), svg_string(&d, &SvgOptions::default()))?;
    out.write(format!("{}.json", scene.name), serde_json::to_vec_pretty(&summary).unwrap_or_default())?;
    let written = out.commit()?;
    Ok(Outcome { summary, report, warnings: Vec::new(), written })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    #[test]
    fn spliced_frames_are_the_svg_writers_output_for_the_whole_frame() {
        for template in ["shaper", "fourbar-linkage", "triad-driven"] {
            let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("templates/{template}.toml"));
            let over: Vec<crate::scene::Override> = vec!["time.steps=8".parse().unwrap()];
            let loaded = crate::scene::load(&path, &over).unwrap();
            let Scene::Linkage(scene) = &loaded.scene else { panic!("{template} is not a linkage") };
            let states = Solver::new(scene.mechanism.clone()).unwrap().run(&scene.times).unwrap();
            let motion: Vec<&[f64]> = states.iter().map(|s| s.q.as_slice()).collect();
            let style = Style::for_length(scene.mechanism.length_scale);
            let spans = fig::guide_spans(scene, &motion, &style);
            // One window for every frame, as the run has (else the headers differ).
            let base = fig::frame_base(scene, &motion, &style);
            let opts = SvgOptions { window: base.bounds(), ..SvgOptions::default() };
            let base_svg = svg_string(&base, &opts);
            for q in &motion {
                let whole = svg_string(&fig::frame(scene, &motion, q, &spans, &style), &opts);
                let moving = svg_string(&fig::frame_moving(scene, q, &spans, &style), &opts);
                assert_eq!(svg::splice(&base_svg, &moving).as_deref(), Some(whole.as_str()), "{template}");
            }
        }
    }
}
