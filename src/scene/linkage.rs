//! Scene kind `linkage`: a general planar linkage of named bodies, revolute and prismatic
//! joints and drivers given as expressions of time (seed 002).
//!
//! ```toml
//! kind = "linkage"
//! name = "slider-crank"
//! units = "mm"
//! time = { from = 0.0, to = 1.0, steps = 36 }   # samples at from + k·(to − from)/steps, k = 0..=steps
//!
//! [ground]                                      # fixed points, global coordinates
//! points = { O = [0.0, 0.0], G1 = [0.0, 0.0], G2 = [100.0, 0.0] }
//!
//! [[body]]
//! name = "crank"
//! points = { O = [0.0, 0.0], A = [30.0, 0.0] }  # body coordinates; the outline joins them in this order
//! at = [0.0, 0.0]                               # initial placement of the body frame (a guess)
//! angle_deg = 0.0
//!
//! [[body]]
//! name = "rod"
//! points = { A = [0.0, 0.0], B = [100.0, 0.0] }
//! at = [30.0, 0.0]
//!
//! [[body]]
//! name = "slider"
//! points = { B = [0.0, 0.0] }
//! at = [130.0, 0.0]
//!
//! [[joint]]
//! name = "O"
//! revolute = ["ground.O", "crank.O"]            # the two points coincide
//! [[joint]]
//! name = "A"
//! revolute = ["crank.A", "rod.A"]
//! [[joint]]
//! name = "B"
//! revolute = ["rod.B", "slider.B"]
//! [[joint]]
//! name = "guide"
//! prismatic = { point = "slider.B", line = ["ground.G1", "ground.G2"] }   # angle_deg: locked φ_slider − φ_guide
//!
//! [[driver]]
//! joint = "O"                                   # relative angle across a revolute (rad), or distance along a prismatic
//! law = "2*pi*t"                                # or: body = "crank" (absolute angle, rad)
//!
//! [[measure]]
//! point = "slider.B"                            # columns B.x, B.vx, B.ax
//! quantities = ["x", "vx", "ax"]
//! symbol = "B"                                  # diagrams sB, vB, aB (default: the label)
//! [[measure]]
//! body = "rod"                                  # columns rod.angle_deg, rod.omega, rod.eps
//! quantities = ["angle", "omega", "eps"]        # diagrams ψ2, ω2, ε2 (the rod is body 2)
//!
//! [diagrams]
//! x = "angle"                                   # abscissa φ1 (the driver's angle, °) or "t"
//! ```

use serde::Deserialize;
use serde::de::{MapAccess, Visitor};

use super::tolerance::{self, Tolerances};
use super::{
    FieldError, MAX_FORCE_N, MAX_GRAVITY, MAX_INERTIA_KG_M2, MAX_MASS_KG, MAX_TIME_S, MAX_TORQUE_N_M, Units, angle_deg,
    finite_point, non_negative_within, pair_within, within,
};
use crate::geom::{Point, Vector, rad, rotate};
use crate::solve::expr::Expr;
use crate::solve::linkage::{
    Anchor, Attach, Body, Driver, DriverTarget, Dynamics, Joint, JointKind, Load, LoadAction, LoadValue,
    MassProperties, Mechanism, TimeWindow,
};
use crate::solve::tolerance::linkage::{LinkageOutput, LinkageParam};

/// Largest number of time steps a scene may ask for.
pub const MAX_STEPS: u32 = 100_000;

/// Named points in file order (`{ A = [x, y], B = [x, y] }`).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct OrderedPoints(pub Vec<(String, [f64; 2])>);

impl<'de> Deserialize<'de> for OrderedPoints {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = OrderedPoints;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a table of named points, e.g. { A = [0.0, 0.0], B = [100.0, 0.0] }")
            }
            fn visit_map<M: MapAccess<'de>>(self, mut map: M) -> Result<OrderedPoints, M::Error> {
                let mut out = Vec::new();
                while let Some(key) = map.next_key::<String>()? {
                    let value: [f64; 2] = map.next_value()?;
                    out.push((key, value));
                }
                Ok(OrderedPoints(out))
            }
        }
        d.deserialize_map(V)
    }
}

/// `time = { from, to, steps }`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawTime {
    /// Start time, s.
    pub from: f64,
    /// End time, s (> from).
    pub to: f64,
    /// Number of intervals; samples are taken at both ends (steps + 1 samples).
    pub steps: u32,
}

/// `[ground]`.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawGround {
    /// Fixed points, global coordinates.
    #[serde(default)]
    pub points: OrderedPoints,
}

/// One `[[body]]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawBody {
    /// Unique name (not `ground`).
    pub name: String,
    /// Named points in body coordinates.
    pub points: OrderedPoints,
    /// Initial placement of the body frame's origin (default [0, 0]).
    #[serde(default)]
    pub at: Option<[f64; 2]>,
    /// Initial placement: angle of the body frame, degrees (default 0).
    #[serde(default)]
    pub angle_deg: f64,
    /// Mass, kg (default 0).
    pub mass: Option<f64>,
    /// Centroid in body coordinates, scene length units (default: the mean of the points).
    pub centroid: Option<[f64; 2]>,
    /// Moment of inertia about the centroid, kg·m² (default 0 for a one-point body,
    /// m·l²/12 for a two-point body; required for other bodies with a mass).
    pub inertia: Option<f64>,
}

/// `[dynamics]`.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawDynamics {
    /// Gravitational acceleration [gx, gy], m/s² (default: none).
    pub g: Option<[f64; 2]>,
}

/// A load value as written: a number or an expression of t.
#[derive(Debug, Clone, Deserialize)]
#[serde(untagged)]
pub enum RawLoadValue {
    /// A number.
    Number(f64),
    /// An expression of t, parsed like the driver laws.
    Expr(String),
}

/// One `[[load]]`: a force `at` a point, or a `torque` on a `body`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawLoad {
    /// Name for messages (default `L1`, `L2`, … by position).
    pub name: Option<String>,
    /// The point the force acts at, `body.point`.
    pub at: Option<String>,
    /// The force [fx, fy], N.
    pub force: Option<[RawLoadValue; 2]>,
    /// The body the torque acts on.
    pub body: Option<String>,
    /// The torque, N·m, counter-clockwise positive.
    pub torque: Option<RawLoadValue>,
    /// The closed range [from, to] of t where the load acts, s (default: always).
    pub t: Option<[f64; 2]>,
}

/// `prismatic = { point, line, angle_deg }`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawPrismatic {
    /// The sliding point, `body.point`.
    pub point: String,
    /// Two points of the guide body, `["body.P", "body.Q"]`; P → Q is the positive direction.
    pub line: [String; 2],
    /// Locked relative rotation φ_slider − φ_guide, degrees (default: its value in the
    /// initial placement).
    pub angle_deg: Option<f64>,
}

/// One `[[joint]]`: exactly one of `revolute`, `prismatic`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawJoint {
    /// Name (default `J1`, `J2`, … by position).
    pub name: Option<String>,
    /// Two points that coincide, `["body.P", "body.Q"]`.
    pub revolute: Option<[String; 2]>,
    /// A point on a line of another body.
    pub prismatic: Option<RawPrismatic>,
}

/// One `[[driver]]`: exactly one of `body`, `joint`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawDriver {
    /// Name for messages (default: the body or joint).
    pub name: Option<String>,
    /// Drive this body's absolute angle (radians).
    pub body: Option<String>,
    /// Drive the relative angle across this revolute joint (radians, φ of its second body
    /// minus φ of its first) or the distance along this prismatic joint (length units).
    pub joint: Option<String>,
    /// The law, an expression of t (s).
    pub law: String,
}

/// One `[[measure]]`: exactly one of `point`, `body`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawMeasure {
    /// A point, `body.point`; quantities x y vx vy ax ay v a.
    pub point: Option<String>,
    /// A body; quantities angle omega eps.
    pub body: Option<String>,
    /// Column prefix (default: the point's or body's name).
    pub label: Option<String>,
    /// Subscript of the diagrams' symbols: s_E, v_E, a_E for a point, ψ3, ω3, ε3 for a
    /// body (default: the label for a point, the body's number in the file for a body).
    pub symbol: Option<String>,
    /// What to measure.
    pub quantities: Vec<String>,
}

/// The scene as written in the file (`kind` removed).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawLinkageScene {
    /// Output file stem.
    pub name: String,
    /// Length units.
    pub units: Units,
    /// Time range.
    pub time: RawTime,
    /// Fixed points.
    #[serde(default)]
    pub ground: RawGround,
    /// Moving bodies.
    pub body: Vec<RawBody>,
    /// Joints.
    #[serde(default)]
    pub joint: Vec<RawJoint>,
    /// Drivers.
    #[serde(default)]
    pub driver: Vec<RawDriver>,
    /// Measured quantities.
    #[serde(default)]
    pub measure: Vec<RawMeasure>,
    /// How the diagrams are drawn.
    #[serde(default)]
    pub diagrams: RawDiagrams,
    /// Gravity.
    pub dynamics: Option<RawDynamics>,
    /// External forces and torques.
    #[serde(default)]
    pub load: Vec<RawLoad>,
    /// What the frames draw beside the mechanism.
    pub polygons: Option<RawPolygons>,
    /// How the frames are drawn.
    pub frames: Option<super::RawFrames>,
    /// What is computed: `"position"`, `"velocity"`, `"acceleration"`, `"forces"`.
    pub outputs: Option<Vec<String>>,
    /// `[tolerances]`: toleranced fields, watched outputs, settings
    /// ([`super::tolerance`]).
    #[serde(default)]
    pub tolerances: Option<toml::Table>,
}

/// What a linkage run computes (the scene's `outputs`; positions always).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Outputs {
    /// Velocities (and with them the velocity polygons, sliding velocities).
    pub velocity: bool,
    /// Accelerations (and the acceleration polygons, Coriolis components).
    pub acceleration: bool,
    /// Reactions and drivers' forces (needs masses or loads).
    pub forces: bool,
}

/// The names `outputs` takes.
pub const OUTPUT_NAMES: &str = "\"position\", \"velocity\", \"acceleration\", \"forces\"";

/// `[polygons]`: which polygons the frames draw and which points they show.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawPolygons {
    /// The velocity polygon (default true).
    pub velocity: Option<bool>,
    /// The acceleration polygon (default true).
    pub acceleration: Option<bool>,
    /// The force polygons, the table and the reactions on the mechanism (default true
    /// when the scene has forces).
    pub forces: Option<bool>,
    /// The points shown, by name (default: every body point).
    pub points: Option<Vec<String>>,
    /// `"groups"` (one force figure per Assur group, the default) or `"bodies"` (one per
    /// moving body).
    pub force_figures: Option<String>,
}

/// What the frames draw beside the mechanism (from `[polygons]`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Polygons {
    /// The velocity polygon.
    pub velocity: bool,
    /// The acceleration polygon.
    pub acceleration: bool,
    /// The force figures (when the scene has forces).
    pub forces: bool,
    /// The points shown (`None`: every body point).
    pub points: Option<Vec<String>>,
    /// One force figure per moving body instead of one per Assur group.
    pub per_body: bool,
}

/// `[diagrams]`.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawDiagrams {
    /// Abscissa: `"angle"` (the driver's angle φ, degrees) or `"t"` (time, s); default
    /// `"angle"` when the mechanism has a single angular driver, else `"t"`.
    pub x: Option<String>,
}

/// The abscissa of the diagrams.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DiagramAxis {
    /// The single angular driver's angle, degrees.
    DriverAngle,
    /// Time, s.
    Time,
}

/// A measured quantity.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// x of a point.
    X,
    /// y of a point.
    Y,
    /// x-velocity.
    Vx,
    /// y-velocity.
    Vy,
    /// x-acceleration.
    Ax,
    /// y-acceleration.
    Ay,
    /// Speed |v|.
    V,
    /// |a|.
    A,
    /// Body angle (reported in degrees).
    Angle,
    /// Angular velocity, rad/s.
    Omega,
    /// Angular acceleration, rad/s².
    Eps,
}

const POINT_QUANTITIES: &[(&str, Quantity)] = &[
    ("x", Quantity::X),
    ("y", Quantity::Y),
    ("vx", Quantity::Vx),
    ("vy", Quantity::Vy),
    ("ax", Quantity::Ax),
    ("ay", Quantity::Ay),
    ("v", Quantity::V),
    ("a", Quantity::A),
];
const BODY_QUANTITIES: &[(&str, Quantity)] =
    &[("angle", Quantity::Angle), ("omega", Quantity::Omega), ("eps", Quantity::Eps)];

impl Quantity {
    /// Column suffix (`x`, `vx`, `angle_deg`, `omega`…).
    pub fn column(self) -> &'static str {
        match self {
            Quantity::Angle => "angle_deg",
            q => POINT_QUANTITIES.iter().chain(BODY_QUANTITIES).find(|(_, v)| *v == q).map_or("?", |(n, _)| n),
        }
    }
}

/// What a measure looks at.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MeasureTarget {
    /// A point.
    Point(Anchor),
    /// A body.
    Body(Attach),
}

/// A checked measure: one CSV column per quantity, named `label.quantity`.
#[derive(Debug, Clone, PartialEq)]
pub struct Measure {
    /// Column prefix.
    pub label: String,
    /// Point or body.
    pub target: MeasureTarget,
    /// Quantities, in the order asked.
    pub quantities: Vec<Quantity>,
    /// Subscript of the diagrams' symbols (`E` in s_E, `3` in ω3).
    pub symbol: String,
}

/// A checked `linkage` scene.
#[derive(Debug, Clone)]
pub struct LinkageScene {
    /// Output file stem.
    pub name: String,
    /// Length units.
    pub units: Units,
    /// Sample times, s (steps + 1 of them).
    pub times: Vec<f64>,
    /// Ground points (global), in file order.
    pub ground_points: Vec<(String, Point)>,
    /// The mechanism for the solver.
    pub mechanism: Mechanism,
    /// Measures.
    pub measures: Vec<Measure>,
    /// Abscissa of the diagrams.
    pub diagram_axis: DiagramAxis,
    /// Masses, gravity and loads, when the scene has any (a body with a `mass` or an
    /// `inertia`, a `[dynamics]` table or a `[[load]]`): then the run computes forces.
    pub dynamics: Option<Dynamics>,
    /// What the frames draw beside the mechanism.
    pub polygons: Polygons,
    /// How the frames' polygon scales are chosen.
    pub frame_scales: super::FrameScales,
    /// What is computed.
    pub outputs: Outputs,
    /// `[tolerances]`, checked (boxed: most scenes have none).
    pub tolerances: Option<Box<LinkageTolerances>>,
}

/// A linkage's checked `[tolerances]`: the study and the watched outputs.
#[derive(Debug, Clone, PartialEq)]
pub struct LinkageTolerances {
    /// Dimensions, the mechanism's numbers each moves, settings.
    pub study: Tolerances<LinkageParam>,
    /// The watched outputs (points first, then angles).
    pub outputs: Vec<LinkageOutput>,
}

/// What a `[tolerances]` key of a linkage may name.
const TOLERANCE_FIELDS: &str = "ground.points.P[0|1] (a ground point's x or y), body[i].points.P[0|1] (a body point's x or y, \
in body coordinates), joint[i].prismatic.angle_deg (a prismatic joint's locked angle); quote the key, e.g. \
\"body[1].points.B\" = [0.05, 0.05]";

/// The joint anchors (joint, role: revolute 0, 1; prismatic 0 point, 1 and 2 the line)
/// made from the point `body.point` as the scene names it.
fn anchors_named(joints: &[RawJoint], spec: &str) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    for (j, raw) in joints.iter().enumerate() {
        let specs: Vec<&String> = match (&raw.revolute, &raw.prismatic) {
            (Some(pair), _) => pair.iter().collect(),
            (_, Some(p)) => std::iter::once(&p.point).chain(p.line.iter()).collect(),
            _ => Vec::new(),
        };
        out.extend(specs.iter().enumerate().filter(|(_, s)| s.as_str() == spec).map(|(role, _)| (j, role)));
    }
    out
}

/// The field a `[tolerances]` path names in a linkage (`ground.points.O[1]`,
/// `body[2].points.B[0]`, `joint[3].prismatic.angle_deg`) and its nominal value.
fn tolerance_field(
    path: &str,
    ground: &[(String, Point)],
    mech: &Mechanism,
    joints: &[RawJoint],
) -> Result<(LinkageParam, f64), String> {
    let bad = || format!("is not a number of the linkage that a tolerance can act on; valid: {TOLERANCE_FIELDS}");
    let coordinate = |rest: &str| -> Option<(String, usize)> {
        let (name, idx) = rest.strip_suffix(']')?.rsplit_once('[')?;
        let c = idx.parse::<usize>().ok().filter(|c| *c < 2)?;
        Some((name.to_string(), c))
    };
    if let Some(rest) = path.strip_prefix("ground.points.") {
        let (name, c) = coordinate(rest).ok_or_else(bad)?;
        let Some((_, at)) = ground.iter().find(|(n, _)| *n == name) else {
            return Err(format!(
                "the ground has no point `{name}`; its points are: {}",
                ground.iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>().join(", ")
            ));
        };
        let anchors = anchors_named(joints, &format!("ground.{name}"));
        if anchors.is_empty() {
            return Err(format!("ground point `{name}` is in no joint: a tolerance on it moves nothing"));
        }
        return Ok((LinkageParam::point(None, &anchors, c), if c == 0 { at.x } else { at.y }));
    }
    if let Some(rest) = path.strip_prefix("body[") {
        let (i, rest) = rest.split_once(']').ok_or_else(bad)?;
        let i: usize = i.parse().map_err(|_| bad())?;
        let rest = rest.strip_prefix(".points.").ok_or_else(bad)?;
        let (name, c) = coordinate(rest).ok_or_else(bad)?;
        let Some(body) = mech.bodies.get(i) else {
            return Err(format!("there is no body[{i}]: the scene has {} bodies (body[0]..)", mech.bodies.len()));
        };
        let Some(k) = body.points.iter().position(|(n, _)| *n == name) else {
            return Err(format!(
                "body[{i}] (`{}`) has no point `{name}`; its points are: {}",
                body.name,
                body.points.iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>().join(", ")
            ));
        };
        let v = body.points[k].1;
        let anchors = anchors_named(joints, &format!("{}.{name}", body.name));
        return Ok((LinkageParam::point(Some((i, k)), &anchors, c), if c == 0 { v.x } else { v.y }));
    }
    if let Some(rest) = path.strip_prefix("joint[") {
        let (j, rest) = rest.split_once(']').ok_or_else(bad)?;
        let j: usize = j.parse().map_err(|_| bad())?;
        if rest != ".prismatic.angle_deg" {
            return Err(bad());
        }
        return match mech.joints.get(j).map(|x| &x.kind) {
            Some(JointKind::Prismatic { angle, .. }) => Ok((LinkageParam::prismatic_angle(j), angle.to_degrees())),
            Some(_) => Err(format!("joint[{j}] is not prismatic: only a prismatic joint has a locked angle")),
            None => Err(format!("there is no joint[{j}]: the scene has {} joints (joint[0]..)", mech.joints.len())),
        };
    }
    Err(bad())
}

/// Checks a linkage's `[tolerances]` table (a motion of `count` positions).
fn check_tolerances(
    t: &toml::Table,
    ground: &[(String, Point)],
    mech: &Mechanism,
    joints: &[RawJoint],
    count: usize,
) -> Result<LinkageTolerances, FieldError> {
    let field_of = |path: &str| tolerance_field(path, ground, mech, joints);
    let study = tolerance::check(t, &tolerance::Kind { resolve: &field_of, positions: count, components: (4, 1) })?;
    if study.outputs.is_empty() {
        return Err(FieldError::new(
            "tolerances.outputs",
            "name what to watch: points = [\"body.P\", ...] (a body's point), angles = [\"body\", ...], velocities = [...] or accelerations = [...] (points or bodies)",
        ));
    }
    // A body's point as (body, point index), or why it cannot be watched.
    let body_point = |spec: &str, field: &str| -> Result<(usize, usize), FieldError> {
        let a = resolve(spec, ground, &mech.bodies).map_err(|m| FieldError::new(field, m))?;
        let Attach::Body(body) = a.body else {
            return Err(FieldError::new(field, format!("`{spec}` is a ground point: it does not move")));
        };
        let pname = spec.split_once('.').map_or("", |(_, p)| p);
        Ok((body, mech.bodies[body].points.iter().position(|(n, _)| n == pname).unwrap_or(0)))
    };
    let mut outputs = Vec::new();
    for (i, spec) in study.outputs.points.iter().enumerate() {
        let (body, point) = body_point(spec, &format!("tolerances.outputs.points[{i}]"))?;
        outputs.push(LinkageOutput::Point { name: spec.clone(), body, point });
    }
    for (i, name) in study.outputs.angles.iter().enumerate() {
        let Some(body) = mech.bodies.iter().position(|b| b.name == *name) else {
            return Err(FieldError::new(
                format!("tolerances.outputs.angles[{i}]"),
                format!(
                    "\"{name}\" is not a body; the bodies are: {}",
                    mech.bodies.iter().map(|b| b.name.as_str()).collect::<Vec<_>>().join(", ")
                ),
            ));
        };
        outputs.push(LinkageOutput::Angle { name: format!("{name}_deg"), body });
    }
    for (key, names) in [("velocities", &study.outputs.velocities), ("accelerations", &study.outputs.accelerations)] {
        let velocity = key == "velocities";
        for (i, spec) in names.iter().enumerate() {
            let field = format!("tolerances.outputs.{key}[{i}]");
            // A body's name watches its angular velocity or acceleration; `body.P`, the point's.
            if let Some(body) = mech.bodies.iter().position(|b| b.name == *spec) {
                outputs.push(if velocity {
                    LinkageOutput::Omega { name: format!("{spec}.omega"), body }
                } else {
                    LinkageOutput::Eps { name: format!("{spec}.eps"), body }
                });
                continue;
            }
            let (body, point) = body_point(spec, &field)?;
            outputs.push(if velocity {
                LinkageOutput::Velocity { name: format!("{spec}.v"), body, point }
            } else {
                LinkageOutput::Acceleration { name: format!("{spec}.a"), body, point }
            });
        }
    }
    if let Some((_, dup)) = outputs.iter().enumerate().find(|(i, o)| outputs[..*i].contains(o)) {
        return Err(FieldError::new("tolerances.outputs", format!("names {} twice", dup.name())));
    }
    Ok(LinkageTolerances { study, outputs })
}

impl LinkageScene {
    /// Resolves `body.point` (as written in scene files and `--drag`) to an anchor.
    pub fn anchor(&self, spec: &str) -> Result<Anchor, String> {
        resolve(spec, &self.ground_points, &self.mechanism.bodies)
    }

    /// `body.point` name of an anchor (for labels), if it is a named point.
    pub fn point_name(&self, a: Anchor) -> Option<&str> {
        match a.body {
            Attach::Ground => self.ground_points.iter().find(|(_, p)| p.coords == a.local).map(|(n, _)| n.as_str()),
            Attach::Body(i) => {
                self.mechanism.bodies[i].points.iter().find(|(_, p)| *p == a.local).map(|(n, _)| n.as_str())
            }
        }
    }

    /// Name of a body (`ground` for the ground).
    pub fn body_name(&self, b: Attach) -> &str {
        match b {
            Attach::Ground => "ground",
            Attach::Body(i) => &self.mechanism.bodies[i].name,
        }
    }
}

fn valid_ident(s: &str) -> bool {
    !s.is_empty() && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
}

fn resolve(spec: &str, ground: &[(String, Point)], bodies: &[Body]) -> Result<Anchor, String> {
    let Some((b, p)) = spec.split_once('.') else {
        return Err(format!("`{spec}` is not a point reference: write body.point, e.g. crank.A or ground.O1"));
    };
    let body_list =
        || std::iter::once("ground").chain(bodies.iter().map(|b| b.name.as_str())).collect::<Vec<_>>().join(", ");
    if b == "ground" {
        return match ground.iter().find(|(n, _)| n == p) {
            Some((_, pt)) => Ok(Anchor { body: Attach::Ground, local: pt.coords }),
            None => Err(format!(
                "the ground has no point `{p}`; its points are: {}",
                if ground.is_empty() {
                    "(none: add them under [ground] points)".to_string()
                } else {
                    ground.iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>().join(", ")
                }
            )),
        };
    }
    let Some(i) = bodies.iter().position(|x| x.name == b) else {
        return Err(format!("unknown body `{b}` in `{spec}`; the bodies are: {}", body_list()));
    };
    match bodies[i].points.iter().find(|(n, _)| n == p) {
        Some((_, v)) => Ok(Anchor { body: Attach::Body(i), local: *v }),
        None => Err(format!(
            "body `{b}` has no point `{p}`; its points are: {}",
            bodies[i].points.iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>().join(", ")
        )),
    }
}

/// Validates the raw scene: the time range, the ground points, the bodies, the joints, the
/// drivers against the degrees of freedom, the measures, in that order (the first field in
/// error is reported).
pub fn check(raw: RawLinkageScene) -> Result<LinkageScene, FieldError> {
    check_with(raw, Redundancy::Refused)
}

/// Whether a scene whose joints repeat equations (a redundant, passive link) is accepted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Redundancy {
    /// Refused with the counts and why ([`check`]): the solver needs independent joints.
    Refused,
    /// Accepted when the joints at the scene's placement leave as many degrees of freedom as
    /// there are drivers although the formula's count is off: `mechdraw report` draws such
    /// a scene's structure (the formula's mobility against the rank's) and stops there.
    /// Any other mismatch is refused as by [`check`].
    Accepted,
}

/// [`check`], with a redundant link accepted or not.
pub fn check_with(raw: RawLinkageScene, redundancy: Redundancy) -> Result<LinkageScene, FieldError> {
    let name = super::check_name(&raw.name)?;
    let times = check_time(&raw.time)?;
    let ground_points = check_ground(&raw.ground)?;
    let bodies = check_bodies(&raw.body)?;
    let length_scale = length_scale(&ground_points, &bodies)?;
    let joints = check_joints(&raw.joint, &ground_points, &bodies, length_scale)?;
    let drivers = check_drivers(&raw.driver, &bodies, &joints)?;
    for (k, d) in drivers.iter().enumerate() {
        let field = format!("driver[{k}].law");
        check_law_range(&field, &d.law, &times, (None, true), MAX_LAW, "a driver's value")?;
    }
    check_degrees_of_freedom(&bodies, &joints, &drivers, length_scale, redundancy)?;
    let measures = check_measures(&raw.measure, &ground_points, &bodies)?;
    let mechanism = Mechanism { bodies, joints, drivers, length_scale };
    let diagram_axis = check_diagram_axis(&raw.diagrams, &mechanism, &times)?;
    let dynamics = check_dynamics(&raw, raw.units, &ground_points, &mechanism)?;
    if let Some(d) = &dynamics {
        check_load_ranges(&d.loads, &times)?;
    }
    let polygons = check_polygons(raw.polygons.as_ref(), &mechanism)?;
    let frame_scales = super::check_frames(raw.frames.as_ref())?;
    let outputs = check_outputs(raw.outputs.as_deref(), dynamics.is_some(), &raw.measure, &measures)?;
    let tolerances = raw
        .tolerances
        .as_ref()
        .map(|t| check_tolerances(t, &ground_points, &mechanism, &raw.joint, times.len()).map(Box::new))
        .transpose()?;
    Ok(LinkageScene {
        name,
        units: raw.units,
        times,
        ground_points,
        mechanism,
        measures,
        diagram_axis,
        dynamics,
        polygons,
        frame_scales,
        outputs,
        tolerances,
    })
}

/// Largest magnitude of a driver law's value (rad or the scene's unit), rate (per s) and
/// acceleration (per s²) at the scene's times: beyond it the kinematics overflow (an
/// acceleration ω²·l at 1e15 rad/s and 1e15 units is 1e45, its inertia force 1e75 N).
pub const MAX_LAW: f64 = 1e15;

/// Refuses an expression whose value (and with `rates`, its rate or acceleration) is finite
/// but beyond ±`max` at one of `times` (within the window when given), naming the field,
/// the time and the value. A value that is not finite is the solver's to report (with the
/// time).
fn check_law_range(
    field: &str,
    law: &Expr,
    times: &[f64],
    (window, with_rates): (Option<&TimeWindow>, bool),
    max: f64,
    what: &str,
) -> Result<(), FieldError> {
    for &t in times.iter().filter(|t| window.is_none_or(|w| w.contains(**t))) {
        let j = law.eval(t);
        let parts: &[(f64, &str)] = if with_rates {
            &[(j.value, ""), (j.d1, " (its rate, per s)"), (j.d2, " (its acceleration, per s²)")]
        } else {
            &[(j.value, "")]
        };
        if let Some((v, which)) = parts.iter().find(|(v, _)| v.is_finite() && v.abs() > max) {
            return Err(FieldError::new(
                field,
                format!(
                    "`{}` gives {v:e}{which} at t = {t} s: {what} must stay within ±{max:e} over the motion",
                    crate::text::excerpt(law.source())
                ),
            ));
        }
    }
    Ok(())
}

/// The loads' expressions within their ranges ([`super::MAX_FORCE_N`], [`super::MAX_TORQUE_N_M`])
/// at the scene's times in their windows.
fn check_load_ranges(loads: &[Load], times: &[f64]) -> Result<(), FieldError> {
    for (k, load) in loads.iter().enumerate() {
        let w = (load.window.as_ref(), false);
        match &load.action {
            LoadAction::Force { force, .. } => {
                for (i, v) in force.iter().enumerate() {
                    if let LoadValue::Law(e) = v {
                        check_law_range(&format!("load[{k}].force[{i}]"), e, times, w, MAX_FORCE_N, "a force in N")?;
                    }
                }
            }
            LoadAction::Torque { torque: LoadValue::Law(e), .. } => {
                check_law_range(&format!("load[{k}].torque"), e, times, w, MAX_TORQUE_N_M, "a torque in N·m")?;
            }
            LoadAction::Torque { .. } => {}
        }
    }
    Ok(())
}

/// `outputs`: known names, `"forces"` only with masses or loads, and every measured
/// quantity computed (a velocity needs `"velocity"`, an acceleration `"acceleration"`).
/// Default: everything the scene can give (forces when it has masses or loads).
fn check_outputs(
    raw: Option<&[String]>,
    has_dynamics: bool,
    raw_measures: &[RawMeasure],
    measures: &[Measure],
) -> Result<Outputs, FieldError> {
    let Some(list) = raw else {
        return Ok(Outputs { velocity: true, acceleration: true, forces: has_dynamics });
    };
    if list.is_empty() {
        return Err(FieldError::new("outputs", format!("must name at least \"position\"; valid: {OUTPUT_NAMES}")));
    }
    let mut o = Outputs { velocity: false, acceleration: false, forces: false };
    for (i, name) in list.iter().enumerate() {
        match name.as_str() {
            "position" => {}
            "velocity" => o.velocity = true,
            "acceleration" => o.acceleration = true,
            "forces" => o.forces = true,
            other => {
                return Err(FieldError::new(
                    format!("outputs[{i}]"),
                    format!("\"{other}\" is not an output; valid: {OUTPUT_NAMES}"),
                ));
            }
        }
    }
    if o.forces && !has_dynamics {
        return Err(FieldError::new(
            "outputs",
            "\"forces\" needs masses or loads (a body's `mass`, a [dynamics] table or a [[load]])",
        ));
    }
    if o.forces && !(o.velocity && o.acceleration) {
        return Err(FieldError::new(
            "outputs",
            "\"forces\" needs \"velocity\" and \"acceleration\" too (the inertia forces are m·a)",
        ));
    }
    if o.acceleration && !o.velocity {
        return Err(FieldError::new("outputs", "\"acceleration\" needs \"velocity\" too"));
    }
    for (i, (m, rm)) in measures.iter().zip(raw_measures).enumerate() {
        for (j, q) in m.quantities.iter().enumerate() {
            let needs = match q {
                Quantity::Vx | Quantity::Vy | Quantity::V | Quantity::Omega => (!o.velocity).then_some("velocity"),
                Quantity::Ax | Quantity::Ay | Quantity::A | Quantity::Eps => {
                    (!o.acceleration).then_some("acceleration")
                }
                _ => None,
            };
            if let Some(what) = needs {
                return Err(FieldError::new(
                    format!("measure[{i}].quantities[{j}]"),
                    format!("`{}` needs \"{what}\" in `outputs`", rm.quantities[j]),
                ));
            }
        }
    }
    Ok(o)
}

/// `[polygons]`: every point named must be a point of a moving body.
fn check_polygons(raw: Option<&RawPolygons>, mech: &Mechanism) -> Result<Polygons, FieldError> {
    let raw = raw.cloned().unwrap_or_default();
    if let Some(points) = &raw.points {
        let known: Vec<&str> = mech.bodies.iter().flat_map(|b| b.points.iter().map(|(n, _)| n.as_str())).collect();
        for (i, p) in points.iter().enumerate() {
            if !known.contains(&p.as_str()) {
                let mut valid = known.clone();
                valid.sort_unstable();
                valid.dedup();
                return Err(FieldError::new(
                    format!("polygons.points[{i}]"),
                    format!("no moving body has a point `{p}`; the bodies' points are: {}", valid.join(", ")),
                ));
            }
        }
    }
    let per_body = match raw.force_figures.as_deref() {
        None | Some("groups") => false,
        Some("bodies") => true,
        Some(other) => {
            return Err(FieldError::new(
                "polygons.force_figures",
                format!(
                    "`{other}` is not a choice: \"groups\" (one force figure per Assur group, the default) or \
                     \"bodies\" (one per moving body)"
                ),
            ));
        }
    };
    Ok(Polygons {
        velocity: raw.velocity.unwrap_or(true),
        acceleration: raw.acceleration.unwrap_or(true),
        forces: raw.forces.unwrap_or(true),
        points: raw.points,
        per_body,
    })
}

/// Masses, gravity and loads: `None` when the scene has none of them (no body with a
/// `mass` or an `inertia`, no `[dynamics]`, no `[[load]]`); else every body's mass
/// properties (kg, centroid in body coordinates, kg·m²), g (m/s²) and the loads, checked.
fn check_dynamics(
    raw: &RawLinkageScene,
    units: Units,
    ground_points: &[(String, Point)],
    mech: &Mechanism,
) -> Result<Option<Dynamics>, FieldError> {
    let any_mass = raw.body.iter().any(|b| b.mass.is_some() || b.inertia.is_some());
    if !any_mass && raw.dynamics.is_none() && raw.load.is_empty() {
        return Ok(None);
    }
    let length_unit_m = match units {
        Units::Mm => 1e-3,
        Units::Si => 1.0,
    };
    let mut bodies = Vec::new();
    for (i, (rb, b)) in raw.body.iter().zip(&mech.bodies).enumerate() {
        bodies.push(check_mass_properties(&format!("body[{i}]"), rb, b, length_unit_m)?);
    }
    let gravity = match raw.dynamics.as_ref().and_then(|d| d.g) {
        Some(g) => pair_within("dynamics.g", g, MAX_GRAVITY, "an acceleration in m/s²")?,
        None => Vector::zeros(),
    };
    let mut loads: Vec<Load> = Vec::new();
    for (k, l) in raw.load.iter().enumerate() {
        let load = check_load(&format!("load[{k}]"), k, l, ground_points, &mech.bodies)?;
        if loads.iter().any(|x| x.name == load.name) {
            return Err(FieldError::new(
                format!("load[{k}].name"),
                format!("a load named `{}` already exists: give this one its own `name`", load.name),
            ));
        }
        loads.push(load);
    }
    Ok(Some(Dynamics { length_unit_m, gravity, bodies, loads }))
}

/// A body's `mass` (kg, ≥ 0, default 0), `centroid` (body coordinates, default the mean
/// of its points) and `inertia` (kg·m² about the centroid, ≥ 0; default 0 for a one-point
/// body, m·l²/12 for a two-point body of length l, required for other bodies with a mass).
fn check_mass_properties(
    field: &str,
    raw: &RawBody,
    body: &Body,
    length_unit_m: f64,
) -> Result<MassProperties, FieldError> {
    let mass = match raw.mass {
        Some(m) => non_negative_within(&format!("{field}.mass"), m, MAX_MASS_KG, "a mass in kg")?,
        None => 0.0,
    };
    let centroid = match raw.centroid {
        Some(c) => finite_point(&format!("{field}.centroid"), c)?.coords,
        None => body.points.iter().map(|(_, p)| *p).sum::<Vector>() / body.points.len() as f64,
    };
    let inertia = match (raw.inertia, body.points.as_slice()) {
        (Some(j), _) => non_negative_within(
            &format!("{field}.inertia"),
            j,
            MAX_INERTIA_KG_M2,
            "a moment of inertia in kg·m² about the centroid",
        )?,
        (None, [_]) => 0.0,
        (None, [(_, p1), (_, p2)]) => {
            let l = (p2 - p1).norm() * length_unit_m;
            mass * l * l / 12.0
        }
        (None, _) if mass == 0.0 => 0.0,
        (None, points) => {
            return Err(FieldError::new(
                format!("{field}.inertia"),
                format!(
                    "body `{}` has a mass and {} points: give its moment of inertia about the centroid, kg·m² (the \
                     default m·l²/12 is for a two-point body, a bar)",
                    body.name,
                    points.len()
                ),
            ));
        }
    };
    Ok(MassProperties { mass, centroid, inertia })
}

/// One `[[load]]`: exactly one of a force `at` a point of a moving body or a `torque` on a
/// moving body; values that are numbers or expressions of t that parse; a window
/// `t = [from, to]` with from ≤ to.
fn check_load(
    field: &str,
    k: usize,
    raw: &RawLoad,
    ground_points: &[(String, Point)],
    bodies: &[Body],
) -> Result<Load, FieldError> {
    let name = raw.name.clone().unwrap_or_else(|| format!("L{}", k + 1));
    if !valid_ident(&name) {
        return Err(FieldError::new(format!("{field}.name"), "load names use letters, digits, '_' and '-'"));
    }
    let value = |f: String, v: &RawLoadValue, max: f64, what: &str| match v {
        RawLoadValue::Number(x) => within(&f, *x, max, what).map(LoadValue::Number),
        RawLoadValue::Expr(text) => Expr::parse(text)
            .map(LoadValue::Law)
            .map_err(|e| FieldError::new(f, format!("cannot parse the expression: {e}"))),
    };
    let on_ground =
        |f: String| FieldError::new(f, "a load on the ground does nothing: put it on a moving body".to_string());
    let action = match (&raw.at, &raw.force, &raw.body, &raw.torque) {
        (Some(at), Some(force), None, None) => {
            let anchor = resolve(at, ground_points, bodies).map_err(|m| FieldError::new(format!("{field}.at"), m))?;
            if anchor.body == Attach::Ground {
                return Err(on_ground(format!("{field}.at")));
            }
            let fx = value(format!("{field}.force[0]"), &force[0], MAX_FORCE_N, "a force in N")?;
            let fy = value(format!("{field}.force[1]"), &force[1], MAX_FORCE_N, "a force in N")?;
            LoadAction::Force { at: anchor, force: [fx, fy] }
        }
        (None, None, Some(b), Some(torque)) => {
            if b == "ground" {
                return Err(on_ground(format!("{field}.body")));
            }
            let Some(i) = bodies.iter().position(|x| &x.name == b) else {
                return Err(FieldError::new(
                    format!("{field}.body"),
                    format!(
                        "unknown body `{b}`; the bodies are: {}",
                        bodies.iter().map(|b| b.name.as_str()).collect::<Vec<_>>().join(", ")
                    ),
                ));
            };
            let torque = value(format!("{field}.torque"), torque, MAX_TORQUE_N_M, "a torque in N·m")?;
            LoadAction::Torque { body: i, torque }
        }
        _ => {
            return Err(FieldError::new(
                field,
                "give either a force `at = \"body.P\"` with `force = [fx, fy]` (N), or a torque `body = \"...\"` with \
                 `torque = M` (N·m)",
            ));
        }
    };
    let window = match raw.t {
        None => None,
        Some([from, to]) => {
            let f = format!("{field}.t");
            let from = within(&f, from, MAX_TIME_S, "a time in s")?;
            let to = within(&f, to, MAX_TIME_S, "a time in s")?;
            if from > to {
                return Err(FieldError::new(
                    f,
                    format!("the window [from, to] = [{from}, {to}] has from > to: write the earlier time first"),
                ));
            }
            Some(TimeWindow { from, to })
        }
    };
    Ok(Load { name, action, window })
}

/// `[diagrams] x`: `"angle"` needs a single angular driver (a body angle or a revolute
/// joint's angle) that turns one way over the motion (else the curves would fold back);
/// the default is the angle when there is such a driver, else time.
fn check_diagram_axis(raw: &RawDiagrams, mechanism: &Mechanism, times: &[f64]) -> Result<DiagramAxis, FieldError> {
    let driver = mechanism.angular_driver();
    let one_way = driver.is_some_and(|(d, _)| crate::solve::stroke::one_way(&d.law, times));
    match raw.x.as_deref() {
        None => Ok(if one_way { DiagramAxis::DriverAngle } else { DiagramAxis::Time }),
        Some("t") => Ok(DiagramAxis::Time),
        Some("angle") if one_way => Ok(DiagramAxis::DriverAngle),
        Some("angle") => Err(FieldError::new(
            "diagrams.x",
            match driver {
                Some((d, _)) => format!(
                    "\"angle\" needs the driver's angle to turn one way over the motion, but `{}` = {} turns back or stands still: use \"t\"",
                    d.name,
                    crate::text::excerpt(d.law.source())
                ),
                None => "\"angle\" needs a single driver that turns a body or a revolute joint; this mechanism has none: use \"t\"".to_string(),
            },
        )),
        Some(other) => Err(FieldError::new("diagrams.x", format!("unknown abscissa `{other}`; valid: \"angle\", \"t\""))),
    }
}

/// `time = { from, to, steps }`: the sample times, s (steps + 1 of them).
fn check_time(raw: &RawTime) -> Result<Vec<f64>, FieldError> {
    let from = within("time.from", raw.from, MAX_TIME_S, "a time in s")?;
    let to = within("time.to", raw.to, MAX_TIME_S, "a time in s")?;
    if to <= from {
        return Err(FieldError::new("time.to", format!("must be later than time.from ({from}), got {to}")));
    }
    if raw.steps == 0 || raw.steps > MAX_STEPS {
        return Err(FieldError::new("time.steps", format!("must be 1 to {MAX_STEPS}, got {}", raw.steps)));
    }
    let steps = raw.steps;
    Ok((0..=steps).map(|k| from + (to - from) * k as f64 / steps as f64).collect())
}

/// `[ground] points`: named, finite, in file order.
fn check_ground(raw: &RawGround) -> Result<Vec<(String, Point)>, FieldError> {
    let mut ground_points = Vec::new();
    for (pname, p) in &raw.points.0 {
        let field = format!("ground.points.{pname}");
        if !valid_ident(pname) {
            return Err(FieldError::new(field, "point names use letters, digits, '_' and '-'"));
        }
        ground_points.push((pname.clone(), finite_point(&field, *p)?));
    }
    Ok(ground_points)
}

/// `[[body]]`: at least one; unique names (not `ground`); named, finite points; the
/// initial placement.
fn check_bodies(raw: &[RawBody]) -> Result<Vec<Body>, FieldError> {
    if raw.is_empty() {
        return Err(FieldError::new("body", "at least one [[body]] is needed"));
    }
    let mut bodies: Vec<Body> = Vec::new();
    for (i, b) in raw.iter().enumerate() {
        let field = format!("body[{i}]");
        if !valid_ident(&b.name) || b.name == "ground" {
            return Err(FieldError::new(
                format!("{field}.name"),
                format!("\"{}\" cannot name a body: use letters, digits, '_' and '-', and not `ground`", b.name),
            ));
        }
        if bodies.iter().any(|x| x.name == b.name) {
            return Err(FieldError::new(format!("{field}.name"), format!("a body named `{}` already exists", b.name)));
        }
        if b.points.0.is_empty() {
            return Err(FieldError::new(format!("{field}.points"), "a body needs at least one named point"));
        }
        let mut points: Vec<(String, Vector)> = Vec::new();
        for (pname, p) in &b.points.0 {
            let pf = format!("{field}.points.{pname}");
            if !valid_ident(pname) {
                return Err(FieldError::new(pf, "point names use letters, digits, '_' and '-'"));
            }
            points.push((pname.clone(), finite_point(&pf, *p)?.coords));
        }
        let at = finite_point(&format!("{field}.at"), b.at.unwrap_or([0.0, 0.0]))?;
        let angle = rad(angle_deg(&format!("{field}.angle_deg"), b.angle_deg)?);
        bodies.push(Body { name: b.name.clone(), points, at, angle });
    }
    Ok(bodies)
}

/// Characteristic length: extent of every point in the initial placement (and of every
/// body point from its body's origin). Refuses a mechanism with no size.
fn length_scale(ground_points: &[(String, Point)], bodies: &[Body]) -> Result<f64, FieldError> {
    let mut all: Vec<Point> = ground_points.iter().map(|(_, p)| *p).collect();
    for b in bodies {
        all.extend(b.points.iter().map(|(_, v)| b.at + rotate(*v, b.angle)));
    }
    let (mut lo, mut hi) = (all[0], all[0]);
    for p in &all {
        lo = Point::new(lo.x.min(p.x), lo.y.min(p.y));
        hi = Point::new(hi.x.max(p.x), hi.y.max(p.y));
    }
    let mut length_scale = (hi - lo).norm();
    for b in bodies {
        for (_, v) in &b.points {
            length_scale = length_scale.max(v.norm());
        }
    }
    if length_scale <= 0.0 || !length_scale.is_finite() {
        return Err(FieldError::new("body", "every point is at the same place: the mechanism has no size"));
    }
    Ok(length_scale)
}

/// `[[joint]]`: unique names (default `J1`, `J2`, …), each exactly one of a revolute or a
/// prismatic joint between two bodies.
fn check_joints(
    raw: &[RawJoint],
    ground_points: &[(String, Point)],
    bodies: &[Body],
    length_scale: f64,
) -> Result<Vec<Joint>, FieldError> {
    let tiny = crate::geom::tol::LENGTH_REL * length_scale;
    let mut joints: Vec<Joint> = Vec::new();
    for (k, j) in raw.iter().enumerate() {
        let field = format!("joint[{k}]");
        let name = j.name.clone().unwrap_or_else(|| format!("J{}", k + 1));
        // It names the joint's force diagrams, diagrams/<scene>/<joint>.R.svg.
        let name = super::check_file_name(&format!("{field}.name"), &name)?;
        if joints.iter().any(|x| x.name == name) {
            return Err(FieldError::new(format!("{field}.name"), format!("a joint named `{name}` already exists")));
        }
        let res = |f: String, spec: &str| resolve(spec, ground_points, bodies).map_err(|m| FieldError::new(f, m));
        let kind = match (&j.revolute, &j.prismatic) {
            (Some(pair), None) => check_revolute(&field, pair, res)?,
            (None, Some(p)) => check_prismatic(&field, p, bodies, tiny, res)?,
            _ => {
                return Err(FieldError::new(
                    field,
                    "give exactly one of `revolute = [\"body.P\", \"body.Q\"]` or `prismatic = { point = \"body.P\", line = [\"body.Q\", \"body.R\"] }`",
                ));
            }
        };
        joints.push(Joint { name, kind });
    }
    Ok(joints)
}

/// `revolute = ["body.P", "body.Q"]`: two points on two different bodies. `res` resolves
/// a point reference, naming the field in its error.
fn check_revolute(
    field: &str,
    pair: &[String; 2],
    res: impl Fn(String, &str) -> Result<Anchor, FieldError>,
) -> Result<JointKind, FieldError> {
    let a = res(format!("{field}.revolute[0]"), &pair[0])?;
    let b = res(format!("{field}.revolute[1]"), &pair[1])?;
    if a.body == b.body {
        return Err(FieldError::new(
            format!("{field}.revolute"),
            "both points are on the same body: a revolute joint connects two bodies",
        ));
    }
    Ok(JointKind::Revolute { a, b })
}

/// `prismatic = { point, line, angle_deg }`: a point of one body on a line through two
/// distinct points (farther apart than `tiny`) of another; the locked relative angle
/// defaults to its value in the initial placement.
fn check_prismatic(
    field: &str,
    p: &RawPrismatic,
    bodies: &[Body],
    tiny: f64,
    res: impl Fn(String, &str) -> Result<Anchor, FieldError>,
) -> Result<JointKind, FieldError> {
    let point = res(format!("{field}.prismatic.point"), &p.point)?;
    let q1 = res(format!("{field}.prismatic.line[0]"), &p.line[0])?;
    let q2 = res(format!("{field}.prismatic.line[1]"), &p.line[1])?;
    if q1.body != q2.body {
        return Err(FieldError::new(
            format!("{field}.prismatic.line"),
            "the two points of the line must be on the same body (the guide)",
        ));
    }
    if (q2.local - q1.local).norm() <= tiny {
        return Err(FieldError::new(
            format!("{field}.prismatic.line"),
            "the two points of the line coincide: they must be distinct to give a direction",
        ));
    }
    if point.body == q1.body {
        return Err(FieldError::new(
            format!("{field}.prismatic"),
            "the point and the line are on the same body: a prismatic joint connects two bodies",
        ));
    }
    let phi = |a: Attach| match a {
        Attach::Ground => 0.0,
        Attach::Body(i) => bodies[i].angle,
    };
    let angle = match p.angle_deg {
        Some(d) => rad(angle_deg(&format!("{field}.prismatic.angle_deg"), d)?),
        None => phi(point.body) - phi(q1.body),
    };
    Ok(JointKind::Prismatic { point, q1, q2, angle })
}

/// `[[driver]]`: a law that parses, on exactly one of a body (absolute angle) or a joint
/// (relative angle across a revolute, distance along a prismatic); unique names (default:
/// the body or joint driven), which key the drivers' forces in the outputs.
fn check_drivers(raw: &[RawDriver], bodies: &[Body], joints: &[Joint]) -> Result<Vec<Driver>, FieldError> {
    let mut drivers = Vec::new();
    for (k, d) in raw.iter().enumerate() {
        let field = format!("driver[{k}]");
        let law = Expr::parse(&d.law)
            .map_err(|e| FieldError::new(format!("{field}.law"), format!("cannot parse the law: {e}")))?;
        let (target, default_name) = match (&d.body, &d.joint) {
            (Some(b), None) => match bodies.iter().position(|x| &x.name == b) {
                Some(i) => (DriverTarget::BodyAngle(i), b.clone()),
                None => {
                    return Err(FieldError::new(
                        format!("{field}.body"),
                        format!(
                            "unknown body `{b}`; the bodies are: {}",
                            bodies.iter().map(|b| b.name.as_str()).collect::<Vec<_>>().join(", ")
                        ),
                    ));
                }
            },
            (None, Some(j)) => match joints.iter().position(|x| &x.name == j) {
                Some(i) => match joints[i].kind {
                    JointKind::Revolute { .. } => (DriverTarget::JointAngle(i), j.clone()),
                    JointKind::Prismatic { .. } => (DriverTarget::JointDistance(i), j.clone()),
                },
                None => {
                    return Err(FieldError::new(
                        format!("{field}.joint"),
                        format!(
                            "unknown joint `{j}`; the joints are: {}",
                            joints.iter().map(|j| j.name.as_str()).collect::<Vec<_>>().join(", ")
                        ),
                    ));
                }
            },
            _ => return Err(FieldError::new(field, "give exactly one of `body = \"...\"` or `joint = \"...\"`")),
        };
        // It names the driver's force diagram, diagrams/<scene>/drive.<driver>.svg.
        let name = super::check_file_name(&format!("{field}.name"), &d.name.clone().unwrap_or(default_name))?;
        if drivers.iter().any(|x: &Driver| x.name == name) {
            return Err(FieldError::new(
                format!("{field}.name"),
                format!("a driver named `{name}` already exists: give this one its own `name`"),
            ));
        }
        drivers.push(Driver { name, target, law });
    }
    Ok(drivers)
}

/// Degrees of freedom (3 per body, −2 per joint) against the number of drivers, before any
/// solving; the message says what to add or remove. When the count is off but the joints at
/// the scene's placement leave as many degrees of freedom as there are drivers (3n − rank of
/// the joint equations: a redundant, passive link such as a parallelogram's third crank),
/// the message says so: the solver needs independent joints (with [`Redundancy::Accepted`],
/// that case passes).
fn check_degrees_of_freedom(
    bodies: &[Body],
    joints: &[Joint],
    drivers: &[Driver],
    length_scale: f64,
    redundancy: Redundancy,
) -> Result<(), FieldError> {
    let dof = 3 * bodies.len() as i64 - 2 * joints.len() as i64;
    if dof != drivers.len() as i64 {
        let m = Mechanism { bodies: bodies.to_vec(), joints: joints.to_vec(), drivers: Vec::new(), length_scale };
        let q: Vec<f64> = bodies.iter().flat_map(|b| [b.at.x, b.at.y, b.angle]).collect();
        let at_placement = 3 * bodies.len() as i64 - crate::solve::linkage::structure::joint_rank(&m, &q) as i64;
        let redundant = at_placement == drivers.len() as i64 && dof < at_placement;
        if redundant && redundancy == Redundancy::Accepted {
            return Ok(());
        }
        let advice = if redundant {
            format!(
                "the count does not see that at the scene's placement the joints leave {at_placement} (3n − rank of \
                 the joint equations = {} − {}): {} joint equation(s) repeat others, a redundant (passive) link such \
                 as a parallelogram's third crank; the solver needs independent joints: remove the redundant link and \
                 its joints (`mechdraw report` draws the scene's structural analysis as it is)",
                3 * bodies.len(),
                3 * bodies.len() as i64 - at_placement,
                at_placement - dof
            )
        } else if dof <= 0 {
            "the joints leave no motion; remove a joint or add a body".to_string()
        } else if (drivers.len() as i64) < dof {
            format!("add {}", crate::text::counted(dof - drivers.len() as i64, "driver", "drivers"))
        } else {
            format!("remove {}", crate::text::counted(drivers.len() as i64 - dof, "driver", "drivers"))
        };
        return Err(FieldError::new(
            "driver",
            format!(
                "the mechanism has {} (3 × {} bodies − 2 × {} joints) but {} {} given: {advice}",
                crate::text::counted(dof, "degree of freedom", "degrees of freedom"),
                bodies.len(),
                joints.len(),
                crate::text::counted(drivers.len() as i64, "driver", "drivers"),
                if drivers.len() == 1 { "is" } else { "are" },
            ),
        ));
    }
    Ok(())
}

/// `[[measure]]`: exactly one of a point or a body, a unique label (default: the point's
/// or body's name), and at least one quantity valid for that target.
fn check_measures(
    raw: &[RawMeasure],
    ground_points: &[(String, Point)],
    bodies: &[Body],
) -> Result<Vec<Measure>, FieldError> {
    let mut measures: Vec<Measure> = Vec::new();
    for (k, m) in raw.iter().enumerate() {
        let field = format!("measure[{k}]");
        let (target, default_label, table) = match (&m.point, &m.body) {
            (Some(p), None) => {
                let a = resolve(p, ground_points, bodies).map_err(|e| FieldError::new(format!("{field}.point"), e))?;
                let label = p.split_once('.').map_or(p.as_str(), |(_, n)| n).to_string();
                (MeasureTarget::Point(a), label, POINT_QUANTITIES)
            }
            (None, Some(b)) => match bodies.iter().position(|x| &x.name == b) {
                Some(i) => (MeasureTarget::Body(Attach::Body(i)), b.clone(), BODY_QUANTITIES),
                None => return Err(FieldError::new(format!("{field}.body"), format!("unknown body `{b}`"))),
            },
            _ => return Err(FieldError::new(field, "give exactly one of `point = \"body.P\"` or `body = \"...\"`")),
        };
        let label = m.label.clone().unwrap_or(default_label);
        if !valid_ident(&label) {
            return Err(FieldError::new(format!("{field}.label"), "labels use letters, digits, '_' and '-'"));
        }
        if measures.iter().any(|x| x.label == label) {
            return Err(FieldError::new(
                format!("{field}.label"),
                format!("the label `{label}` is already used by another measure: give this one its own `label`"),
            ));
        }
        let quantities = check_quantities(&field, &m.quantities, table)?;
        let symbol = match (&m.symbol, target) {
            (Some(s), _) => s.trim().to_string(),
            (None, MeasureTarget::Body(Attach::Body(i))) => (i + 1).to_string(),
            (None, _) => label.clone(),
        };
        if symbol.is_empty() || symbol.chars().any(char::is_whitespace) {
            return Err(FieldError::new(
                format!("{field}.symbol"),
                "the symbol's subscript is one word without spaces, e.g. \"E\" (s_E) or \"3\" (ω3)",
            ));
        }
        measures.push(Measure { label, target, quantities, symbol });
    }
    Ok(measures)
}

/// The quantities of one measure, each looked up in `table` (the point's or the body's).
fn check_quantities(field: &str, raw: &[String], table: &[(&str, Quantity)]) -> Result<Vec<Quantity>, FieldError> {
    let mut quantities = Vec::new();
    for (qi, q) in raw.iter().enumerate() {
        match table.iter().find(|(n, _)| n == q) {
            Some((_, v)) => quantities.push(*v),
            None => {
                return Err(FieldError::new(
                    format!("{field}.quantities[{qi}]"),
                    format!(
                        "unknown quantity `{q}`; valid here: {}",
                        table.iter().map(|(n, _)| *n).collect::<Vec<_>>().join(" ")
                    ),
                ));
            }
        }
    }
    if quantities.is_empty() {
        return Err(FieldError::new(format!("{field}.quantities"), "list at least one quantity"));
    }
    Ok(quantities)
}

#[cfg(test)]
#[allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the code under test calls"
)]
mod tests {
    use crate::scene::{Scene, parse};
    use crate::solve::linkage::Solver;

    /// The module documentation's example scene, as written there.
    fn doc_example() -> String {
        let src = include_str!("linkage.rs");
        let lines: Vec<&str> =
            src.lines().map(|l| l.strip_prefix("//! ").or(l.strip_prefix("//!")).unwrap_or(l)).collect();
        let start = lines.iter().position(|l| *l == "```toml").unwrap() + 1;
        let end = start + lines[start..].iter().position(|l| *l == "```").unwrap();
        lines[start..end].join("\n")
    }

    #[test]
    fn documented_example_loads_and_its_slider_follows_the_slider_crank_formula() {
        let Scene::Linkage(s) = parse(&doc_example(), "doc-example.toml", &[]).unwrap() else { panic!() };
        assert_eq!(s.times.len(), 37);
        let states = Solver::new(s.mechanism.clone()).unwrap().run(&s.times).unwrap();
        let b = s.anchor("slider.B").unwrap();
        for st in &states {
            let phi = std::f64::consts::TAU * st.t;
            let x = 30.0 * phi.cos() + (100.0f64.powi(2) - (30.0 * phi.sin()).powi(2)).sqrt();
            assert!((st.point(b).x - x).abs() < 1e-9, "t = {}", st.t);
        }
    }

    #[test]
    fn field_errors_name_the_field() {
        let text = doc_example();
        let bad = text.replace("line = [\"ground.G1\", \"ground.G2\"]", "line = [\"ground.G1\", \"ground.G1\"]");
        let e = parse(&bad, "x.toml", &[]).unwrap_err().to_string();
        assert!(e.contains("joint[3].prismatic.line") && e.contains("coincide"), "{e}");
        let bad = text.replace("quantities = [\"x\", \"vx\", \"ax\"]", "quantities = [\"x\", \"omega\"]");
        let e = parse(&bad, "x.toml", &[]).unwrap_err().to_string();
        assert!(e.contains("measure[0].quantities[1]") && e.contains("unknown quantity `omega`"), "{e}");
        let bad =
            text.replace("time = { from = 0.0, to = 1.0, steps = 36 }", "time = { from = 1.0, to = 1.0, steps = 36 }");
        let e = parse(&bad, "x.toml", &[]).unwrap_err().to_string();
        assert!(e.contains("time.to"), "{e}");
        let bad = text.replace("name = \"rod\"", "name = \"crank\"");
        let e = parse(&bad, "x.toml", &[]).unwrap_err().to_string();
        assert!(e.contains("body[1].name") && e.contains("already exists"), "{e}");
        let bad = text.replace("angle_deg = 0.0\n", "angle_deg = 0.0\nmasse = 1.0\n");
        let e = parse(&bad, "x.toml", &[]).unwrap_err().to_string();
        assert!(e.contains("body[0].masse") && e.contains("unknown field"), "{e}");
        let bad = text
            .replace("law = \"2*pi*t\"", "law = \"2*pi*t\"\n[[driver]]\njoint = \"guide\"\nname = \"O\"\nlaw = \"t\"");
        let e = parse(&bad, "x.toml", &[]).unwrap_err().to_string();
        assert!(e.contains("driver[1].name") && e.contains("a driver named `O` already exists"), "{e}");
    }

    #[test]
    fn mass_properties_default_as_documented() {
        let text = doc_example()
            .replace(
                "points = { O = [0.0, 0.0], A = [30.0, 0.0] }",
                "points = { O = [0.0, 0.0], A = [30.0, 0.0] }\nmass = 2.0",
            )
            .replace("at = [130.0, 0.0]", "at = [130.0, 0.0]\nmass = 0.5")
            + "\n[[load]]\nbody = \"rod\"\ntorque = \"sin(t)\"\n";
        let Scene::Linkage(s) = parse(&text, "x.toml", &[]).unwrap() else { panic!() };
        let d = s.dynamics.unwrap();
        assert_eq!(d.length_unit_m, 1e-3);
        assert_eq!(d.gravity, crate::geom::Vector::zeros());
        // Crank: a two-point bar, 30 mm = 0.03 m: centroid mid-way, J = m·l²/12.
        assert_eq!(d.bodies[0].centroid, crate::geom::Vector::new(15.0, 0.0));
        assert!((d.bodies[0].inertia - 2.0 * 0.03 * 0.03 / 12.0).abs() < 1e-18);
        // Rod: no mass; slider: one point, J = 0.
        assert_eq!((d.bodies[1].mass, d.bodies[1].inertia), (0.0, 0.0));
        assert_eq!((d.bodies[2].mass, d.bodies[2].inertia), (0.5, 0.0));
        assert_eq!(d.loads[0].name, "L1");
        assert!(d.loads[0].window.is_none());
    }
}
