//! The check table: what the design must do against what mechdraw's own analysis of the
//! written scene finds (`<name>-design.toml` parsed back as any scene is, then solved by
//! the `fourbar` or `linkage` solver). Analysis and synthesis share no code: the
//! four-bar's rocker extremes come from its circle intersection and its rates (Newton on
//! ω3 = 0), the linkages' strokes from the Assur groups and [`crate::solve::stroke`], a
//! coupler position or an output angle from the four-bar's position at the crank angle
//! asked for.

use serde::Serialize;

use crate::geom::{Point, Side, angle_of, wrap_pi};
use crate::scene::fourbar::FourbarScene;
use crate::scene::linkage::{LinkageScene, MeasureTarget};
use crate::scene::{self, Scene};
use crate::solve::fourbar::{Geometry, kinematics, position};
use crate::solve::linkage::{AssurSolver, Attach, Solver};
use crate::solve::stroke;

/// Relative tolerance on ψ, K and H: the 1e-9.
pub const TOL_REL: f64 = 1e-9;
/// Tolerance on a coupler position: its point within 1e-9 of the mechanism's size, its
/// angle within 1e-9 rad.
pub const TOL_POSE: f64 = 1e-9;
/// Tolerance on the generated function at a precision point, relative to the output's
/// range |y(x1) − y(x0)|.
pub const TOL_FUNCTION: f64 = 1e-12;
/// Samples of the crank's turn searched for the rocker's extremes before Newton refines them.
const EXTREME_SAMPLES: usize = 720;

/// One row: a required value against the analysis's.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Row {
    /// What is compared (`ψ [°]`, `K`, `H [mm]`, `P2 x [mm]`).
    pub quantity: String,
    /// Required.
    pub required: f64,
    /// Achieved, by the analysis.
    pub achieved: f64,
    /// |achieved − required|.
    pub error: f64,
    /// The largest error accepted.
    pub tolerance: f64,
    /// error ≤ tolerance.
    pub ok: bool,
}

impl Row {
    /// A row comparing `achieved` with `required` to `tolerance`.
    pub fn new(quantity: impl Into<String>, required: f64, achieved: f64, tolerance: f64) -> Row {
        let error = (achieved - required).abs();
        Row { quantity: quantity.into(), required, achieved, error, tolerance, ok: error <= tolerance }
    }
}

/// The check of a design: its rows and how the analysis got them.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Check {
    /// The rows.
    pub rows: Vec<Row>,
    /// The analysis's route, in words.
    pub route: String,
}

impl Check {
    /// Whether every row is within its tolerance.
    pub fn ok(&self) -> bool {
        self.rows.iter().all(|r| r.ok)
    }
}

/// The scene in `text` (the design file), parsed as `mechdraw run` parses it.
pub fn parse(text: &str, file: &str) -> Result<Scene, String> {
    scene::parse(text, file, &[]).map_err(|e| format!("the design does not load: {e}"))
}

/// The four-bar scene of a design, or why not.
pub fn fourbar_scene(s: &Scene) -> Result<&FourbarScene, String> {
    match s {
        Scene::Fourbar(f) => Ok(f),
        other => Err(format!("the design is a {} scene, not a fourbar", other.kind())),
    }
}

/// The linkage scene of a design, or why not.
pub fn linkage_scene(s: &Scene) -> Result<&LinkageScene, String> {
    match s {
        Scene::Linkage(l) => Ok(l),
        other => Err(format!("the design is a {} scene, not a linkage", other.kind())),
    }
}

/// The rocker's angle φ3 (direction C → B) at crank angle `phi1`, on the scene's branch.
fn phi3(g: &Geometry, phi1: f64) -> Result<f64, String> {
    position(g, phi1, g.branch).map(|p| p.phi3()).map_err(|e| e.to_string())
}

/// The crank angle near `phi1` where the rocker stands still (ω3 = 0), by Newton's method
/// with the four-bar's exact rates at ω1 = 1 (dφ3/dφ1 = ω3, d²φ3/dφ1² = ε3).
fn still(g: &Geometry, mut phi1: f64) -> Result<f64, String> {
    for _ in 0..60 {
        let p = position(g, phi1, g.branch).map_err(|e| e.to_string())?;
        let k = kinematics(g, &p, 1.0).map_err(|e| e.to_string())?;
        if k.eps3 == 0.0 {
            break;
        }
        let step = k.omega3 / k.eps3;
        phi1 -= step;
        if step.abs() <= 1e-16 * phi1.abs().max(1.0) {
            break;
        }
    }
    Ok(phi1)
}

/// The rocker's swing and the time ratio of a crank-rocker design, by the analysis.
/// Returns (ψ, K, crank angles at the smallest and the largest φ3).
pub fn swing(g: &Geometry) -> Result<(f64, f64, [f64; 2]), String> {
    let n = EXTREME_SAMPLES;
    let mut last = phi3(g, 0.0)?;
    let mut unwrapped = vec![last];
    for k in 1..n {
        let v = phi3(g, std::f64::consts::TAU * k as f64 / n as f64)?;
        last += wrap_pi(v - last);
        unwrapped.push(last);
    }
    let arg = |better: fn(f64, f64) -> bool| {
        (0..n).fold(0, |best, k| if better(unwrapped[k], unwrapped[best]) { k } else { best })
    };
    let (kmin, kmax) = (arg(|a, b| a < b), arg(|a, b| a > b));
    let at = |k: usize| std::f64::consts::TAU * k as f64 / n as f64;
    let (lo, hi) = (still(g, at(kmin))?, still(g, at(kmax))?);
    let psi = wrap_pi(phi3(g, hi)? - phi3(g, lo)?).abs();
    let forward = (hi - lo).rem_euclid(std::f64::consts::TAU);
    let back = std::f64::consts::TAU - forward;
    Ok((psi, forward.max(back) / forward.min(back), [lo, hi]))
}

/// H and K of the first measured point that slides on a ground guide, by the linkage
/// solver's Assur groups and [`stroke::stroke`].
pub fn stroke(scene: &LinkageScene) -> Result<(f64, f64), String> {
    let (anchor, guide) = scene
        .measures
        .iter()
        .find_map(|m| match m.target {
            MeasureTarget::Point(a) => match a.body {
                Attach::Body(i) => scene.mechanism.ground_guide(i).map(|(_, u)| (a, u)),
                Attach::Ground => None,
            },
            MeasureTarget::Body(_) => None,
        })
        .ok_or("the design measures no point on a ground guide")?;
    let mut assur = AssurSolver::new(scene.mechanism.clone()).map_err(|e| e.to_string())?;
    let states = assur.run(&scene.times).map_err(|e| e.to_string())?;
    let mut solver = Solver::new(scene.mechanism.clone()).map_err(|e| e.to_string())?;
    let st = stroke::stroke(&mut solver, &states, anchor, guide).map_err(|e| e.to_string())?;
    let k = st.cycle.map_err(|why| format!("no time ratio: {}", why.text()))?.k;
    Ok((st.h, k))
}

/// The coupler's point M and the direction A → B at crank angle `phi1`, by the analysis.
pub fn coupler(g: &Geometry, phi1: f64) -> Result<(Point, f64, Side), String> {
    let p = position(g, phi1, g.branch).map_err(|e| e.to_string())?;
    let side = p.side(g).unwrap_or(g.branch);
    Ok((p.m, angle_of(p.b - p.a), side))
}

/// The rocker's direction C → B at crank angle `phi1` on the scene's branch.
pub fn output_angle(g: &Geometry, phi1: f64) -> Result<f64, String> {
    phi3(g, phi1)
}
