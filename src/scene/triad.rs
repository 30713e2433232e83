//! Scene kind `triad`: a 6R triad, a rigid triangle A1A2A3 with its vertices on three
//! circles (seed 000). Schema and validation.
//!
//! ```toml
//! kind = "triad"
//! name = "triad-popa"
//! units = "mm"
//! o1 = [15.0, 30.0]            # ground pivots O1, O2, O3
//! o2 = [90.0, 20.0]
//! o3 = [150.0, 40.0]
//! r = [50.0, 60.0, 84.0]       # R1 = O1A1, R2 = O2A2, R3 = O3A3
//! l12 = 50.0                   # triangle sides A1A2, A2A3, A1A3
//! l23 = 50.0
//! l13 = 92.0
//! orientation = "both"         # modes searched: "both" (default), "ccw", "cw"
//! [pattern]                    # the seed's secant iteration on phi1 (all optional)
//! phi1_start_deg = 90.0
//! step_deg = 0.01
//! tol = 1e-5
//! max_iterations = 50
//! a2 = "right"                 # A2's side of the directed line O2 → A1
//! orientation = "ccw"          # which intersection is A3: sense of A1 → A2 → A3
//! [newton]                     # Newton–Raphson on (phi1, phi2, phi3) (all optional)
//! start_deg = [90.0, 100.0, 110.0]   # default: the pattern's start triangle
//! max_iterations = 50
//! ```

use serde::Deserialize;

use super::tolerance::{self, Tolerances};
use super::{FieldError, MAX_LENGTH, Units, angle_deg, finite_point, positive};
use crate::geom::{Point, Side};
use crate::solve::tolerance::triad::{TriadOutput, TriadParam};
use crate::solve::triad::Triad;

/// Which triangle orientations the all-modes search covers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum OrientationChoice {
    /// The triangle and its mirror image (the three sides alone allow both).
    #[default]
    Both,
    /// Only A1 → A2 → A3 counter-clockwise.
    Ccw,
    /// Only A1 → A2 → A3 clockwise.
    Cw,
}

/// The sense of A1 → A2 → A3 (picks the intersection that is A3 in the pattern method).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Sense {
    /// Counter-clockwise: A3 left of the directed line A1 → A2 (the seed's choice).
    #[default]
    Ccw,
    /// Clockwise: A3 right of A1 → A2.
    Cw,
}

fn default_start() -> f64 {
    90.0
}
fn default_step() -> f64 {
    0.01
}
fn default_tol() -> f64 {
    1e-5
}
fn default_iterations() -> usize {
    50
}
fn default_a2() -> Side {
    Side::Right
}

/// `[pattern]`: the seed's pattern method.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawPattern {
    /// Start angle phi1, degrees (default 90, the seed's).
    #[serde(default = "default_start")]
    pub phi1_start_deg: f64,
    /// First step Δφ, degrees, refined ÷10 each iteration (default 0.01).
    #[serde(default = "default_step")]
    pub step_deg: f64,
    /// ε: stop when |R3 − |O3A3|| < ε, in the scene's length unit (default 1e-5).
    #[serde(default = "default_tol")]
    pub tol: f64,
    /// Iteration cap (default 50).
    #[serde(default = "default_iterations")]
    pub max_iterations: usize,
    /// A2's side of the directed line O2 → A1: "left" or "right" (default "right", the
    /// seed's second root P2).
    #[serde(default = "default_a2")]
    pub a2: Side,
    /// Sense of A1 → A2 → A3, which picks A3: "ccw" (default, the seed's) or "cw".
    #[serde(default)]
    pub orientation: Sense,
}

impl Default for RawPattern {
    fn default() -> Self {
        RawPattern {
            phi1_start_deg: default_start(),
            step_deg: default_step(),
            tol: default_tol(),
            max_iterations: default_iterations(),
            a2: default_a2(),
            orientation: Sense::Ccw,
        }
    }
}

/// `[newton]`: Newton–Raphson on the three-angle system.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawNewton {
    /// Start [phi1, phi2, phi3], degrees; default: the pattern method's start triangle.
    #[serde(default)]
    pub start_deg: Option<[f64; 3]>,
    /// Iteration cap (default 50).
    #[serde(default = "default_iterations")]
    pub max_iterations: usize,
}

impl Default for RawNewton {
    fn default() -> Self {
        RawNewton { start_deg: None, max_iterations: default_iterations() }
    }
}

/// The scene as written in the file (`kind` removed).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawTriadScene {
    /// Output file stem.
    pub name: String,
    /// Length units.
    pub units: Units,
    /// Ground pivot O1.
    pub o1: [f64; 2],
    /// Ground pivot O2.
    pub o2: [f64; 2],
    /// Ground pivot O3.
    pub o3: [f64; 2],
    /// Radii R1, R2, R3.
    pub r: [f64; 3],
    /// Side A1A2.
    pub l12: f64,
    /// Side A2A3.
    pub l23: f64,
    /// Side A1A3.
    pub l13: f64,
    /// Orientations searched for assembly modes (default both).
    #[serde(default)]
    pub orientation: OrientationChoice,
    /// Pattern method settings.
    #[serde(default)]
    pub pattern: RawPattern,
    /// Newton–Raphson settings.
    #[serde(default)]
    pub newton: RawNewton,
    /// The assembly mode the picture draws, numbered from 1 as the report lists them
    /// (default: the one the pattern method reaches).
    #[serde(default)]
    pub mode: Option<i64>,
    /// `[tolerances]`: toleranced fields, watched outputs, settings
    /// ([`super::tolerance`]).
    #[serde(default)]
    pub tolerances: Option<toml::Table>,
}

/// Checked pattern-method settings (angles in radians).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatternSettings {
    /// Start angle phi1, radians.
    pub phi1_start: f64,
    /// First step, radians (non-zero).
    pub step: f64,
    /// ε, scene length units (> 0).
    pub tol: f64,
    /// Iteration cap (≥ 1).
    pub max_iterations: usize,
    /// A2's side of O2 → A1.
    pub a2: Side,
    /// Sense of A1 → A2 → A3.
    pub orientation: Sense,
}

/// Checked Newton settings (angles in radians).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonSettings {
    /// Start angles, radians; `None`: the pattern's start triangle.
    pub start: Option<[f64; 3]>,
    /// Iteration cap (≥ 1).
    pub max_iterations: usize,
}

/// A checked `triad` scene: finite pivots, positive lengths, a triangle that closes.
#[derive(Debug, Clone)]
pub struct TriadScene {
    /// Output file stem.
    pub name: String,
    /// Length units.
    pub units: Units,
    /// Ground pivots O1, O2, O3.
    pub o: [Point; 3],
    /// Radii R1, R2, R3.
    pub r: [f64; 3],
    /// Side A1A2.
    pub l12: f64,
    /// Side A2A3.
    pub l23: f64,
    /// Side A1A3.
    pub l13: f64,
    /// Orientations searched for assembly modes.
    pub orientation: OrientationChoice,
    /// Pattern method.
    pub pattern: PatternSettings,
    /// Newton–Raphson.
    pub newton: NewtonSettings,
    /// The assembly mode drawn, numbered from 1 (`None`: the pattern method's).
    pub mode: Option<usize>,
    /// `[tolerances]`, checked (boxed: most scenes have none).
    pub tolerances: Option<Box<TriadTolerances>>,
}

/// A triad's checked `[tolerances]`: the study and the watched outputs.
#[derive(Debug, Clone, PartialEq)]
pub struct TriadTolerances {
    /// Dimensions, their fields, settings.
    pub study: Tolerances<TriadParam>,
    /// The watched outputs (vertices first, then angles; the three vertices when none is
    /// named).
    pub outputs: Vec<TriadOutput>,
}

/// Most assembly modes a triad has (6 per orientation): the positions of its study.
const MAX_MODES: usize = 12;

/// Checks a triad's `[tolerances]` table.
fn check_tolerances(t: &toml::Table, triad: &Triad) -> Result<TriadTolerances, FieldError> {
    let valid = TriadParam::ALL.map(TriadParam::field).join(", ");
    let resolve = |path: &str| match TriadParam::from_field(path) {
        Some(p) => Ok((p, p.nominal(triad))),
        None => Err(format!(
            "is not a dimension of the triad that a tolerance can act on; valid: {valid} (o1, o2, o3 are points: o1[0] is x, o1[1] is y)"
        )),
    };
    let study = tolerance::check(t, &tolerance::Kind { resolve: &resolve, positions: MAX_MODES, components: (2, 1) })?;
    for (key, names) in [("velocities", &study.outputs.velocities), ("accelerations", &study.outputs.accelerations)] {
        if !names.is_empty() {
            return Err(FieldError::new(
                format!("tolerances.outputs.{key}"),
                "a triad does not move: watch its vertices (points) and angles (angles)",
            ));
        }
    }
    let mut outputs = Vec::new();
    let points = if study.outputs.points.is_empty() && study.outputs.angles.is_empty() {
        vec!["A1".to_string(), "A2".to_string(), "A3".to_string()]
    } else {
        study.outputs.points.clone()
    };
    for (i, name) in points.iter().enumerate() {
        let o = TriadOutput::point(name).ok_or_else(|| {
            FieldError::new(
                format!("tolerances.outputs.points[{i}]"),
                format!("\"{name}\" is not a vertex of the triad; valid: \"A1\", \"A2\", \"A3\""),
            )
        })?;
        outputs.push(o);
    }
    for (i, name) in study.outputs.angles.iter().enumerate() {
        let o = TriadOutput::angle(name).ok_or_else(|| {
            FieldError::new(
                format!("tolerances.outputs.angles[{i}]"),
                format!(
                    "\"{name}\" is not an angle of the triad; valid: \"phi1\", \"phi2\", \"phi3\" (the links O_iA_i), \"triangle\" (A1 → A2)"
                ),
            )
        })?;
        outputs.push(o);
    }
    if let Some(dup) = outputs.iter().enumerate().find(|(i, o)| outputs[..*i].contains(o)) {
        return Err(FieldError::new("tolerances.outputs", format!("names {} twice", dup.1.name())));
    }
    Ok(TriadTolerances { study, outputs })
}

/// Largest iteration cap accepted.
const MAX_ITERATIONS: usize = 10_000;

fn iterations(field: &str, n: usize) -> Result<usize, FieldError> {
    if (1..=MAX_ITERATIONS).contains(&n) {
        Ok(n)
    } else {
        Err(FieldError::new(field, format!("must be between 1 and {MAX_ITERATIONS}, got {n}")))
    }
}

/// Validates the raw scene.
pub fn check(raw: RawTriadScene) -> Result<TriadScene, FieldError> {
    let name = super::check_name(&raw.name)?;
    let o = [finite_point("o1", raw.o1)?, finite_point("o2", raw.o2)?, finite_point("o3", raw.o3)?];
    let r = [positive("r[0]", raw.r[0])?, positive("r[1]", raw.r[1])?, positive("r[2]", raw.r[2])?];
    let (l12, l23, l13) = (positive("l12", raw.l12)?, positive("l23", raw.l23)?, positive("l13", raw.l13)?);
    for (field, v, others, a, b) in
        [("l12", l12, "l23 + l13", l23, l13), ("l23", l23, "l12 + l13", l12, l13), ("l13", l13, "l12 + l23", l12, l23)]
    {
        if v > (a + b) * (1.0 + crate::geom::tol::LENGTH_REL) {
            return Err(FieldError::new(
                field,
                format!(
                    "{v} is longer than {others} = {}: the triangle A1A2A3 cannot close (each side must be at most the sum of the other two)",
                    a + b
                ),
            ));
        }
    }
    let p = &raw.pattern;
    let phi1_start = angle_deg("pattern.phi1_start_deg", p.phi1_start_deg)?.to_radians();
    let step = angle_deg("pattern.step_deg", p.step_deg)?;
    if step == 0.0 {
        return Err(FieldError::new(
            "pattern.step_deg",
            "must be a non-zero angle step in degrees (the seed uses 0.01)",
        ));
    }
    if !(p.tol.is_finite() && p.tol > 0.0 && p.tol <= MAX_LENGTH) {
        return Err(FieldError::new(
            "pattern.tol",
            format!(
                "must be a positive tolerance in {} of at most {MAX_LENGTH:e} (the seed uses 1e-5), got {:?}",
                raw.units.length(),
                p.tol
            ),
        ));
    }
    let pattern = PatternSettings {
        phi1_start,
        step: step.to_radians(),
        tol: p.tol,
        max_iterations: iterations("pattern.max_iterations", p.max_iterations)?,
        a2: p.a2,
        orientation: p.orientation,
    };
    let start = match raw.newton.start_deg {
        Some(s) => {
            for (i, v) in s.iter().enumerate() {
                angle_deg(&format!("newton.start_deg[{i}]"), *v)?;
            }
            Some(s.map(f64::to_radians))
        }
        None => None,
    };
    let newton =
        NewtonSettings { start, max_iterations: iterations("newton.max_iterations", raw.newton.max_iterations)? };
    let mode = match raw.mode {
        None => None,
        Some(m) if m >= 1 => Some(usize::try_from(m).unwrap_or(usize::MAX)),
        Some(m) => {
            return Err(FieldError::new(
                "mode",
                format!(
                    "must be 1 or more, a whole number ≥ 1 (the assembly modes are numbered from 1 as the report lists them), got {m}"
                ),
            ));
        }
    };
    // The lengths are checked above, so the triad is one.
    let tolerances = match (&raw.tolerances, Triad::new(o, r, l12, l23, l13)) {
        (Some(t), Ok(triad)) => Some(Box::new(check_tolerances(t, &triad)?)),
        _ => None,
    };
    Ok(TriadScene {
        name,
        units: raw.units,
        o,
        r,
        l12,
        l23,
        l13,
        orientation: raw.orientation,
        pattern,
        newton,
        mode,
        tolerances,
    })
}

#[cfg(test)]
mod tests {
    use crate::scene::{Override, Scene, SceneError, parse};

    const SEED: &str = r#"
kind = "triad"
name = "triad-popa"
units = "mm"
o1 = [15.0, 30.0]
o2 = [90.0, 20.0]
o3 = [150.0, 40.0]
r = [50.0, 60.0, 84.0]
l12 = 50.0
l23 = 50.0
l13 = 92.0
[pattern]
phi1_start_deg = 90.0
step_deg = 0.01
tol = 1e-5
"#;

    fn field_error(text: &str, sets: &[&str]) -> (String, String) {
        let o: Vec<Override> = sets.iter().map(|s| s.parse().unwrap()).collect();
        match parse(text, "t.toml", &o) {
            Err(SceneError::Field { field, message, .. }) => (field, message),
            other => panic!("expected a field error, got {other:?}"),
        }
    }

    #[test]
    fn the_design_example_loads_with_defaults() {
        let Scene::Triad(s) = parse(SEED, "t.toml", &[]).unwrap() else { panic!() };
        assert_eq!(s.r, [50.0, 60.0, 84.0]);
        assert_eq!(s.pattern.max_iterations, 50);
        assert_eq!(s.orientation, super::OrientationChoice::Both);
        assert!((s.pattern.step - 0.01f64.to_radians()).abs() < 1e-18);
        assert!(s.newton.start.is_none());
    }

    #[test]
    fn bad_values_name_their_field() {
        assert_eq!(field_error(SEED, &["l12=-5"]).0, "l12");
        assert_eq!(field_error(SEED, &["r[2]=0"]).0, "r[2]");
        let (f, m) = field_error(SEED, &["l13=120"]);
        assert_eq!(f, "l13");
        assert!(m.contains("l12 + l23 = 100"), "{m}");
        assert_eq!(field_error(SEED, &["l23=200"]).0, "l23");
        assert_eq!(field_error(SEED, &["pattern.tol=0"]).0, "pattern.tol");
        assert_eq!(field_error(SEED, &["pattern.step_deg=0"]).0, "pattern.step_deg");
        assert_eq!(field_error(SEED, &["orientation=\"up\""]).0, "orientation");
        assert_eq!(field_error(SEED, &["pattern.a2=\"middle\""]).0, "pattern.a2");
        assert_eq!(field_error(SEED, &["newton.start_deg=[1, 2]"]).0, "newton.start_deg");
        assert_eq!(field_error(SEED, &["l14=3"]).0, "l14");
        assert_eq!(field_error(&SEED.replace("l23 = 50.0\n", ""), &[]).0, "l23");
    }

    #[test]
    fn a_flat_triangle_is_accepted() {
        assert!(parse(SEED, "t.toml", &["l13=100".parse().unwrap()]).is_ok());
    }
}
