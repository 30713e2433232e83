//! The four-bar over a sweep of crank angles: [`solve_motion`] solves every angle, keeps
//! the assembly mode along the motion (and through flat positions), collects the skipped
//! angles ([`Gap`]) and the exact dead points ([`DeadPoint`]), and evaluates kinematics and
//! kineto-statics only when the scene asks for them.

use super::kinematics::{Position, Prepared, kinematics_eps};
use super::kinetostatics::{self, Dynamics, Forces};
use super::{ANGLE_EPS_DEG, FourbarError, Geometry, Grashof, LimitAngle, Reach};
use crate::geom::{self, CircleIntersection, Point, Side};

/// Largest number of crank angles a sweep may have (keeps a typo like `step = 1e-9` from
/// exhausting memory).
pub const MAX_POSITIONS: usize = 1_000_000;

/// The crank angles of a motion: `from_deg, from_deg + step_deg, …` up to and including
/// `to_deg` (within [`ANGLE_EPS_DEG`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sweep {
    /// First crank angle, degrees.
    pub from_deg: f64,
    /// Last crank angle (included when the grid lands on it), degrees; ≥ `from_deg`.
    pub to_deg: f64,
    /// Step, degrees, > 0.
    pub step_deg: f64,
}

impl Sweep {
    /// Number of crank angles.
    pub fn count(&self) -> usize {
        let n = ((self.to_deg - self.from_deg) / self.step_deg + ANGLE_EPS_DEG / self.step_deg).floor();
        if n.is_finite() && n >= 0.0 { n as usize + 1 } else { 0 }
    }

    /// The `k`-th crank angle, degrees.
    pub fn angle_deg(&self, k: usize) -> f64 {
        self.from_deg + k as f64 * self.step_deg
    }
}

/// What a scene asks to compute (its `outputs`). Positions are always computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Outputs {
    /// Velocities (poles, velocity polygons).
    pub velocity: bool,
    /// Accelerations (acceleration polygons).
    pub acceleration: bool,
    /// Kineto-statics (needs accelerations; needs `[dynamics]`).
    pub forces: bool,
}

impl Outputs {
    /// Positions, velocities, accelerations and forces.
    pub const ALL: Outputs = Outputs { velocity: true, acceleration: true, forces: true };
    /// Positions only.
    pub const POSITIONS: Outputs = Outputs { velocity: false, acceleration: false, forces: false };

    /// Whether [`Kinematics`](super::Kinematics) are evaluated: any of velocity, acceleration, forces. (The
    /// velocities and accelerations are evaluated together: a few flops more.)
    pub fn kinematics(&self) -> bool {
        self.velocity || self.acceleration || self.forces
    }
}

/// Everything the motion solver needs: the checked content of a `fourbar` scene.
#[derive(Debug, Clone, PartialEq)]
pub struct MotionSpec {
    /// Link geometry and assembly mode.
    pub geometry: Geometry,
    /// Crank angular velocity, rad/s, counter-clockwise positive, at every position.
    pub omega1: f64,
    /// Crank angular acceleration, rad/s², counter-clockwise positive, at every position
    /// (0: the crank turns uniformly). With `omega1`, the crank's state at each position of
    /// the sweep, as a textbook problem gives it (not integrated along the sweep).
    pub epsilon1: f64,
    /// Crank angles.
    pub sweep: Sweep,
    /// What to compute.
    pub outputs: Outputs,
    /// Masses, gravity and external forces (present when `outputs.forces`).
    pub dynamics: Option<Dynamics>,
}

/// Why crank angles of the sweep were skipped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum GapReason {
    /// The linkage cannot be assembled (|AC| outside the dyad's reach).
    Unassemblable(Reach),
    /// A, B, C collinear at a grid angle: velocities (and reactions) unbounded.
    Singular,
    /// A coincides with C and l_ab = l_bc: position undetermined.
    Coincident,
}

/// A run of consecutive crank angles of the sweep that were skipped (never drawn).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Gap {
    /// Where the gap begins, degrees: the exact limit angle (law of cosines, see
    /// [`Geometry::limit_angles`]) between the last solved grid angle and the first
    /// skipped one; the first skipped grid angle when the gap starts the sweep or for
    /// [`GapReason::Singular`] and [`GapReason::Coincident`].
    pub from_deg: f64,
    /// Where the gap ends, degrees: the exact limit angle between the last skipped grid
    /// angle and the next solved one (the last skipped grid angle when the gap ends the
    /// sweep). For an unassemblable gap the linkage cannot be assembled on the open
    /// interval (from_deg, to_deg).
    pub to_deg: f64,
    /// First skipped grid angle, degrees.
    pub first_skipped_deg: f64,
    /// Last skipped grid angle, degrees.
    pub last_skipped_deg: f64,
    /// Number of skipped grid angles.
    pub skipped: usize,
    /// Why.
    pub reason: GapReason,
}

impl Gap {
    /// One line for the terminal, naming the angles.
    pub fn describe(&self) -> String {
        let why = match self.reason {
            GapReason::Unassemblable(Reach::TooFar) => "cannot be assembled (|AC| > l_ab + l_bc)",
            GapReason::Unassemblable(Reach::TooClose) => "cannot be assembled (|AC| < |l_ab − l_bc|)",
            GapReason::Singular => "singular dyad (A, B, C collinear: dead point)",
            GapReason::Coincident => "undetermined (A coincides with C, l_ab = l_bc)",
        };
        if self.skipped == 1 && self.from_deg == self.to_deg {
            format!("phi1 = {}°: {why}; position skipped", fmt_deg(self.from_deg))
        } else {
            format!(
                "phi1 in ({}°, {}°): {why}; {} positions skipped ({}° … {}°)",
                fmt_deg(self.from_deg),
                fmt_deg(self.to_deg),
                self.skipped,
                fmt_deg(self.first_skipped_deg),
                fmt_deg(self.last_skipped_deg)
            )
        }
    }
}

fn fmt_deg(d: f64) -> String {
    let r = (d * 1e4).round() / 1e4;
    format!("{r}")
}

/// Kind of dead point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum DeadPointKind {
    /// The end of a range where the linkage cannot be assembled (the crank cannot pass).
    Limit,
    /// |AC| only touches the limit and turns back: the linkage passes through a
    /// flat (change-point) position, where the branch may switch.
    Touch,
}

/// A crank angle of the sweep where the transmission angle is 0° or 180° (A, B, C
/// collinear), solved exactly (law of cosines), not just the nearest grid angle.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct DeadPoint {
    /// Crank angle, degrees, within the sweep.
    pub phi1_deg: f64,
    /// Transmission angle there: 180 (|AC| = l_ab + l_bc) or 0 (|AC| = |l_ab − l_bc|).
    pub transmission_deg: f64,
    /// Limit of an unassemblable range, or a touch.
    pub kind: DeadPointKind,
}

impl DeadPoint {
    /// One line for the terminal.
    pub fn describe(&self) -> String {
        let kind = match self.kind {
            DeadPointKind::Limit => "limit of assembly",
            DeadPointKind::Touch => "flat position (branch may switch)",
        };
        format!(
            "dead point at phi1 = {}°: transmission angle {}° ({kind})",
            fmt_deg(self.phi1_deg),
            self.transmission_deg
        )
    }
}

/// The solved motion over the sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct Motion {
    /// Solved positions in sweep order (skipped angles left out; see `gaps`).
    pub positions: Vec<Position>,
    /// Kineto-statics, one per position (same index) when the scene asks for forces;
    /// empty otherwise.
    pub forces: Vec<Forces>,
    /// Skipped crank angles, in sweep order.
    pub gaps: Vec<Gap>,
    /// Dead points within the sweep, in increasing crank angle.
    pub dead_points: Vec<DeadPoint>,
    /// Grashof class of the linkage.
    pub grashof: Grashof,
}

impl Motion {
    /// Warning lines for the terminal: every gap and every dead point.
    pub fn warnings(&self) -> Vec<String> {
        self.gaps.iter().map(Gap::describe).chain(self.dead_points.iter().map(DeadPoint::describe)).collect()
    }
}

/// Dead points of `geom` within `sweep`, exact, in increasing crank angle.
pub fn dead_points(geom: &Geometry, sweep: &Sweep) -> Vec<DeadPoint> {
    let mut out = Vec::new();
    for l in geom.limit_angles() {
        // Every representative l.phi1 + 2πk within [from, to] (within ANGLE_EPS_DEG).
        let base = geom::deg(l.phi1);
        let first = base + 360.0 * ((sweep.from_deg - ANGLE_EPS_DEG - base) / 360.0).ceil();
        let mut d = first;
        while d <= sweep.to_deg + ANGLE_EPS_DEG {
            out.push(DeadPoint {
                phi1_deg: d,
                transmission_deg: l.reach.transmission_deg(),
                kind: if l.touch { DeadPointKind::Touch } else { DeadPointKind::Limit },
            });
            d += 360.0;
        }
    }
    out.sort_by(|a, b| a.phi1_deg.total_cmp(&b.phi1_deg));
    out
}

/// The representative of `angle_deg` (mod 360) in (lo, hi] (within [`ANGLE_EPS_DEG`]), if any.
fn in_bracket(angle_deg: f64, lo: f64, hi: f64) -> Option<f64> {
    let x = lo + (angle_deg - lo).rem_euclid(360.0);
    if x <= hi + ANGLE_EPS_DEG {
        Some(x)
    } else if x >= lo + 360.0 - ANGLE_EPS_DEG {
        Some(x - 360.0) // equal to lo within the tolerance
    } else {
        None
    }
}

/// The exact limit angle of kind `reach` in (lo, hi], degrees, if any.
fn limit_between(limits: &[LimitAngle], reach: Reach, lo: f64, hi: f64) -> Option<f64> {
    limits.iter().filter(|l| l.reach == reach).find_map(|l| in_bracket(geom::deg(l.phi1), lo, hi))
}

/// Builds gaps from consecutive skipped grid angles.
struct GapBuilder {
    open: Option<Gap>,
    prev_ok_deg: Option<f64>,
    gaps: Vec<Gap>,
}

impl GapBuilder {
    fn skip(&mut self, deg: f64, reason: GapReason, limits: &[LimitAngle]) {
        if let Some(g) = &mut self.open
            && g.reason == reason
            && !matches!(reason, GapReason::Singular | GapReason::Coincident)
        {
            g.last_skipped_deg = deg;
            g.to_deg = deg;
            g.skipped += 1;
            return;
        }
        self.close(None, limits);
        let from_deg = match (reason, self.prev_ok_deg) {
            (GapReason::Unassemblable(r), Some(lo)) => limit_between(limits, r, lo, deg).unwrap_or(deg),
            _ => deg,
        };
        self.open =
            Some(Gap { from_deg, to_deg: deg, first_skipped_deg: deg, last_skipped_deg: deg, skipped: 1, reason });
    }

    fn ok(&mut self, deg: f64, limits: &[LimitAngle]) {
        self.close(Some(deg), limits);
        self.prev_ok_deg = Some(deg);
    }

    /// Closes the open gap; `next_ok` is the solved grid angle after it, if any.
    fn close(&mut self, next_ok: Option<f64>, limits: &[LimitAngle]) {
        if let Some(mut g) = self.open.take() {
            if let (GapReason::Unassemblable(r), Some(hi)) = (g.reason, next_ok) {
                // The end limit lies in [last skipped, next ok): search (last, hi] and
                // accept hi only as a tolerance artefact.
                if let Some(x) = limit_between(limits, r, g.last_skipped_deg, hi) {
                    g.to_deg = x;
                }
            }
            self.gaps.push(g);
        }
    }
}

/// Whether the joints of `p` are finite numbers.
fn position_finite(p: &Position) -> bool {
    [p.a, p.b, p.m].iter().all(|q| q.x.is_finite() && q.y.is_finite())
}

/// Solves the motion over the sweep of `spec`.
///
/// Assembly mode along the motion: at the first angle of each assemblable run (the sweep
/// start, or the first angle after an unassemblable gap) B is put on the side
/// `spec.geometry.branch` of the directed line A→C. Within a run the side is kept: it can
/// only change where A, B, C are collinear. Where a [`DeadPointKind::Touch`] dead point lies
/// between the angle before the previous one and the current one, the solution nearest to
/// the linear extrapolation of B from the two previous positions is taken instead (the
/// smooth continuation through the flat position), and its side is kept from then on.
///
/// Skipped angles (unassemblable, singular when kinematics are asked for, undetermined)
/// are reported in [`Motion::gaps`]; a positions-only scene keeps a singular (flat)
/// position. Kinematics are evaluated only when `spec.outputs.kinematics()`, forces only
/// when `spec.outputs.forces` and `spec.dynamics` is present.
pub fn solve_motion(spec: &MotionSpec) -> Result<Motion, FourbarError> {
    let geom = &spec.geometry;
    let prepared = Prepared::new(geom);
    let n = spec.sweep.count().min(MAX_POSITIONS);
    let limits = geom.limit_angles();
    let touches: Vec<f64> = limits.iter().filter(|l| l.touch).map(|l| geom::deg(l.phi1)).collect();
    let want_kin = spec.outputs.kinematics();
    let dynamics = if spec.outputs.forces { spec.dynamics.as_ref() } else { None };
    let mut positions = Vec::with_capacity(n);
    let mut forces = Vec::with_capacity(if dynamics.is_some() { n } else { 0 });
    let mut gaps = GapBuilder { open: None, prev_ok_deg: None, gaps: Vec::new() };
    // The last two solved (degree, B) of the current run, newest last.
    let mut track: [Option<(f64, Point)>; 2] = [None, None];
    let mut side = geom.branch;
    let mut position_sum = 0.0;
    for k in 0..n {
        let deg = spec.sweep.angle_deg(k);
        let phi1 = geom::rad(deg);
        let (a, ix) = match prepared.dyad(phi1) {
            Ok(x) => x,
            Err(e @ FourbarError::NonFinite { .. }) => return Err(e),
            Err(e) => {
                let reason = match e {
                    FourbarError::Unassemblable { reach, .. } => GapReason::Unassemblable(reach),
                    _ => GapReason::Coincident,
                };
                gaps.skip(deg, reason, &limits);
                if matches!(reason, GapReason::Unassemblable(_)) {
                    track = [None, None];
                    side = geom.branch;
                }
                continue;
            }
        };
        let b = match ix {
            CircleIntersection::Two { left, right } => {
                let (l, r) = (left, right);
                match (track, touches.is_empty()) {
                    (_, true) | ([None, _], false) | ([_, None], false) => ix.on(side).unwrap_or(l),
                    ([Some((d0, b0)), Some((d1, b1))], false) => {
                        if touches.iter().any(|&t| in_bracket(t, d0 - ANGLE_EPS_DEG, deg).is_some()) {
                            let pred = b1 + (b1 - b0) * ((deg - d1) / (d1 - d0));
                            side = if (l - pred).norm() <= (r - pred).norm() { Side::Left } else { Side::Right };
                        }
                        ix.on(side).unwrap_or(l)
                    }
                }
            }
            CircleIntersection::Tangent(p) => p,
            CircleIntersection::None => a, // refused by `dyad`
        };
        track = [track[1], Some((deg, b))];
        let mut pos = prepared.complete(phi1, a, b);
        // Checked once after the loop (a branch here costs the positions-only loop ~20 %).
        position_sum += pos.a.x + pos.a.y + pos.b.x + pos.b.y + pos.m.x + pos.m.y;
        if want_kin {
            match kinematics_eps(geom, &pos, spec.omega1, spec.epsilon1) {
                Ok(kin) if !kin.is_finite() => {
                    let quantity = if position_finite(&pos) { "velocities and accelerations" } else { "positions" };
                    return Err(FourbarError::NonFinite { phi1_deg: deg, quantity });
                }
                Ok(kin) => pos.kin = Some(kin),
                Err(_) => {
                    gaps.skip(deg, GapReason::Singular, &limits);
                    continue;
                }
            }
            if let (Some(dynamics), Some(kin)) = (dynamics, pos.kin.as_ref()) {
                match kinetostatics::forces(geom, &pos, kin, dynamics) {
                    Ok(f) if !f.is_finite() => {
                        return Err(FourbarError::NonFinite { phi1_deg: deg, quantity: "reactions" });
                    }
                    Ok(f) => forces.push(f),
                    Err(_) => {
                        gaps.skip(deg, GapReason::Singular, &limits);
                        continue;
                    }
                }
            }
        }
        gaps.ok(deg, &limits);
        positions.push(pos);
    }
    if !position_sum.is_finite()
        && let Some(p) = positions.iter().find(|p| !position_finite(p))
    {
        return Err(FourbarError::NonFinite { phi1_deg: geom::deg(p.phi1), quantity: "positions" });
    }
    gaps.close(None, &limits);
    if positions.is_empty() {
        return Err(FourbarError::NeverAssembled { from_deg: spec.sweep.from_deg, to_deg: spec.sweep.to_deg });
    }
    Ok(Motion {
        positions,
        forces,
        gaps: gaps.gaps,
        dead_points: dead_points(geom, &spec.sweep),
        grashof: geom.grashof(),
    })
}
