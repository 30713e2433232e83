//! The linkage pipeline: assemble at the first time, step through the time range keeping
//! the assembly mode, measure the asked quantities, draw every position, and write the
//! DXF (a layer per position), SVG frames with the HTML viewer, diagrams, CSV and JSON.
//! With `--drag`, the dragged configuration is written instead of the motion.

use std::collections::BTreeMap;
use std::sync::{Arc, Mutex};

use serde::Serialize;

use super::positions::DriveAxis;
use super::products::{self, Extras, Picture, PositionsSource, Products};
use super::solve_err;
use crate::Error;
use crate::draw::{Aci, LineType};
use crate::figure::linkage as fig;
use crate::figure::linkage::forces as linkage_forces;
use crate::figure::linkage::frame::{LinkageFrames, RunForces, Show};
use crate::figure::linkage::sheet::{LinkageSheets, row_counts};
use crate::figure::shared::animation::{Animation, Drive, DriveState};
use crate::figure::shared::labels::Label;
use crate::figure::shared::plot::{Diagram, Series, diagram, track};
use crate::figure::shared::sheet::{self, Paper};
use crate::geom::{Point, deg};
use crate::par::prelude::*;
use crate::report::Csv;
use crate::scene::Units;
use crate::scene::linkage::{DiagramAxis, LinkageScene, Measure, MeasureTarget, Quantity};
use crate::solve::linkage::{
    Anchor, AssurSolver, Attach, DriverTarget, Forces, JointKind, LinkageError, NEAR_SINGULAR_PIVOT_REL, NearSingular,
    Solver, State,
};
use crate::solve::stroke::{self, Extreme, Stroke};

/// One measured column: its name and values over the motion (the CSV's and the JSON's;
/// the diagrams draw them in textbook form, see `plot_of`).
#[derive(Debug, Clone)]
pub struct Column {
    /// `E.x`, `rocker.omega`, …
    pub name: String,
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
    let mut out = Vec::new();
    for m in &scene.measures {
        for &q in &m.quantities {
            out.push(Column {
                name: format!("{}.{}", m.label, q.column()),
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
    let bad = |message: String| Error::Option { option: format!("--drag {}", crate::text::excerpt(spec)), message };
    let Some((point, xy)) = spec.split_once('=') else {
        return Err(bad("expected BODY.POINT=x,y, e.g. crank.A=10,20".into()));
    };
    let anchor = scene.anchor(point.trim()).map_err(bad)?;
    if anchor.body == Attach::Ground {
        let movable: Vec<String> = scene
            .mechanism
            .bodies
            .iter()
            .flat_map(|b| b.points.iter().map(move |(p, _)| format!("{}.{p}", b.name)))
            .collect();
        return Err(bad(format!(
            "`{}` is a point of the ground, which does not move: drag a point of a moving body ({})",
            point.trim(),
            crate::text::excerpt(&movable.join(", "))
        )));
    }
    let parts: Vec<&str> = xy.split(',').collect();
    let nums: Vec<f64> = parts.iter().filter_map(|s| s.trim().parse::<f64>().ok()).collect();
    let limit = crate::scene::MAX_LENGTH;
    if parts.len() != 2 || nums.len() != 2 || !nums.iter().all(|v| v.is_finite() && v.abs() <= limit) {
        return Err(bad(format!(
            "`{}` is not a target x,y of two numbers within ±{limit:e} (the scene's unit), e.g. 10,20",
            crate::text::excerpt(xy)
        )));
    }
    Ok((anchor, Point::new(nums[0], nums[1])))
}

pub(super) fn products(scene: &LinkageScene, file: &str, opts: &super::RunOptions) -> Result<Products, Error> {
    let serr = |e: LinkageError| solve_err(file)(e.into());
    let mut solver = Solver::new(scene.mechanism.clone()).map_err(serr)?;
    if !opts.drag.is_empty() {
        return drag_products(scene, file, &opts.drag, solver);
    }
    // The Assur groups in solving order, each in closed form or by its own Newton
    // iterations (the general solver stays for the strokes' refinement and --drag).
    let mut assur = AssurSolver::new(scene.mechanism.clone()).map_err(serr)?;
    let (states, forces) = solve_motion(scene, &mut assur).map_err(serr)?;
    let cols = columns(scene, &states);
    let mut warnings = column_warnings(scene, &cols, &states).map_err(serr)?;

    let figure = figure_of(scene);
    let show = show_of(scene);
    let run_forces =
        scene.dynamics.as_ref().zip(forces.as_deref()).map(|(dynamics, forces)| RunForces { dynamics, forces });
    let mut frames = LinkageFrames::new(&figure, &scene.mechanism, &states, run_forces, show.clone());
    frames.frame.hold(&opts.held_scales);
    let names: Vec<String> = (0..states.len()).map(|k| format!("POS_{k:03}")).collect();
    // The positions drawn (`--positions`: times t in seconds).
    let times: Vec<f64> = states.iter().map(|s| s.t).collect();
    let step = match scene.times.as_slice() {
        [a, b, ..] => (b - a).abs(),
        _ => 1.0,
    };
    let drawn =
        super::drawn_positions(opts.positions.as_ref(), &times, DriveAxis { name: "time t", unit: " s", step })?;

    let extras = if opts.picture_only {
        Extras::default()
    } else {
        let run = Solved { scene, assur: &assur, states: &states, forces: forces.as_deref(), cols: &cols };
        let strokes = guided_strokes(scene, &mut solver, &states).map_err(serr)?;
        let plots = plots(scene, &states, &strokes);
        let pages = match opts.sheets {
            Some(paper) => {
                let sheet_forces = scene.dynamics.as_ref().zip(forces.as_deref());
                sheet_pages(paper, scene, &figure, &states, sheet_forces, &plots, show, &names, &drawn)
            }
            None => Vec::new(),
        };
        let mut extras = Extras {
            sheets: Vec::new(),
            pages,
            diagrams: run.diagrams(plots),
            tables: vec![products::Table { suffix: String::new(), csv: run.csv() }],
            summary: run.summary(&strokes)?,
            report: run.report(&strokes),
        };
        if let Some(study) =
            super::tolerance::linkage(scene, None).map_err(|e| super::tolerance::tolerance_err(file, e))?
        {
            warnings.extend(study.add_to(&mut extras));
        }
        extras
    };
    let motion = Motion { frames, figure, states, forces: forces.unwrap_or_default(), names, drawn };
    let animation = motion.animation(scene, file, opts.positions.is_some())?;
    let (animation, frame_scales) = animation;
    Ok(extras.with_motion(
        scene.name.clone(),
        super::mm_per_unit(scene.units),
        animation,
        PositionsSource { field: "time.steps", advice: "use fewer steps" },
        warnings,
        frame_scales,
    ))
}

/// The motion at every sample, by the Assur route: only what `outputs` asks for — forces
/// (with their states), or the rates, or positions alone (the rates then zero, and nothing
/// reads them: no rate is measured or drawn).
fn solve_motion(
    scene: &LinkageScene,
    assur: &mut AssurSolver,
) -> Result<(Vec<State>, Option<Vec<Forces>>), LinkageError> {
    let out = scene.outputs;
    Ok(match &scene.dynamics {
        Some(d) if out.forces => {
            let (states, forces) = assur.run_kinetostatics(&scene.times, d)?;
            (states, Some(forces))
        }
        _ if out.velocity => (assur.run(&scene.times)?, None),
        _ => (assur.run_positions_states(&scene.times)?, None),
    })
}

/// The run's warnings about its measured columns and its states (no measure; each
/// near-singular sample), or the error of a column that is not finite.
fn column_warnings(scene: &LinkageScene, cols: &[Column], states: &[State]) -> Result<Vec<String>, LinkageError> {
    let mut warnings = Vec::new();
    if scene.measures.is_empty() {
        warnings.push("no [[measure]] in the scene: the CSV and the diagrams have no quantity columns".to_string());
    }
    warnings.extend(states.iter().filter_map(|s| s.near_singular.as_ref()).map(near_singular_warning));
    if let Some(c) = cols.iter().find(|c| c.values.iter().any(|v| !v.is_finite())) {
        return Err(LinkageError::InvalidModel { what: format!("measured column {} is not finite", c.name) });
    }
    Ok(warnings)
}

/// What the frames and sheets draw, from the scene's `[polygons]`, `[frames]` and outputs.
pub(super) fn show_of(scene: &LinkageScene) -> Show {
    let (p, out) = (&scene.polygons, scene.outputs);
    Show {
        velocity: p.velocity && out.velocity,
        acceleration: p.acceleration && out.acceleration,
        forces: p.forces && out.forces,
        points: p.points.clone(),
        per_body: p.per_body,
        scales: super::scale_choice(scene.frame_scales),
    }
}

/// A diagram of each measured column, as a textbook draws it.
pub(super) fn plots(scene: &LinkageScene, states: &[State], strokes: &[Guided]) -> Vec<Plot> {
    scene
        .measures
        .iter()
        .flat_map(|m| m.quantities.iter().map(move |&q| (m, q)))
        .map(|(m, q)| plot_of(scene, m, q, states, strokes))
        .collect()
}

/// A run's solved motion, for its files.
struct Solved<'a> {
    scene: &'a LinkageScene,
    assur: &'a AssurSolver,
    states: &'a [State],
    forces: Option<&'a [Forces]>,
    cols: &'a [Column],
}

impl Solved<'_> {
    /// The residual's largest, and the Newton iterations' largest and mean over the steps
    /// after the first.
    fn iterations(&self) -> (f64, usize, f64) {
        let states = self.states;
        let max_residual = states.iter().map(|s| s.residual).fold(0.0, f64::max);
        let max_iter = states.iter().skip(1).map(|s| s.iterations).max().unwrap_or(0);
        let mean_iter = if states.len() > 1 {
            states.iter().skip(1).map(|s| s.iterations as f64).sum::<f64>() / (states.len() - 1) as f64
        } else {
            0.0
        };
        (max_residual, max_iter, mean_iter)
    }

    /// The largest virtual-power residual over the motion (with forces).
    fn power_residual_max(&self) -> Option<f64> {
        self.forces.map(|f| f.iter().map(|x| x.power_residual).fold(0.0, f64::max))
    }

    /// Each sample of the JSON summary: its time, its columns, its reactions, drivers,
    /// power residual and sliding.
    fn samples(&self) -> Vec<Sample> {
        let (scene, forces) = (self.scene, self.forces);
        self.states
            .iter()
            .enumerate()
            .map(|(k, s)| Sample {
                t: s.t,
                values: self.cols.iter().map(|c| (c.name.clone(), c.values[k])).collect(),
                near_singular: s.near_singular.is_some().then_some(true),
                reactions: forces.map(|f| reaction_records(scene, &f[k])),
                drivers: forces.map(|f| {
                    scene.mechanism.drivers.iter().zip(&f[k].drivers).map(|(d, v)| (d.name.clone(), v + 0.0)).collect()
                }),
                power_residual: forces.map(|f| f[k].power_residual),
                sliding: if scene.outputs.velocity { sliding_records(scene, s) } else { BTreeMap::new() },
            })
            .collect()
    }

    /// Each column's least and largest value, and when.
    fn extremes(&self) -> BTreeMap<String, Extremes> {
        self.cols
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
                let (t_min, t_max) = (self.states[kmin].t, self.states[kmax].t);
                (c.name.clone(), Extremes { min: c.values[kmin], t_min, max: c.values[kmax], t_max })
            })
            .collect()
    }

    /// The JSON summary.
    fn summary(&self, strokes: &[Guided]) -> Result<serde_json::Value, Error> {
        let (scene, states) = (self.scene, self.states);
        let (out, mech) = (scene.outputs, &scene.mechanism);
        let (max_residual, max_iter, mean_iter) = self.iterations();
        products::summary_value(
            &MotionSummary {
                kind: "linkage",
                name: &scene.name,
                units: scene.units.length(),
                outputs: [(true, "position"), (out.velocity, "velocity"), (out.acceleration, "acceleration")]
                    .into_iter()
                    .chain([(self.forces.is_some(), "forces")])
                    .filter_map(|(on, name)| on.then_some(name))
                    .collect(),
                bodies: mech.bodies.len(),
                joints: mech.joints.len(),
                drivers: mech.drivers.len(),
                positions: states.len(),
                t_from: scene.times[0],
                t_to: scene.times[scene.times.len() - 1],
                max_residual,
                newton_iterations_max: max_iter,
                newton_iterations_mean: mean_iter,
                columns: self.cols.iter().map(|c| c.name.as_str()).collect(),
                extremes: self.extremes(),
                strokes: strokes.iter().map(|g| (g.measure.label.clone(), stroke_record(scene, &g.stroke))).collect(),
                power_residual_max: self.power_residual_max(),
                groups: group_records(scene, self.assur),
                near_singular: states
                    .iter()
                    .filter_map(|s| s.near_singular.as_ref())
                    .map(|n| NearSingularRecord {
                        t: n.t,
                        drivers: &n.drivers,
                        constraints: &n.constraints,
                        pivot: n.pivot,
                    })
                    .collect(),
                samples: self.samples(),
            },
            &scene.name,
        )
    }

    /// The run's report on stderr: the counts, the residual and iterations, the groups, the
    /// strokes, the forces' balance.
    fn report(&self, strokes: &[Guided]) -> String {
        let (scene, mech) = (self.scene, &self.scene.mechanism);
        let (max_residual, max_iter, mean_iter) = self.iterations();
        let iterations = if self.assur.all_closed_form() && max_iter == 0 {
            "no Newton iterations (every group in closed form)".to_string()
        } else {
            format!("Newton iterations per step ≤ {max_iter} (mean {mean_iter:.2})")
        };
        let mut report = format!(
            "linkage {}: {} bodies, {} joints, {}; {} positions, t = {}..{} s; max residual {:.1e} (relative); \
             {iterations}",
            scene.name,
            mech.bodies.len(),
            mech.joints.len(),
            crate::text::counted(mech.drivers.len() as i64, "driver", "drivers"),
            self.states.len(),
            // At most 6 decimals: a span of π/10 s reads 0..0.314159 s.
            crate::solve::chain::graph::fmt_value(scene.times[0]),
            crate::solve::chain::graph::fmt_value(scene.times[scene.times.len() - 1]),
            max_residual,
        );
        report.push('\n');
        report.push_str(&format!(
            "groups: {}",
            self.assur
                .routes()
                .into_iter()
                .map(|(g, route)| format!("{} by {}", g.describe(mech), route.name()))
                .collect::<Vec<_>>()
                .join("; ")
        ));
        for g in strokes {
            report.push('\n');
            report.push_str(&stroke_line(scene, g));
        }
        if let (Some(f), Some(p)) = (self.forces, self.power_residual_max()) {
            report.push('\n');
            report.push_str(&forces_line(scene, f, p));
        }
        report
    }

    /// The diagrams: one per measured column (its `plots`), then one per reaction and
    /// driver force, against the same abscissa.
    fn diagrams(&self, plots: Vec<Plot>) -> Vec<products::Diagram> {
        let (x_label, x) = abscissa(self.scene, self.states);
        let mut diagrams: Vec<products::Diagram> = plots
            .into_iter()
            .zip(self.cols)
            .map(|(p, c)| {
                let d = Diagram {
                    title: p.title,
                    x_label: x_label.clone(),
                    y_label: p.y_label,
                    series: vec![Series { label: c.name.clone(), x: x.clone(), y: p.values }],
                };
                products::Diagram { stem: c.name.clone(), drawing: diagram(&d), track: track(&d, &Default::default()) }
            })
            .collect();
        if let Some(f) = self.forces {
            diagrams.extend(force_diagrams(self.scene, f, &x_label, &x).into_iter().map(|(stem, d)| {
                products::Diagram { stem, drawing: diagram(&d), track: track(&d, &Default::default()) }
            }));
        }
        diagrams
    }

    /// The CSV: t, the measured columns, the forces' columns.
    fn csv(&self) -> Csv {
        let force_cols = self.forces.map(|f| force_columns(self.scene, f)).unwrap_or_default();
        let all_cols = || self.cols.iter().chain(&force_cols);
        let mut csv = Csv::new(std::iter::once("t".to_string()).chain(all_cols().map(|c| c.name.clone())));
        for (k, s) in self.states.iter().enumerate() {
            csv.row(std::iter::once(s.t).chain(all_cols().map(|c| c.values[k])));
        }
        csv
    }
}

/// Each Assur group in solving order, as the JSON summary lists it.
fn group_records<'a>(scene: &'a LinkageScene, assur: &AssurSolver) -> Vec<GroupRecord<'a>> {
    assur
        .routes()
        .into_iter()
        .map(|(g, route)| GroupRecord {
            kind: g.kind_name(),
            bodies: g.bodies.iter().map(|&b| scene.mechanism.bodies[b].name.as_str()).collect(),
            joints: g.joints.iter().map(|&j| scene.mechanism.joints[j].name.as_str()).collect(),
            route: route.name(),
        })
        .collect()
}

/// A run's motion as its frames draw it: the frames, the figure, the states and forces at
/// every sample, the positions' names and the ones drawn.
struct Motion {
    frames: LinkageFrames,
    figure: fig::LinkageFigure,
    states: Vec<State>,
    forces: Vec<Forces>,
    names: Vec<String>,
    drawn: Vec<usize>,
}

impl Motion {
    /// The animation of the run (only the `drawn` positions when `chosen`), with its drive
    /// (the Assur route at any time between the samples, for a drag), and the scales each
    /// drawn frame is drawn at (in the animation's order).
    fn animation(
        self,
        scene: &LinkageScene,
        file: &str,
        chosen: bool,
    ) -> Result<(Animation, Vec<crate::figure::shared::panels::FrameScales>), Error> {
        let Motion { frames, figure, states, forces, names, drawn } = self;
        let motion: Vec<&[f64]> = states.iter().map(|s| s.q.as_slice()).collect();
        let base = frames.base(&figure, &motion);
        let window = frames.frame.window;
        let labels = states.iter().map(|s| format!("t = {:.4} s", s.t)).collect();
        let (mech, dynamics) = (scene.mechanism.clone(), scene.dynamics.clone());
        let (frames, figure, states) = (Arc::new(frames), Arc::new(figure), Arc::new(states));
        let at = Arc::new(SolveAt {
            solver: Mutex::new(AssurSolver::new(mech.clone()).map_err(|e| solve_err(file)(e.into()))?),
            states: states.clone(),
            dynamics: dynamics.clone().filter(|_| scene.outputs.forces),
            rates: scene.outputs.velocity,
        });
        let drive = Drive {
            values: states.iter().map(|s| s.t).collect(),
            solve: {
                let at = at.clone();
                Box::new(move |k, t| {
                    let (state, _) = at.solve(k, t)?;
                    Ok(linkage_drive_state(&at.solver, &state))
                })
            },
            draw: {
                let (frames, figure, mech) = (frames.clone(), figure.clone(), mech.clone());
                Box::new(move |k, t| {
                    let (state, force) = at.solve(k, t)?;
                    let force = at.dynamics.as_ref().zip(force.as_ref());
                    Ok(frames.moving(k, &figure, &mech, &state, force))
                })
            },
        };
        let frame_scales = if chosen { drawn.clone() } else { (0..states.len()).collect() }
            .into_iter()
            .map(|k| frames.frame.scales_at(k))
            .collect();
        let pose = move |k: usize| {
            let force = dynamics.as_ref().zip(forces.get(k));
            frames.moving(k, &figure, &mech, &states[k], force)
        };
        let animation = Animation::new(scene.name.clone(), base, Some(window), names, labels, pose).with_drive(drive);
        Ok((if chosen { animation.keep(drawn) } else { animation }, frame_scales))
    }
}

/// The Assur route at any time between the run's samples (for a drag), continuing the
/// assembly mode of a sample, computing what the run computed.
struct SolveAt {
    solver: Mutex<AssurSolver>,
    states: Arc<Vec<State>>,
    dynamics: Option<crate::solve::linkage::Dynamics>,
    rates: bool,
}

impl SolveAt {
    /// The state (and forces) at `t`, from sample `k`.
    fn solve(&self, k: usize, t: f64) -> Result<(State, Option<crate::solve::linkage::Forces>), String> {
        let mut solver = self.solver.lock().map_err(|_| "the solver failed earlier".to_string())?;
        if let Some(s) = self.states.get(k) {
            solver.resume(s);
        }
        let at = |e: LinkageError| format!("at t = {t} s: {e}");
        match &self.dynamics {
            Some(d) => {
                let (mut states, mut forces) = solver.run_kinetostatics(&[t], d).map_err(at)?;
                Ok((states.remove(0), forces.pop()))
            }
            None if self.rates => Ok((solver.run(&[t]).map_err(at)?.remove(0), None)),
            None => {
                solver.step_positions(t).map_err(at)?;
                Ok((solver.state(), None))
            }
        }
    }
}

/// Every named point of every body (`crank.A`), and the state's residual.
fn linkage_drive_state(solver: &Mutex<AssurSolver>, state: &State) -> DriveState {
    let points = match solver.lock() {
        Ok(s) => s
            .mechanism()
            .bodies
            .iter()
            .enumerate()
            .flat_map(|(i, b)| {
                b.points.iter().map(move |(name, local)| {
                    (format!("{}.{name}", b.name), state.point(Anchor { body: Attach::Body(i), local: *local }))
                })
            })
            .collect(),
        Err(_) => Vec::new(),
    };
    DriveState { label: format!("t = {:.4} s", state.t), points, residual: state.residual }
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
    let motion = [state.q.as_slice()];
    let figure = figure_of(scene);
    let style = fig::paper_style(&figure, &motion);
    let spans = fig::guide_spans(&figure, &motion, &style);
    let mut d = fig::new_drawing(&style);
    let layer = d.layer("DRAG", Aci::BLACK, LineType::Continuous);
    fig::mechanism(&mut d, layer, &figure, &state.q, &spans, &style);
    Ok(Products {
        name: scene.name.clone(),
        mm_per_unit: super::mm_per_unit(scene.units),
        picture: Picture::Still(d),
        positions: None,
        sheets: Vec::new(),
        pages: Vec::new(),
        diagrams: Vec::new(),
        tables: Vec::new(),
        texts: Vec::new(),
        summary,
        report,
        warnings: Vec::new(),
        derived: Vec::new(),
        frame_scales: Vec::new(),
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
    let units = match scene.units {
        crate::scene::Units::Mm => crate::figure::shared::vocab::ModelUnits::MM,
        crate::scene::Units::Si => crate::figure::shared::vocab::ModelUnits::SI,
    };
    fig::LinkageFigure::new(&scene.mechanism, |a| scene.point_name(a), traced).with_units(units)
}

/// The force columns of the CSV: `<joint>.Fx`, `<joint>.Fy` for every joint (N; the
/// force of the joint's first body on its second, see [`crate::solve::linkage::Forces`]),
/// `<joint>.M` for a prismatic joint (N·m), `drive.<driver>` for every driver (N·m or N),
/// and `power_residual`.
pub(super) fn force_columns(scene: &LinkageScene, forces: &[Forces]) -> Vec<Column> {
    let mech = &scene.mechanism;
    let mut out = Vec::new();
    // + 0.0 turns −0 into 0.
    let col =
        |name: String, f: &dyn Fn(&Forces) -> f64| Column { name, values: forces.iter().map(|x| f(x) + 0.0).collect() };
    for (j, joint) in mech.joints.iter().enumerate() {
        out.push(col(format!("{}.Fx", joint.name), &|f| f.reactions[j].force.x));
        out.push(col(format!("{}.Fy", joint.name), &|f| f.reactions[j].force.y));
        if matches!(joint.kind, JointKind::Prismatic { .. }) {
            out.push(col(format!("{}.M", joint.name), &|f| f.reactions[j].torque));
        }
    }
    for (d, driver) in mech.drivers.iter().enumerate() {
        out.push(col(format!("drive.{}", driver.name), &|f| f.drivers[d]));
    }
    out.push(col("power_residual".into(), &|f| f.power_residual));
    out
}

/// Which body acts on which in a joint's reaction: (acting, acted on).
fn joint_bodies<'a>(scene: &'a LinkageScene, kind: &JointKind) -> (&'a str, &'a str) {
    match *kind {
        JointKind::Revolute { a, b } => (scene.body_name(a.body), scene.body_name(b.body)),
        JointKind::Prismatic { point, q1, .. } => (scene.body_name(q1.body), scene.body_name(point.body)),
    }
}

/// The JSON reactions of one sample, by joint name.
fn reaction_records(scene: &LinkageScene, f: &Forces) -> BTreeMap<String, ReactionRecord> {
    scene
        .mechanism
        .joints
        .iter()
        .zip(&f.reactions)
        // + 0.0 turns −0 into 0.
        .map(|(j, r)| {
            (j.name.clone(), ReactionRecord { force: [r.force.x + 0.0, r.force.y + 0.0], torque: r.torque + 0.0 })
        })
        .collect()
}

/// Diagrams of the forces against the measures' abscissa (`x_label`, `x`), with their
/// stems: every reaction's magnitude (`<joint>.R`), every prismatic joint's couple
/// (`<joint>.M`) and every driver's force (`drive.<driver>`).
pub(super) fn force_diagrams(
    scene: &LinkageScene,
    forces: &[Forces],
    x_label: &str,
    x: &[f64],
) -> Vec<(String, Diagram)> {
    let mech = &scene.mechanism;
    let mut out = Vec::new();
    let plot = |stem: String, title: String, y_label: String, values: Vec<f64>| {
        let series = vec![Series { label: stem.clone(), x: x.to_vec(), y: values }];
        (stem, Diagram { title, x_label: x_label.to_string(), y_label, series })
    };
    for (j, joint) in mech.joints.iter().enumerate() {
        let (by, on) = joint_bodies(scene, &joint.kind);
        let name = &joint.name;
        out.push(plot(
            format!("{name}.R"),
            format!("Reaction in joint {name} ({by} on {on})"),
            format!("|R_{name}| [N]"),
            forces.iter().map(|f| f.reactions[j].force.norm()).collect(),
        ));
        if let JointKind::Prismatic { point, .. } = joint.kind {
            let about = scene.point_name(point).map_or(String::new(), |p| format!(", about {on}.{p}"));
            out.push(plot(
                format!("{name}.M"),
                format!("Couple in joint {name} ({by} on {on}{about}, CCW positive)"),
                format!("M_{name} [N·m]"),
                forces.iter().map(|f| f.reactions[j].torque).collect(),
            ));
        }
    }
    for (d, driver) in mech.drivers.iter().enumerate() {
        let name = &driver.name;
        // Named as the table and the sheets name it (Me1, Fe1).
        let symbol = linkage_forces::driver_name(mech, d);
        let (title, y_label) = match driver.target {
            DriverTarget::JointDistance(_) => {
                (format!("Balancing force {symbol} of driver {name} (along its guide)"), format!("{symbol} [N]"))
            }
            _ => (
                format!("Balancing moment {symbol} of driver {name} (positive with the driver)"),
                format!("{symbol} [N·m]"),
            ),
        };
        out.push(plot(format!("drive.{name}"), title, y_label, forces.iter().map(|f| f.drivers[d]).collect()));
    }
    out
}

/// The report's line on the forces: the largest reaction and driver force, and the largest
/// virtual-power residual.
fn forces_line(scene: &LinkageScene, forces: &[Forces], power_residual_max: f64) -> String {
    let mech = &scene.mechanism;
    let mut s = String::from("forces:");
    let largest = mech
        .joints
        .iter()
        .enumerate()
        .map(|(j, joint)| (joint.name.as_str(), forces.iter().map(|f| f.reactions[j].force.norm()).fold(0.0, f64::max)))
        .fold(None, |acc: Option<(&str, f64)>, x| if acc.is_none_or(|a| x.1 > a.1) { Some(x) } else { acc });
    if let Some((name, r)) = largest {
        s.push_str(&format!(" largest reaction {r:.4} N in joint {name};"));
    }
    for (d, driver) in mech.drivers.iter().enumerate() {
        let unit = match driver.target {
            DriverTarget::JointDistance(_) => "N",
            _ => "N·m",
        };
        let (lo, hi) = forces
            .iter()
            .map(|f| f.drivers[d])
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
        s.push_str(&format!(" driver {} {lo:.4} … {hi:.4} {unit};", driver.name));
    }
    s.push_str(&format!(" virtual-power residual ≤ {power_residual_max:.1e}"));
    s
}

/// A measured point on a body that slides on a ground guide, with its stroke.
pub(super) struct Guided<'a> {
    /// The measure of the point.
    pub measure: &'a Measure,
    /// The guide's direction (q1 → q2, global, unit).
    pub guide: crate::geom::Vector,
    /// Its stroke.
    pub stroke: Stroke,
}

/// The stroke of every measured point whose body slides on a ground guide.
pub(super) fn guided_strokes<'a>(
    scene: &'a LinkageScene,
    solver: &mut Solver,
    states: &[State],
) -> Result<Vec<Guided<'a>>, LinkageError> {
    let mut out = Vec::new();
    for m in &scene.measures {
        let MeasureTarget::Point(a) = m.target else { continue };
        let Attach::Body(i) = a.body else { continue };
        let Some((_, guide)) = scene.mechanism.ground_guide(i) else { continue };
        let stroke = stroke::stroke(solver, states, a, guide)?;
        out.push(Guided { measure: m, guide, stroke });
    }
    Ok(out)
}

/// Metres per length unit of the scene (velocities and accelerations are drawn in m/s and
/// m/s², as textbooks print them, whatever the length unit).
pub(super) fn metres_per_unit(units: Units) -> f64 {
    match units {
        Units::Mm => 1e-3,
        Units::Si => 1.0,
    }
}

/// The diagrams' abscissa: the single angular driver's angle φ (degrees, the law's value
/// over the motion) or t.
pub(super) fn abscissa(scene: &LinkageScene, states: &[State]) -> (String, Vec<f64>) {
    match (scene.diagram_axis, scene.mechanism.angular_driver()) {
        (DiagramAxis::DriverAngle, Some((driver, body))) => {
            let sub = body_symbol(scene, body);
            (format!("φ{sub} [°]"), states.iter().map(|s| deg(driver.law.eval(s.t).value)).collect())
        }
        _ => ("t [s]".into(), states.iter().map(|s| s.t).collect()),
    }
}

/// A body's subscript: the `symbol` of a measure of that body, else its number in the
/// scene (1, 2, …).
pub(super) fn body_symbol(scene: &LinkageScene, body: Attach) -> String {
    let measured = scene.measures.iter().find(|m| m.target == MeasureTarget::Body(body));
    match (measured, body) {
        (Some(m), _) => m.symbol.clone(),
        (None, Attach::Body(i)) => (i + 1).to_string(),
        (None, Attach::Ground) => "0".into(),
    }
}

/// One diagram's title, axis label and values.
pub(super) struct Plot {
    /// Its title.
    pub title: String,
    /// Its ordinate's label with the unit.
    pub y_label: String,
    /// Its values.
    pub values: Vec<f64>,
}

/// How one measured quantity is drawn: textbook symbol and title, velocities and
/// accelerations in m/s and m/s². A guided point's quantity along its guide's main axis
/// (x for a guide nearer the x axis) is drawn as s, v, a along the guide, s from the
/// extreme where the working stroke starts (docs/linkage.md).
pub(super) fn plot_of(scene: &LinkageScene, m: &Measure, q: Quantity, states: &[State], strokes: &[Guided]) -> Plot {
    let lu = scene.units.length();
    let k = metres_per_unit(scene.units);
    let sym = &m.symbol;
    let raw: Vec<f64> = states.iter().map(|s| quantity(s, m.target, q)).collect();
    let scaled = |f: f64| raw.iter().map(|v| v * f).collect::<Vec<f64>>();
    match m.target {
        MeasureTarget::Point(a) => {
            let whose = format!("the {} point {sym}", scene.body_name(a.body));
            let guided = strokes.iter().find(|g| g.measure.label == m.label);
            let along = guided.filter(|g| {
                let x_axis = g.guide.x.abs() >= g.guide.y.abs();
                matches!(
                    (q, x_axis),
                    (Quantity::X | Quantity::Vx | Quantity::Ax, true)
                        | (Quantity::Y | Quantity::Vy | Quantity::Ay, false)
                )
            });
            if let Some(g) = along {
                let w = g.stroke.direction;
                let (title, y_label, values) = match q {
                    Quantity::X | Quantity::Y => (
                        "Displacement",
                        format!("s{sym} [{lu}]"),
                        states.iter().map(|s| g.stroke.s(s.point(a))).collect(),
                    ),
                    Quantity::Vx | Quantity::Vy => (
                        "Velocity",
                        format!("v{sym} [m/s]"),
                        states.iter().map(|s| s.velocity(a).dot(&w) * k).collect(),
                    ),
                    _ => (
                        "Acceleration",
                        format!("a{sym} [m/s²]"),
                        states.iter().map(|s| s.acceleration(a).dot(&w) * k).collect(),
                    ),
                };
                return Plot { title: format!("{title} of {whose}"), y_label, values };
            }
            let (title, y_label, values) = match q {
                Quantity::X => (format!("x-coordinate of {whose}"), format!("x{sym} [{lu}]"), raw),
                Quantity::Y => (format!("y-coordinate of {whose}"), format!("y{sym} [{lu}]"), raw),
                Quantity::Vx => (format!("Velocity of {whose}, x-component"), format!("v{sym}x [m/s]"), scaled(k)),
                Quantity::Vy => (format!("Velocity of {whose}, y-component"), format!("v{sym}y [m/s]"), scaled(k)),
                Quantity::V => (format!("Speed of {whose}"), format!("|v{sym}| [m/s]"), scaled(k)),
                Quantity::Ax => (format!("Acceleration of {whose}, x-component"), format!("a{sym}x [m/s²]"), scaled(k)),
                Quantity::Ay => (format!("Acceleration of {whose}, y-component"), format!("a{sym}y [m/s²]"), scaled(k)),
                _ => (format!("Acceleration of {whose}, magnitude"), format!("|a{sym}| [m/s²]"), scaled(k)),
            };
            Plot { title, y_label, values }
        }
        MeasureTarget::Body(b) => {
            let name = scene.body_name(b);
            let driven = scene.mechanism.angular_driver().is_some_and(|(_, d)| d == b);
            let angle = if driven { "φ" } else { "ψ" };
            let (title, y_label) = match q {
                Quantity::Angle => (format!("Angle of the {name}"), format!("{angle}{sym} [°]")),
                Quantity::Omega => (format!("Angular velocity of the {name}"), format!("ω{sym} [rad/s]")),
                _ => (format!("Angular acceleration of the {name}"), format!("ε{sym} [rad/s²]")),
            };
            Plot { title, y_label, values: raw }
        }
    }
}

/// The report's line for one guided point.
pub(super) fn stroke_line(scene: &LinkageScene, g: &Guided) -> String {
    let st = &g.stroke;
    let lu = scene.units.length();
    let sym = &g.measure.symbol;
    let mut s = format!("stroke of {sym}: H = {:.4} {lu}", st.h);
    match &st.cycle {
        Ok(c) => s.push_str(&format!(
            ", K = {:.4} (working stroke {:.4} s from t = {:.4} s{}, return {:.4} s)",
            c.k,
            c.working_time,
            st.start.t,
            driver_text(scene, &st.start),
            c.return_time
        )),
        Err(why) => s.push_str(&format!("; K not reported: {}", why.text())),
    }
    s
}

/// ", φ1 = 335.3757°" for an extreme when the driver is angular.
pub(super) fn driver_text(scene: &LinkageScene, e: &Extreme) -> String {
    match (scene.mechanism.angular_driver(), e.driver) {
        (Some((_, body)), Some(v)) => format!(", φ{} = {:.4}°", body_symbol(scene, body), deg(v)),
        _ => String::new(),
    }
}

/// The JSON record of a stroke (docs/linkage.md).
fn stroke_record(scene: &LinkageScene, st: &Stroke) -> StrokeRecord {
    let angular = scene.mechanism.angular_driver().is_some();
    let ext =
        |e: &Extreme| ExtremeRecord { t: e.t, at: [e.at.x, e.at.y], driver_deg: e.driver.filter(|_| angular).map(deg) };
    StrokeRecord {
        h: st.h,
        k: st.cycle.as_ref().ok().map(|c| c.k),
        k_not_reported: st.cycle.as_ref().err().map(|w| w.text()),
        // + 0.0 turns −0 into 0.
        direction: [st.direction.x + 0.0, st.direction.y + 0.0],
        start: ext(&st.start),
        end: ext(&st.end),
        working_time: st.cycle.as_ref().ok().map(|c| c.working_time),
        return_time: st.cycle.as_ref().ok().map(|c| c.return_time),
        period: st.cycle.as_ref().ok().map(|c| c.period),
    }
}

/// An extreme position in the JSON summary.
#[derive(Debug, Serialize)]
struct ExtremeRecord {
    t: f64,
    at: [f64; 2],
    #[serde(skip_serializing_if = "Option::is_none")]
    driver_deg: Option<f64>,
}

/// The stroke of a guided point in the JSON summary.
#[derive(Debug, Serialize)]
struct StrokeRecord {
    #[serde(rename = "H")]
    h: f64,
    #[serde(rename = "K", skip_serializing_if = "Option::is_none")]
    k: Option<f64>,
    #[serde(rename = "K_not_reported", skip_serializing_if = "Option::is_none")]
    k_not_reported: Option<&'static str>,
    direction: [f64; 2],
    start: ExtremeRecord,
    end: ExtremeRecord,
    #[serde(skip_serializing_if = "Option::is_none")]
    working_time: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    return_time: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    period: Option<f64>,
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
    /// By joint name (scenes with forces).
    #[serde(skip_serializing_if = "Option::is_none")]
    reactions: Option<BTreeMap<String, ReactionRecord>>,
    /// By driver name (scenes with forces).
    #[serde(skip_serializing_if = "Option::is_none")]
    drivers: Option<BTreeMap<String, f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    power_residual: Option<f64>,
    /// By prismatic joint name.
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    sliding: BTreeMap<String, SlidingRecord>,
}

/// The relative motion at a prismatic joint in the JSON (scene length unit per s, per s²;
/// see [`crate::solve::linkage::Sliding`]).
#[derive(Debug, Serialize)]
struct SlidingRecord {
    v_rel: [f64; 2],
    a_rel: [f64; 2],
    a_cor: [f64; 2],
}

/// The relative motion at every prismatic joint of one sample, by joint name.
fn sliding_records(scene: &LinkageScene, state: &State) -> BTreeMap<String, SlidingRecord> {
    // + 0.0 turns −0 into 0.
    let xy = |v: crate::geom::Vector| [v.x + 0.0, v.y + 0.0];
    scene
        .mechanism
        .joints
        .iter()
        .filter_map(|j| {
            let s = state.sliding(&j.kind)?;
            Some((j.name.clone(), SlidingRecord { v_rel: xy(s.v_rel), a_rel: xy(s.a_rel), a_cor: xy(s.a_cor) }))
        })
        .collect()
}

/// A joint's reaction in the JSON: force N, couple N·m.
#[derive(Debug, Serialize)]
struct ReactionRecord {
    force: [f64; 2],
    torque: f64,
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
    /// What was computed: "position", "velocity", "acceleration", "forces".
    outputs: Vec<&'static str>,
    bodies: usize,
    joints: usize,
    drivers: usize,
    positions: usize,
    t_from: f64,
    t_to: f64,
    max_residual: f64,
    newton_iterations_max: usize,
    newton_iterations_mean: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    power_residual_max: Option<f64>,
    columns: Vec<&'a str>,
    /// The Assur groups in solving order and how each was solved.
    groups: Vec<GroupRecord<'a>>,
    extremes: BTreeMap<String, Extremes>,
    strokes: BTreeMap<String, StrokeRecord>,
    near_singular: Vec<NearSingularRecord<'a>>,
    samples: Vec<Sample>,
}

/// One group of the Assur decomposition in the JSON (docs/linkage.md): its kind (`RRR`,
/// `RRP`, `RPR`, `PRP`, `RPP`, `driven (angle)`, `driven (distance)`, `triad`, `general`),
/// bodies and joints in the kind's order, and `closed form` or `Newton`.
#[derive(Debug, Serialize)]
struct GroupRecord<'a> {
    kind: &'static str,
    bodies: Vec<&'a str>,
    joints: Vec<&'a str>,
    route: &'static str,
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

/// One sample's values for its sheet: each measured quantity (its diagram's symbol and
/// unit) and, with forces, every applied force, every reaction's magnitude and the
/// drivers' forces, 4 significant digits ([`sheet::number`]); rounding noise as 0.
pub(super) fn sheet_table(
    scene: &LinkageScene,
    plots: &[Plot],
    k: usize,
    forces: Option<(&crate::solve::linkage::Dynamics, &State, &Forces)>,
) -> sheet::Table {
    let header = ["", "value", "unit"].map(String::from).to_vec();
    // One unit system on the page: the scene's (the diagrams draw velocities in m/s; a mm
    // scene's sheet in mm/s, as its polygons).
    let per_m = 1.0 / metres_per_unit(scene.units);
    let lu = scene.units.length();
    let mut names = Vec::new();
    let mut rows: Vec<Vec<String>> = plots
        .iter()
        .map(|p| {
            let (name, unit) = match p.y_label.rsplit_once(" [") {
                Some((n, u)) => (n.to_string(), u.trim_end_matches(']').to_string()),
                None => (p.y_label.clone(), String::new()),
            };
            let (factor, unit) = match unit.as_str() {
                "m/s" => (per_m, format!("{lu}/s")),
                "m/s²" => (per_m, format!("{lu}/s²")),
                _ => (1.0, unit),
            };
            // A value below 1e-9 of its series' largest is rounding noise (ω = 1e-15 rad/s
            // at a dead centre) and prints as 0.
            let largest = p.values.iter().filter(|v| v.is_finite()).fold(0.0, |m: f64, v| m.max(v.abs()));
            let v = p.values[k];
            let text = if v.abs() < 1e-9 * largest { "0".to_string() } else { sheet::number(v * factor) };
            // `vE`, `|aE|`, `φ1`: a symbol and its subscript (the point's or body's name).
            names.push(Label::quantity(&name).runs);
            vec![name, text, unit]
        })
        .collect();
    if let Some((dynamics, state, f)) = forces {
        let mech = &scene.mechanism;
        // Every applied force (inertia forces, weights, loads), then the reactions and the
        // drivers' forces.
        let applied = linkage_forces::applied_magnitudes(mech, dynamics, state, f);
        let all: Vec<_> =
            applied.into_iter().chain(linkage_forces::magnitudes(mech, f, &format!("N·{lu}"), per_m)).collect();
        // A value below 1e-9 of the largest of its unit on the page is rounding noise (the
        // inertia force 7e-14 N of a slider at rest) and prints as 0.
        let largest = |unit: &str| {
            all.iter().filter(|m| m.unit == unit && m.value.is_finite()).fold(0.0, |a: f64, m| a.max(m.value.abs()))
        };
        for m in &all {
            let text = if m.value.abs() < 1e-9 * largest(&m.unit) { "0".to_string() } else { sheet::number(m.value) };
            rows.push(vec![m.name.clone(), text, m.unit.clone()]);
            names.push(m.label().runs);
        }
    }
    sheet::Table { header, rows, names }
}

/// The printed pages, one per drawn sample (`drawn`: indices into the samples; in parallel):
/// `sheets/<name>/<position>.svg` and the PDF, numbered among themselves.
#[allow(clippy::too_many_arguments)]
fn sheet_pages(
    paper: Paper,
    scene: &LinkageScene,
    figure: &fig::LinkageFigure,
    states: &[State],
    forces: Option<(&crate::solve::linkage::Dynamics, &[Forces])>,
    plots: &[Plot],
    show: Show,
    names: &[String],
    drawn: &[usize],
) -> Vec<products::Page> {
    // The table's rows: the most any sample has (a load acts only on part of the motion).
    let rows = (0..states.len())
        .map(|k| row_counts(&sheet_table(scene, plots, k, forces.map(|(d, f)| (d, &states[k], &f[k])))))
        .fold((0, 0), |(a, b), (c, d)| (a.max(c), b.max(d)));
    let sheets =
        LinkageSheets::new(paper, &scene.name, &scene.mechanism, figure, states, show, forces.is_some(), rows, None);
    let per = sheets.per_position();
    let total = drawn.len() * per;
    let sets: Vec<Vec<products::Page>> = drawn
        .par_iter()
        .enumerate()
        .map(|(j, &k)| {
            let st = &states[k];
            let force = forces.map(|(d, f)| (d, &f[k]));
            let table = sheet_table(scene, plots, k, force.map(|(d, f)| (d, st, f)));
            sheets
                .pages(&scene.mechanism, st, force, &table, (j * per + 1, total))
                .into_iter()
                .map(|(kind, drawing)| products::Page::printed(&names[k], kind, drawing, paper))
                .collect()
        })
        .collect();
    sets.into_iter().flatten().collect()
}
