//! The four-bar pipeline: solve the motion, draw every position (mechanism and the
//! polygons the scene's `outputs` ask for), and write the DXF with one layer per position,
//! one SVG frame per position, the HTML viewer, the diagrams, the CSV and the JSON summary.
//! The output formats are documented in docs/fourbar-output.md.

use crate::par::prelude::*;
use std::collections::BTreeMap;

use serde::Serialize;
use serde_json::{Value, json};

use super::fourbar_teaching as teaching;
use super::positions::DriveAxis;
use super::products::{self, Extras, PositionsSource, Products};
use super::solve_err;
use crate::Error;
use std::sync::Arc;

use crate::figure::fourbar::sheet::FourbarSheets;
use crate::figure::fourbar::{Layout, ModelUnits, Show, angle_text};
use crate::figure::shared::animation::{Animation, Drive, DriveState};
use crate::figure::shared::labels::Label;
use crate::figure::shared::plot::{self, Diagram, Series};
use crate::figure::shared::sheet::{self, Paper};
use crate::geom::{self, Point, Side, Vector, deg};
use crate::report::{self, Csv};
use crate::scene::Units;
use crate::scene::fourbar::FourbarScene;
use crate::solve::fourbar::Forces;
use crate::solve::fourbar::transmission::{gamma, gamma_min};
use crate::solve::fourbar::{
    FourbarError, Geometry, Motion, MotionSpec, Position, kinematics_eps, kinetostatics, position, solve_motion,
};

/// A jump of more than this many sweep steps between consecutive solved positions is a
/// gap (skipped angles): curves break there.
const GAP_STEPS: f64 = 1.5;

pub(super) fn products(scene: &FourbarScene, file: &str, opts: &super::RunOptions) -> Result<Products, Error> {
    let (paper, chosen, picture_only) = (opts.sheets, opts.positions.as_ref(), opts.picture_only);
    let spec = &scene.spec;
    let motion = solve_motion(spec).map_err(|e| solve_err(file)(e.into()))?;
    // The positions drawn (`--positions`: crank angles φ1 in degrees).
    let angles: Vec<f64> = motion.positions.iter().map(|p| deg(p.phi1)).collect();
    let axis = DriveAxis { name: "crank angle φ1", unit: "°", step: spec.sweep.step_deg.abs() };
    let drawn = super::drawn_positions(chosen, &angles, axis)?;
    let units = match scene.units {
        Units::Si => ModelUnits::SI,
        Units::Mm => ModelUnits::MM,
    };
    let show = Show {
        velocity: spec.outputs.velocity,
        acceleration: spec.outputs.acceleration,
        forces: spec.outputs.forces && !motion.forces.is_empty(),
        scales: super::scale_choice(scene.frame_scales),
    };
    let forces = if show.forces { Some(motion.forces.as_slice()) } else { None };
    let external = spec.dynamics.as_ref().map_or(&[][..], |d| d.forces.as_slice());
    let link_loads = spec.dynamics.as_ref().map_or(&[][..], |d| d.loads.as_slice());
    let mut layout = Layout::new(&spec.geometry, &motion.positions, forces, show, units)
        .with_drive(spec.omega1, external)
        .with_link_loads(link_loads);
    layout.frame.hold(&opts.held_scales);
    let mut warnings = motion.warnings();
    if motion.positions.is_empty() {
        warnings.push("no crank angle of the sweep could be assembled: nothing to draw".to_string());
    }
    // Issue 14 item 10: γ_min, Joukowski's lever, the instantaneous centres.
    let gamma_min = gamma_min(&motion.positions);
    if let Some(m) = &gamma_min {
        warnings.extend(teaching::gamma_warning(m));
    }
    let name = &scene.name;
    let step = spec.sweep.step_deg;
    let geom = spec.geometry;
    let mut curve = runs(&motion.positions, step, |p| p.m);
    close_full_turn(&mut curve, &motion.positions, step);
    let base = layout.base(&geom, &curve);
    let layout = layout.with_backdrop(&base);
    let names = position_names(&motion.positions, spec.sweep.from_deg, step);
    let labels = motion.positions.iter().map(|p| format!("φ1 = {}°", angle_text(deg(p.phi1)))).collect();
    let extras = if picture_only {
        Extras::default()
    } else {
        let drawn_as = Drawn { curve: &curve, names: &names, drawn: &drawn, paper };
        let (extras, study_warnings) = extras(scene, &motion, &layout, gamma_min, drawn_as, units)?;
        warnings.extend(study_warnings);
        extras
    };
    let title = format!("{name}: four-bar, {} positions", motion.positions.len());
    let chosen = chosen.is_some().then_some(drawn);
    let (animation, frame_scales) = animation(spec, motion, layout, base, title, names, labels, chosen);
    Ok(extras.with_motion(
        name.clone(),
        super::mm_per_unit(scene.units),
        animation,
        PositionsSource { field: "phi1_deg.step", advice: "use a larger step" },
        warnings,
        frame_scales,
    ))
}

/// Where a run draws its positions: the coupler curve's runs, every position's name, the
/// positions drawn, and the paper of the printed sheets (`--sheets`).
#[derive(Clone, Copy)]
struct Drawn<'a> {
    curve: &'a [Vec<Point>],
    names: &'a [String],
    drawn: &'a [usize],
    paper: Option<Paper>,
}

/// A run's files besides its picture: the table, the summary and the report, Joukowski's
/// levers, the centres' and Joukowski's sheets, the diagrams, the printed pages and the
/// tolerance study; with the study's warnings.
fn extras(
    scene: &FourbarScene,
    motion: &Motion,
    layout: &Layout,
    gamma_min: Option<crate::solve::fourbar::transmission::GammaMin>,
    at: Drawn<'_>,
    units: ModelUnits,
) -> Result<(Extras, Vec<String>), Error> {
    let spec = &scene.spec;
    let qs = reported(&spec.outputs, layout.show.forces);
    // The table, the summary with the report, and Joukowski's levers side by side.
    let (mut csv, ((summary, mut report), levers)) = crate::par::join(
        || table(motion, &qs, layout.show.forces),
        || {
            crate::par::join(
                || (summary(scene, motion, layout, &qs), report_text(scene, motion, layout)),
                || if layout.show.forces { teaching::levers(spec, &motion.positions) } else { Vec::new() },
            )
        },
    );
    let mut summary = summary?;
    teaching::add_to_tables(&mut csv, &mut summary, &levers, gamma_min);
    if let Some(m) = &gamma_min {
        report.push_str(&format!("{}\n", teaching::gamma_min_text(m)));
    }
    let mut sheets = Vec::new();
    if scene.centres {
        sheets.extend(teaching::centres(&spec.geometry, &motion.positions, units));
    }
    if layout.show.forces {
        sheets.extend(teaching::joukowski(spec, &motion.positions, &motion.forces, &levers, units));
    }
    let pages = match at.paper {
        Some(paper) => sheet_pages(paper, scene, motion, at.curve, &qs, layout.show, units, at.names, at.drawn),
        None => Vec::new(),
    };
    let mut extras = Extras {
        sheets,
        pages,
        diagrams: drawn_diagrams(motion, spec.sweep.step_deg, &qs, layout.show.forces, units, gamma_min),
        tables: vec![products::Table { suffix: String::new(), csv }],
        summary,
        report,
    };
    let warnings = match super::tolerance::fourbar(scene, &motion.positions, None) {
        Some(study) => study.add_to(&mut extras),
        None => Vec::new(),
    };
    Ok((extras, warnings))
}

/// The diagrams drawn: γ's with its least value marked, the others plain.
fn drawn_diagrams(
    motion: &Motion,
    step: f64,
    qs: &[Quantity],
    forces: bool,
    units: ModelUnits,
    gamma_min: Option<crate::solve::fourbar::transmission::GammaMin>,
) -> Vec<products::Diagram> {
    diagrams(motion, step, qs, forces, units)
        .into_par_iter()
        .map(|(stem, d)| match stem.as_str() {
            "gamma_deg" => {
                let marks = teaching::gamma_marks(gamma_min);
                products::Diagram {
                    stem: "gamma".into(),
                    drawing: plot::diagram_marked(&d, &marks),
                    track: plot::track(&d, &marks),
                }
            }
            _ => products::Diagram { stem, drawing: plot::diagram(&d), track: plot::track(&d, &Default::default()) },
        })
        .collect()
}

/// The run's animation (only the `chosen` positions when some are), with its drive (the
/// position at any crank angle between the sweep's, on the side each position's B is),
/// and the scales each drawn frame is drawn at (in the animation's order).
#[allow(clippy::too_many_arguments)]
fn animation(
    spec: &MotionSpec,
    motion: Motion,
    layout: Layout,
    base: crate::draw::Drawing,
    title: String,
    names: Vec<String>,
    labels: Vec<String>,
    chosen: Option<Vec<usize>>,
) -> (Animation, Vec<crate::figure::shared::panels::FrameScales>) {
    let (geom, show) = (spec.geometry, layout.show);
    let window = layout.frame.window;
    let Motion { positions, forces, .. } = motion;
    let values = positions.iter().map(|p| deg(p.phi1)).collect();
    let sides: Vec<Side> = positions.iter().map(|p| p.side(&geom).unwrap_or(geom.branch)).collect();
    let (layout, sides) = (Arc::new(layout), Arc::new(sides));
    let drive = Drive {
        values,
        solve: {
            let (spec, sides) = (spec.clone(), sides.clone());
            Box::new(move |k, s_deg| {
                let (pos, _) = solve_at(&spec, sides.get(k).copied().unwrap_or(spec.geometry.branch), s_deg)?;
                Ok(drive_state(&spec.geometry, &pos))
            })
        },
        draw: {
            let (spec, layout) = (spec.clone(), layout.clone());
            Box::new(move |k, s_deg| {
                let (pos, force) = solve_at(&spec, sides.get(k).copied().unwrap_or(spec.geometry.branch), s_deg)?;
                Ok(layout.moving(k, &spec.geometry, &pos, force.as_ref().filter(|_| show.forces)))
            })
        },
    };
    let frame_scales = match &chosen {
        Some(drawn) => drawn.clone(),
        None => (0..positions.len()).collect(),
    }
    .into_iter()
    .map(|k| layout.frame.scales_at(k))
    .collect();
    let pose = move |k: usize| layout.moving(k, &geom, &positions[k], forces.get(k).filter(|_| show.forces));
    let animation = Animation::new(title, base, Some(window), names, labels, pose).with_drive(drive);
    let animation = match chosen {
        Some(drawn) => animation.keep(drawn),
        None => animation,
    };
    (animation, frame_scales)
}

/// The position at crank angle `phi1_deg` with B on `side`, with its kinematics and forces
/// as the scene asks for them (as `solve_motion` computes each position of the sweep).
pub(super) fn solve_at(spec: &MotionSpec, side: Side, phi1_deg: f64) -> Result<(Position, Option<Forces>), String> {
    let geom = &spec.geometry;
    let at = |e: FourbarError| format!("at φ1 = {}°: {e}", angle_text(phi1_deg));
    let mut pos = position(geom, geom::rad(phi1_deg), side).map_err(at)?;
    let mut force = None;
    if spec.outputs.kinematics() {
        let kin = kinematics_eps(geom, &pos, spec.omega1, spec.epsilon1).map_err(at)?;
        if let Some(d) = spec.dynamics.as_ref().filter(|_| spec.outputs.forces) {
            force = Some(kinetostatics::forces(geom, &pos, &kin, d).map_err(at)?);
        }
        pos.kin = Some(kin);
    }
    Ok((pos, force))
}

/// The named points of a position (as the mechanism's picture names them) and its loop
/// residual: the largest miss of |O1A| = l1, |AB| = l_ab, |CB| = l_bc, relative to the
/// longest link.
fn drive_state(geom: &Geometry, pos: &Position) -> DriveState {
    let miss = [
        ((pos.a - geom.o1).norm(), geom.l1),
        ((pos.b - pos.a).norm(), geom.l_ab),
        ((pos.b - geom.c).norm(), geom.l_bc),
    ];
    let size = geom.l1.max(geom.l_ab).max(geom.l_bc);
    DriveState {
        label: format!("φ1 = {}°", angle_text(deg(pos.phi1))),
        points: vec![
            ("O1".into(), geom.o1),
            ("A".into(), pos.a),
            ("B".into(), pos.b),
            ("M".into(), pos.m),
            ("C".into(), geom.c),
        ],
        residual: miss.iter().map(|(d, l)| (d - l).abs()).fold(0.0, f64::max) / size,
    }
}

/// Layer (and frame file) names: `POS_ddd` with the crank angle in whole degrees when every
/// solved angle is a distinct whole degree in 0…999, else `POS_kkk` with the index of the
/// angle in the sweep (3 digits at least).
fn position_names(positions: &[Position], from_deg: f64, step_deg: f64) -> Vec<String> {
    let degs: Vec<f64> = positions.iter().map(|p| deg(p.phi1)).collect();
    let whole = degs.iter().all(|d| (d - d.round()).abs() < 1e-6 && d.round() >= 0.0 && d.round() <= 999.0);
    let mut seen = std::collections::HashSet::new();
    if whole && degs.iter().all(|d| seen.insert(d.round() as i64)) {
        return degs.iter().map(|d| format!("POS_{:03}", d.round() as i64)).collect();
    }
    degs.iter().map(|d| format!("POS_{:03}", ((d - from_deg) / step_deg).round().max(0.0) as i64)).collect()
}

/// Runs of consecutive positions (no skipped angle between them), mapped by `f`.
pub(super) fn runs<T>(positions: &[Position], step_deg: f64, f: impl Fn(&Position) -> T) -> Vec<Vec<T>> {
    let mut out: Vec<Vec<T>> = Vec::new();
    let mut prev: Option<f64> = None;
    for p in positions {
        let d = deg(p.phi1);
        if prev.is_none_or(|q| d - q > GAP_STEPS * step_deg) {
            out.push(Vec::new());
        }
        if let Some(run) = out.last_mut() {
            run.push(f(p));
        }
        prev = Some(d);
    }
    out
}

/// When the solved positions cover a whole turn without a gap (the last angle one step
/// short of the first plus 360°), the coupler curve closes: its last run joins its first.
pub(super) fn close_full_turn(curve: &mut [Vec<Point>], positions: &[Position], step_deg: f64) {
    let (Some(first), Some(last)) = (positions.first(), positions.last()) else { return };
    let wrap = deg(first.phi1) + 360.0 - deg(last.phi1);
    if (wrap - step_deg).abs() > 1e-6 * step_deg.max(1.0) || wrap > GAP_STEPS * step_deg {
        return;
    }
    if let Some(start) = curve.first().and_then(|r| r.first()).copied()
        && let Some(end_run) = curve.last_mut()
    {
        end_run.push(start);
    }
}

/// What a quantity belongs to: it is reported when the scene's outputs ask for it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Group {
    Position,
    Velocity,
    Acceleration,
    Forces,
}

/// A quantity's unit, written for the scene's length unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Unit {
    Degree,
    Length,
    RadPerS,
    RadPerS2,
    Speed,
    Acceleration,
    Force,
    Moment,
}

impl Unit {
    fn text(self, units: ModelUnits) -> String {
        let len = units.length;
        match self {
            Unit::Degree => "°".into(),
            Unit::Length => len.into(),
            Unit::RadPerS => "rad/s".into(),
            Unit::RadPerS2 => "rad/s²".into(),
            Unit::Speed => format!("{len}/s"),
            Unit::Acceleration => format!("{len}/s²"),
            Unit::Force => "N".into(),
            Unit::Moment if len == "m" => "N·m".into(),
            Unit::Moment => format!("N·{len}"),
        }
    }
}

/// How a quantity is read off a position (and its forces, when computed).
#[derive(Clone, Copy)]
enum Get {
    Scalar(fn(&Position, Option<&Forces>) -> f64),
    Pair(fn(&Position, Option<&Forces>) -> Vector),
}

/// One per-position quantity, named once: its CSV columns (`name`, or `name_x`, `name_y`
/// and with `magnitude` `name_mag`), its key in the JSON position records (a pair as
/// `[x, y]`), and its diagram (`diagrams/<scene>/<name>.svg`; a pair plotted as its
/// magnitude).
pub(super) struct Quantity {
    name: &'static str,
    group: Group,
    unit: Unit,
    get: Get,
    /// CSV (and JSON) also carry the magnitude `<name>_mag`.
    magnitude: bool,
    /// In the JSON position records (the CSV carries every quantity).
    json: bool,
    /// (title, symbol) of its diagram, if it has one.
    diagram: Option<(&'static str, &'static str)>,
}

fn kin_of(p: &Position) -> crate::solve::fourbar::Kinematics {
    // Quantities of a group are read only when the motion has that group.
    p.kin.unwrap_or(crate::solve::fourbar::Kinematics {
        omega1: f64::NAN,
        eps1: f64::NAN,
        omega2: f64::NAN,
        omega3: f64::NAN,
        eps2: f64::NAN,
        eps3: f64::NAN,
        v_a: Vector::repeat(f64::NAN),
        v_b: Vector::repeat(f64::NAN),
        v_m: Vector::repeat(f64::NAN),
        v_ba: Vector::repeat(f64::NAN),
        a_a: Vector::repeat(f64::NAN),
        a_b: Vector::repeat(f64::NAN),
        a_m: Vector::repeat(f64::NAN),
        a_ba_n: Vector::repeat(f64::NAN),
        a_ba_t: Vector::repeat(f64::NAN),
        a_bc_n: Vector::repeat(f64::NAN),
        a_bc_t: Vector::repeat(f64::NAN),
        a_g1: Vector::repeat(f64::NAN),
        a_g21: Vector::repeat(f64::NAN),
        a_g22: Vector::repeat(f64::NAN),
        a_g3: Vector::repeat(f64::NAN),
    })
}

/// Every quantity of the four-bar, in CSV order.
fn quantities() -> Vec<Quantity> {
    use Group as G;
    use Unit as U;
    let q = |name, group, unit, get, magnitude, json, diagram| Quantity {
        name,
        group,
        unit,
        get,
        magnitude,
        json,
        diagram,
    };
    macro_rules! kin_pair {
        ($f:ident) => {
            Get::Pair(|p, _| kin_of(p).$f)
        };
    }
    macro_rules! kin_scalar {
        ($f:ident) => {
            Get::Scalar(|p, _| kin_of(p).$f)
        };
    }
    macro_rules! force_pair {
        ($f:ident) => {
            Get::Pair(|_, f| f.map_or(Vector::repeat(f64::NAN), |f| f.$f))
        };
    }
    macro_rules! force_scalar {
        ($f:ident) => {
            Get::Scalar(|_, f| f.map_or(f64::NAN, |f| f.$f))
        };
    }
    vec![
        q("phi1_deg", G::Position, U::Degree, Get::Scalar(|p, _| deg(p.phi1)), false, true, None),
        q("A", G::Position, U::Length, Get::Pair(|p, _| p.a.coords), false, true, None),
        q("B", G::Position, U::Length, Get::Pair(|p, _| p.b.coords), false, true, None),
        q("M", G::Position, U::Length, Get::Pair(|p, _| p.m.coords), false, true, None),
        q(
            "phi2_deg",
            G::Position,
            U::Degree,
            Get::Scalar(|p, _| deg(p.phi2())),
            false,
            true,
            Some(("Coupler angle φ2", "φ2")),
        ),
        q(
            "phi3_deg",
            G::Position,
            U::Degree,
            Get::Scalar(|p, _| deg(p.phi3())),
            false,
            true,
            Some(("Rocker angle φ3", "φ3")),
        ),
        q("transmission_deg", G::Position, U::Degree, Get::Scalar(|p, _| deg(p.transmission())), false, true, None),
        q(
            "gamma_deg",
            G::Position,
            U::Degree,
            Get::Scalar(|p, _| deg(gamma(p))),
            false,
            true,
            Some(("Transmission angle γ (acute angle between AB and BC)", "γ")),
        ),
        q(
            "omega2",
            G::Velocity,
            U::RadPerS,
            kin_scalar!(omega2),
            false,
            true,
            Some(("Angular velocity of the coupler ω2", "ω2")),
        ),
        q(
            "omega3",
            G::Velocity,
            U::RadPerS,
            kin_scalar!(omega3),
            false,
            true,
            Some(("Angular velocity of the rocker ω3", "ω3")),
        ),
        q("vA", G::Velocity, U::Speed, kin_pair!(v_a), true, true, None),
        q("vB", G::Velocity, U::Speed, kin_pair!(v_b), true, true, None),
        q("vM", G::Velocity, U::Speed, kin_pair!(v_m), true, true, Some(("Speed of the coupler point M", "vM"))),
        q("vBA", G::Velocity, U::Speed, kin_pair!(v_ba), true, true, None),
        q(
            "eps2",
            G::Acceleration,
            U::RadPerS2,
            kin_scalar!(eps2),
            false,
            true,
            Some(("Angular acceleration of the coupler ε2", "ε2")),
        ),
        q(
            "eps3",
            G::Acceleration,
            U::RadPerS2,
            kin_scalar!(eps3),
            false,
            true,
            Some(("Angular acceleration of the rocker ε3", "ε3")),
        ),
        q("aA", G::Acceleration, U::Acceleration, kin_pair!(a_a), true, true, None),
        q("aB", G::Acceleration, U::Acceleration, kin_pair!(a_b), true, true, None),
        q(
            "aM",
            G::Acceleration,
            U::Acceleration,
            kin_pair!(a_m),
            true,
            true,
            Some(("Acceleration of the coupler point M", "aM")),
        ),
        q("aBA_n", G::Acceleration, U::Acceleration, kin_pair!(a_ba_n), false, false, None),
        q("aBA_t", G::Acceleration, U::Acceleration, kin_pair!(a_ba_t), false, false, None),
        q("aBC_n", G::Acceleration, U::Acceleration, kin_pair!(a_bc_n), false, false, None),
        q("aBC_t", G::Acceleration, U::Acceleration, kin_pair!(a_bc_t), false, false, None),
        q("aG1", G::Acceleration, U::Acceleration, kin_pair!(a_g1), false, false, None),
        q("aG21", G::Acceleration, U::Acceleration, kin_pair!(a_g21), false, false, None),
        q("aG22", G::Acceleration, U::Acceleration, kin_pair!(a_g22), false, false, None),
        q("aG3", G::Acceleration, U::Acceleration, kin_pair!(a_g3), false, false, None),
        q("R_A", G::Forces, U::Force, force_pair!(r_a), true, true, Some(("Reaction in A (link 1 on link 2)", "R_A"))),
        q("R_B", G::Forces, U::Force, force_pair!(r_b), true, true, Some(("Reaction in B (link 3 on link 2)", "R_B"))),
        q("R_C", G::Forces, U::Force, force_pair!(r_c), true, true, Some(("Reaction in C (ground on link 3)", "R_C"))),
        q("R_O", G::Forces, U::Force, force_pair!(r_o), true, true, Some(("Reaction in O1 (ground on link 1)", "R_O"))),
        q("R_An", G::Forces, U::Force, force_pair!(r_a_n), false, false, None),
        q("R_At", G::Forces, U::Force, force_pair!(r_a_t), false, false, None),
        q("R_Cn", G::Forces, U::Force, force_pair!(r_c_n), false, false, None),
        q("R_Ct", G::Forces, U::Force, force_pair!(r_c_t), false, false, None),
        q("Fi1", G::Forces, U::Force, force_pair!(fi1), false, false, None),
        q("Fi21", G::Forces, U::Force, force_pair!(fi21), false, false, None),
        q("Fi22", G::Forces, U::Force, force_pair!(fi22), false, false, None),
        q("Fi3", G::Forces, U::Force, force_pair!(fi3), false, false, None),
        q("F", G::Forces, U::Force, force_pair!(f_ext), false, false, None),
        q("G1", G::Forces, U::Force, force_pair!(g1), false, false, None),
        q("G21", G::Forces, U::Force, force_pair!(g21), false, false, None),
        q("G22", G::Forces, U::Force, force_pair!(g22), false, false, None),
        q("G3", G::Forces, U::Force, force_pair!(g3), false, false, None),
        q("Mi1", G::Forces, U::Moment, force_scalar!(mi1), false, false, None),
        q("Mi21", G::Forces, U::Moment, force_scalar!(mi21), false, false, None),
        q("Mi22", G::Forces, U::Moment, force_scalar!(mi22), false, false, None),
        q("Mi3", G::Forces, U::Moment, force_scalar!(mi3), false, false, None),
        q(
            "Me1",
            G::Forces,
            U::Moment,
            force_scalar!(me1),
            false,
            true,
            Some(("Balancing moment on the crank (CCW positive)", "Me1")),
        ),
    ]
}

/// The quantities a run reports: positions always; velocities and accelerations when asked
/// for or when forces are (they need both); forces when computed.
pub(super) fn reported(o: &crate::solve::fourbar::Outputs, forces: bool) -> Vec<Quantity> {
    let velocity = o.velocity || o.forces;
    let acceleration = o.acceleration || o.forces;
    quantities()
        .into_iter()
        .filter(|q| match q.group {
            Group::Position => true,
            Group::Velocity => velocity,
            Group::Acceleration => acceleration,
            Group::Forces => forces,
        })
        .collect()
}

/// The forces at position `i`, when computed.
fn forces_at(motion: &Motion, i: usize, forces: bool) -> Option<&Forces> {
    if forces { motion.forces.get(i) } else { None }
}

/// The CSV: one row per position, the columns of [`Quantity`].
pub(super) fn table(motion: &Motion, qs: &[Quantity], forces: bool) -> Csv {
    let mut header = Vec::new();
    for q in qs {
        match q.get {
            Get::Scalar(_) => header.push(q.name.to_string()),
            Get::Pair(_) => {
                header.push(format!("{}_x", q.name));
                header.push(format!("{}_y", q.name));
                if q.magnitude {
                    header.push(format!("{}_mag", q.name));
                }
            }
        }
    }
    let mut csv = Csv::new(header);
    let rows: Vec<Vec<f64>> = motion
        .positions
        .par_iter()
        .enumerate()
        .map(|(i, p)| {
            let f = forces_at(motion, i, forces);
            let mut row = Vec::new();
            for q in qs {
                match q.get {
                    Get::Scalar(g) => row.push(g(p, f)),
                    Get::Pair(g) => {
                        let v = g(p, f);
                        row.extend([v.x, v.y]);
                        if q.magnitude {
                            row.push(v.norm());
                        }
                    }
                }
            }
            row
        })
        .collect();
    csv.rows(&rows);
    csv
}

/// One position's JSON record: the quantities marked `json`, pairs as `[x, y]`. A number
/// that is not finite fails (JSON would write it as `null`), naming `positions[i].<key>` of
/// `<name>.json`.
fn position_record(
    p: &Position,
    f: Option<&Forces>,
    qs: &[Quantity],
    at: (&str, usize),
) -> Result<BTreeMap<String, Value>, Error> {
    let mut r = BTreeMap::new();
    let checked = |key: String, values: &[f64]| {
        if values.iter().all(|v| v.is_finite()) {
            Ok(key)
        } else {
            Err(Error::NonFinite { what: format!("{}.json", at.0), at: format!("positions[{}].{key}", at.1) })
        }
    };
    for q in qs.iter().filter(|q| q.json) {
        match q.get {
            Get::Scalar(g) => {
                let v = g(p, f);
                r.insert(checked(q.name.to_string(), &[v])?, json!(v));
            }
            Get::Pair(g) => {
                let v = g(p, f);
                r.insert(checked(q.name.to_string(), &[v.x, v.y])?, report::vector(v));
                if q.magnitude {
                    let m = v.norm();
                    r.insert(checked(format!("{}_mag", q.name), &[m])?, json!(m));
                }
            }
        }
    }
    Ok(r)
}

/// A drawing scale in the summary: the value per millimetre of printed paper and its unit.
#[derive(Debug, Serialize)]
struct ScaleRecord {
    value: f64,
    unit: String,
}

/// The length scale of the mechanism and the scales of the polygons drawn (`null` for one
/// not drawn), per millimetre of printed paper.
#[derive(Debug, Serialize)]
struct Scales {
    k_l: ScaleRecord,
    k_v: Option<ScaleRecord>,
    k_a: Option<ScaleRecord>,
    k_f: Option<ScaleRecord>,
}

/// The crank angles swept, degrees.
#[derive(Debug, Serialize)]
struct SweepRecord {
    from_deg: f64,
    to_deg: f64,
    step_deg: f64,
}

/// The four-bar's JSON summary (docs/fourbar-output.md).
#[derive(Debug, Serialize)]
struct Summary<'a> {
    kind: &'static str,
    name: &'a str,
    units: &'static str,
    omega1: f64,
    epsilon1: f64,
    sweep: SweepRecord,
    outputs: Vec<&'static str>,
    grashof: crate::solve::fourbar::Grashof,
    solved: usize,
    gaps: &'a [crate::solve::fourbar::Gap],
    dead_points: &'a [crate::solve::fourbar::DeadPoint],
    scales: Scales,
    /// Empty when serialised: the records are put into the value afterwards.
    positions: Vec<Value>,
}

fn summary(scene: &FourbarScene, motion: &Motion, layout: &Layout, qs: &[Quantity]) -> Result<Value, Error> {
    let spec = &scene.spec;
    let o = &spec.outputs;
    let forces = layout.show.forces;
    // The records made in parallel and put into the summary's value as they are (not
    // serialised into a second copy with the rest).
    let positions: Vec<Value> = motion
        .positions
        .par_iter()
        .enumerate()
        .map(|(i, p)| {
            let mut record = position_record(p, forces_at(motion, i, forces), qs, (&scene.name, i))?;
            // The scales this position's frame is drawn at (each frame its own by default).
            let k = layout.frame.scales_at(i);
            let mut scales = serde_json::Map::new();
            scales.extend(k.k_v.map(|v| ("k_v".to_string(), Value::from(v))));
            scales.extend(k.k_a.map(|v| ("k_a".to_string(), Value::from(v))));
            if !k.k_f.is_empty() {
                scales.insert("k_f".to_string(), Value::from(k.k_f.clone()));
            }
            record.insert("scales".to_string(), Value::Object(scales));
            Ok(Value::Object(record.into_iter().collect()))
        })
        .collect::<Result<_, Error>>()?;
    let outputs = [
        ("position", true),
        ("velocity", o.velocity),
        ("acceleration", o.acceleration),
        ("forces", o.forces),
        ("centres", scene.centres),
    ]
    .into_iter()
    .filter_map(|(n, on)| on.then_some(n))
    .collect();
    let len = layout.frame.units.length;
    // The first frame's scales (each frame prints its own with scales per frame).
    let first = layout.frame.scales_at(0);
    let scale = |s: Option<f64>, unit: String| s.map(|value| ScaleRecord { value, unit });
    let s = Summary {
        kind: "fourbar",
        name: &scene.name,
        units: len,
        omega1: spec.omega1,
        epsilon1: spec.epsilon1,
        sweep: SweepRecord { from_deg: spec.sweep.from_deg, to_deg: spec.sweep.to_deg, step_deg: spec.sweep.step_deg },
        outputs,
        grashof: motion.grashof,
        solved: motion.positions.len(),
        gaps: &motion.gaps,
        dead_points: &motion.dead_points,
        scales: Scales {
            k_l: ScaleRecord { value: layout.frame.k_l, unit: format!("{len}/mm") },
            k_v: scale(first.k_v, format!("({len}/s)/mm")),
            k_a: scale(first.k_a, format!("({len}/s²)/mm")),
            k_f: scale(first.k_f.first().copied(), "N/mm".to_string()),
        },
        positions: Vec::new(),
    };
    let mut value = products::summary_value(&s, &scene.name)?;
    if let Value::Object(map) = &mut value {
        map.insert("positions".to_string(), Value::Array(positions));
    }
    Ok(value)
}

fn report_text(scene: &FourbarScene, motion: &Motion, layout: &Layout) -> String {
    let mut s = format!("{}: four-bar, {} positions solved", scene.name, motion.positions.len());
    let skipped: usize = motion.gaps.iter().map(|g| g.skipped).sum();
    if skipped > 0 {
        s.push_str(&format!(", {skipped} skipped"));
    }
    let k_l = crate::figure::fourbar::scale_text(layout.frame.k_l);
    s.push_str(&format!("; k_l = {k_l} {}/mm", layout.frame.units.length));
    let first = layout.frame.scales_at(0);
    for (n, sc, u) in [
        ("k_v", first.k_v, format!("({}/s)/mm", layout.frame.units.length)),
        ("k_a", first.k_a, format!("({}/s²)/mm", layout.frame.units.length)),
        ("k_f", first.k_f.first().copied(), "N/mm".to_string()),
    ] {
        if let Some(sc) = sc {
            s.push_str(&format!("; {n} = {} {u}", crate::figure::fourbar::scale_text(sc)));
        }
    }
    if layout.show.scales == crate::figure::fourbar::ScaleChoice::PerFrame {
        s.push_str(" at the first frame (each frame prints its own)");
    }
    s.push('\n');
    s
}

/// The diagrams of the reported quantities that have one, against φ1 (curves broken over
/// skipped angles).
pub(super) fn diagrams(
    motion: &Motion,
    step_deg: f64,
    qs: &[Quantity],
    forces: bool,
    units: ModelUnits,
) -> Vec<(String, Diagram)> {
    qs.iter()
        .filter_map(|q| q.diagram.map(|d| (q, d)))
        .map(|(q, (title, symbol))| {
            let y_label = match q.get {
                Get::Scalar(_) => format!("{symbol} [{}]", q.unit.text(units)),
                Get::Pair(_) => format!("|{symbol}| [{}]", q.unit.text(units)),
            };
            // NaN between runs breaks the curve over skipped angles.
            let mut x = Vec::with_capacity(motion.positions.len() + 4);
            let mut y = Vec::with_capacity(motion.positions.len() + 4);
            let mut prev: Option<f64> = None;
            for (i, p) in motion.positions.iter().enumerate() {
                let d = deg(p.phi1);
                if prev.is_some_and(|q| d - q > GAP_STEPS * step_deg) {
                    x.push(f64::NAN);
                    y.push(f64::NAN);
                }
                x.push(d);
                let f = forces_at(motion, i, forces);
                y.push(match q.get {
                    Get::Scalar(g) => g(p, f),
                    Get::Pair(g) => g(p, f).norm(),
                });
                prev = Some(d);
            }
            let series = vec![Series { label: q.name.to_string(), x, y }];
            (q.name.to_string(), Diagram { title: title.to_string(), x_label: "φ1 [°]".into(), y_label, series })
        })
        .collect()
}

/// Quantities on a sheet besides those of the JSON records: the force polygon's sides.
const SHEET_EXTRA: [&str; 9] = ["R_An", "R_At", "R_Cn", "R_Ct", "Fi1", "Fi21", "Fi22", "Fi3", "F"];

/// A quantity's name as a textbook writes it (`omega2` → `ω2`, `phi1_deg` → `φ1`).
fn symbol(name: &str) -> String {
    let name = name.strip_suffix("_deg").unwrap_or(name);
    match name {
        // The angle between BA and BC in [0°, 180°], and γ, the same folded to 0–90°.
        "transmission" => return "∠ABC".to_string(),
        "gamma" => return "γ".to_string(),
        _ => {}
    }
    for (from, to) in [("phi", "φ"), ("omega", "ω"), ("eps", "ε")] {
        if let Some(rest) = name.strip_prefix(from) {
            return format!("{to}{rest}");
        }
    }
    name.to_string()
}

/// One position's values for its sheet: a row per quantity (the JSON records' and the
/// force polygon's sides), pairs as x, y and magnitude (positions without one), scalars in
/// the value column; 4 significant digits ([`sheet::number`]). A value below 1e-9 of the
/// largest of its unit on the page is rounding noise (x_A = 2.4e-18 m at φ1 = 90°) and
/// prints as 0.
pub(super) fn sheet_table(p: &Position, f: Option<&Forces>, qs: &[Quantity], units: ModelUnits) -> sheet::Table {
    let header = ["", "x", "y", "value", "unit"].map(String::from).to_vec();
    let raw: Vec<(&Quantity, [Option<f64>; 3])> = qs
        .iter()
        .filter(|q| q.json || SHEET_EXTRA.contains(&q.name))
        .map(|q| {
            let cells = match q.get {
                Get::Scalar(g) => [None, None, Some(g(p, f))],
                Get::Pair(g) => {
                    let v = g(p, f);
                    [Some(v.x), Some(v.y), (q.group != Group::Position).then(|| v.norm())]
                }
            };
            (q, cells)
        })
        .collect();
    let largest = |unit: Unit| {
        raw.iter()
            .filter(|(q, _)| q.unit == unit)
            .flat_map(|(_, c)| c.iter().flatten().map(|v| v.abs()))
            .filter(|v| v.is_finite())
            .fold(0.0, f64::max)
    };
    let names: Vec<Label> = raw.iter().map(|(q, _)| table_name(q)).collect();
    let rows = raw
        .iter()
        .zip(&names)
        .map(|((q, cells), name)| {
            let noise = 1e-9 * largest(q.unit);
            let mut row = vec![name.text.clone()];
            row.extend(cells.iter().map(|c| match c {
                Some(v) if v.abs() < noise => "0".to_string(),
                Some(v) => sheet::number(*v),
                None => String::new(),
            }));
            row.push(q.unit.text(units));
            row
        })
        .collect();
    sheet::Table { header, rows, names: names.into_iter().map(|n| n.runs).collect() }
}

/// A quantity's name in a sheet's table as a textbook writes it: a point's (`A`) and an
/// angle named by its points (`∠ABC`) flat, the others a symbol and its subscript with the
/// CSV's `_` left out (`R_An` → R_An, `aBA_n` → a_BAn, `omega2` → ω_2, `Me1` → M_e1).
fn table_name(q: &Quantity) -> Label {
    let flat = symbol(q.name);
    if (q.group == Group::Position && q.unit == Unit::Length) || flat.starts_with('∠') {
        return Label::from(flat);
    }
    Label::quantity(&flat.replace('_', ""))
}

/// The printed pages, a set per drawn position (`drawn`: indices into the motion's positions,
/// in parallel): `sheets/<name>/<position>-<page>.svg` (`mechanism`, `polygons`, `forces`)
/// and the PDF with every page in order, numbered among themselves.
#[allow(clippy::too_many_arguments)]
fn sheet_pages(
    paper: Paper,
    scene: &FourbarScene,
    motion: &Motion,
    curve: &[Vec<Point>],
    qs: &[Quantity],
    show: Show,
    units: ModelUnits,
    names: &[String],
    drawn: &[usize],
) -> Vec<products::Page> {
    let geom = scene.spec.geometry;
    let rows =
        motion.positions.first().map_or(0, |p| sheet_table(p, forces_at(motion, 0, show.forces), qs, units).rows.len());
    let (external, loads) =
        scene.spec.dynamics.as_ref().map_or((&[][..], &[][..]), |d| (d.forces.as_slice(), d.loads.as_slice()));
    let sheets =
        FourbarSheets::new(paper, &scene.name, scene.spec.omega1, &geom, &motion.positions, curve, show, units, rows)
            .with_loads(external, loads);
    let per = sheets.per_position();
    let total = drawn.len() * per;
    let sets: Vec<Vec<products::Page>> = drawn
        .par_iter()
        .enumerate()
        .map(|(j, &i)| {
            let p = &motion.positions[i];
            let f = forces_at(motion, i, show.forces);
            let table = sheet_table(p, f, qs, units);
            let set = sheets.pages(&geom, p, f, &table, (j * per + 1, total));
            set.pages
                .into_iter()
                .map(|(kind, drawing)| products::Page::printed(&names[i], kind, drawing, paper))
                .collect()
        })
        .collect();
    sets.into_iter().flatten().collect()
}
