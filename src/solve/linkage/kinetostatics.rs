//! Kineto-statics of any linkage (issue 15 §1; seed 003's method for every mechanism):
//! the reactions in the joints and the drivers' forces are the Lagrange multipliers λ of
//! the constraint Jacobian that the kinematics already factor,
//!
//! ```text
//! Φqᵀ·λ = Q − M·q̈
//! ```
//!
//! with the weights, the loads and the inertia forces and torques (d'Alembert: −m·a_G at
//! the centroid, −J_G·ε) in the right-hand side as generalised forces of the body
//! coordinates (x, y, φ). One transposed solve per sample on the LU of the last step.
//!
//! Units: masses kg, inertias kg·m², g m/s², forces N, torques N·m, whatever the scene's
//! length unit (a mm scene is converted here, once: lengths times
//! [`Dynamics::length_unit_m`]).
//!
//! Sign conventions (the constraint forces on the system are −Φqᵀ·λ):
//! - a revolute joint `["a.P", "b.P"]` (Φ = r_a − r_b): the force of body a on body b is
//!   (λx, λy), N; it has no torque;
//! - a prismatic joint `{ point = "b.P", line = ["a.X", "a.Y"] }` (Φ = n_a·(r_P − r_X),
//!   φ_b − φ_a − θ): the force of the guide a on the slider b is −λ₁·n_a, across the guide,
//!   acting at P, and the couple of a on b about P is −λ₂, N·m, counter-clockwise positive;
//! - a driver (Φ = coordinate − f(t)): its generalised force on the driven body is
//!   D = −λ, positive in the driver's positive direction, so that its power is D·ḟ (for
//!   a crank driven by its angle, the balancing moment Me1 of seed 003, N·m; for a
//!   distance driver, the force along the guide, N).
//!
//! Check: the virtual-power balance Σ P = Σ D·ḟ + Σ F·v + Σ M·ω over drivers, loads,
//! weights and inertia forces and torques is zero on the actual motion (the joints are
//! ideal and do no work); [`Forces::power_residual`] is |Σ P| / Σ |P|.

use super::kinematics::{Solver, State};
use super::{Anchor, Attach, DriverTarget, JointKind, LinkageError, Mechanism, pz, rate};
use crate::geom::{Point, Vector, cross, perp};
use crate::solve::expr::Expr;

/// Tolerance of a load's time window, relative to the larger of |from| and |to|: a sample
/// time that roundoff puts a few ulps past an end still counts as inside.
pub const TIME_WINDOW_EPS_REL: f64 = 1e-9;

/// Mass properties of one moving body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassProperties {
    /// Mass, kg (≥ 0).
    pub mass: f64,
    /// Centroid in body coordinates, scene length units.
    pub centroid: Vector,
    /// Moment of inertia about the centroid, kg·m² (≥ 0).
    pub inertia: f64,
}

/// A load value: a number, or an expression of t (s) parsed like the driver laws.
#[derive(Debug, Clone, PartialEq)]
pub enum LoadValue {
    /// A constant.
    Number(f64),
    /// An expression of t.
    Law(Expr),
}

impl LoadValue {
    /// The value at time `t`.
    pub fn at(&self, t: f64) -> f64 {
        match self {
            LoadValue::Number(v) => *v,
            LoadValue::Law(e) => e.eval(t).value,
        }
    }

    /// The value as written (for messages).
    pub fn text(&self) -> String {
        match self {
            LoadValue::Number(v) => v.to_string(),
            LoadValue::Law(e) => crate::text::excerpt(e.source()),
        }
    }
}

/// The closed range of t where a load acts, s (`from` ≤ `to`; both ends included within
/// [`TIME_WINDOW_EPS_REL`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeWindow {
    /// Start, s.
    pub from: f64,
    /// End (included), s.
    pub to: f64,
}

impl TimeWindow {
    /// Whether `t` lies in the window.
    pub fn contains(&self, t: f64) -> bool {
        let eps = TIME_WINDOW_EPS_REL * self.from.abs().max(self.to.abs());
        t >= self.from - eps && t <= self.to + eps
    }
}

/// What a load does.
#[derive(Debug, Clone, PartialEq)]
pub enum LoadAction {
    /// A force at a point of a moving body, N, global components [fx, fy].
    Force {
        /// Where it acts.
        at: Anchor,
        /// Its components, N.
        force: [LoadValue; 2],
    },
    /// A torque on a moving body (index into [`Mechanism::bodies`]), N·m,
    /// counter-clockwise positive.
    Torque {
        /// The body.
        body: usize,
        /// The torque, N·m.
        torque: LoadValue,
    },
}

/// An external load.
#[derive(Debug, Clone, PartialEq)]
pub struct Load {
    /// Name for messages.
    pub name: String,
    /// The force or torque.
    pub action: LoadAction,
    /// When it acts; `None`: always.
    pub window: Option<TimeWindow>,
}

/// Everything the kineto-statics need beyond the kinematics.
#[derive(Debug, Clone, PartialEq)]
pub struct Dynamics {
    /// Metres per length unit of the mechanism (1 for SI, 0.001 for mm).
    pub length_unit_m: f64,
    /// Gravitational acceleration, m/s² (zero: no gravity).
    pub gravity: Vector,
    /// One per moving body, in the mechanism's order.
    pub bodies: Vec<MassProperties>,
    /// External loads.
    pub loads: Vec<Load>,
}

/// The reaction in one joint (see the module docs for which body acts on which).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Reaction {
    /// Force, N.
    pub force: Vector,
    /// Couple, N·m, counter-clockwise positive (0 for a revolute joint).
    pub torque: f64,
}

/// Forces at one sample.
#[derive(Debug, Clone, PartialEq)]
pub struct Forces {
    /// One per joint, in the mechanism's order.
    pub reactions: Vec<Reaction>,
    /// One per driver: its generalised force, N·m (angle) or N (distance), positive in
    /// the driver's positive direction.
    pub drivers: Vec<f64>,
    /// |Σ P| / Σ |P| of the virtual-power balance (0 when nothing moves).
    pub power_residual: f64,
}

impl Forces {
    /// Zero forces for `mech` (a buffer for [`Solver::forces_into`]).
    pub fn zeros(mech: &Mechanism) -> Forces {
        Forces {
            reactions: vec![Reaction::default(); mech.joints.len()],
            drivers: vec![0.0; mech.drivers.len()],
            power_residual: 0.0,
        }
    }
}

/// Running sums of the virtual-power balance.
#[derive(Debug, Default)]
struct Power {
    sum: f64,
    abs: f64,
}

impl Power {
    fn add(&mut self, p: f64) {
        self.sum += p;
        self.abs += p.abs();
    }

    fn residual(&self) -> f64 {
        if self.abs > 0.0 { self.sum.abs() / self.abs } else { 0.0 }
    }
}

impl Solver {
    /// Solves at every time in `times`, as [`Solver::run`] does, and the forces at each
    /// (one transposed solve per sample on the factorisation the kinematics used).
    pub fn run_kinetostatics(
        &mut self,
        times: &[f64],
        dynamics: &Dynamics,
    ) -> Result<(Vec<State>, Vec<Forces>), LinkageError> {
        check_dynamics(&self.mech, dynamics)?;
        let mut forces = Vec::with_capacity(times.len());
        let states = self.run_each(times, |s| {
            let mut f = Forces::zeros(&s.mech);
            s.forces_into(dynamics, &mut f)?;
            forces.push(f);
            Ok(())
        })?;
        Ok((states, forces))
    }

    /// The forces at the current step (after [`Solver::step`] or [`Solver::assemble`]).
    pub fn forces(&mut self, dynamics: &Dynamics) -> Result<Forces, LinkageError> {
        check_dynamics(&self.mech, dynamics)?;
        let mut f = Forces::zeros(&self.mech);
        self.forces_into(dynamics, &mut f)?;
        Ok(f)
    }

    /// [`Solver::forces`] into a buffer from [`Forces::zeros`], allocation-free (the
    /// dynamics are assumed to fit the mechanism: [`Solver::forces`] checks them).
    pub fn forces_into(&mut self, dynamics: &Dynamics, out: &mut Forces) -> Result<(), LinkageError> {
        let Some(t) = self.t else {
            return Err(LinkageError::InvalidModel { what: "forces asked for before the first step".into() });
        };
        let n = self.n;
        let k = dynamics.length_unit_m;
        let mut power = Power::default();
        // Q − M·q̈ into rhs: x, y rows in N, φ rows in N·(length unit).
        self.rhs[..n].iter_mut().for_each(|v| *v = 0.0);
        for (i, body) in dynamics.bodies.iter().enumerate() {
            let p = self.poses[i];
            let (v, w) = rate(&self.qd, Attach::Body(i));
            let (a, e) = rate(&self.qdd, Attach::Body(i));
            let s = p.rot(body.centroid);
            let v_g = (v + perp(s) * w) * k;
            let a_g = (a + perp(s) * e - s * (w * w)) * k;
            let weight = dynamics.gravity * body.mass;
            let inertia_force = -a_g * body.mass;
            let inertia_torque = -body.inertia * e;
            let f = weight + inertia_force;
            self.rhs[3 * i] += f.x;
            self.rhs[3 * i + 1] += f.y;
            self.rhs[3 * i + 2] += cross(s, f) + inertia_torque / k;
            power.add(weight.dot(&v_g));
            power.add(inertia_force.dot(&v_g));
            power.add(inertia_torque * w);
        }
        for load in &dynamics.loads {
            if load.window.is_some_and(|win| !win.contains(t)) {
                continue;
            }
            let value = |v: &LoadValue, what: &'static str| {
                let x = v.at(t);
                if x.is_finite() {
                    Ok(x)
                } else {
                    Err(LinkageError::LoadNotFinite { load: load.name.clone(), what, expr: v.text(), t, value: x })
                }
            };
            match &load.action {
                LoadAction::Force { at, force } => {
                    let f = Vector::new(value(&force[0], "force x")?, value(&force[1], "force y")?);
                    let Attach::Body(i) = at.body else { continue };
                    let p = self.poses[i];
                    let (v, w) = rate(&self.qd, at.body);
                    let s = p.rot(at.local);
                    self.rhs[3 * i] += f.x;
                    self.rhs[3 * i + 1] += f.y;
                    self.rhs[3 * i + 2] += cross(s, f);
                    power.add(f.dot(&(v + perp(s) * w)) * k);
                }
                LoadAction::Torque { body, torque } => {
                    let m = value(torque, "torque")?;
                    self.rhs[3 * body + 2] += m / k;
                    power.add(m * rate(&self.qd, Attach::Body(*body)).1);
                }
            }
        }
        self.solve_transposed_in_place();
        let lambda = &self.rhs;
        for (j, (joint, r)) in self.mech.joints.iter().zip(out.reactions.iter_mut()).enumerate() {
            let (l1, l2) = (lambda[2 * j], lambda[2 * j + 1]);
            *r = match joint.kind {
                JointKind::Revolute { .. } => Reaction { force: Vector::new(l1, l2), torque: 0.0 },
                JointKind::Prismatic { q1, q2, .. } => {
                    let u = pz(&self.poses, q1.body).rot((q2.local - q1.local).normalize());
                    Reaction { force: -perp(u) * l1, torque: -l2 * k }
                }
            };
            if !(r.force.x.is_finite() && r.force.y.is_finite() && r.torque.is_finite()) {
                return Err(LinkageError::ForcesNotFinite { t, what: format!("joint `{}`", joint.name) });
            }
        }
        let rows = 2 * self.mech.joints.len();
        for (d, (driver, out_d)) in self.mech.drivers.iter().zip(out.drivers.iter_mut()).enumerate() {
            let raw = -lambda[rows + d];
            let rate_f = self.laws[d].1;
            // Angles: λ in N·(length unit) → N·m; distances: λ in N, ḟ in length units/s.
            let (force, p) = match driver.target {
                DriverTarget::JointDistance(_) => (raw, raw * rate_f * k),
                DriverTarget::BodyAngle(_) | DriverTarget::JointAngle(_) => (raw * k, raw * k * rate_f),
            };
            if !force.is_finite() {
                return Err(LinkageError::ForcesNotFinite { t, what: format!("driver `{}`", driver.name) });
            }
            *out_d = force;
            power.add(p);
        }
        out.power_residual = power.residual();
        Ok(())
    }
}

/// What a force acting on a body (other than a joint's reaction) is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AppliedKind {
    /// The inertia force −m·a_G at the centroid (d'Alembert).
    Inertia,
    /// The weight m·g at the centroid.
    Weight,
    /// An external force: index into [`Dynamics::loads`].
    Load(usize),
    /// A distance driver's force along its guide (index into [`Mechanism::drivers`]):
    /// +D·u on the slider, −D·u on the guide body.
    Driver(usize),
}

/// A force acting on a moving body at one sample, besides the reactions of its joints:
/// its kind, the body, where it acts, the force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Applied {
    /// What it is.
    pub kind: AppliedKind,
    /// The body it acts on (index into [`Mechanism::bodies`]).
    pub body: usize,
    /// Where it acts (global, scene length units).
    pub at: Point,
    /// The force, N.
    pub force: Vector,
}

/// Every force acting on the moving bodies at `state` besides the joints' reactions — the
/// inertia forces and weights at the centroids (bodies with a mass), the loads acting at
/// `state.t`, the forces of distance drivers (from `forces`) — so that for each body these
/// and its reactions ([`Forces::reactions`], with the sign conventions of the module docs)
/// sum to zero: the body's force polygon closes. Torques (inertia torques, torque loads,
/// angle drivers, prismatic couples) are not forces and are not listed.
pub fn applied_forces(mech: &Mechanism, dynamics: &Dynamics, state: &State, forces: &Forces) -> Vec<Applied> {
    let mut out = Vec::new();
    let k = dynamics.length_unit_m;
    for (i, body) in dynamics.bodies.iter().enumerate() {
        if body.mass == 0.0 {
            continue;
        }
        let g = Anchor { body: Attach::Body(i), local: body.centroid };
        let at = state.point(g);
        out.push(Applied { kind: AppliedKind::Inertia, body: i, at, force: -state.acceleration(g) * (k * body.mass) });
        if dynamics.gravity != Vector::zeros() {
            out.push(Applied { kind: AppliedKind::Weight, body: i, at, force: dynamics.gravity * body.mass });
        }
    }
    for (l, load) in dynamics.loads.iter().enumerate() {
        if load.window.is_some_and(|w| !w.contains(state.t)) {
            continue;
        }
        if let LoadAction::Force { at, force } = &load.action
            && let Attach::Body(i) = at.body
        {
            let f = Vector::new(force[0].at(state.t), force[1].at(state.t));
            out.push(Applied { kind: AppliedKind::Load(l), body: i, at: state.point(*at), force: f });
        }
    }
    for (d, (driver, value)) in mech.drivers.iter().zip(&forces.drivers).enumerate() {
        let DriverTarget::JointDistance(j) = driver.target else { continue };
        let Some(JointKind::Prismatic { point, q1, q2, .. }) = mech.joints.get(j).map(|j| &j.kind) else { continue };
        let u = (state.point(*q2) - state.point(*q1)).normalize();
        let at = state.point(*point);
        for (body, sign) in [(point.body, 1.0), (q1.body, -1.0)] {
            if let Attach::Body(i) = body {
                out.push(Applied { kind: AppliedKind::Driver(d), body: i, at, force: u * (sign * value) });
            }
        }
    }
    out
}

/// The dynamics fit the mechanism: one set of mass properties per body, loads on its
/// bodies, a positive length unit.
fn check_dynamics(mech: &Mechanism, d: &Dynamics) -> Result<(), LinkageError> {
    let bad = |what: String| Err(LinkageError::InvalidModel { what });
    if d.bodies.len() != mech.bodies.len() {
        return bad(format!("{} mass properties for {} bodies", d.bodies.len(), mech.bodies.len()));
    }
    if !(d.length_unit_m.is_finite() && d.length_unit_m > 0.0) {
        return bad(format!("length unit {} m", d.length_unit_m));
    }
    for l in &d.loads {
        let body = match l.action {
            LoadAction::Force { at, .. } => at.body,
            LoadAction::Torque { body, .. } => Attach::Body(body),
        };
        if let Attach::Body(i) = body
            && i >= mech.bodies.len()
        {
            return bad(format!("load `{}` on body {i} of {}", l.name, mech.bodies.len()));
        }
    }
    Ok(())
}
