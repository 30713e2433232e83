//! A linkage scene's report: solved by its Assur groups as `mechdraw run` solves it; the
//! dead positions are the guided points' extremes (refined by the stroke's Newton
//! iterations) or, without one, the extremes of the first body angle measured (refined on
//! ω = 0); each chosen position gets the printed sheet's page at its own scales.

use std::sync::Arc;

use super::Frame;
use super::motion::{self, At, Chosen, Cycle, Dead, DriveAxis, MotionReport};
use crate::Error;
use crate::figure::linkage::sheet::{LinkageSheets, row_counts};
use crate::figure::report::diagrams::MarkedDiagram;
use crate::figure::report::freebody::{self, FreeBodyPage};
use crate::figure::report::plan::PlanDimension;
use crate::figure::report::sketch::{DriverMark, LoadMark, Sketch};
use crate::figure::report::table::{Align, PaperTable};
use crate::figure::shared::labels::Label;
use crate::figure::shared::plot::{self, Diagram, Marks, Series};
use crate::figure::shared::sheet;
use crate::geom::{Vector, deg};
use crate::report::Csv;
use crate::run::linkage as run;
use crate::scene::linkage::{LinkageScene, MeasureTarget, Quantity};
use crate::solve::linkage::{
    Anchor, AssurSolver, Attach, DriverTarget, Dynamics, Forces, JointKind, LoadAction, Solver, State, Structure, place,
};

/// Newton iterations allowed to refine a body angle's extreme on ω = 0.
const REFINE_ITERATIONS: usize = 20;
/// Relative change of t at which that refinement stops.
const REFINE_TOL_REL: f64 = 1e-14;

/// What the report solved: the samples, and the positions it added (the dead ones).
struct Solved {
    states: Vec<State>,
    forces: Option<Vec<Forces>>,
    extra: Vec<State>,
    extra_forces: Vec<Forces>,
}

impl Solved {
    fn state(&self, at: At) -> &State {
        match at {
            At::Sample(k) => &self.states[k],
            At::Exact(i) => &self.extra[i],
        }
    }
    fn force(&self, at: At) -> Option<&Forces> {
        match at {
            At::Sample(k) => self.forces.as_ref().and_then(|f| f.get(k)),
            At::Exact(i) => self.extra_forces.get(i),
        }
    }
}

/// Solves at `t` continuing from sample `k`, with the forces when `dynamics` is given.
fn solve_at(
    assur: &mut AssurSolver,
    from: &State,
    t: f64,
    dynamics: Option<&Dynamics>,
) -> Result<(State, Option<Forces>), crate::solve::linkage::LinkageError> {
    assur.resume(from);
    match dynamics {
        Some(d) => {
            let (mut s, mut f) = assur.run_kinetostatics(&[t], d)?;
            Ok((s.remove(0), f.pop()))
        }
        None => Ok((assur.run(&[t])?.remove(0), None)),
    }
}

/// The sample nearest `t`.
fn nearest_sample(states: &[State], t: f64) -> usize {
    let mut best = 0;
    for (k, s) in states.iter().enumerate() {
        if (s.t - t).abs() < (states[best].t - t).abs() {
            best = k;
        }
    }
    best
}

/// The extremes of body `b`'s angle over the samples, refined on ω = 0 (Newton on t with
/// ε the derivative): (t, what) for the smallest and the largest.
fn body_extremes(assur: &mut AssurSolver, states: &[State], b: usize, name: &str) -> Vec<(f64, String)> {
    let angle = |s: &State| s.q[3 * b + 2];
    let (mut kmin, mut kmax) = (0, 0);
    for (k, s) in states.iter().enumerate() {
        if angle(s) < angle(&states[kmin]) {
            kmin = k;
        }
        if angle(s) > angle(&states[kmax]) {
            kmax = k;
        }
    }
    let mut out = Vec::new();
    for (k, what) in [(kmin, format!("smallest angle of the {name}")), (kmax, format!("largest angle of the {name}"))] {
        // An extreme at an end of an open motion is not a dead position.
        if k == 0 || k + 1 == states.len() {
            continue;
        }
        let mut t = states[k].t;
        for _ in 0..REFINE_ITERATIONS {
            let Ok(s) = assur.run(&[t]).map(|mut v| v.remove(0)) else { break };
            let (_, w, e) = s.angular(Attach::Body(b));
            if e == 0.0 || !e.is_finite() {
                break;
            }
            let next = t - w / e;
            if !next.is_finite() || (next - states[k].t).abs() > 2.0 * (states[1].t - states[0].t).abs() {
                break;
            }
            let done = (next - t).abs() <= REFINE_TOL_REL * t.abs().max(1.0);
            t = next;
            if done {
                break;
            }
            assur.resume(&states[k]);
        }
        out.push((t, what));
    }
    out
}

/// The linkage's mechanism as the report draws it.
fn sketch(scene: &LinkageScene) -> Sketch {
    let figure = run::figure_of(scene);
    let mech = &scene.mechanism;
    let t0 = scene.times[0];
    let driver = mech.angular_driver().and_then(|(d, body)| {
        let Attach::Body(b) = body else { return None };
        let pivot = mech.joints.iter().find_map(|j| match j.kind {
            JointKind::Revolute { a, b: bb } if a.body == body && bb.body == Attach::Ground => Some(a),
            JointKind::Revolute { a, b: bb } if bb.body == body && a.body == Attach::Ground => Some(bb),
            _ => None,
        })?;
        let rate = d.law.eval(t0).d1;
        let sub = run::body_symbol(scene, body);
        Some(DriverMark { body: b, pivot, sense: if rate < 0.0 { -1.0 } else { 1.0 }, symbol: format!("ω{sub}") })
    });
    let loads = scene
        .dynamics
        .iter()
        .flat_map(|d| d.loads.iter())
        .filter_map(|l| match &l.action {
            LoadAction::Force { at, force } => {
                let t = l.window.map_or(t0, |w| 0.5 * (w.from + w.to));
                Some(LoadMark { at: *at, direction: Vector::new(force[0].at(t), force[1].at(t)), name: l.name.clone() })
            }
            LoadAction::Torque { .. } => None,
        })
        .collect();
    Sketch { figure, names: mech.bodies.iter().map(|b| b.name.clone()).collect(), driver, loads }
}

/// Significant digits of the title page's data.
const DATA_DIGITS: u32 = 6;

/// The title page's data: the ground points, each link's lengths, the masses, the driver,
/// the loads, gravity and the time range.
fn data(scene: &LinkageScene) -> PaperTable {
    let u = scene.units.length();
    let mut t = PaperTable::new(&["quantity", "value", "unit"], &[Align::Left, Align::Right, Align::Left]);
    // Six significant digits: what a student copies from the data sheet.
    let num = |v: f64| crate::figure::report::page::significant(v, DATA_DIGITS);
    for (name, p) in &scene.ground_points {
        t.row(vec![format!("ground point {name}"), format!("({}, {})", num(p.x), num(p.y)), u.into()]);
    }
    let mech = &scene.mechanism;
    for (i, b) in mech.bodies.iter().enumerate() {
        let pts = &b.points;
        let sides = if pts.len() >= 3 { pts.len() } else { pts.len().saturating_sub(1) };
        for k in 0..sides {
            let (a, c) = (&pts[k], &pts[(k + 1) % pts.len()]);
            t.row(vec![format!("link {} {}: {}{}", i + 1, b.name, a.0, c.0), num((c.1 - a.1).norm()), u.into()]);
        }
        if let Some(m) =
            scene.dynamics.as_ref().and_then(|d| d.bodies.get(i)).filter(|m| m.mass > 0.0 || m.inertia > 0.0)
        {
            // m_2 and J_2 with their subscripts; the body's name as the user wrote it.
            let mass = Label::marked(&format!("m_{} (", i + 1)).then(&b.name).then(")");
            t.row(vec![mass, num(m.mass).into(), "kg".into()]);
            let inertia = Label::marked(&format!("J_{} about its centroid", i + 1));
            t.row(vec![inertia, num(m.inertia).into(), "kg·m²".into()]);
        }
    }
    for d in &mech.drivers {
        let j = d.law.eval(scene.times[0]);
        t.row(vec![format!("driver {}: law", d.name), d.law.source().to_string(), String::new()]);
        let rate_unit = match d.target {
            DriverTarget::JointDistance(_) => format!("{u}/s"),
            DriverTarget::BodyAngle(_) | DriverTarget::JointAngle(_) => "rad/s".into(),
        };
        t.row(vec![format!("driver {}: rate at t = {}", d.name, num(scene.times[0])), num(j.d1), rate_unit]);
    }
    if let Some(dy) = &scene.dynamics {
        t.row(vec!["g".into(), format!("({}, {})", num(dy.gravity.x), num(dy.gravity.y)), "m/s²".into()]);
        for l in &dy.loads {
            let when = l.window.map_or(String::new(), |w| format!(", t ∈ [{}, {}] s", num(w.from), num(w.to)));
            match &l.action {
                LoadAction::Force { at, force } => t.row(vec![
                    format!("load {} at {}{when}", l.name, scene.point_name(*at).unwrap_or("?")),
                    format!("({}, {})", force[0].text(), force[1].text()),
                    "N".into(),
                ]),
                LoadAction::Torque { body, torque } => t.row(vec![
                    format!("torque {} on {}{when}", l.name, mech.bodies[*body].name),
                    torque.text(),
                    "N·m".into(),
                ]),
            }
        }
    }
    let (a, b) = (scene.times[0], scene.times[scene.times.len() - 1]);
    t.row(vec!["time".into(), format!("{} … {} in {} steps", num(a), num(b), scene.times.len() - 1), "s".into()]);
    t
}

/// Four significant digits, as the plan's notes write times, strokes and ratios.
fn sig(v: f64) -> String {
    crate::figure::report::page::significant(v, 4)
}

/// ` (φ1 = 335.4°)`: the angular driver's angle at `t`, or nothing.
fn angle_note(scene: &LinkageScene, t: f64) -> String {
    scene.mechanism.angular_driver().map_or(String::new(), |(d, body)| {
        format!(" (φ{} = {}°)", run::body_symbol(scene, body), sig(deg(d.law.eval(t).value).rem_euclid(360.0)))
    })
}

/// The plan's note of a guided point's stroke: H, K and the strokes' times.
fn stroke_note(scene: &LinkageScene, g: &run::Guided) -> String {
    let st = &g.stroke;
    let mut s = format!("stroke of {}: H = {} {}", g.measure.symbol, sig(st.h), scene.units.length());
    match &st.cycle {
        Ok(c) => s.push_str(&format!(
            ", K = {}: working stroke {} s from t = {} s{}, return {} s",
            sig(c.k),
            sig(c.working_time),
            sig(st.start.t),
            angle_note(scene, st.start.t),
            sig(c.return_time)
        )),
        Err(why) => s.push_str(&format!("; K not reported: {}", why.text())),
    }
    s
}

/// Whether the motion's last sample repeats its first (the driver turns whole turns).
fn cycle(scene: &LinkageScene) -> Cycle {
    let Some((d, _)) = scene.mechanism.angular_driver() else { return Cycle::Open };
    let (a, b) = (scene.times[0], scene.times[scene.times.len() - 1]);
    let turns = (d.law.eval(b).value - d.law.eval(a).value) / std::f64::consts::TAU;
    if turns.abs() >= 1.0 - 1e-9 && (turns - turns.round()).abs() < 1e-9 { Cycle::Closes } else { Cycle::Open }
}

/// A chosen position's label with the driver's angle (`t = 0.25 s (φ1 = 90°)`).
fn with_angle(scene: &LinkageScene, c: &mut Chosen) {
    if let Some((d, body)) = scene.mechanism.angular_driver() {
        let phi = deg(d.law.eval(c.drive).value);
        c.label.push_str(&format!(
            " (φ{} = {}°)",
            run::body_symbol(scene, body),
            motion::trimmed((phi * 1e4).round() / 1e4)
        ));
    }
}

/// The report of a linkage scene.
pub(super) fn motion_report<'a>(
    scene: &'a LinkageScene,
    file: &str,
    opts: &super::ReportOptions,
    frame: Frame,
) -> Result<(MotionReport<'a>, Csv, serde_json::Value, Vec<String>), Error> {
    let serr = |e: crate::solve::linkage::LinkageError| Error::Solve { file: file.to_string(), source: e.into() };
    let mech = &scene.mechanism;
    let mut assur = AssurSolver::new(mech.clone()).map_err(serr)?;
    let dynamics = scene.dynamics.as_ref().filter(|_| scene.outputs.forces);
    let (states, forces) = match dynamics {
        Some(d) => {
            let (s, f) = assur.run_kinetostatics(&scene.times, d).map_err(serr)?;
            (s, Some(f))
        }
        None => (assur.run(&scene.times).map_err(serr)?, None),
    };
    let mut general = Solver::new(mech.clone()).map_err(serr)?;
    let strokes = run::guided_strokes(scene, &mut general, &states).map_err(serr)?;
    let extremes = dead_extremes(scene, &mut assur, &states, &strokes);
    let mut solved = Solved { states, forces, extra: Vec::new(), extra_forces: Vec::new() };
    let (dead, warnings) = solve_dead(&mut assur, &mut solved, extremes, dynamics);
    let times: Vec<f64> = solved.states.iter().map(|s| s.t).collect();
    let (chosen, plan_idx, base) = choose(scene, opts, &times, &dead)?;
    let plan: Vec<(String, Vec<f64>)> =
        plan_idx.iter().enumerate().map(|(i, &k)| ((i + base).to_string(), solved.states[k].q.clone())).collect();
    let dead_drawn: Vec<(String, Vec<f64>)> = dead
        .iter()
        .enumerate()
        .map(|(i, d)| (crate::solve::linkage::structure::roman(i as u32 + 1), d.q.clone()))
        .collect();
    let sk = sketch(scene);
    let numbered = numbered_point(&sk, &solved.states[0].q);
    let unit = scene.units.length();
    let (dimensions, notes) = plan_marks(scene, &strokes, &dead, &plan_idx, base, &times);
    let structure = Structure::of(mech, Some(&solved.states[0].q));
    let lists = kinematic_lists(scene);
    let kin_label = format!("t = {} s", motion::trimmed(times[plan_idx.first().copied().unwrap_or(0)]));
    // The diagrams of the run, with the chosen positions' points.
    let diagrams = marked_diagrams(scene, &solved, &strokes, &chosen);
    let table = chosen_table(scene, &solved, &chosen);
    // The kinematic diagram's own drafting scale, for the sheets to share.
    let kin_scale = {
        let motion: Vec<&[f64]> = solved.states.iter().map(|s| s.q.as_slice()).collect();
        let q0 = plan.first().map_or(&[][..], |(_, q)| q.as_slice());
        let probe = crate::figure::report::kinematic::KinematicPage {
            sketch: &sk,
            q: q0,
            motion: &motion,
            position: kin_label.clone(),
            unit,
            lists: lists.clone(),
            held: None,
        };
        crate::figure::report::kinematic::scale(&frame.frame, &probe)
    };
    let pages = PositionPages::new(scene, &frame, &solved, &strokes, kin_scale);
    let (drafting, per_position) = (pages.drafting, pages.per_position());
    let motion: Vec<Vec<f64>> = solved.states.iter().map(|s| s.q.clone()).collect();
    let fb = (sk.clone(), structure.clone(), frame.clone());
    let draw_position = pages.drawer(scene, Arc::new(solved), &strokes, fb);
    let summary = serde_json::json!({
        "kind": "linkage",
        "mobility": structure.mobility.formula,
        "mobility_at_placement": structure.mobility.actual,
        "groups": groups_json(&structure, mech),
        "positions": chosen.iter().map(|c| serde_json::json!({"mark": c.mark, "label": c.label, "note": c.note, "t": c.drive})).collect::<Vec<_>>(),
    });
    let r = MotionReport {
        frame,
        title: (
            "Graph-analytical analysis of a planar linkage".into(),
            format!("linkage {} ({} bodies, {} joints)", scene.name, mech.bodies.len(), mech.joints.len()),
            data(scene),
        ),
        sketch: sk,
        mechanism: mech.clone(),
        structure,
        motion,
        plan,
        dead: dead_drawn,
        numbered,
        dimensions,
        notes,
        kinematic: (kin_label, lists),
        drafting: Some(drafting),
        unit,
        chosen,
        position_pages: per_position,
        draw_position,
        diagrams,
    };
    Ok((r, table, summary, warnings))
}

/// The dead positions to solve exactly: the guided points' extremes (the working stroke's
/// start and end), else a measured body angle's; each time and what it is.
fn dead_extremes(
    scene: &LinkageScene,
    assur: &mut AssurSolver,
    states: &[State],
    strokes: &[run::Guided],
) -> Vec<(f64, String)> {
    let mut extremes: Vec<(f64, String)> = Vec::new();
    for g in strokes {
        let sym = &g.measure.symbol;
        let (first, second) = match &g.stroke.cycle {
            Ok(_) => ("start of the working stroke", "end of the working stroke"),
            Err(_) => ("one extreme", "the other extreme"),
        };
        extremes.push((g.stroke.start.t, format!("{first} of {sym}")));
        extremes.push((g.stroke.end.t, format!("{second} of {sym}")));
    }
    if extremes.is_empty()
        && let Some(b) = scene.measures.iter().find_map(|m| match m.target {
            MeasureTarget::Body(Attach::Body(b)) if m.quantities.contains(&Quantity::Angle) => Some(b),
            _ => None,
        })
    {
        assur.resume(&states[0]);
        extremes = body_extremes(assur, states, b, &scene.mechanism.bodies[b].name);
    }
    extremes
}

/// Each dead position solved at its exact time from the sample nearest it, added to
/// `solved`'s extra states; one that cannot be is left out with a warning.
fn solve_dead(
    assur: &mut AssurSolver,
    solved: &mut Solved,
    extremes: Vec<(f64, String)>,
    dynamics: Option<&Dynamics>,
) -> (Vec<Dead>, Vec<String>) {
    let (mut dead, mut warnings) = (Vec::new(), Vec::new());
    for (t, what) in extremes {
        let k = nearest_sample(&solved.states, t);
        match solve_at(assur, &solved.states[k], t, dynamics) {
            Ok((s, f)) => {
                dead.push(Dead { drive: t, what, q: s.q.clone() });
                solved.extra.push(s);
                solved.extra_forces.extend(f);
            }
            Err(e) => warnings.push(format!("the {what} at t = {t} s is left out of the report: {e}")),
        }
    }
    (dead, warnings)
}

/// The chosen positions (marked with their number on the plan, with the driver's angle),
/// the plan's samples (the positions asked for, or twelve evenly spaced) and the plan's
/// first number (0, or 1 for positions asked for).
fn choose(
    scene: &LinkageScene,
    opts: &super::ReportOptions,
    times: &[f64],
    dead: &[Dead],
) -> Result<(Vec<Chosen>, Vec<usize>, usize), Error> {
    let step = (scene.times[1] - scene.times[0]).abs();
    let axis = DriveAxis { name: "time t", unit: " s", step };
    let (mut chosen, plan_idx, base) =
        motion::choose_with_plan(times, axis, cycle(scene), opts.positions.as_ref(), dead)?;
    for c in &mut chosen {
        with_angle(scene, c);
    }
    Ok((chosen, plan_idx, base))
}

/// The point the plan numbers its positions at: the driven body's point farthest from its
/// pivot (a crank's pin).
fn numbered_point(sk: &Sketch, q0: &[f64]) -> Option<Anchor> {
    let dm = sk.driver.as_ref()?;
    let pivot = place(q0, dm.pivot.body, dm.pivot.local);
    let from_pivot = |v: &Vector| (place(q0, Attach::Body(dm.body), *v) - pivot).norm();
    sk.figure
        .bodies
        .get(dm.body)?
        .points
        .iter()
        .max_by(|a, b| from_pivot(&a.1).total_cmp(&from_pivot(&b.1)))
        .map(|(_, v)| Anchor { body: Attach::Body(dm.body), local: *v })
}

/// The plan's dimensions (each guided point's stroke H) and its notes: the strokes, the
/// dead positions, the positions of the plan.
fn plan_marks(
    scene: &LinkageScene,
    strokes: &[run::Guided],
    dead: &[Dead],
    plan_idx: &[usize],
    base: usize,
    times: &[f64],
) -> (Vec<PlanDimension>, Vec<String>) {
    let unit = scene.units.length();
    let mut dimensions = Vec::new();
    let mut notes = Vec::new();
    for g in strokes {
        let st = &g.stroke;
        dimensions.push(PlanDimension::Stroke {
            from: st.start.at,
            to: st.end.at,
            text: format!("H = {} {unit}", sig(st.h)),
        });
        notes.push(stroke_note(scene, g));
    }
    for (i, d) in dead.iter().enumerate() {
        notes.push(format!(
            "{}: {} at t = {} s{}",
            crate::solve::linkage::structure::roman(i as u32 + 1),
            d.what,
            sig(d.drive),
            angle_note(scene, d.drive)
        ));
    }
    notes.push(format!(
        "positions of the plan: {}",
        plan_idx
            .iter()
            .enumerate()
            .map(|(i, &k)| format!("{} (t = {} s)", i + base, sig(times[k])))
            .collect::<Vec<_>>()
            .join(", ")
    ));
    (dimensions, notes)
}

/// A chosen position's pages as `run --sheets` lays them out, at one drafting scale with
/// the kinematic diagram, and (with forces) a page of the groups' free-body figures.
struct PositionPages {
    sheets: LinkageSheets,
    /// The mechanism's scale on the kinematic diagram and the position pages.
    drafting: f64,
    /// A free-body page after each position's sheets.
    free_bodies: bool,
    /// Each table row's series over the run (a position's value is read against them).
    series: Vec<Vec<f64>>,
}

impl PositionPages {
    /// The pages of `solved`'s positions: the sheets at the coarser of their own scale and
    /// the kinematic diagram's `kin_scale`, the table's most rows over the run.
    fn new(
        scene: &LinkageScene,
        frame: &Frame,
        solved: &Solved,
        strokes: &[run::Guided],
        kin_scale: f64,
    ) -> PositionPages {
        let figure = run::figure_of(scene);
        let show = run::show_of(scene);
        // The run's plots (each table row's series, to read a position's value against)
        // and the table's most rows over the run, as `run --sheets` lays its sheets out.
        let all_plots = run::plots(scene, &solved.states, strokes);
        let rows = (0..solved.states.len())
            .map(|k| {
                let f = scene.dynamics.as_ref().zip(solved.forces.as_ref().and_then(|f| f.get(k)));
                row_counts(&run::sheet_table(scene, &all_plots, k, f.map(|(d, f)| (d, &solved.states[k], f))))
            })
            .fold((0, 0), |(a, b), (c, d)| (a.max(c), b.max(d)));
        let free_bodies = show.forces && solved.forces.is_some() && scene.dynamics.is_some();
        let new_sheets = |held: Option<f64>| {
            let (paper, forces) = (frame.frame.paper, solved.forces.is_some());
            let (name, mech) = (&scene.name, &scene.mechanism);
            LinkageSheets::new(paper, name, mech, &figure, &solved.states, show.clone(), forces, rows, held)
        };
        // One drafting scale for the mechanism: the kinematic diagram's and the position
        // pages' (the same drawing), the coarser of the two pages' own.
        let sheets = new_sheets(None);
        let drafting = kin_scale.max(sheets.k_l());
        let sheets = if drafting > sheets.k_l() { new_sheets(Some(drafting)) } else { sheets };
        PositionPages { sheets, drafting, free_bodies, series: all_plots.into_iter().map(|p| p.values).collect() }
    }

    /// Pages per chosen position.
    fn per_position(&self) -> usize {
        self.sheets.per_position() + usize::from(self.free_bodies)
    }

    /// What draws a chosen position's pages, given its first page's number and the total:
    /// its sheets, with the table's values read against the run's series, then its
    /// free-body page (`fb`: the sketch, the structure and the frame it is drawn with).
    #[allow(clippy::type_complexity)]
    fn drawer<'a>(
        self,
        scene: &'a LinkageScene,
        solved: Arc<Solved>,
        strokes: &[run::Guided],
        fb: (Sketch, Structure, Frame),
    ) -> Box<dyn Fn(&Chosen, usize, usize) -> Result<Vec<crate::draw::Drawing>, Error> + Sync + 'a> {
        let PositionPages { sheets, series, free_bodies, .. } = self;
        let unit = scene.units.length();
        let strokes_owned: Vec<(String, Vector, crate::solve::stroke::Stroke)> =
            strokes.iter().map(|g| (g.measure.label.clone(), g.guide, g.stroke.clone())).collect();
        Box::new(move |c: &Chosen, first: usize, total: usize| -> Result<Vec<crate::draw::Drawing>, Error> {
            let state = solved.state(c.at);
            let force = solved.force(c.at);
            let strokes: Vec<run::Guided> = strokes_owned
                .iter()
                .filter_map(|(label, guide, stroke)| {
                    let measure = scene.measures.iter().find(|m| &m.label == label)?;
                    Some(run::Guided { measure, guide: *guide, stroke: stroke.clone() })
                })
                .collect();
            // The table's values: the position's, after the run's (so that a value is read
            // against its series' largest, as `run --sheets` reads it).
            let plots: Vec<run::Plot> = scene
                .measures
                .iter()
                .flat_map(|m| m.quantities.iter().map(move |&q| (m, q)))
                .zip(series.iter())
                .map(|((m, q), whole)| {
                    let mut p = run::plot_of(scene, m, q, std::slice::from_ref(state), &strokes);
                    p.values.splice(0..0, whole.iter().copied());
                    p
                })
                .collect();
            let force = scene.dynamics.as_ref().zip(force);
            let table = run::sheet_table(scene, &plots, solved.states.len(), force.map(|(d, f)| (d, state, f)));
            let pages = sheets.pages(&scene.mechanism, state, force, &table, (first, total));
            let mut out: Vec<crate::draw::Drawing> = pages.into_iter().map(|(_, drawing)| drawing).collect();
            if let (true, Some((dynamics, f))) = (free_bodies, force) {
                let (sketch, structure, frame) = &fb;
                let p = FreeBodyPage {
                    sketch,
                    mechanism: &scene.mechanism,
                    structure,
                    q: &state.q,
                    loads: freebody::linkage_loads(&scene.mechanism, structure, dynamics, state, f),
                    position: c.label.clone(),
                    unit,
                    couple_factor: 1.0 / dynamics.length_unit_m,
                };
                let part = format!("5  Position {}: free-body figures of the groups", c.mark);
                out.push(freebody::page(&frame.frame, &frame.title(&part, first + out.len(), total), &p));
            }
            Ok(out)
        })
    }
}

/// The kinematic diagram's lists: links, joints, drivers, loads.
fn kinematic_lists(scene: &LinkageScene) -> Vec<String> {
    let mech = &scene.mechanism;
    let mut out = vec!["0 the frame".to_string()];
    for (i, b) in mech.bodies.iter().enumerate() {
        let pts: Vec<&str> = b.points.iter().map(|(n, _)| n.as_str()).collect();
        out.push(format!("{} {} ({})", i + 1, b.name, pts.join(", ")));
    }
    let number = |a: Attach| match a {
        Attach::Ground => 0,
        Attach::Body(b) => b + 1,
    };
    for j in &mech.joints {
        out.push(match j.kind {
            JointKind::Revolute { a, b } => format!("{}: revolute {}–{}", j.name, number(a.body), number(b.body)),
            JointKind::Prismatic { point, q1, .. } => {
                format!("{}: prismatic, {} on a guide of {}", j.name, number(point.body), number(q1.body))
            }
        });
    }
    for d in &mech.drivers {
        out.push(format!("driver {}: {}", d.name, d.law.source()));
    }
    for l in scene.dynamics.iter().flat_map(|d| d.loads.iter()) {
        let when = l
            .window
            .map_or(String::new(), |w| format!(" for t ∈ [{}, {}] s", sheet::number(w.from), sheet::number(w.to)));
        out.push(format!("load {}{when} (arrow not to scale)", l.name));
    }
    out
}

/// The run's diagrams (each measured quantity, each reaction, each driver), with the
/// chosen positions placed on them.
fn marked_diagrams(
    scene: &LinkageScene,
    solved: &Solved,
    strokes: &[run::Guided],
    chosen: &[Chosen],
) -> Vec<MarkedDiagram> {
    let series = |states: &[State], forces: Option<&[Forces]>| -> Vec<Diagram> {
        let (x_label, x) = run::abscissa(scene, states);
        let mut out: Vec<Diagram> = scene
            .measures
            .iter()
            .flat_map(|m| m.quantities.iter().map(move |&q| (m, q)))
            .map(|(m, q)| {
                let p = run::plot_of(scene, m, q, states, strokes);
                Diagram {
                    title: p.title,
                    x_label: x_label.clone(),
                    y_label: p.y_label,
                    series: vec![Series { label: String::new(), x: x.clone(), y: p.values }],
                }
            })
            .collect();
        if let Some(f) = forces {
            out.extend(run::force_diagrams(scene, f, &x_label, &x).into_iter().map(|(_, d)| d));
        }
        out
    };
    let all = series(&solved.states, solved.forces.as_deref());
    let picked: Vec<State> = chosen.iter().map(|c| solved.state(c.at).clone()).collect();
    let picked_forces: Option<Vec<Forces>> =
        solved.forces.as_ref().map(|_| chosen.iter().filter_map(|c| solved.force(c.at).cloned()).collect());
    let at_chosen = series(&picked, picked_forces.as_deref());
    all.iter()
        .zip(&at_chosen)
        .map(|(d, c)| {
            let marks = Marks::default();
            let points = motion::marks(chosen, |ch| {
                let i = chosen.iter().position(|x| x == ch)?;
                let s = c.series.first()?;
                let (x, y) = (*s.x.get(i)?, *s.y.get(i)?);
                (x.is_finite() && y.is_finite()).then(|| plot::place(d, &marks, x, y))
            });
            MarkedDiagram { drawing: plot::diagram(d), marks: points }
        })
        .collect()
}

/// The chosen positions' values: the run's CSV columns, a row per position.
fn chosen_table(scene: &LinkageScene, solved: &Solved, chosen: &[Chosen]) -> Csv {
    let picked: Vec<State> = chosen.iter().map(|c| solved.state(c.at).clone()).collect();
    let cols = run::columns(scene, &picked);
    let force_cols = solved
        .forces
        .as_ref()
        .map(|_| {
            let f: Vec<Forces> = chosen.iter().filter_map(|c| solved.force(c.at).cloned()).collect();
            run::force_columns(scene, &f)
        })
        .unwrap_or_default();
    let header =
        ["position", "t"].into_iter().map(String::from).chain(cols.iter().chain(&force_cols).map(|c| c.name.clone()));
    let mut csv = Csv::new(header);
    for (i, c) in chosen.iter().enumerate() {
        let row = std::iter::once(c.mark.clone())
            .chain(std::iter::once(crate::report::number(picked[i].t)))
            .chain(cols.iter().chain(&force_cols).map(|col| crate::report::number(col.values[i])));
        csv.row_text(row);
    }
    csv
}

/// Whether the scene's joints repeat equations (a redundant, passive link: the formula's
/// mobility is not the number of drivers while the joints at the scene's placement leave
/// that many; only [`crate::scene::linkage::Redundancy::Accepted`] lets such a scene load).
pub(super) fn is_redundant(scene: &LinkageScene) -> bool {
    scene.mechanism.drivers.len() as i64 != Structure::of(&scene.mechanism, None).mobility.formula
}

/// The placement written in the scene (x, y, φ per body): what a redundant scene's pages
/// draw, the solver not having assembled it.
fn placement(scene: &LinkageScene) -> Vec<f64> {
    scene.mechanism.bodies.iter().flat_map(|b| [b.at.x, b.at.y, b.angle]).collect()
}

/// The report of a scene with a redundant link ([`is_redundant`]): the solver needs
/// independent joint equations, so there is no motion to analyse; the report is the title
/// page, the structural analysis (the formula's mobility against the rank's, and why the
/// report stops there) and the kinematic diagram, at the scene's placement.
pub(super) fn structure_report<'a>(
    scene: &'a LinkageScene,
    file: &str,
    opts: &super::ReportOptions,
    frame: Frame,
) -> Result<super::Gathered<'a>, Error> {
    let mech = &scene.mechanism;
    let q0 = Arc::new(placement(scene));
    let structure = Arc::new(Structure::of(mech, Some(&q0)));
    let m = structure.mobility;
    if opts.positions.is_some() {
        return Err(Error::Option {
            option: "--positions".into(),
            message: format!(
                "{file} has a redundant link ({}, but the joints leave {}): its motion is not solved, so there are no \
                 positions to choose; its report is the structural analysis (leave out --positions)",
                m.worked(),
                m.actual.unwrap_or(m.formula)
            ),
        });
    }
    let sk = Arc::new(sketch(scene));
    let unit = scene.units.length();
    let title = super::title_part(
        frame.clone(),
        "Structural analysis of a planar linkage with a redundant link".into(),
        format!("linkage {} ({} bodies, {} joints)", scene.name, mech.bodies.len(), mech.joints.len()),
        data(scene),
    );
    let structure_part = {
        let (f, sk, st, q0) = (frame.clone(), sk.clone(), structure.clone(), q0.clone());
        super::Part {
            title: "Structural analysis".into(),
            stem: "structure".into(),
            pages: 1,
            draw: Box::new(move |n| {
                let motion = [q0.as_slice()];
                let p = crate::figure::report::structure::StructurePage {
                    sketch: &sk,
                    mechanism: mech,
                    structure: &st,
                    q: &q0,
                    motion: &motion,
                    unit,
                };
                let title = f.title("2  Structural analysis", n.first, n.total);
                Ok(vec![crate::figure::report::structure::page(&f.frame, &title, &p)])
            }),
        }
    };
    let kinematic_part = {
        let (f, sk, q0) = (frame.clone(), sk.clone(), q0.clone());
        let lists = kinematic_lists(scene);
        super::Part {
            title: "Kinematic diagram".into(),
            stem: "kinematic".into(),
            pages: 1,
            draw: Box::new(move |n| {
                let motion = [q0.as_slice()];
                let p = crate::figure::report::kinematic::KinematicPage {
                    sketch: &sk,
                    q: &q0,
                    motion: &motion,
                    position: "the scene's placement".into(),
                    unit,
                    lists: lists.clone(),
                    held: None,
                };
                let title = f.title("3  Kinematic diagram", n.first, n.total);
                Ok(vec![crate::figure::report::kinematic::page(&f.frame, &title, &p).0])
            }),
        }
    };
    let summary = serde_json::json!({
        "kind": "linkage",
        "mobility": m.formula,
        "mobility_at_placement": m.actual,
        "redundant": m.redundant(),
        "groups": groups_json(&structure, mech),
        "positions": [],
    });
    let warnings = vec![format!(
        "{file} has a redundant link ({}, the joints leave {}): the report is its structure; the solver needs \
         independent joints for the motion's pages",
        m.worked(),
        m.actual.unwrap_or(m.formula)
    )];
    Ok(super::Gathered { parts: vec![title, structure_part, kinematic_part], table: None, summary, warnings })
}

/// The summary's groups: each group's kind, bodies, class and order.
fn groups_json(structure: &Structure, mech: &crate::solve::linkage::Mechanism) -> Vec<serde_json::Value> {
    structure
        .groups
        .iter()
        .map(|g| {
            serde_json::json!({
                "kind": g.group.kind_name(),
                "bodies": g.group.bodies.iter().map(|&b| mech.bodies[b].name.clone()).collect::<Vec<_>>(),
                "class": g.class,
                "order": g.order,
            })
        })
        .collect()
}
