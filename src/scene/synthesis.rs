//! Scene kind `synthesis`: a requirement for a mechanism instead of the mechanism. The
//! field `task` names what is required; each task has its own fields, at the top level of
//! the file beside `name` and `units` (docs/synthesis.md):
//!
//! | `task` | requirement | free choices |
//! |---|---|---|
//! | `crank-rocker` | `psi_deg`, `time_ratio`, `rocker` | `ground` or `extreme_to_ground_deg` (else the best γ_min) |
//! | `slider-crank` | `stroke`, `time_ratio` | `offset` (else the best γ_min) |
//! | `quick-return` | `stroke`, `time_ratio`, `crank` or `ground` | `link`, `ram_height` |
//! | `motion` | `positions` (2 or 3 `{ at, angle_deg }`), `a1`, `b1` | `bisector_distance` (two positions), `crank`, `turning` |
//! | `function` | `function` (of x), `x_range`, `input_deg`, `output_deg`, `ground` | `precision_x` (else Chebyshev's) |
//!
//! Every task takes `omega1` (the design's crank speed, rad/s, counter-clockwise; default
//! 2π: one turn a second). The checked scene holds the solvers' requirement types.

use serde::Deserialize;

use super::{FieldError, SceneError, Units, finite, finite_point, positive};
use crate::solve::expr::Expr;
use crate::solve::synthesis::{self, crank_rocker, function, motion, quick_return, slider_crank};

/// The tasks, as written in the `task` field.
pub const TASKS: &[&str] = &["crank-rocker", "slider-crank", "quick-return", "motion", "function"];

/// A checked synthesis scene.
#[derive(Debug, Clone)]
pub struct SynthesisScene {
    /// Output file stem (the design is `<name>-design`).
    pub name: String,
    /// Length units of the requirement and of the design.
    pub units: Units,
    /// The design's crank speed, rad/s, counter-clockwise positive.
    pub omega1: f64,
    /// What is required.
    pub task: Task,
}

/// What is required, as the solver takes it.
#[derive(Debug, Clone)]
pub enum Task {
    /// `task = "crank-rocker"`.
    CrankRocker(crank_rocker::Requirement),
    /// `task = "slider-crank"`.
    SliderCrank(slider_crank::Requirement),
    /// `task = "quick-return"`.
    QuickReturn(quick_return::Requirement),
    /// `task = "motion"`.
    Motion(motion::Requirement),
    /// `task = "function"`.
    Function {
        /// The requirement.
        requirement: function::Requirement,
        /// y = f(x), parsed (the variable is x).
        function: Expr,
    },
}

impl Task {
    /// The `task` string.
    pub fn name(&self) -> &'static str {
        match self {
            Task::CrankRocker(_) => "crank-rocker",
            Task::SliderCrank(_) => "slider-crank",
            Task::QuickReturn(_) => "quick-return",
            Task::Motion(_) => "motion",
            Task::Function { .. } => "function",
        }
    }
}

/// The default crank speed of a design, rad/s: one turn a second (the shaper template's
/// 360°/s).
pub const DEFAULT_OMEGA1: f64 = std::f64::consts::TAU;

/// `task = "crank-rocker"`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCrankRocker {
    name: String,
    units: Units,
    #[serde(default)]
    omega1: Option<f64>,
    psi_deg: f64,
    time_ratio: f64,
    rocker: f64,
    #[serde(default)]
    ground: Option<f64>,
    #[serde(default)]
    extreme_to_ground_deg: Option<f64>,
}

/// `task = "slider-crank"`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSliderCrank {
    name: String,
    units: Units,
    #[serde(default)]
    omega1: Option<f64>,
    stroke: f64,
    time_ratio: f64,
    #[serde(default)]
    offset: Option<f64>,
}

/// `task = "quick-return"`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawQuickReturn {
    name: String,
    units: Units,
    #[serde(default)]
    omega1: Option<f64>,
    stroke: f64,
    time_ratio: f64,
    #[serde(default)]
    crank: Option<f64>,
    #[serde(default)]
    ground: Option<f64>,
    #[serde(default)]
    link: Option<f64>,
    #[serde(default)]
    ram_height: Option<f64>,
}

/// One required position of the coupler line.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPose {
    at: [f64; 2],
    angle_deg: f64,
}

/// `task = "motion"`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMotion {
    name: String,
    units: Units,
    #[serde(default)]
    omega1: Option<f64>,
    positions: Vec<RawPose>,
    a1: [f64; 2],
    b1: [f64; 2],
    #[serde(default)]
    bisector_distance: Option<[f64; 2]>,
    #[serde(default)]
    crank: Option<bool>,
    #[serde(default)]
    turning: Option<motion::Turning>,
}

/// `task = "function"`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFunction {
    name: String,
    units: Units,
    #[serde(default)]
    omega1: Option<f64>,
    function: String,
    x_range: [f64; 2],
    input_deg: [f64; 2],
    output_deg: [f64; 2],
    ground: f64,
    #[serde(default)]
    precision_x: Option<[f64; 3]>,
}

/// Reads and checks the table of a `kind = "synthesis"` scene (`kind` removed) from `file`.
pub(super) fn check(mut table: toml::Table, file: &str) -> Result<SynthesisScene, SceneError> {
    let field = |message: String| SceneError::Field { file: file.to_string(), field: "task".into(), message };
    let task = match table.remove("task") {
        None => return Err(field(format!("missing: say what is required, one of {}", TASKS.join(", ")))),
        Some(toml::Value::String(t)) => t,
        Some(v) => return Err(field(format!("must be a string, one of {}; got {v}", TASKS.join(", ")))),
    };
    let checked = match task.as_str() {
        "crank-rocker" => crank_rocker_scene(super::read(table, file)?),
        "slider-crank" => slider_crank_scene(super::read(table, file)?),
        "quick-return" => quick_return_scene(super::read(table, file)?),
        "motion" => motion_scene(super::read(table, file)?),
        "function" => function_scene(super::read(table, file)?),
        other => return Err(field(format!("\"{other}\" is not a synthesis task; valid: {}", TASKS.join(", ")))),
    };
    checked.map_err(|e| SceneError::Field { file: file.to_string(), field: e.field, message: e.message })
}

/// The common fields: the name and the crank speed.
fn common(name: &str, omega1: Option<f64>) -> Result<(String, f64), FieldError> {
    let name = super::check_name(name)?;
    // The design is written as `<name>-design.toml` and runs under that name: it must pass
    // the same check.
    super::check_name(&format!("{name}-design"))
        .map_err(|e| FieldError::new("name", format!("{} (the design is written as `<name>-design`)", e.message)))?;
    let omega1 = finite("omega1", omega1.unwrap_or(DEFAULT_OMEGA1))?;
    if omega1 == 0.0 {
        return Err(FieldError::new(
            "omega1",
            "must not be 0: the design's crank must turn (rad/s, counter-clockwise positive)",
        ));
    }
    Ok((name, omega1))
}

/// A time ratio, checked by the solver's rule, named as the field.
fn time_ratio(k: f64) -> Result<f64, FieldError> {
    synthesis::excess_angle(k).map(|_| k).map_err(|e| FieldError::new("time_ratio", e.to_string()))
}

fn crank_rocker_scene(r: RawCrankRocker) -> Result<SynthesisScene, FieldError> {
    let (name, omega1) = common(&r.name, r.omega1)?;
    let psi = synthesis::swing(finite("psi_deg", r.psi_deg)?.to_radians())
        .map_err(|e| FieldError::new("psi_deg", e.to_string()))?;
    let choice = match (r.ground, r.extreme_to_ground_deg) {
        (Some(_), Some(_)) => {
            return Err(FieldError::new(
                "extreme_to_ground_deg",
                "give at most one free choice: `ground` (the length O1C) or `extreme_to_ground_deg` (the ground line's angle to an extreme of the rocker); without either the design with the largest γ_min is proposed",
            ));
        }
        (Some(d), None) => crank_rocker::Choice::Ground(positive("ground", d)?),
        (None, Some(a)) => crank_rocker::Choice::ExtremeToGround(finite("extreme_to_ground_deg", a)?.to_radians()),
        (None, None) => crank_rocker::Choice::BestTransmission,
    };
    let requirement = crank_rocker::Requirement {
        psi,
        time_ratio: time_ratio(r.time_ratio)?,
        rocker: positive("rocker", r.rocker)?,
        choice,
    };
    Ok(SynthesisScene { name, units: r.units, omega1, task: Task::CrankRocker(requirement) })
}

fn slider_crank_scene(r: RawSliderCrank) -> Result<SynthesisScene, FieldError> {
    let (name, omega1) = common(&r.name, r.omega1)?;
    let choice = match r.offset {
        Some(e) => slider_crank::Choice::Offset(positive("offset", e)?),
        None => slider_crank::Choice::BestTransmission,
    };
    let requirement = slider_crank::Requirement {
        stroke: positive("stroke", r.stroke)?,
        time_ratio: time_ratio(r.time_ratio)?,
        choice,
    };
    Ok(SynthesisScene { name, units: r.units, omega1, task: Task::SliderCrank(requirement) })
}

fn quick_return_scene(r: RawQuickReturn) -> Result<SynthesisScene, FieldError> {
    let (name, omega1) = common(&r.name, r.omega1)?;
    let size = match (r.crank, r.ground) {
        (Some(c), None) => quick_return::Size::Crank(positive("crank", c)?),
        (None, Some(d)) => quick_return::Size::Ground(positive("ground", d)?),
        _ => {
            return Err(FieldError::new(
                "crank",
                "give exactly one of `crank` (O1A) and `ground` (O1O3): with the stroke and K it sets the mechanism's size",
            ));
        }
    };
    let requirement = quick_return::Requirement {
        stroke: positive("stroke", r.stroke)?,
        time_ratio: time_ratio(r.time_ratio)?,
        size,
        link: r.link.map(|l| positive("link", l)).transpose()?,
        ram_height: r.ram_height.map(|h| finite("ram_height", h)).transpose()?,
    };
    Ok(SynthesisScene { name, units: r.units, omega1, task: Task::QuickReturn(requirement) })
}

fn motion_scene(r: RawMotion) -> Result<SynthesisScene, FieldError> {
    let (name, omega1) = common(&r.name, r.omega1)?;
    if !(2..=3).contains(&r.positions.len()) {
        return Err(FieldError::new(
            "positions",
            format!(
                "{} given: give 2 or 3 positions of the coupler line",
                crate::text::counted(r.positions.len() as i64, "position", "positions")
            ),
        ));
    }
    let mut poses = Vec::new();
    for (i, p) in r.positions.iter().enumerate() {
        poses.push(motion::Pose {
            at: finite_point(&format!("positions[{i}].at"), p.at)?,
            angle: finite(&format!("positions[{i}].angle_deg"), p.angle_deg)?.to_radians(),
        });
    }
    let bisector_distance = match (poses.len(), r.bisector_distance) {
        (2, Some(s)) => [finite("bisector_distance[0]", s[0])?, finite("bisector_distance[1]", s[1])?],
        (2, None) => {
            return Err(FieldError::new(
                "bisector_distance",
                "two positions leave each fixed pivot free on its perpendicular bisector: give [s_A, s_B], each pivot's signed distance from the chord's middle (positive to the left of A1 → A2, resp. B1 → B2)",
            ));
        }
        (_, Some(_)) => {
            return Err(FieldError::new(
                "bisector_distance",
                "three positions fix the pivots (where the bisectors meet): leave `bisector_distance` out",
            ));
        }
        (_, None) => [0.0, 0.0],
    };
    let requirement = motion::Requirement {
        poses,
        a1: finite_point("a1", r.a1)?,
        b1: finite_point("b1", r.b1)?,
        bisector_distance,
        crank: r.crank.unwrap_or(false),
        turning: r.turning.unwrap_or(motion::Turning::Either),
    };
    Ok(SynthesisScene { name, units: r.units, omega1, task: Task::Motion(requirement) })
}

fn function_scene(r: RawFunction) -> Result<SynthesisScene, FieldError> {
    let (name, omega1) = common(&r.name, r.omega1)?;
    let function = Expr::parse_in(&r.function, "x")
        .map_err(|e| FieldError::new("function", format!("cannot parse y = f(x): {e}")))?;
    let pair = |field: &str, v: [f64; 2]| -> Result<(f64, f64), FieldError> {
        Ok((finite(&format!("{field}[0]"), v[0])?, finite(&format!("{field}[1]"), v[1])?))
    };
    let x_range = pair("x_range", r.x_range)?;
    if x_range.0 == x_range.1 {
        return Err(FieldError::new("x_range", "must be two different values [x0, x1]"));
    }
    let deg = |(a, b): (f64, f64)| (a.to_radians(), b.to_radians());
    let input = deg(pair("input_deg", r.input_deg)?);
    let output = deg(pair("output_deg", r.output_deg)?);
    for (field, (a, b)) in [("input_deg", input), ("output_deg", output)] {
        if a == b {
            return Err(FieldError::new(field, "must span a non-zero angle: [at x0, at x1]"));
        }
    }
    let precision = match r.precision_x {
        Some(p) => {
            let mut out = [0.0; 3];
            for (i, v) in p.iter().enumerate() {
                out[i] = finite(&format!("precision_x[{i}]"), *v)?;
            }
            Some(out)
        }
        None => None,
    };
    let requirement =
        function::Requirement { x_range, input, output, ground: positive("ground", r.ground)?, precision };
    Ok(SynthesisScene { name, units: r.units, omega1, task: Task::Function { requirement, function } })
}
