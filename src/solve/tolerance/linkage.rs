//! The general linkage under tolerances: its toleranced numbers ([`LinkageParam`]: a body
//! point's or a ground point's coordinate, a prismatic joint's locked angle), its watched
//! outputs ([`LinkageOutput`]: a body point's position, a body's angle), their sensitivities
//! from the position equations, and a sample solved at every position through the Assur
//! route ([`LinkageModel`]).
//!
//! Sensitivities (implicit function theorem): at a solved position Φ(q, p) = 0, so
//! Φq·∂q/∂p = −∂Φ/∂p, solved on the general solver's equilibrated factorisation of Φq at
//! the nominal q. ∂Φ/∂p is the central difference of Φ at that fixed q between the
//! mechanisms with the dimension at p ± h: every constraint is a polynomial of degree ≤ 2
//! in a body point's or a ground point's coordinates (a revolute's r_a − r_b is linear in
//! them, a prismatic's n·(r_P − r_Q) is linear in P and Q and the guide's direction is
//! normalised), and affine in a locked angle, so the difference is exact but for rounding
//! and the guide direction's normalisation (relative error ~ (h/L)², h/L =
//! [`DIFFERENCE_STEP`]). A watched point r = R + A(φ)·s then moves by
//! dR + dφ·A(φ)·s⊥ + A(φ)·ds (ds the point's own toleranced coordinate).
//!
//! Samples: a thread's [`AssurSolver`] of the nominal is refitted to each sample
//! ([`AssurSolver::refit`]: every toleranced number moved by its deviation — a body point
//! and the joint anchors made from it, a ground point's anchors, a locked angle — the
//! constraints and the groups' closed forms recompiled, nothing decomposed or allocated),
//! resumed from the nominal's state at the first position and swept over the motion by the
//! groups' closed forms: the first position from the nominal's pose, each next one from the
//! one before, each group's root the one nearest the prediction (the nominal's assembly
//! mode, kept by continuity). A position the sample cannot be assembled at is marked, and
//! the sweep resumes after it from the nominal's state there.

use super::monte_carlo::Model;
use super::{Dimension, wrap_deg};
use crate::geom::{Point, Vector, perp, rotate};
use crate::solve::linkage::{AssurSolver, Attach, JointKind, LinkageError, Mechanism, Motion, Solver, State};

/// ∂q̇/∂p and ∂q̈/∂p at one position, field-major.
type RateSensitivities = (Vec<f64>, Vec<f64>);

/// Coordinates, velocities and accelerations (q, q̇, q̈) of one position.
type Rates<'a> = (&'a [f64], &'a [f64], &'a [f64]);

/// The step of the central difference of Φ, relative to the mechanism's length scale (for
/// a coordinate) or in degrees (for an angle).
pub const DIFFERENCE_STEP: f64 = 1e-5;

/// One number of the mechanism a toleranced scene field moves, and how much per unit of
/// the field (1 for a coordinate, π/180 for an angle in degrees).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Slot {
    /// Coordinate `coord` (0 x, 1 y) of point `point` of body `body`.
    BodyPoint { body: usize, point: usize, coord: usize },
    /// Coordinate `coord` of anchor `role` (revolute: 0 a, 1 b; prismatic: 0 point, 1 q1,
    /// 2 q2) of joint `joint`.
    Anchor { joint: usize, role: usize, coord: usize },
    /// The locked relative angle of prismatic joint `joint`, radians.
    Angle { joint: usize },
}

/// A toleranced field of a linkage scene, resolved to the mechanism's numbers it moves.
#[derive(Debug, Clone, PartialEq)]
pub struct LinkageParam {
    slots: Vec<Slot>,
    /// Mechanism units per field unit (1, or π/180 for degrees).
    slope: f64,
    /// Whether the field is a length (its difference step scales with the mechanism).
    length: bool,
}

fn coord(v: &mut Vector, c: usize) -> &mut f64 {
    if c == 0 { &mut v.x } else { &mut v.y }
}

/// The number a slot names in `mech` (`None` if the mechanism has no such anchor).
fn slot(mech: &mut Mechanism, s: Slot) -> Option<&mut f64> {
    match s {
        Slot::BodyPoint { body, point, coord: c } => {
            Some(coord(&mut mech.bodies.get_mut(body)?.points.get_mut(point)?.1, c))
        }
        Slot::Anchor { joint, role, coord: c } => {
            let a = match (&mut mech.joints.get_mut(joint)?.kind, role) {
                (JointKind::Revolute { a, .. }, 0) | (JointKind::Prismatic { point: a, .. }, 0) => a,
                (JointKind::Revolute { b: a, .. }, 1) | (JointKind::Prismatic { q1: a, .. }, 1) => a,
                (JointKind::Prismatic { q2: a, .. }, 2) => a,
                _ => return None,
            };
            Some(coord(&mut a.local, c))
        }
        Slot::Angle { joint } => match &mut mech.joints.get_mut(joint)?.kind {
            JointKind::Prismatic { angle, .. } => Some(angle),
            JointKind::Revolute { .. } => None,
        },
    }
}

impl LinkageParam {
    /// Coordinate `c` (0 x, 1 y) of a point: of body point `point` (body, index in the
    /// body; `None` for a ground point) and of the joint anchors made from it (`anchors`:
    /// joint, role — revolute 0 a, 1 b; prismatic 0 point, 1 q1, 2 q2). The caller names
    /// them: two points at the same place (a ground pivot and a guide's end) are two fields.
    pub fn point(point: Option<(usize, usize)>, anchors: &[(usize, usize)], c: usize) -> LinkageParam {
        let mut slots: Vec<Slot> =
            point.map(|(body, point)| Slot::BodyPoint { body, point, coord: c }).into_iter().collect();
        slots.extend(anchors.iter().map(|&(joint, role)| Slot::Anchor { joint, role, coord: c }));
        LinkageParam { slots, slope: 1.0, length: true }
    }

    /// The locked angle of prismatic joint `joint`, in degrees.
    pub fn prismatic_angle(joint: usize) -> LinkageParam {
        LinkageParam { slots: vec![Slot::Angle { joint }], slope: std::f64::consts::PI / 180.0, length: false }
    }

    /// Adds the deviation `d` (the field's unit) to every number the field moves in `mech`.
    pub fn apply(&self, mech: &mut Mechanism, d: f64) {
        let v = d * self.slope;
        for s in &self.slots {
            if let Some(x) = slot(mech, *s) {
                *x += v;
            }
        }
    }

    /// The prismatic joint whose locked angle the field is, if it is one.
    fn locked_angle(&self) -> Option<usize> {
        self.slots.iter().find_map(|s| match *s {
            Slot::Angle { joint } => Some(joint),
            _ => None,
        })
    }

    /// Sets every number the field moves in `mech` back to its value in `nominal`.
    fn reset(&self, mech: &mut Mechanism, nominal: &mut Mechanism) {
        for s in &self.slots {
            if let (Some(x), Some(n)) = (slot(mech, *s), slot(nominal, *s)) {
                *x = *n;
            }
        }
    }

    /// How far the field's own coordinate of body `body`'s point `point` moves per unit
    /// of the field (0, or 1 along x or y).
    fn moves_point(&self, body: usize, point: usize) -> Vector {
        let mut v = Vector::zeros();
        for s in &self.slots {
            if let Slot::BodyPoint { body: b, point: p, coord: c } = *s
                && b == body
                && p == point
            {
                *coord(&mut v, c) += self.slope;
            }
        }
        v
    }
}

/// A watched output of a linkage.
#[derive(Debug, Clone, PartialEq)]
pub enum LinkageOutput {
    /// Point `point` of body `body`: two channels, x and y.
    Point {
        /// Its name in columns (`rod.B`).
        name: String,
        /// The body.
        body: usize,
        /// The point's index in the body.
        point: usize,
    },
    /// Body `body`'s angle, degrees: one channel.
    Angle {
        /// Its name in columns (`rod_deg`).
        name: String,
        /// The body.
        body: usize,
    },
    /// The velocity (units/s) of point `point` of body `body`: two channels, x and y.
    Velocity {
        /// Its name in columns (`piston.B.v`).
        name: String,
        /// The body.
        body: usize,
        /// The point's index in the body.
        point: usize,
    },
    /// The acceleration (units/s²) of point `point` of body `body`: two channels.
    Acceleration {
        /// Its name in columns (`piston.B.a`).
        name: String,
        /// The body.
        body: usize,
        /// The point's index in the body.
        point: usize,
    },
    /// Body `body`'s angular velocity, rad/s, counter-clockwise positive: one channel.
    Omega {
        /// Its name in columns (`rod.omega`).
        name: String,
        /// The body.
        body: usize,
    },
    /// Body `body`'s angular acceleration, rad/s²: one channel.
    Eps {
        /// Its name in columns (`rod.eps`).
        name: String,
        /// The body.
        body: usize,
    },
}

impl LinkageOutput {
    /// The output's name in columns.
    pub fn name(&self) -> &str {
        match self {
            LinkageOutput::Point { name, .. }
            | LinkageOutput::Angle { name, .. }
            | LinkageOutput::Velocity { name, .. }
            | LinkageOutput::Acceleration { name, .. }
            | LinkageOutput::Omega { name, .. }
            | LinkageOutput::Eps { name, .. } => name,
        }
    }

    /// Its channels: 2 for a point's position, velocity or acceleration, 1 for a body's
    /// angle or its rates.
    pub fn channels(&self) -> usize {
        if self.is_vector() { 2 } else { 1 }
    }

    /// Whether it is a point's (two channels).
    pub fn is_vector(&self) -> bool {
        matches!(
            self,
            LinkageOutput::Point { .. } | LinkageOutput::Velocity { .. } | LinkageOutput::Acceleration { .. }
        )
    }

    /// Whether it is a rate (a velocity or an acceleration).
    pub fn is_rate(&self) -> bool {
        !matches!(self, LinkageOutput::Point { .. } | LinkageOutput::Angle { .. })
    }

    /// The body and point whose position, velocity or acceleration it is.
    pub fn point(&self) -> Option<(usize, usize)> {
        match *self {
            LinkageOutput::Point { body, point, .. }
            | LinkageOutput::Velocity { body, point, .. }
            | LinkageOutput::Acceleration { body, point, .. } => Some((body, point)),
            _ => None,
        }
    }
}

/// Why a linkage cannot be studied.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LinkageToleranceError {
    /// The nominal mechanism cannot be solved over its motion.
    #[error("the nominal mechanism: {0}")]
    Nominal(#[from] LinkageError),
}

/// The linkage under tolerances: the nominal mechanism and its solved states, the
/// toleranced fields and the watched outputs, the sensitivities at every position.
#[derive(Debug, Clone)]
pub struct LinkageModel {
    mechanism: Mechanism,
    times: Vec<f64>,
    params: Vec<LinkageParam>,
    outputs: Vec<LinkageOutput>,
    /// The nominal's states (positions and rates) at `times`.
    states: Vec<State>,
    /// Channel values of the nominal, position-major.
    nominal: Vec<f64>,
    channels: usize,
    /// ∂channel/∂field per position (channel-major), `None` where Φq is singular.
    sensitivities: Vec<Option<Vec<f64>>>,
}

/// Per-thread buffers of the samples: a solver of the nominal mechanism (refitted to each
/// sample), a copy of the nominal's numbers, and the sample's q over the motion.
#[derive(Debug)]
pub struct LinkageWork {
    solver: Option<AssurSolver>,
    nominal: Mechanism,
    /// The sample's q over the motion (and q̇, q̈ when a rate is watched).
    motion: Motion,
    /// The state a sample starts from (the nominal's first, its locked angles the sample's).
    start: Option<State>,
}

impl LinkageModel {
    /// The model of `mechanism` solved at `times` (through the Assur route, as a run
    /// solves it), with the fields `params` toleranced and `outputs` watched.
    pub fn new(
        mechanism: Mechanism,
        times: &[f64],
        params: Vec<LinkageParam>,
        outputs: Vec<LinkageOutput>,
    ) -> Result<LinkageModel, LinkageToleranceError> {
        let states = AssurSolver::new(mechanism.clone())?.run(times)?;
        let channels = outputs.iter().map(LinkageOutput::channels).sum();
        let mut nominal = Vec::with_capacity(states.len() * channels);
        for s in &states {
            Self::values(&mechanism, &outputs, (&s.q, &s.qd, &s.qdd), &mut nominal);
        }
        let mut model = LinkageModel {
            mechanism,
            times: times.to_vec(),
            params,
            outputs,
            states,
            nominal,
            channels,
            sensitivities: Vec::new(),
        };
        model.sensitivities = model.all_sensitivities()?;
        Ok(model)
    }

    /// Appends the outputs' values at coordinates `q`, velocities `qd` and accelerations
    /// `qdd` of `mech` (angles in degrees).
    fn values(mech: &Mechanism, outputs: &[LinkageOutput], (q, qd, qdd): Rates<'_>, out: &mut Vec<f64>) {
        for o in outputs {
            let v = match *o {
                LinkageOutput::Point { body, point, .. } => Self::point(mech, q, body, point).coords,
                LinkageOutput::Angle { body, .. } => Vector::new(q[3 * body + 2].to_degrees(), 0.0),
                LinkageOutput::Velocity { body, point, .. } => {
                    let s = rotate(mech.bodies[body].points[point].1, q[3 * body + 2]);
                    Vector::new(qd[3 * body], qd[3 * body + 1]) + perp(s) * qd[3 * body + 2]
                }
                LinkageOutput::Acceleration { body, point, .. } => {
                    let s = rotate(mech.bodies[body].points[point].1, q[3 * body + 2]);
                    let w = qd[3 * body + 2];
                    Vector::new(qdd[3 * body], qdd[3 * body + 1]) + perp(s) * qdd[3 * body + 2] - s * (w * w)
                }
                LinkageOutput::Omega { body, .. } => Vector::new(qd[3 * body + 2], 0.0),
                LinkageOutput::Eps { body, .. } => Vector::new(qdd[3 * body + 2], 0.0),
            };
            out.extend_from_slice(&[v.x, v.y][..o.channels()]);
        }
    }

    #[inline]
    fn point(mech: &Mechanism, q: &[f64], body: usize, point: usize) -> Point {
        Point::new(q[3 * body], q[3 * body + 1]) + rotate(mech.bodies[body].points[point].1, q[3 * body + 2])
    }

    /// The nominal channel values, position-major.
    pub fn nominal(&self) -> &[f64] {
        &self.nominal
    }

    /// The watched outputs.
    pub fn outputs(&self) -> &[LinkageOutput] {
        &self.outputs
    }

    /// The nominal's states at the watched positions.
    pub fn states(&self) -> &[State] {
        &self.states
    }

    /// The nominal mechanism.
    pub fn mechanism(&self) -> &Mechanism {
        &self.mechanism
    }

    /// Each field's difference step, in its unit.
    fn step(&self, p: &LinkageParam) -> f64 {
        if p.length { DIFFERENCE_STEP * self.mechanism.length_scale } else { DIFFERENCE_STEP }
    }

    /// ∂channel/∂field at every position (see the module's doc).
    fn all_sensitivities(&self) -> Result<Vec<Option<Vec<f64>>>, LinkageToleranceError> {
        let deviated = |p: &LinkageParam, d: f64| -> Result<Solver, LinkageError> {
            let mut m = self.mechanism.clone();
            p.apply(&mut m, d);
            Solver::new(m)
        };
        let mut pairs = Vec::with_capacity(self.params.len());
        for p in &self.params {
            let h = self.step(p);
            pairs.push((deviated(p, h)?, deviated(p, -h)?, h));
        }
        let mut nominal = Solver::new(self.mechanism.clone())?;
        let n = nominal.coordinates();
        let np = self.params.len();
        let rates = self.outputs.iter().any(LinkageOutput::is_rate);
        let mut out = Vec::with_capacity(self.states.len());
        for s in &self.states {
            // Columns −∂Φ/∂p, one per field, solved in place into ∂q/∂p.
            let mut cols = vec![0.0; n * np];
            for (j, (plus, minus, h)) in pairs.iter_mut().enumerate() {
                let (fp, fm) = (plus.residual_at(s.t, &s.q)?, minus.residual_at(s.t, &s.q)?);
                for i in 0..n {
                    cols[j * n + i] = -(fp[i] - fm[i]) / (2.0 * *h);
                }
            }
            if !nominal.solve_jacobian_at(&s.q, &mut cols) {
                out.push(None);
                continue;
            }
            let d = if rates {
                match Self::rate_sensitivities(&mut nominal, &mut pairs, s, &cols)? {
                    Some((vel, acc)) => [cols, vel, acc],
                    None => {
                        out.push(None);
                        continue;
                    }
                }
            } else {
                [cols, Vec::new(), Vec::new()]
            };
            out.push(Some(self.channel_sensitivities(s, &d)));
        }
        Ok(out)
    }

    /// ∂q̇/∂p and ∂q̈/∂p (field-major, n each) at the nominal state `s` from ∂q/∂p (`dq`),
    /// `pairs` the mechanisms with each field at p ± h. The velocity equation Φq·q̇ = −Φt
    /// (Φt depends on neither q nor p) differentiated: Φq·∂q̇ = −B(q̇, ∂q) − ∂p(Φq)·q̇; the
    /// acceleration equation Φq·q̈ = γ(q, q̇, p): Φq·∂q̈ = γ_q·∂q − 2·B(q̇, ∂q̇) + ∂p(γ)
    /// − B(q̈, ∂q) − ∂p(Φq)·q̈ (γ_q̇·w = −2·B(q̇, w); B the second variation, see
    /// [`Solver::second_variation_at`]); ∂p(·) the central difference between the pair at
    /// fixed q, q̇ (polynomials of degree ≤ 2 in a point's coordinates, affine in a locked
    /// angle, as Φ is). `None` where Φq is singular.
    fn rate_sensitivities(
        nominal: &mut Solver,
        pairs: &mut [(Solver, Solver, f64)],
        s: &State,
        dq: &[f64],
    ) -> Result<Option<RateSensitivities>, LinkageError> {
        let n = s.q.len();
        let diff =
            |p: &[f64], m: &[f64], h: f64| -> Vec<f64> { p.iter().zip(m).map(|(p, m)| (p - m) / (2.0 * h)).collect() };
        let mut vel = vec![0.0; dq.len()];
        for (j, (plus, minus, h)) in pairs.iter().enumerate() {
            let b = nominal.second_variation_at(s.t, &s.q, &s.qd, &dq[j * n..(j + 1) * n])?;
            let dj = diff(&plus.jacobian_times_at(&s.q, &s.qd), &minus.jacobian_times_at(&s.q, &s.qd), *h);
            for i in 0..n {
                vel[j * n + i] = -(b[i] + dj[i]);
            }
        }
        if !nominal.solve_jacobian_at(&s.q, &mut vel) {
            return Ok(None);
        }
        let mut acc = vec![0.0; dq.len()];
        for (j, (plus, minus, h)) in pairs.iter_mut().enumerate() {
            let (sj, vj) = (&dq[j * n..(j + 1) * n], &vel[j * n..(j + 1) * n]);
            let gq = nominal.gamma_derivative_at(&s.q, &s.qd, sj);
            let bv = nominal.second_variation_at(s.t, &s.q, &s.qd, vj)?;
            let ba = nominal.second_variation_at(s.t, &s.q, &s.qdd, sj)?;
            let dg = diff(&plus.gamma_at(s.t, &s.q, &s.qd)?, &minus.gamma_at(s.t, &s.q, &s.qd)?, *h);
            let dj = diff(&plus.jacobian_times_at(&s.q, &s.qdd), &minus.jacobian_times_at(&s.q, &s.qdd), *h);
            for i in 0..n {
                acc[j * n + i] = gq[i] - 2.0 * bv[i] + dg[i] - ba[i] - dj[i];
            }
        }
        if !nominal.solve_jacobian_at(&s.q, &mut acc) {
            return Ok(None);
        }
        Ok(Some((vel, acc)))
    }

    /// The channels' sensitivities (channel-major) at the nominal state `s` from ∂q/∂p,
    /// ∂q̇/∂p and ∂q̈/∂p (`d`, field-major; the last two empty when no rate is watched). A
    /// point r = R + A(φ)·s moves by dR + A(φ)·s⊥·dφ + A(φ)·ds; its velocity
    /// v = Ṙ + (A·s)⊥·ω and acceleration a = R̈ + (A·s)⊥·ε − A·s·ω² are differentiated
    /// alike.
    fn channel_sensitivities(&self, s: &State, d: &[Vec<f64>; 3]) -> Vec<f64> {
        let (n, np) = (s.q.len(), self.params.len());
        let mut out = vec![0.0; self.channels * np];
        let three = |v: &[f64], j: usize, b: usize| {
            if v.is_empty() {
                (Vector::zeros(), 0.0)
            } else {
                (Vector::new(v[j * n + 3 * b], v[j * n + 3 * b + 1]), v[j * n + 3 * b + 2])
            }
        };
        for (j, p) in self.params.iter().enumerate() {
            let mut ch = 0;
            for o in &self.outputs {
                let body = match *o {
                    LinkageOutput::Point { body, .. }
                    | LinkageOutput::Angle { body, .. }
                    | LinkageOutput::Velocity { body, .. }
                    | LinkageOutput::Acceleration { body, .. }
                    | LinkageOutput::Omega { body, .. }
                    | LinkageOutput::Eps { body, .. } => body,
                };
                let (dr, dphi) = three(&d[0], j, body);
                let (dv, dw) = three(&d[1], j, body);
                let (da, de) = three(&d[2], j, body);
                let phi = s.q[3 * body + 2];
                let (w, e) = (s.qd[3 * body + 2], s.qdd[3 * body + 2]);
                // A·s and its change, for a point's outputs.
                let arm = |point: usize| {
                    let r = rotate(self.mechanism.bodies[body].points[point].1, phi);
                    (r, perp(r) * dphi + rotate(p.moves_point(body, point), phi))
                };
                let v = match *o {
                    LinkageOutput::Point { point, .. } => dr + arm(point).1,
                    LinkageOutput::Velocity { point, .. } => {
                        let (r, dr_) = arm(point);
                        dv + perp(dr_) * w + perp(r) * dw
                    }
                    LinkageOutput::Acceleration { point, .. } => {
                        let (r, dr_) = arm(point);
                        da + perp(dr_) * e + perp(r) * de - dr_ * (w * w) - r * (2.0 * w * dw)
                    }
                    LinkageOutput::Angle { .. } => Vector::new(dphi.to_degrees(), 0.0),
                    LinkageOutput::Omega { .. } => Vector::new(dw, 0.0),
                    LinkageOutput::Eps { .. } => Vector::new(de, 0.0),
                };
                out[ch * np + j] = v.x;
                if o.channels() == 2 {
                    out[(ch + 1) * np + j] = v.y;
                }
                ch += o.channels();
            }
        }
        out
    }

    /// ∂channel/∂field at position `k`, channel-major; `None` where Φq is singular.
    pub fn sensitivities(&self, k: usize) -> Option<Vec<f64>> {
        self.sensitivities.get(k).cloned().flatten()
    }

    /// The unit tangent of watched point `output`'s nominal path at each position (the
    /// point's velocity from the nominal's rates; where it is zero, the chord between the
    /// neighbouring positions; a zero vector where neither is defined).
    pub fn tangents(&self, output: usize) -> Vec<Vector> {
        let Some((body, point)) = self.outputs[output].point() else {
            return vec![Vector::zeros(); self.states.len()];
        };
        let at = |k: usize| Self::point(&self.mechanism, &self.states[k].q, body, point);
        let n = self.states.len();
        (0..n)
            .map(|k| {
                let s = &self.states[k];
                let r = rotate(self.mechanism.bodies[body].points[point].1, s.q[3 * body + 2]);
                let v = Vector::new(s.qd[3 * body], s.qd[3 * body + 1]) + perp(r) * s.qd[3 * body + 2];
                let v = if v.norm() > 0.0 && v.norm().is_finite() {
                    v
                } else {
                    at((k + 1).min(n - 1)) - at(k.saturating_sub(1))
                };
                let len = v.norm();
                if len > 0.0 && len.is_finite() { v / len } else { Vector::zeros() }
            })
            .collect()
    }

    /// The sample's q at every position into `work.motion` (n per position; with q̇ and q̈
    /// when a rate is watched; a position it cannot be assembled at is set in `failed`,
    /// its state the nominal's there): the solver refitted to the sample's numbers,
    /// resumed from the nominal's first state and swept over the motion. `false` when the
    /// sample is no mechanism at all.
    fn solve_sample(&self, work: &mut LinkageWork, dev: &[f64], failed: &mut [bool]) -> bool {
        let LinkageWork { solver, nominal, motion, start } = work;
        let Some(solver) = solver.as_mut() else { return false };
        let refit = solver.refit(|m| {
            for p in &self.params {
                p.reset(m, nominal);
            }
            for (p, d) in self.params.iter().zip(dev) {
                p.apply(m, *d);
            }
        });
        if refit.is_err() {
            return false;
        }
        let rates = self.outputs.iter().any(LinkageOutput::is_rate);
        let n = solver.q().len().max(1);
        motion.clear();
        let mut k = 0;
        if let (Some(first), Some(start)) = (self.states.first(), start.as_mut()) {
            start.q.copy_from_slice(&first.q);
            self.turn_locked(dev, &mut start.q);
            solver.resume(start);
        }
        while k < self.times.len() {
            let before = motion.q.len() / n;
            let done = if rates {
                solver.motion_into(&self.times[k..], motion)
            } else {
                solver.positions_into(&self.times[k..], &mut motion.q)
            };
            k += motion.q.len() / n - before;
            if done.is_ok() {
                break;
            }
            // Position k cannot be assembled: mark it, resume from the nominal's state there.
            failed[k] = true;
            let st = &self.states[k];
            motion.q.extend_from_slice(&st.q);
            if rates {
                motion.qd.extend_from_slice(&st.qd);
                motion.qdd.extend_from_slice(&st.qdd);
            }
            solver.resume(st);
            k += 1;
        }
        true
    }
}

impl LinkageModel {
    /// Turns the bodies in `q` (the nominal's first pose) so that every prismatic joint's
    /// locked angle is the sample's (deviations `dev`): a group's closed form continues a
    /// slider's and its guide's angles by one turn, so the pose a sample starts from must
    /// hold their new difference. Each body's turn follows from the ground's (none) through
    /// the prismatic joints; a set of bodies locked only among themselves keeps its first
    /// body still.
    fn turn_locked(&self, dev: &[f64], q: &mut [f64]) {
        let mut change = vec![0.0; self.mechanism.joints.len()];
        let mut any = false;
        for (p, d) in self.params.iter().zip(dev) {
            if let Some(j) = p.locked_angle() {
                change[j] += d * p.slope;
                any = true;
            }
        }
        if !any {
            return;
        }
        let locks: Vec<(Attach, Attach, f64)> = self
            .mechanism
            .joints
            .iter()
            .zip(&change)
            .filter_map(|(j, d)| match j.kind {
                JointKind::Prismatic { point, q1, .. } => Some((point.body, q1.body, *d)),
                JointKind::Revolute { .. } => None,
            })
            .collect();
        let nb = self.mechanism.bodies.len();
        let mut turn: Vec<Option<f64>> = vec![None; nb];
        let of = |t: &[Option<f64>], a: Attach| match a {
            Attach::Ground => Some(0.0),
            Attach::Body(b) => t[b],
        };
        loop {
            let mut progress = false;
            for &(slider, guide, d) in &locks {
                match (of(&turn, slider), of(&turn, guide), slider, guide) {
                    (Some(ts), None, _, Attach::Body(g)) => turn[g] = Some(ts - d),
                    (None, Some(tg), Attach::Body(s), _) => turn[s] = Some(tg + d),
                    _ => continue,
                }
                progress = true;
            }
            if progress {
                continue;
            }
            // A set locked only among itself: its first body stays.
            let free = locks.iter().find_map(|&(s, g, _)| match (s, g) {
                (Attach::Body(b), _) if turn[b].is_none() => Some(b),
                (_, Attach::Body(b)) if turn[b].is_none() => Some(b),
                _ => None,
            });
            match free {
                Some(b) => turn[b] = Some(0.0),
                None => break,
            }
        }
        for (b, t) in turn.iter().enumerate() {
            q[3 * b + 2] += t.unwrap_or(0.0);
        }
    }
}

impl Model for LinkageModel {
    type Work = LinkageWork;

    fn positions(&self) -> usize {
        self.states.len()
    }

    fn channels(&self) -> usize {
        self.channels
    }

    fn work(&self) -> LinkageWork {
        LinkageWork {
            solver: AssurSolver::new(self.mechanism.clone()).ok(),
            nominal: self.mechanism.clone(),
            motion: Motion::default(),
            start: self.states.first().cloned(),
        }
    }

    fn evaluate(&self, work: &mut LinkageWork, dev: &[f64], out: &mut [f64], failed: &mut [bool]) -> bool {
        if !self.solve_sample(work, dev, failed) {
            failed.iter_mut().for_each(|f| *f = true);
            return true;
        }
        let Some(solver) = work.solver.as_ref() else { return true };
        let mech = solver.mechanism();
        let ch = self.channels;
        let m = &work.motion;
        let n = m.q.len() / self.states.len().max(1);
        let mut any = false;
        let mut row = Vec::with_capacity(ch);
        // Positions alone (no rate watched): the rates are not read.
        let zero = if m.qd.is_empty() { vec![0.0; n] } else { Vec::new() };
        for k in 0..self.states.len() {
            if failed[k] {
                any = true;
                continue;
            }
            let at = k * n..(k + 1) * n;
            let q = &m.q[at.clone()];
            let (qd, qdd) = if m.qd.is_empty() { (&zero[..], &zero[..]) } else { (&m.qd[at.clone()], &m.qdd[at]) };
            row.clear();
            Self::values(mech, &self.outputs, (q, qd, qdd), &mut row);
            let nominal = &self.nominal[k * ch..(k + 1) * ch];
            let out = &mut out[k * ch..(k + 1) * ch];
            let mut c = 0;
            for o in &self.outputs {
                for i in 0..o.channels() {
                    let d = row[c + i] - nominal[c + i];
                    out[c + i] = if matches!(o, LinkageOutput::Angle { .. }) { wrap_deg(d) } else { d };
                }
                c += o.channels();
            }
        }
        any
    }
}

impl super::Sensitive for LinkageModel {
    fn sensitivities(&self, k: usize) -> Option<Vec<f64>> {
        LinkageModel::sensitivities(self, k)
    }

    fn dead_point(&self, k: usize, _dims: &[Dimension]) -> Option<String> {
        self.states[k].near_singular.as_ref().map(|n| {
            format!(
                "near a dead point: Φq's smallest relative pivot is {:.2e} (constraints {})",
                n.pivot, n.constraints
            )
        })
    }
}
