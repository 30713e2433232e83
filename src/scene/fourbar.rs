//! Scene kind `fourbar` (design.md §4b): schema and validation. The checked scene holds
//! the solver's input types ([`MotionSpec`]), so the pipeline hands `scene.spec` to
//! [`crate::solve::fourbar::solve_motion`]. The schema is documented field by field in
//! docs/fourbar-solver.md.

use serde::Deserialize;

use super::tolerance::{self, Tolerances};
use super::{
    FieldError, MAX_ANGULAR_ACCELERATION, MAX_ANGULAR_SPEED, MAX_FORCE_N, MAX_GRAVITY, MAX_INERTIA_KG_M2, MAX_MASS_KG,
    MAX_TORQUE_N_M, Units, angle_deg, finite_point, non_negative_within, pair_within, positive, within,
};
use crate::geom::{Side, Vector};
use crate::solve::fourbar::{ANGLE_EPS_DEG, Geometry, MAX_POSITIONS, MotionSpec, Outputs, Sweep};
use crate::solve::fourbar::{CrankRange, Dynamics, ExternalForce, ForcePoint, Link, LinkLoad, LinkMass};
use crate::solve::tolerance::fourbar::{FourbarOutput, FourbarParam};

/// Standard gravity in m/s², the default `dynamics.g` (in every scene: g is in m/s²
/// whatever the length unit).
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// Largest `dynamics.g` accepted in a mm scene, m/s² (about 100 g). Before forces were
/// read in N everywhere, a mm scene's g was in mm/s² (9806.65); such a value is refused
/// with a message saying so, instead of being read as 1000 g.
pub const MAX_G_MM_SCENE: f64 = 1000.0;

/// The scene as written in the file (`kind` removed).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawFourbarScene {
    /// Output file stem.
    pub name: String,
    /// Length units.
    pub units: Units,
    /// Crank pivot O1.
    pub o1: [f64; 2],
    /// Rocker pivot C.
    pub c: [f64; 2],
    /// Crank length O1A.
    pub l1: f64,
    /// Coupler side AB.
    pub l_ab: f64,
    /// Coupler side BM.
    pub l_bm: f64,
    /// Angle from ray B→A to ray B→M, degrees, CCW.
    pub alpha_deg: f64,
    /// Rocker length BC.
    pub l_bc: f64,
    /// Crank angular velocity, rad/s, CCW positive.
    pub omega1: f64,
    /// Crank angular acceleration, rad/s², CCW positive (default 0).
    #[serde(default)]
    pub epsilon1: Option<f64>,
    /// Crank angles.
    pub phi1_deg: RawSweep,
    /// Side of B relative to the directed line A→C at the first crank angle.
    #[serde(default)]
    pub branch: Option<Side>,
    /// What to compute.
    #[serde(default)]
    pub outputs: Option<Vec<String>>,
    /// Masses, gravity and external forces.
    #[serde(default)]
    pub dynamics: Option<RawDynamics>,
    /// `[tolerances]`: toleranced fields, watched outputs, settings
    /// ([`super::tolerance`]).
    #[serde(default)]
    pub tolerances: Option<toml::Table>,
    /// How the frames are drawn.
    #[serde(default)]
    pub frames: Option<super::RawFrames>,
}

/// `phi1_deg = { from, to, step }`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSweep {
    /// First angle, degrees.
    pub from: f64,
    /// Last angle (included when the grid lands on it), degrees.
    pub to: f64,
    /// Step, degrees.
    pub step: f64,
}

/// `[dynamics]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawDynamics {
    /// Gravity, m/s²: a number (along −y) or a vector [gx, gy].
    #[serde(default)]
    pub g: Option<RawGravity>,
    /// Crank mass, kg.
    pub m1: f64,
    /// Coupler bar AB mass, kg.
    pub m21: f64,
    /// Coupler bar BM mass, kg.
    pub m22: f64,
    /// Rocker mass, kg.
    pub m3: f64,
    /// `[[dynamics.force]]`.
    #[serde(default)]
    pub force: Vec<RawForce>,
    /// `[dynamics.crank]`: centroid offset and inertia of the crank.
    #[serde(default)]
    pub crank: Option<RawLinkMass>,
    /// `[dynamics.AB]`.
    #[serde(default, rename = "AB")]
    pub ab: Option<RawLinkMass>,
    /// `[dynamics.BM]`.
    #[serde(default, rename = "BM")]
    pub bm: Option<RawLinkMass>,
    /// `[dynamics.rocker]`.
    #[serde(default)]
    pub rocker: Option<RawLinkMass>,
    /// `[[dynamics.load]]`: forces at any point of any link, torques on any link.
    #[serde(default)]
    pub load: Vec<RawLoad>,
}

/// `dynamics.g`: a number (m/s² along −y) or a vector [gx, gy] (m/s²).
#[derive(Debug, Clone, Deserialize)]
#[serde(untagged)]
pub enum RawGravity {
    /// Along −y.
    Down(f64),
    /// Any direction.
    Vector([f64; 2]),
}

/// `[dynamics.crank]`, `[dynamics.AB]`, `[dynamics.BM]`, `[dynamics.rocker]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawLinkMass {
    /// Offset of the centroid from the bar's middle, link coordinates, length units.
    #[serde(default)]
    pub centroid: Option<[f64; 2]>,
    /// Moment of inertia about the centroid, kg·m².
    #[serde(default)]
    pub inertia: Option<f64>,
}

/// `[[dynamics.load]]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawLoad {
    /// "crank", "AB", "BM" or "rocker".
    pub link: String,
    /// Point of application, link coordinates from the link's first point, length units.
    #[serde(default)]
    pub at: Option<[f64; 2]>,
    /// [fx, fy], N.
    #[serde(default)]
    pub force: Option<[f64; 2]>,
    /// Torque, N·m, CCW positive.
    #[serde(default)]
    pub torque: Option<f64>,
    /// [from, to], degrees, closed, counter-clockwise from `from`.
    #[serde(default)]
    pub phi1_deg: Option<[f64; 2]>,
}

/// `[[dynamics.force]]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawForce {
    /// "A", "B" or "M".
    pub at: String,
    /// [fx, fy], N.
    pub value: [f64; 2],
    /// [from, to], degrees, closed, counter-clockwise from `from`.
    #[serde(default)]
    pub phi1_deg: Option<[f64; 2]>,
}

/// A checked `fourbar` scene.
#[derive(Debug, Clone)]
pub struct FourbarScene {
    /// Output file stem.
    pub name: String,
    /// Length units.
    pub units: Units,
    /// The solver's input: geometry, omega1, sweep, outputs, dynamics.
    pub spec: MotionSpec,
    /// `outputs` names "centres": draw the instantaneous centres with Kennedy's lines (a
    /// sheet `<name>-centres`).
    pub centres: bool,
    /// `[tolerances]`, checked (boxed: most scenes have none).
    pub tolerances: Option<Box<FourbarTolerances>>,
    /// How the frames' polygon scales are chosen.
    pub frame_scales: super::FrameScales,
}

/// A four-bar's checked `[tolerances]`: the study and the watched outputs.
#[derive(Debug, Clone, PartialEq)]
pub struct FourbarTolerances {
    /// Dimensions, their fields, settings.
    pub study: Tolerances<FourbarParam>,
    /// The watched outputs (points first, then angles; `M` when none is named).
    pub outputs: Vec<FourbarOutput>,
}

/// Checks a four-bar's `[tolerances]` table (sweep of `count` positions).
fn check_tolerances(t: &toml::Table, geometry: &Geometry, count: usize) -> Result<FourbarTolerances, FieldError> {
    let valid = FourbarParam::ALL.map(FourbarParam::field).join(", ");
    let resolve = |path: &str| match FourbarParam::from_field(path) {
        Some(p) => Ok((p, p.nominal(geometry))),
        None => Err(format!(
            "is not a dimension of the four-bar that a tolerance can act on; valid: {valid} (o1 and c are points: o1[0] is x, o1[1] is y)"
        )),
    };
    let study = tolerance::check(t, &tolerance::Kind { resolve: &resolve, positions: count, components: (4, 1) })?;
    let mut outputs = Vec::new();
    let points = if study.outputs.is_empty() { vec!["M".to_string()] } else { study.outputs.points.clone() };
    for (i, name) in points.iter().enumerate() {
        match FourbarOutput::from_name(name) {
            Some(o @ FourbarOutput::Point(_)) => outputs.push(o),
            _ => {
                return Err(FieldError::new(
                    format!("tolerances.outputs.points[{i}]"),
                    format!("\"{name}\" is not a point of the four-bar; valid: \"A\", \"B\", \"M\""),
                ));
            }
        }
    }
    for (i, name) in study.outputs.angles.iter().enumerate() {
        match FourbarOutput::from_name(name) {
            Some(o @ (FourbarOutput::Phi2 | FourbarOutput::Phi3)) => outputs.push(o),
            _ => {
                return Err(FieldError::new(
                    format!("tolerances.outputs.angles[{i}]"),
                    format!(
                        "\"{name}\" is not a link whose angle is watched; valid: \"coupler\" (φ2), \"rocker\" (φ3)"
                    ),
                ));
            }
        }
    }
    let rates = [
        ("velocities", &study.outputs.velocities, FourbarOutput::velocity as fn(&str) -> Option<FourbarOutput>),
        ("accelerations", &study.outputs.accelerations, FourbarOutput::acceleration),
    ];
    for (key, names, of) in rates {
        for (i, name) in names.iter().enumerate() {
            let Some(o) = of(name) else {
                return Err(FieldError::new(
                    format!("tolerances.outputs.{key}[{i}]"),
                    format!(
                        "\"{name}\" is neither a point nor a moving link of the four-bar; valid: \"A\", \"B\", \"M\" (a point), \"coupler\", \"rocker\" (a link)"
                    ),
                ));
            };
            outputs.push(o);
        }
    }
    if let Some(dup) = outputs.iter().enumerate().find(|(i, o)| outputs[..*i].contains(o)) {
        return Err(FieldError::new("tolerances.outputs", format!("names {} twice", dup.1.name())));
    }
    Ok(FourbarTolerances { study, outputs })
}

const OUTPUT_NAMES: &str = "\"position\", \"velocity\", \"acceleration\", \"forces\", \"centres\"";

/// Validates the raw scene.
pub fn check(raw: RawFourbarScene) -> Result<FourbarScene, FieldError> {
    let name = super::check_name(&raw.name)?;
    let o1 = finite_point("o1", raw.o1)?;
    let c = finite_point("c", raw.c)?;
    if o1 == c {
        return Err(FieldError::new("c", "must differ from o1 (the ground link O1C has zero length)"));
    }
    let alpha_deg = angle_deg("alpha_deg", raw.alpha_deg)?;
    let geometry = Geometry {
        o1,
        c,
        l1: positive("l1", raw.l1)?,
        l_ab: positive("l_ab", raw.l_ab)?,
        l_bm: positive("l_bm", raw.l_bm)?,
        alpha: alpha_deg.to_radians(),
        l_bc: positive("l_bc", raw.l_bc)?,
        branch: raw.branch.unwrap_or(Side::Left),
    };
    let omega1 = within("omega1", raw.omega1, MAX_ANGULAR_SPEED, "an angular speed in rad/s")?;
    let epsilon1 =
        within("epsilon1", raw.epsilon1.unwrap_or(0.0), MAX_ANGULAR_ACCELERATION, "an angular acceleration in rad/s²")?;
    let sweep = check_sweep(&raw.phi1_deg)?;

    let outputs = match &raw.outputs {
        None => Outputs { velocity: true, acceleration: true, forces: raw.dynamics.is_some() },
        Some(list) => {
            if list.is_empty() {
                return Err(FieldError::new(
                    "outputs",
                    format!("must name at least \"position\"; valid: {OUTPUT_NAMES}"),
                ));
            }
            let mut o = Outputs::POSITIONS;
            for (i, s) in list.iter().enumerate() {
                match s.as_str() {
                    "position" => {}
                    "velocity" => o.velocity = true,
                    "acceleration" => o.acceleration = true,
                    "forces" => o.forces = true,
                    "centres" => {}
                    other => {
                        return Err(FieldError::new(
                            format!("outputs[{i}]"),
                            format!("\"{other}\" is not an output; valid: {OUTPUT_NAMES}"),
                        ));
                    }
                }
            }
            o
        }
    };
    if outputs.forces && raw.dynamics.is_none() {
        return Err(FieldError::new(
            "outputs",
            "\"forces\" needs a [dynamics] table (g, m1, m21, m22, m3 and optional [[dynamics.force]])",
        ));
    }
    let dynamics = raw.dynamics.as_ref().map(|d| check_dynamics(d, raw.units)).transpose()?;
    let centres = raw.outputs.as_ref().is_some_and(|l| l.iter().any(|s| s == "centres"));
    let tolerances =
        raw.tolerances.as_ref().map(|t| check_tolerances(t, &geometry, sweep.count()).map(Box::new)).transpose()?;
    let frame_scales = super::check_frames(raw.frames.as_ref())?;
    Ok(FourbarScene {
        name,
        units: raw.units,
        spec: MotionSpec { geometry, omega1, epsilon1, sweep, outputs, dynamics },
        centres,
        tolerances,
        frame_scales,
    })
}

fn check_sweep(s: &RawSweep) -> Result<Sweep, FieldError> {
    let from_deg = angle_deg("phi1_deg.from", s.from)?;
    let to_deg = angle_deg("phi1_deg.to", s.to)?;
    let step_deg = angle_deg("phi1_deg.step", s.step)?;
    if step_deg <= 0.0 {
        return Err(FieldError::new("phi1_deg.step", format!("must be a positive angle in degrees, got {step_deg}")));
    }
    if to_deg < from_deg {
        return Err(FieldError::new(
            "phi1_deg.to",
            format!("must be at least phi1_deg.from = {from_deg} (the crank turns counter-clockwise), got {to_deg}"),
        ));
    }
    let sweep = Sweep { from_deg, to_deg, step_deg };
    let n = (to_deg - from_deg) / step_deg + ANGLE_EPS_DEG;
    if n >= MAX_POSITIONS as f64 {
        return Err(FieldError::new(
            "phi1_deg.step",
            format!("gives {} crank angles; at most {MAX_POSITIONS} are allowed: use a larger step", n.floor() + 1.0),
        ));
    }
    Ok(sweep)
}

/// `phi1_deg = [from, to]` of a load: where it acts, degrees.
fn crank_range(field: String, r: Option<[f64; 2]>) -> Result<Option<CrankRange>, FieldError> {
    match r {
        None => Ok(None),
        Some([from, to]) => {
            if !(from.is_finite()
                && to.is_finite()
                && from.abs() <= super::MAX_ANGLE_DEG
                && to.abs() <= super::MAX_ANGLE_DEG)
            {
                return Err(FieldError::new(
                    field,
                    format!(
                        "must be [from, to] in degrees, each within ±{:e}, got [{from:?}, {to:?}]",
                        super::MAX_ANGLE_DEG
                    ),
                ));
            }
            Ok(Some(CrankRange { from_deg: from, to_deg: to }))
        }
    }
}

fn check_dynamics(d: &RawDynamics, units: Units) -> Result<Dynamics, FieldError> {
    let gravity = match &d.g {
        None => Vector::new(0.0, -STANDARD_GRAVITY),
        Some(RawGravity::Down(g)) => {
            let g = within("dynamics.g", *g, MAX_GRAVITY, "an acceleration in m/s²")?;
            if g < 0.0 {
                return Err(FieldError::new(
                    "dynamics.g",
                    format!(
                        "must be ≥ 0 in m/s² (a number acts along −y; write [gx, gy] for another direction), got {g}"
                    ),
                ));
            }
            Vector::new(0.0, -g)
        }
        Some(RawGravity::Vector(v)) => pair_within("dynamics.g", *v, MAX_GRAVITY, "an acceleration in m/s²")?,
    };
    let g = gravity.norm();
    if units == Units::Mm && g > MAX_G_MM_SCENE {
        return Err(FieldError::new(
            "dynamics.g",
            format!(
                "is in m/s² in every scene, mm scenes too (forces are in N, masses in kg); {g} m/s² is {:.0} g. \
                 For standard gravity write {STANDARD_GRAVITY} or leave g out (a value in mm/s² such as 9806.65 \
                 is from before this rule: divide it by 1000)",
                g / STANDARD_GRAVITY
            ),
        ));
    }
    let mass = |field: &str, v: f64| non_negative_within(field, v, MAX_MASS_KG, "a mass in kg");
    let mut links = [LinkMass::default(); 4];
    for (link, name, raw) in [
        (Link::Crank, "crank", &d.crank),
        (Link::Ab, "AB", &d.ab),
        (Link::Bm, "BM", &d.bm),
        (Link::Rocker, "rocker", &d.rocker),
    ] {
        let Some(raw) = raw else { continue };
        let lm = &mut links[link.index()];
        if let Some(c) = raw.centroid {
            let c = finite_point(&format!("dynamics.{name}.centroid"), c)?;
            lm.centroid = Vector::new(c.x, c.y);
        }
        if let Some(j) = raw.inertia {
            let field = format!("dynamics.{name}.inertia");
            lm.inertia = Some(non_negative_within(&field, j, MAX_INERTIA_KG_M2, "a moment of inertia in kg·m²")?);
        }
    }
    let mut loads = Vec::with_capacity(d.load.len());
    for (i, l) in d.load.iter().enumerate() {
        let link = match l.link.as_str() {
            "crank" => Link::Crank,
            "AB" => Link::Ab,
            "BM" => Link::Bm,
            "rocker" => Link::Rocker,
            other => {
                return Err(FieldError::new(
                    format!("dynamics.load[{i}].link"),
                    format!("\"{other}\" is not a link; valid: \"crank\", \"AB\", \"BM\", \"rocker\""),
                ));
            }
        };
        if l.force.is_none() && l.torque.is_none() {
            return Err(FieldError::new(
                format!("dynamics.load[{i}]"),
                "needs a force = [fx, fy] (N) or a torque (N·m)",
            ));
        }
        let at = finite_point(&format!("dynamics.load[{i}].at"), l.at.unwrap_or([0.0, 0.0]))?;
        let force = pair_within(
            &format!("dynamics.load[{i}].force"),
            l.force.unwrap_or([0.0, 0.0]),
            MAX_FORCE_N,
            "a force in N",
        )?;
        let torque =
            within(&format!("dynamics.load[{i}].torque"), l.torque.unwrap_or(0.0), MAX_TORQUE_N_M, "a torque in N·m")?;
        loads.push(LinkLoad {
            link,
            at: Vector::new(at.x, at.y),
            force: Vector::new(force.x, force.y),
            torque,
            range: crank_range(format!("dynamics.load[{i}].phi1_deg"), l.phi1_deg)?,
        });
    }
    let mut forces = Vec::with_capacity(d.force.len());
    for (i, f) in d.force.iter().enumerate() {
        let at = match f.at.as_str() {
            "A" => ForcePoint::A,
            "B" => ForcePoint::B,
            "M" => ForcePoint::M,
            other => {
                return Err(FieldError::new(
                    format!("dynamics.force[{i}].at"),
                    format!("\"{other}\" is not a point of the coupler; valid: \"A\", \"B\", \"M\""),
                ));
            }
        };
        let value = pair_within(&format!("dynamics.force[{i}].value"), f.value, MAX_FORCE_N, "a force in N")?;
        let range = crank_range(format!("dynamics.force[{i}].phi1_deg"), f.phi1_deg)?;
        forces.push(ExternalForce { at, value, range });
    }
    Ok(Dynamics {
        length_unit_m: match units {
            Units::Si => 1.0,
            Units::Mm => 0.001,
        },
        gravity,
        m1: mass("dynamics.m1", d.m1)?,
        m21: mass("dynamics.m21", d.m21)?,
        m22: mass("dynamics.m22", d.m22)?,
        m3: mass("dynamics.m3", d.m3)?,
        forces,
        links,
        loads,
    })
}
