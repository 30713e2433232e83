//! Positions, velocities and accelerations: Newton–Raphson on Φ(q, t) = 0, then
//! Φq·q̇ = −Φt and Φq·q̈ = γ on the same factorisation (see the parent module).

use super::lu::Lu;
use super::{Anchor, Attach, DriverTarget, JointKind, LinkageError, Mechanism, Pose, col, fill_poses, pose, pz, rate};
use super::{MAX_ASSEMBLY_ITERATIONS, MAX_NEWTON_ITERATIONS, NEAR_SINGULAR_PIVOT_REL, NEWTON_TOL};
use crate::geom::{Point, Vector, perp};

/// Iterations allowed to the singular value decomposition that names the constraints of a
/// singularity (nalgebra's default, 0, means no limit; it converges in a few dozen sweeps on
/// a finite Jacobian of our sizes).
const SVD_MAX_ITERATIONS: usize = 10_000;
/// Component of the left singular vector above which a constraint is named as taking part
/// in a singularity.
const SINGULAR_SHARE: f64 = 0.1;

/// One compiled constraint (one or two rows of Φ).
#[derive(Debug, Clone)]
pub(super) enum Con {
    /// r_a − r_b = 0 (2 rows).
    Coincide { a: Anchor, b: Anchor },
    /// n_g · (r_P − r_Q) = 0, n_g the guide's unit normal (1 row, length).
    OnLine { p: Anchor, q: Anchor, guide: Attach, u: Vector },
    /// φ_i − φ_j − offset − f(t) = 0 (1 row, angle); `law` None for a lock.
    Angle { i: Attach, j: Attach, offset: f64, law: Option<usize> },
    /// u_g · (r_P − r_Q) − f(t) = 0 (1 row, length).
    Distance { p: Anchor, q: Anchor, guide: Attach, u: Vector, law: usize },
}

impl Con {
    pub(super) fn rows(&self) -> usize {
        match self {
            Con::Coincide { .. } => 2,
            _ => 1,
        }
    }
    fn is_length(&self) -> bool {
        !matches!(self, Con::Angle { .. })
    }
}

/// Φ of one constraint at the cached `poses` into `out` (its one or two rows), the
/// drivers' laws evaluated in `laws` (value, f′, f″).
pub(super) fn con_residual(c: &Con, q: &[Pose], laws: &[(f64, f64, f64)], out: &mut [f64]) {
    match *c {
        Con::Coincide { a, b } => {
            let (pa, pb) = (pz(q, a.body), pz(q, b.body));
            let d = pa.r + pa.rot(a.local) - pb.r - pb.rot(b.local);
            out[0] = d.x;
            out[1] = d.y;
        }
        Con::OnLine { p, q: qa, guide, u } => {
            let (pp, pg) = (pz(q, p.body), pz(q, guide));
            let d = pp.r + pp.rot(p.local) - pg.r - pg.rot(qa.local);
            out[0] = perp(pg.rot(u)).dot(&d);
        }
        Con::Angle { i, j, offset, law } => {
            let f = law.map_or(0.0, |k| laws[k].0);
            out[0] = pz(q, i).phi - pz(q, j).phi - offset - f;
        }
        Con::Distance { p, q: qa, guide, u, law } => {
            let (pp, pg) = (pz(q, p.body), pz(q, guide));
            let d = pp.r + pp.rot(p.local) - pg.r - pg.rot(qa.local);
            out[0] = pg.rot(u).dot(&d) - laws[law].0;
        }
    }
}

/// The Jacobian entries of one constraint at the cached poses: `put(row, body, ∂/∂x,
/// ∂/∂y, ∂/∂φ)` for each of its rows (0 or 1) and each body it involves (the ground too:
/// callers skip it). Entries of one row and body may come in two calls; callers add them.
pub(super) fn con_jacobian(c: &Con, q: &[Pose], mut put: impl FnMut(usize, Attach, f64, f64, f64)) {
    match *c {
        Con::Coincide { a, b } => {
            let (pa, pb) = (pz(q, a.body), pz(q, b.body));
            let (ba, bb) = (perp(pa.rot(a.local)), perp(pb.rot(b.local)));
            put(0, a.body, 1.0, 0.0, ba.x);
            put(1, a.body, 0.0, 1.0, ba.y);
            put(0, b.body, -1.0, 0.0, -bb.x);
            put(1, b.body, 0.0, -1.0, -bb.y);
        }
        Con::OnLine { p, guide, u, .. } | Con::Distance { p, guide, u, .. } => {
            let (pp, pg) = (pz(q, p.body), pz(q, guide));
            let sp = pp.rot(p.local);
            let rp = pp.r + sp;
            let ug = pg.rot(u);
            let ng = perp(ug);
            // Normal row (OnLine): n·(r_P − r_Q); tangential row (Distance): u·(r_P − r_Q).
            // ∂/∂φ_guide of n·(r_P − R_g − A s_Q) = −u·(r_P − R_g); of u·(...) = n·(r_P − R_g).
            let (dir, dphi_g) =
                if matches!(c, Con::OnLine { .. }) { (ng, -ug.dot(&(rp - pg.r))) } else { (ug, ng.dot(&(rp - pg.r))) };
            put(0, p.body, dir.x, dir.y, dir.dot(&perp(sp)));
            put(0, guide, -dir.x, -dir.y, dphi_g);
        }
        Con::Angle { i, j, .. } => {
            put(0, i, 0.0, 0.0, 1.0);
            put(0, j, 0.0, 0.0, -1.0);
        }
    }
}

/// −Φt of one constraint's first row: f′ on a driver row, 0 otherwise (second rows are 0).
pub(super) fn con_rate(c: &Con, laws: &[(f64, f64, f64)]) -> f64 {
    match *c {
        Con::Angle { law: Some(k), .. } | Con::Distance { law: k, .. } => laws[k].1,
        _ => 0.0,
    }
}

/// γ of one constraint (Φq·q̈ = γ) at the cached poses and the velocities `qd`, into `out`.
pub(super) fn con_gamma(c: &Con, q: &[Pose], qd: &[f64], laws: &[(f64, f64, f64)], out: &mut [f64]) {
    match *c {
        Con::Coincide { a, b } => {
            let (pa, pb) = (pz(q, a.body), pz(q, b.body));
            let (wa, wb) = (rate(qd, a.body).1, rate(qd, b.body).1);
            let g = pa.rot(a.local) * (wa * wa) - pb.rot(b.local) * (wb * wb);
            out[0] = g.x;
            out[1] = g.y;
        }
        Con::Angle { law, .. } => out[0] = law.map_or(0.0, |k| laws[k].2),
        Con::OnLine { p, q: qa, guide, u } | Con::Distance { p, q: qa, guide, u, .. } => {
            let GuideTerms { d, dd, ug, ng, centripetal, wg, .. } = GuideTerms::new(q, qd, p, qa, guide, u);
            out[0] = match *c {
                // Φ = n·d: Φ̈ = Φq·q̈ − ωg²·n·d − 2ωg·u·ḋ − n·(ωp² s_P − ωg² s_Q)
                Con::OnLine { .. } => wg * wg * ng.dot(&d) + 2.0 * wg * ug.dot(&dd) + ng.dot(&centripetal),
                // Φ = u·d − f: Φ̈ = Φq·q̈ − ωg²·u·d + 2ωg·n·ḋ − u·(ωp² s_P − ωg² s_Q) − f″
                Con::Distance { law, .. } => {
                    laws[law].2 + wg * wg * ug.dot(&d) - 2.0 * wg * ng.dot(&dd) + ug.dot(&centripetal)
                }
                _ => 0.0,
            };
        }
    }
}

/// The terms of a point P (on one body) against a guide through Q (on the guide's body)
/// that an `OnLine` or `Distance` constraint's γ is made of, at the poses `q` and the
/// velocities `qd`: arms s = A(φ)·local, d = r_P − r_Q, its rate ḋ, the guide's unit
/// direction u and normal n, the arms' centripetal difference, the bodies' ω.
pub(super) struct GuideTerms {
    pub sp: Vector,
    pub sq: Vector,
    pub d: Vector,
    pub dd: Vector,
    pub ug: Vector,
    pub ng: Vector,
    pub centripetal: Vector,
    pub wp: f64,
    pub wg: f64,
}

impl GuideTerms {
    pub(super) fn new(q: &[Pose], qd: &[f64], p: Anchor, qa: Anchor, guide: Attach, u: Vector) -> Self {
        let (pp, pg) = (pz(q, p.body), pz(q, guide));
        let (vp, wp) = rate(qd, p.body);
        let (vg, wg) = rate(qd, guide);
        let sp = pp.rot(p.local);
        let sq = pg.rot(qa.local);
        let d = pp.r + sp - pg.r - sq;
        let dd = vp + perp(sp) * wp - vg - perp(sq) * wg;
        let ug = pg.rot(u);
        let ng = perp(ug);
        let centripetal = sp * (wp * wp) - sq * (wg * wg);
        GuideTerms { sp, sq, d, dd, ug, ng, centripetal, wp, wg }
    }
}

/// The state at one instant.
#[derive(Debug, Clone, PartialEq)]
pub struct State {
    /// Time, s.
    pub t: f64,
    /// Coordinates (x, y, φ) per body.
    pub q: Vec<f64>,
    /// Their time derivatives.
    pub qd: Vec<f64>,
    /// Their second time derivatives.
    pub qdd: Vec<f64>,
    /// Newton iterations this step took (corrections applied).
    pub iterations: usize,
    /// Largest relative constraint residual at the answer.
    pub residual: f64,
    /// Set when the step was solved close to a singular position (a dead point): the
    /// position is right, the velocities and accelerations are not to be trusted.
    pub near_singular: Option<NearSingular>,
}

/// A step solved close to a singular Jacobian (smallest relative pivot below
/// [`NEAR_SINGULAR_PIVOT_REL`] but above [`SINGULAR_PIVOT_REL`](super::SINGULAR_PIVOT_REL)), typically a time step
/// landing on or within ~1e-9 rad of a dead point. The position is kept (it is right to
/// the Newton tolerance); the velocities and accelerations are kept too (finite, never
/// NaN) but are not reliable there: callers report the step (the run pipeline prints a
/// warning and lists it in the JSON summary).
#[derive(Debug, Clone, PartialEq)]
pub struct NearSingular {
    /// Time, s.
    pub t: f64,
    /// Smallest pivot of the equilibrated Jacobian relative to its ∞-norm at the answer.
    pub pivot: f64,
    /// The drivers' values there, e.g. "driver `rocker` = 78.4630°".
    pub drivers: String,
    /// The constraints that take part (from the left singular vector), comma-separated.
    pub constraints: String,
}

impl State {
    /// Global position of `anchor`.
    pub fn point(&self, anchor: Anchor) -> Point {
        let p = pose(&self.q, anchor.body);
        Point::from(p.r + p.rot(anchor.local))
    }

    /// Velocity of `anchor`.
    pub fn velocity(&self, anchor: Anchor) -> Vector {
        let p = pose(&self.q, anchor.body);
        let (rd, w) = rate(&self.qd, anchor.body);
        rd + perp(p.rot(anchor.local)) * w
    }

    /// Acceleration of `anchor`.
    pub fn acceleration(&self, anchor: Anchor) -> Vector {
        let p = pose(&self.q, anchor.body);
        let (_, w) = rate(&self.qd, anchor.body);
        let (rdd, e) = rate(&self.qdd, anchor.body);
        let s = p.rot(anchor.local);
        rdd + perp(s) * e - s * (w * w)
    }

    /// Angle, angular velocity and angular acceleration of a body (radians, rad/s, rad/s²).
    pub fn angular(&self, body: Attach) -> (f64, f64, f64) {
        (pose(&self.q, body).phi, rate(&self.qd, body).1, rate(&self.qdd, body).1)
    }

    /// The relative motion at a prismatic joint (`None` for a revolute joint): the sliding
    /// point P against the point of the guide body under it at this instant,
    /// a_P = a_P,guide + a_cor + a_rel (the textbook decomposition; see [`Sliding`]).
    pub fn sliding(&self, joint: &JointKind) -> Option<Sliding> {
        let JointKind::Prismatic { point, q1, .. } = *joint else { return None };
        let guide = q1.body;
        let g = pose(&self.q, guide);
        let (vg, wg) = rate(&self.qd, guide);
        let (ag, eg) = rate(&self.qdd, guide);
        // P's position relative to the guide body's frame origin.
        let d = self.point(point) - Point::from(g.r);
        let v_guide = vg + perp(d) * wg;
        let a_guide = ag + perp(d) * eg - d * (wg * wg);
        let v_rel = self.velocity(point) - v_guide;
        let a_cor = perp(v_rel) * (2.0 * wg);
        let a_rel = self.acceleration(point) - a_guide - a_cor;
        Some(Sliding { v_rel, a_rel, a_cor })
    }
}

/// Relative motion at a prismatic joint, in the scene's length unit per s and per s²:
/// the sliding point P of the slider body against the coincident point of the guide body
/// (the body of the joint's line), so that v_P = v_P,guide + `v_rel` and
/// a_P = a_P,guide + `a_cor` + `a_rel`. `v_rel` and `a_rel` lie along the guide;
/// `a_cor` = 2·ω_guide × `v_rel` (ω_guide counter-clockwise positive), across it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sliding {
    /// Sliding velocity of P relative to the guide.
    pub v_rel: Vector,
    /// Sliding (relative) acceleration of P along the guide.
    pub a_rel: Vector,
    /// Coriolis acceleration 2·ω_guide × v_rel.
    pub a_cor: Vector,
}

/// The Newton–Raphson solver of one mechanism, with every buffer sized once.
#[derive(Debug, Clone)]
pub struct Solver {
    pub(super) mech: Mechanism,
    pub(super) cons: Vec<Con>,
    /// Description of each row, for messages.
    pub(super) row_names: Vec<String>,
    /// 1 for angle rows, the length scale for length rows.
    pub(super) row_scale: Vec<f64>,
    /// The length scale for x/y columns, 1 for φ columns.
    pub(super) col_scale: Vec<f64>,
    pub(super) n: usize,
    pub(super) m: usize,
    pub(super) q: Vec<f64>,
    pub(super) qd: Vec<f64>,
    pub(super) qdd: Vec<f64>,
    /// q̈ of the step before (for the third-order predictor).
    pub(super) qdd_prev: Vec<f64>,
    /// Length of the previous step, when there was one.
    pub(super) dt_prev: Option<f64>,
    pub(super) t: Option<f64>,
    pub(super) phi: Vec<f64>,
    pub(super) rhs: Vec<f64>,
    pub(super) lu: Lu,
    pub(super) laws: Vec<(f64, f64, f64)>,
    /// Poses of the bodies at the current q (refreshed by `residual`).
    pub(super) poses: Vec<Pose>,
    /// Newton stops when the largest relative residual is at or below this.
    pub(super) newton_tol: f64,
    /// The near-singular report of the last step, if any.
    pub(super) near: Option<NearSingular>,
}

/// The mechanism's constraints into `cons` (cleared first; its memory kept): joints in
/// order (a revolute's coincidence, a prismatic's point on line and locked rotation), then
/// the drivers.
fn compile(mech: &Mechanism, cons: &mut Vec<Con>) -> Result<(), LinkageError> {
    cons.clear();
    for jt in &mech.joints {
        match jt.kind {
            JointKind::Revolute { a, b } => cons.push(Con::Coincide { a, b }),
            JointKind::Prismatic { point, q1, q2, angle } => {
                let u = (q2.local - q1.local).normalize();
                cons.push(Con::OnLine { p: point, q: q1, guide: q1.body, u });
                cons.push(Con::Angle { i: point.body, j: q1.body, offset: angle, law: None });
            }
        }
    }
    for (k, d) in mech.drivers.iter().enumerate() {
        match d.target {
            DriverTarget::BodyAngle(b) => {
                cons.push(Con::Angle { i: Attach::Body(b), j: Attach::Ground, offset: 0.0, law: Some(k) })
            }
            DriverTarget::JointAngle(j) => match mech.joints[j].kind {
                JointKind::Revolute { a, b } => {
                    cons.push(Con::Angle { i: b.body, j: a.body, offset: 0.0, law: Some(k) })
                }
                JointKind::Prismatic { .. } => {
                    return Err(LinkageError::InvalidModel {
                        what: format!("driver `{}`: an angle driver on a prismatic joint", d.name),
                    });
                }
            },
            DriverTarget::JointDistance(j) => match mech.joints[j].kind {
                JointKind::Prismatic { point, q1, q2, .. } => {
                    let u = (q2.local - q1.local).normalize();
                    cons.push(Con::Distance { p: point, q: q1, guide: q1.body, u, law: k })
                }
                JointKind::Revolute { .. } => {
                    return Err(LinkageError::InvalidModel {
                        what: format!("driver `{}`: a distance driver on a revolute joint", d.name),
                    });
                }
            },
        }
    }
    Ok(())
}

/// The names of the constraints' rows, in [`compile`]'s order (for messages).
fn constraint_names(mech: &Mechanism) -> Vec<String> {
    let mut names = Vec::new();
    for jt in &mech.joints {
        match jt.kind {
            JointKind::Revolute { .. } => {
                names.push(format!("revolute joint `{}` (x)", jt.name));
                names.push(format!("revolute joint `{}` (y)", jt.name));
            }
            JointKind::Prismatic { .. } => {
                names.push(format!("prismatic joint `{}` (point on line)", jt.name));
                names.push(format!("prismatic joint `{}` (rotation locked)", jt.name));
            }
        }
    }
    names.extend(mech.drivers.iter().map(|d| format!("driver `{}`", d.name)));
    names
}

impl Solver {
    /// Compiles the mechanism; counts degrees of freedom against drivers first.
    pub fn new(mech: Mechanism) -> Result<Solver, LinkageError> {
        let nb = mech.bodies.len();
        let n = 3 * nb;
        let equations = 2 * mech.joints.len();
        let dof = n as i64 - equations as i64;
        if dof != mech.drivers.len() as i64 {
            let d = mech.drivers.len() as i64;
            let hint = if dof <= 0 {
                "the joints leave no motion (a structure or over-constrained): remove a joint or add a body".to_string()
            } else if d < dof {
                format!(
                    "add {} (a body angle, a joint angle or a joint distance)",
                    crate::text::counted(dof - d, "driver", "drivers")
                )
            } else {
                format!("remove {}", crate::text::counted(d - dof, "driver", "drivers"))
            };
            return Err(LinkageError::DofMismatch { bodies: nb, equations, dof, drivers: mech.drivers.len(), hint });
        }
        let mut cons = Vec::new();
        compile(&mech, &mut cons)?;
        let names = constraint_names(&mech);
        let mut row_scale = Vec::new();
        for c in &cons {
            for _ in 0..c.rows() {
                row_scale.push(if c.is_length() { mech.length_scale } else { 1.0 });
            }
        }
        let m = row_scale.len();
        let mut q = vec![0.0; n];
        for (i, b) in mech.bodies.iter().enumerate() {
            q[3 * i] = b.at.x;
            q[3 * i + 1] = b.at.y;
            q[3 * i + 2] = b.angle;
        }
        let laws = vec![(0.0, 0.0, 0.0); mech.drivers.len()];
        let col_scale = (0..n).map(|c| if c % 3 == 2 { 1.0 } else { mech.length_scale }).collect();
        Ok(Solver {
            mech,
            cons,
            row_names: names,
            row_scale,
            col_scale,
            n,
            m,
            q,
            qd: vec![0.0; n],
            qdd: vec![0.0; n],
            qdd_prev: vec![0.0; n],
            dt_prev: None,
            t: None,
            phi: vec![0.0; m],
            rhs: vec![0.0; m.max(n)],
            lu: Lu::new(n),
            laws,
            poses: Vec::with_capacity(nb),
            newton_tol: NEWTON_TOL,
            near: None,
        })
    }

    /// Recompiles the constraints from the mechanism's numbers after they changed in place
    /// (points, anchors, locked angles; the same bodies, joints and drivers), keeping the
    /// buffers.
    pub(super) fn recompile(&mut self) -> Result<(), LinkageError> {
        let mut cons = std::mem::take(&mut self.cons);
        let done = compile(&self.mech, &mut cons);
        self.cons = cons;
        done
    }

    /// Sets the Newton goal: the largest relative constraint residual at which an
    /// iteration stops (default [`NEWTON_TOL`]; `mechdraw bench` charts speed
    /// against accuracy with it). Non-finite or negative values are ignored.
    pub fn set_newton_tolerance(&mut self, rel: f64) {
        if rel.is_finite() && rel >= 0.0 {
            self.newton_tol = rel;
        }
    }

    /// The mechanism.
    pub fn mechanism(&self) -> &Mechanism {
        &self.mech
    }

    /// Number of coordinates (3 per moving body).
    pub fn coordinates(&self) -> usize {
        self.n
    }

    /// Current coordinates.
    pub fn q(&self) -> &[f64] {
        &self.q
    }

    /// The state after the last step.
    pub fn state(&self) -> State {
        State {
            t: self.t.unwrap_or(0.0),
            q: self.q.clone(),
            qd: self.qd.clone(),
            qdd: self.qdd.clone(),
            iterations: 0,
            residual: self.residual_norm().0,
            near_singular: self.near.clone(),
        }
    }

    /// Smallest pivot of the equilibrated Jacobian relative to its ∞-norm, at the answer of
    /// the last step (an estimate of 1/κ∞; `INFINITY` before the first step).
    pub fn min_pivot_rel(&self) -> f64 {
        self.lu.min_pivot_rel
    }

    /// The near-singular report at the current answer (Φq factored there), or None.
    fn near_singular(&self, t: f64) -> Option<NearSingular> {
        let pivot = self.lu.min_pivot_rel;
        (pivot < NEAR_SINGULAR_PIVOT_REL).then(|| NearSingular {
            t,
            pivot,
            drivers: self.driver_values(),
            constraints: self.singular_constraints(),
        })
    }

    #[inline]
    pub(super) fn eval_laws(&mut self, t: f64) -> Result<(), LinkageError> {
        for (d, law) in self.mech.drivers.iter().zip(self.laws.iter_mut()) {
            let j = d.law.eval(t);
            *law = j.finite().ok_or_else(|| not_finite(d, t, j))?;
        }
        Ok(())
    }

    /// The laws' values alone at `t` (a positions-only step reads no more): f′ and f″ are
    /// left as they were, except for a law whose value does not tell whether its rates are
    /// finite ([`Expr::value`](crate::solve::expr::Expr::value) gives `None`), evaluated
    /// whole. The same error as [`Solver::eval_laws`] where any of them is not finite.
    #[inline]
    pub(super) fn eval_law_values(&mut self, t: f64) -> Result<(), LinkageError> {
        for (d, law) in self.mech.drivers.iter().zip(self.laws.iter_mut()) {
            match d.law.value(t) {
                Some(v) if v.is_finite() => law.0 = v,
                _ => *law = whole_law(d, t)?,
            }
        }
        Ok(())
    }

    /// Φ(q, t) into `self.phi` (laws already evaluated), only the first `rows` rows
    /// (drag leaves out the drivers, which come last).
    pub(super) fn residual(&mut self) {
        fill_poses(&self.q, &mut self.poses);
        let mut r = 0;
        for c in &self.cons {
            con_residual(c, &self.poses, &self.laws, &mut self.phi[r..r + c.rows()]);
            r += c.rows();
        }
    }

    /// Φq into `jac` (row-major, `rows` × n).
    fn jacobian(cons: &[Con], q: &[f64], n: usize, jac: &mut [f64]) {
        let mut poses = Vec::with_capacity(n / 3);
        fill_poses(q, &mut poses);
        Self::jacobian_with(cons, &poses, n, jac);
    }

    /// Φq into `jac` from cached poses (allocation-free).
    fn jacobian_with(cons: &[Con], q: &[Pose], n: usize, jac: &mut [f64]) {
        jac.iter_mut().for_each(|v| *v = 0.0);
        let mut r = 0;
        for c in cons {
            con_jacobian(c, q, |row, a, dx, dy, dphi| {
                if let Some(k) = col(a) {
                    let row = r + row;
                    jac[row * n + k] += dx;
                    jac[row * n + k + 1] += dy;
                    jac[row * n + k + 2] += dphi;
                }
            });
            r += c.rows();
        }
    }

    /// −Φt (velocity right-hand side): f′ on driver rows.
    fn velocity_rhs(&mut self) {
        let mut r = 0;
        for c in &self.cons {
            let v = con_rate(c, &self.laws);
            for k in 0..c.rows() {
                self.rhs[r + k] = if k == 0 { v } else { 0.0 };
            }
            r += c.rows();
        }
    }

    /// γ (acceleration right-hand side), analytic per constraint type.
    fn gamma(&mut self) {
        // Poses cached by the last residual() at this q.
        let mut r = 0;
        for c in &self.cons {
            con_gamma(c, &self.poses, &self.qd, &self.laws, &mut self.rhs[r..r + c.rows()]);
            r += c.rows();
        }
    }

    /// Largest relative residual and the row where it is.
    pub(super) fn residual_norm(&self) -> (f64, usize) {
        let mut worst = (0.0, 0);
        for (k, (&p, &s)) in self.phi.iter().zip(&self.row_scale).enumerate() {
            let v = (p / s).abs();
            if v > worst.0 || v.is_nan() {
                worst = (v, k);
            }
        }
        worst
    }

    /// Writes the equilibrated Jacobian J̃ = D_r⁻¹·Φq·D_c into `jac` (rows divided by
    /// their unit, x/y columns multiplied by the length scale), so every entry is
    /// dimensionless and O(1).
    fn scaled_jacobian(&self, q: &[f64], jac: &mut [f64]) {
        let n = self.n;
        Self::jacobian(&self.cons, q, n, jac);
        self.equilibrate(jac);
    }

    /// Row and column scaling of a Jacobian in place (see [`Solver::scaled_jacobian`]).
    fn equilibrate(&self, jac: &mut [f64]) {
        let n = self.n;
        for (row, rs) in jac.chunks_exact_mut(n).zip(&self.row_scale) {
            let ir = 1.0 / rs;
            for (x, cs) in row.iter_mut().zip(&self.col_scale) {
                *x *= cs * ir;
            }
        }
    }

    /// Builds and factors the equilibrated Φq at the current q; false if a pivot falls
    /// below [`SINGULAR_PIVOT_REL`] · ‖J̃‖∞.
    pub(super) fn factor(&mut self) -> bool {
        let n = self.n;
        let mut a = std::mem::take(&mut self.lu.a);
        // Poses were cached by residual() at this q.
        Self::jacobian_with(&self.cons, &self.poses, n, &mut a);
        self.equilibrate(&mut a);
        let mut norm: f64 = 0.0;
        for r in 0..n {
            norm = norm.max(a[r * n..(r + 1) * n].iter().map(|v| v.abs()).sum::<f64>());
        }
        self.lu.a = a;
        self.lu.factor(norm)
    }

    /// Solves Φqᵀ·λ = rhs[..n] in place with the factored J̃ (the kineto-statics' one
    /// extra solve per sample): J̃ = D_r⁻¹·Φq·D_c, so Φqᵀ = D_c⁻¹·J̃ᵀ·D_r and
    /// J̃ᵀ·(D_r·λ) = D_c·rhs.
    pub(super) fn solve_transposed_in_place(&mut self) {
        let n = self.n;
        for c in 0..n {
            self.rhs[c] *= self.col_scale[c];
        }
        self.lu.solve_transposed(&mut self.rhs[..n]);
        for r in 0..n {
            self.rhs[r] /= self.row_scale[r];
        }
    }

    /// Solves Φq·x = rhs[..n] in place with the factored J̃.
    pub(super) fn solve_in_place(&mut self) {
        let n = self.n;
        for r in 0..n {
            self.rhs[r] /= self.row_scale[r];
        }
        self.lu.solve(&mut self.rhs[..n]);
        for c in 0..n {
            self.rhs[c] *= self.col_scale[c];
        }
    }

    /// The drivers' current values, for messages (angles in degrees).
    pub(super) fn driver_values(&self) -> String {
        self.mech
            .drivers
            .iter()
            .zip(&self.laws)
            .map(|(d, l)| match d.target {
                DriverTarget::JointDistance(_) => format!("driver `{}` = {:.6}", d.name, l.0),
                _ => format!("driver `{}` = {:.4}°", d.name, l.0.to_degrees()),
            })
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// Names of the constraints that take part in a singular Jacobian at q: the rows with
    /// a large share in the left singular vector of the smallest singular value.
    fn singular_constraints(&self) -> String {
        let n = self.n;
        let mut jac = vec![0.0; n * n];
        self.scaled_jacobian(&self.q, &mut jac);
        if jac.iter().any(|v| !v.is_finite()) {
            // nalgebra's SVD does not terminate on NaN or infinite entries.
            return "(not determined: the Jacobian has non-finite entries)".into();
        }
        let mat = nalgebra::DMatrix::from_row_slice(n, n, &jac);
        let Some(svd) = mat.try_svd(true, false, f64::EPSILON, SVD_MAX_ITERATIONS) else {
            return "(not determined: the singular value decomposition did not converge)".into();
        };
        let Some(u) = svd.u else { return "(unknown)".into() };
        let (k, _) = svd
            .singular_values
            .iter()
            .enumerate()
            .fold((0, f64::INFINITY), |acc, (i, &s)| if s < acc.1 { (i, s) } else { acc });
        let mut names: Vec<&str> = Vec::new();
        for r in 0..n {
            if u[(r, k)].abs() > SINGULAR_SHARE {
                let name = self.row_names[r].as_str();
                if !names.contains(&name) {
                    names.push(name);
                }
            }
        }
        names.join(", ")
    }

    /// Newton–Raphson from the current q at time t; leaves Φq factored at the answer.
    fn newton(&mut self, t: f64, max_iter: usize) -> Result<usize, LinkageError> {
        let mut iterations = 0;
        loop {
            self.residual();
            let (res, worst) = self.residual_norm();
            let converged = res <= self.newton_tol;
            if !self.factor() {
                return Err(LinkageError::Singular {
                    t,
                    drivers: self.driver_values(),
                    constraints: self.singular_constraints(),
                });
            }
            if converged {
                return Ok(iterations);
            }
            if iterations >= max_iter || !res.is_finite() {
                // Accept a residual at the crate tolerance when roundoff stalls the tighter goal.
                if res <= crate::geom::tol::RESIDUAL_REL {
                    return Ok(iterations);
                }
                return Err(LinkageError::NoConvergence {
                    t,
                    iterations,
                    residual: res,
                    worst: self.row_names[worst].clone(),
                });
            }
            for k in 0..self.n {
                self.rhs[k] = -self.phi[k];
            }
            self.solve_in_place();
            for k in 0..self.n {
                self.q[k] += self.rhs[k];
            }
            iterations += 1;
        }
    }

    /// q̇ and q̈ from Φq factored at q (poses cached by `residual`).
    pub(super) fn kinematics(&mut self) {
        let n = self.n;
        self.velocity_rhs();
        self.solve_in_place();
        self.qd.copy_from_slice(&self.rhs[..n]);
        self.gamma();
        self.solve_in_place();
        self.qdd.copy_from_slice(&self.rhs[..n]);
    }

    /// Assembles the mechanism at `t` from the initial placement (damped Gauss–Newton,
    /// then Newton), and computes velocities and accelerations there.
    pub fn assemble(&mut self, t: f64) -> Result<State, LinkageError> {
        self.eval_laws(t)?;
        self.levenberg_marquardt(t)?;
        let iterations = self.newton(t, MAX_NEWTON_ITERATIONS)?;
        self.near = self.near_singular(t);
        self.kinematics();
        self.dt_prev = None;
        self.t = Some(t);
        Ok(State {
            t,
            q: self.q.clone(),
            qd: self.qd.clone(),
            qdd: self.qdd.clone(),
            iterations,
            residual: self.residual_norm().0,
            near_singular: self.near.clone(),
        })
    }

    /// Levenberg–Marquardt on ½‖Φ/scale‖² from the current q (robust from a rough
    /// initial placement); fails when it stalls at a nonzero residual.
    fn levenberg_marquardt(&mut self, t: f64) -> Result<(), LinkageError> {
        let n = self.n;
        let l = self.mech.length_scale;
        // Variables scaled so that every column is a length / L: x/L, y/L, φ.
        let colscale: Vec<f64> = (0..n).map(|c| if c % 3 == 2 { 1.0 } else { l }).collect();
        let mut jac = vec![0.0; n * n];
        let mut mu = 1e-3;
        let cost = |s: &Solver| s.phi.iter().zip(&s.row_scale).map(|(p, sc)| (p / sc) * (p / sc)).sum::<f64>();
        self.residual();
        let mut f = cost(self);
        for _ in 0..MAX_ASSEMBLY_ITERATIONS {
            if f.sqrt() <= 1e-10 {
                return Ok(());
            }
            Self::jacobian(&self.cons, &self.q, n, &mut jac);
            let j = nalgebra::DMatrix::from_fn(n, n, |r, c| jac[r * n + c] * colscale[c] / self.row_scale[r]);
            let e = nalgebra::DVector::from_fn(n, |r, _| self.phi[r] / self.row_scale[r]);
            let jtj = j.transpose() * &j;
            let g = j.transpose() * &e;
            let q0 = self.q.clone();
            let mut improved = false;
            for _ in 0..30 {
                let mut a = jtj.clone();
                for k in 0..n {
                    a[(k, k)] += mu * (1.0 + jtj[(k, k)]);
                }
                let Some(step) = a.lu().solve(&(-&g)) else {
                    mu *= 10.0;
                    continue;
                };
                for k in 0..n {
                    self.q[k] = q0[k] + step[k] * colscale[k];
                }
                self.residual();
                let f_new = cost(self);
                if f_new < f {
                    f = f_new;
                    mu = (mu / 3.0).max(1e-12);
                    improved = true;
                    break;
                }
                mu *= 10.0;
            }
            if !improved {
                self.q.copy_from_slice(&q0);
                self.residual();
                break;
            }
        }
        self.residual();
        let (res, worst) = self.residual_norm();
        if res <= 1e-6 {
            return Ok(());
        }
        Err(LinkageError::CannotAssemble { t, residual: res, worst: self.row_names[worst].clone() })
    }

    /// Advances to time `t` from the previous state (extrapolated), keeping the assembly
    /// mode. Allocation-free, except on a near-singular step (the SVD that names the
    /// constraints, see [`NearSingular`]). Returns the Newton iterations.
    pub fn step(&mut self, t: f64) -> Result<usize, LinkageError> {
        let Some(t0) = self.t else {
            return self.assemble(t).map(|s| s.iterations);
        };
        self.eval_laws(t)?;
        let dt = t - t0;
        // Taylor predictor q + q̇·Δt + ½·q̈·Δt² (+ ⅙·q⃛·Δt³ with q⃛ from the last two q̈).
        let jerk = self.dt_prev.filter(|d| *d != 0.0).map(|d| 1.0 / d);
        for k in 0..self.n {
            let third = jerk.map_or(0.0, |inv| (self.qdd[k] - self.qdd_prev[k]) * inv * dt * dt * dt / 6.0);
            self.q[k] += self.qd[k] * dt + 0.5 * self.qdd[k] * dt * dt + third;
        }
        let it = self.newton(t, MAX_NEWTON_ITERATIONS)?;
        self.near = self.near_singular(t);
        self.qdd_prev.copy_from_slice(&self.qdd);
        self.kinematics();
        self.dt_prev = Some(dt);
        self.t = Some(t);
        Ok(it)
    }

    /// Resumes from `state` (a state this solver computed): the next [`Solver::step`]
    /// starts from it, extrapolated to its time (second order), in its assembly mode. Used
    /// to solve at a time between samples (e.g. to refine an extreme position).
    pub fn resume(&mut self, state: &State) {
        if state.q.len() != self.n || state.qd.len() != self.n || state.qdd.len() != self.n {
            return;
        }
        self.q.copy_from_slice(&state.q);
        self.qd.copy_from_slice(&state.qd);
        self.qdd.copy_from_slice(&state.qdd);
        self.qdd_prev.copy_from_slice(&state.qdd);
        self.dt_prev = None;
        self.t = Some(state.t);
        self.near = state.near_singular.clone();
    }

    /// Solves at every time in `times` (the first assembles from the initial placement).
    pub fn run(&mut self, times: &[f64]) -> Result<Vec<State>, LinkageError> {
        self.run_each(times, |_| Ok(()))
    }

    /// [`Solver::run`], calling `each` after every step (the solver at that step, Φq
    /// factored at its answer) before its state is stored.
    pub(super) fn run_each(
        &mut self,
        times: &[f64],
        mut each: impl FnMut(&mut Solver) -> Result<(), LinkageError>,
    ) -> Result<Vec<State>, LinkageError> {
        let mut out = Vec::with_capacity(times.len());
        for &t in times {
            let iterations = self.step(t)?;
            self.residual();
            each(self)?;
            out.push(State {
                t,
                q: self.q.clone(),
                qd: self.qd.clone(),
                qdd: self.qdd.clone(),
                iterations,
                residual: self.residual_norm().0,
                near_singular: self.near.clone(),
            });
        }
        Ok(out)
    }

    /// Φ(q, t) at the coordinates `q` (raw rows in the solver's constraint order, the
    /// drivers' rows last): what a tolerance study differences between two mechanisms that
    /// differ in one dimension. Leaves the solver's own q as it was.
    pub fn residual_at(&mut self, t: f64, q: &[f64]) -> Result<Vec<f64>, LinkageError> {
        let saved = std::mem::replace(&mut self.q, q.to_vec());
        self.eval_law_values(t)?;
        self.residual();
        self.q = saved;
        fill_poses(&self.q, &mut self.poses);
        Ok(self.phi.clone())
    }

    /// Solves Φq(q)·x = b at the coordinates `q` for each column b of `cols` (n values
    /// each, in place), on the equilibrated factorisation the solver steps with; `false`
    /// (`cols` unchanged) when Φq is singular there. Leaves the solver at `q`.
    pub fn solve_jacobian_at(&mut self, q: &[f64], cols: &mut [f64]) -> bool {
        let n = self.n;
        if q.len() != n || n == 0 || !cols.len().is_multiple_of(n) {
            return false;
        }
        self.q.copy_from_slice(q);
        fill_poses(&self.q, &mut self.poses);
        if !self.factor() {
            return false;
        }
        for c in cols.chunks_exact_mut(n) {
            self.rhs[..n].copy_from_slice(c);
            self.solve_in_place();
            c.copy_from_slice(&self.rhs[..n]);
        }
        true
    }

    /// Relative residual of every constraint row at `state` (for checks).
    pub fn residuals(&mut self, state: &State) -> Result<Vec<f64>, LinkageError> {
        let saved = std::mem::replace(&mut self.q, state.q.clone());
        self.eval_laws(state.t)?;
        self.residual();
        self.q = saved;
        Ok(self.phi.iter().zip(&self.row_scale).map(|(p, s)| p / s).collect())
    }

    /// Projects `s.q` onto the joint equations (the first `mk` rows) with minimum-norm
    /// Newton corrections; returns the relative residual reached.
    fn project(s: &mut Solver, mk: usize, jac: &mut [f64]) -> f64 {
        let n = s.n;
        let res = |s: &Solver| (0..mk).map(|r| (s.phi[r] / s.row_scale[r]).abs()).fold(0.0, f64::max);
        for _ in 0..30 {
            s.residual();
            if res(s) <= crate::geom::tol::RESIDUAL_REL * 1e-2 {
                break;
            }
            Self::jacobian(&s.cons, &s.q, n, jac);
            let j = nalgebra::DMatrix::from_fn(mk, n, |r, c| jac[r * n + c] * s.col_scale[c] / s.row_scale[r]);
            let phi = nalgebra::DVector::from_fn(mk, |r, _| s.phi[r] / s.row_scale[r]);
            let jjt = &j * j.transpose();
            let Some(y) = jjt.lu().solve(&phi) else { break };
            let dq = j.transpose() * y;
            for k in 0..n {
                s.q[k] -= dq[k] * s.col_scale[k];
            }
        }
        s.residual();
        res(s)
    }

    /// The drag constraint (seed 002): from `state`, moves `anchor` as close as the joints
    /// allow to `target`, with the drivers released: minimises ½|r(q) − target|² on the
    /// manifold of the joint equations (Gauss–Newton steps from the KKT system, each
    /// projected back onto the joints, with a backtracking line search), so the result is
    /// the nearest reachable configuration in the current assembly mode. Returns the new
    /// coordinates (velocities and accelerations zero).
    pub fn drag(&self, state: &State, anchor: Anchor, target: Point) -> Result<State, LinkageError> {
        let n = self.n;
        let mk = self.m - self.mech.drivers.len();
        let l = self.mech.length_scale;
        let mut s = self.clone();
        s.q.copy_from_slice(&state.q);
        let mut jac = vec![0.0; self.m * n];
        let point_jac = |q: &[f64]| -> (Point, [[f64; 3]; 2]) {
            let p = pose(q, anchor.body);
            let sv = p.rot(anchor.local);
            let b = perp(sv);
            (Point::from(p.r + sv), [[1.0, 0.0, b.x], [0.0, 1.0, b.y]])
        };
        let dist = |q: &[f64]| (point_jac(q).0 - target).norm();
        Self::project(&mut s, mk, &mut jac);
        let mut converged = false;
        let mut lambda = vec![0.0; mk];
        for _ in 0..500 {
            s.residual();
            Self::jacobian(&s.cons, &s.q, n, &mut jac);
            let (p, pj) = point_jac(&s.q);
            let e = p - target;
            // KKT: [H + μI, Φqᵀ; Φq, 0] [Δq; λ] = [−Jpᵀ e; −Φ], with H the Hessian of the
            // Lagrangian ½|e|² + λ·Φ (central differences of its gradient; Gauss–Newton's
            // JpᵀJp alone overshoots when the target is far out of reach).
            let size = n + mk;
            let mut a = nalgebra::DMatrix::<f64>::zeros(size, size);
            let mut b = nalgebra::DVector::<f64>::zeros(size);
            let grad = |s: &Solver, q: &[f64], jac: &mut [f64]| -> Vec<f64> {
                let mut g = vec![0.0; n];
                let (p, pj) = point_jac(q);
                let e = p - target;
                if let Some(k0) = col(anchor.body) {
                    for r in 0..3 {
                        g[k0 + r] += pj[0][r] * e.x + pj[1][r] * e.y;
                    }
                }
                Self::jacobian(&s.cons, q, n, jac);
                for r in 0..mk {
                    for c in 0..n {
                        g[c] += jac[r * n + c] * lambda[r];
                    }
                }
                g
            };
            let mut work = vec![0.0; self.m * n];
            let mut qh = s.q.clone();
            for c in 0..n {
                let h = 1e-6 * s.col_scale[c];
                qh[c] = s.q[c] + h;
                let gp = grad(&s, &qh, &mut work);
                qh[c] = s.q[c] - h;
                let gm = grad(&s, &qh, &mut work);
                qh[c] = s.q[c];
                for r in 0..n {
                    let v = 0.5 * (gp[r] - gm[r]) / (2.0 * h);
                    a[(r, c)] += v;
                    a[(c, r)] += v;
                }
            }
            // The Gauss–Newton matrix JpᵀJp: a descent direction when the full Hessian's is not.
            let mut gn = nalgebra::DMatrix::<f64>::zeros(size, size);
            Self::jacobian(&s.cons, &s.q, n, &mut jac);
            if let Some(k0) = col(anchor.body) {
                for r in 0..3 {
                    for c in 0..3 {
                        gn[(k0 + r, k0 + c)] += pj[0][r] * pj[0][c] + pj[1][r] * pj[1][c];
                    }
                    b[k0 + r] -= pj[0][r] * e.x + pj[1][r] * e.y;
                }
            }
            for m in [&mut a, &mut gn] {
                for k in 0..n {
                    // Levenberg damping keeps the step finite in directions the point does not see.
                    m[(k, k)] += 1e-9 * if k % 3 == 2 { l * l } else { 1.0 };
                }
                for r in 0..mk {
                    for c in 0..n {
                        m[(n + r, c)] = jac[r * n + c];
                        m[(c, n + r)] = jac[r * n + c];
                    }
                }
            }
            for r in 0..mk {
                b[n + r] = -s.phi[r];
            }
            let q0 = s.q.clone();
            let d0 = dist(&q0);
            let mut accepted = false;
            let mut small = false;
            for (k, m) in [a, gn].into_iter().enumerate() {
                let Some(step) = m.lu().solve(&b) else { continue };
                if k == 0 {
                    for r in 0..mk {
                        lambda[r] = step[n + r];
                    }
                }
                let mut norm: f64 = 0.0;
                for c in 0..n {
                    norm = norm.max(if c % 3 == 2 { step[c].abs() * l } else { step[c].abs() });
                }
                if norm <= 1e-11 * l {
                    small = true;
                    break;
                }
                // Backtracking: at most a tenth of the mechanism's size per step.
                let mut alpha = if norm > 0.1 * l { 0.1 * l / norm } else { 1.0 };
                for _ in 0..40 {
                    for c in 0..n {
                        s.q[c] = q0[c] + alpha * step[c];
                    }
                    let res = Self::project(&mut s, mk, &mut jac);
                    // Near the minimum the distance changes below its roundoff: accept a
                    // step that does not increase it beyond that.
                    if res <= crate::geom::tol::RESIDUAL_REL && dist(&s.q) <= d0 + 1e-14 * l {
                        accepted = true;
                        break;
                    }
                    alpha *= 0.5;
                }
                if accepted {
                    break;
                }
            }
            if small || !accepted {
                // The step vanishes, or no feasible step lowers the distance: a constrained minimum.
                if !accepted {
                    s.q.copy_from_slice(&q0);
                }
                converged = true;
                break;
            }
        }
        let res = Self::project(&mut s, mk, &mut jac);
        if !converged || res > crate::geom::tol::RESIDUAL_REL {
            return Err(LinkageError::Drag { what: format!("did not converge (joint residual {res:.3e} relative)") });
        }
        Ok(State {
            t: state.t,
            q: s.q.clone(),
            qd: vec![0.0; n],
            qdd: vec![0.0; n],
            iterations: 0,
            residual: res,
            near_singular: None,
        })
    }
}

/// A law's whole jet at `t` (out of the positions-only step's hot path), or the error
/// where it is not finite.
#[cold]
#[inline(never)]
pub(super) fn whole_law(d: &super::Driver, t: f64) -> Result<(f64, f64, f64), LinkageError> {
    let j = d.law.eval(t);
    j.finite().ok_or_else(|| not_finite(d, t, j))
}

/// The error for a driver law that is not finite at `t` (out of the step's hot path).
#[cold]
#[inline(never)]
fn not_finite(d: &super::Driver, t: f64, j: crate::solve::expr::Jet) -> LinkageError {
    LinkageError::DriverNotFinite {
        driver: d.name.clone(),
        law: crate::text::excerpt(d.law.source()),
        t,
        value: j.value,
        d1: j.d1,
        d2: j.d2,
    }
}

#[cfg(test)]
#[allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the code under test calls"
)]
mod tests {
    use super::super::{Body, Driver, Joint};
    use super::*;
    use crate::solve::expr::Expr;

    /// A slider-crank: crank (O at origin, A at r), rod (A, B), slider B on the x axis.
    fn slider_crank(law: &str) -> Mechanism {
        let r = 1.0;
        let l = 3.0;
        let phi0: f64 = 0.3;
        let a = Vector::new(r * phi0.cos(), r * phi0.sin());
        let beta = (-(a.y / l)).asin();
        let bx = a.x + l * beta.cos();
        Mechanism {
            bodies: vec![
                Body {
                    name: "crank".into(),
                    points: vec![("O".into(), Vector::zeros()), ("A".into(), Vector::new(r, 0.0))],
                    at: Point::origin(),
                    angle: phi0,
                },
                Body {
                    name: "rod".into(),
                    points: vec![("A".into(), Vector::zeros()), ("B".into(), Vector::new(l, 0.0))],
                    at: Point::from(a),
                    angle: beta,
                },
                Body {
                    name: "slider".into(),
                    points: vec![("B".into(), Vector::zeros())],
                    at: Point::new(bx, 0.0),
                    angle: 0.0,
                },
            ],
            joints: vec![
                Joint {
                    name: "O".into(),
                    kind: JointKind::Revolute {
                        a: Anchor { body: Attach::Ground, local: Vector::zeros() },
                        b: Anchor { body: Attach::Body(0), local: Vector::zeros() },
                    },
                },
                Joint {
                    name: "A".into(),
                    kind: JointKind::Revolute {
                        a: Anchor { body: Attach::Body(0), local: Vector::new(r, 0.0) },
                        b: Anchor { body: Attach::Body(1), local: Vector::zeros() },
                    },
                },
                Joint {
                    name: "B".into(),
                    kind: JointKind::Revolute {
                        a: Anchor { body: Attach::Body(1), local: Vector::new(l, 0.0) },
                        b: Anchor { body: Attach::Body(2), local: Vector::zeros() },
                    },
                },
                Joint {
                    name: "guide".into(),
                    kind: JointKind::Prismatic {
                        point: Anchor { body: Attach::Body(2), local: Vector::zeros() },
                        q1: Anchor { body: Attach::Ground, local: Vector::new(-1.0, 0.0) },
                        q2: Anchor { body: Attach::Ground, local: Vector::new(1.0, 0.0) },
                        angle: 0.0,
                    },
                },
            ],
            drivers: vec![Driver {
                name: "crank".into(),
                target: DriverTarget::JointAngle(0),
                law: Expr::parse(law).unwrap(),
            }],
            length_scale: 4.0,
        }
    }

    #[test]
    fn jacobian_matches_finite_differences() {
        let mut s = Solver::new(slider_crank("0.3 + 2*t")).unwrap();
        // A generic (non-assembled) q so that every term is exercised.
        let q0: Vec<f64> = (0..s.n).map(|k| 0.3 + 0.17 * k as f64).collect();
        let n = s.n;
        let mut jac = vec![0.0; n * n];
        Solver::jacobian(&s.cons, &q0, n, &mut jac);
        s.eval_laws(0.2).unwrap();
        let h = 1e-6;
        for c in 0..n {
            s.q.copy_from_slice(&q0);
            s.q[c] += h;
            s.residual();
            let plus = s.phi.clone();
            s.q[c] -= 2.0 * h;
            s.residual();
            for r in 0..n {
                let fd = (plus[r] - s.phi[r]) / (2.0 * h);
                assert!((fd - jac[r * n + c]).abs() < 1e-7, "row {r} col {c}: fd {fd} vs {}", jac[r * n + c]);
            }
        }
    }

    #[test]
    fn slider_crank_matches_its_closed_form() {
        let mut s = Solver::new(slider_crank("0.3 + 2*t")).unwrap();
        let times: Vec<f64> = (0..50).map(|k| k as f64 * 0.07).collect();
        let states = s.run(&times).unwrap();
        let slider = Anchor { body: Attach::Body(2), local: Vector::zeros() };
        for st in &states {
            let phi = 0.3 + 2.0 * st.t;
            let (r, l, w) = (1.0_f64, 3.0_f64, 2.0_f64);
            let root = (l * l - (r * phi.sin()).powi(2)).sqrt();
            let x = r * phi.cos() + root;
            let v = -r * w * phi.sin() - r * r * w * phi.sin() * phi.cos() / root;
            let p = st.point(slider);
            assert!((p.x - x).abs() < 1e-12 && p.y.abs() < 1e-12, "t={}: {p:?} vs {x}", st.t);
            let vs = st.velocity(slider);
            assert!((vs.x - v).abs() < 1e-11, "t={}: v {} vs {v}", st.t, vs.x);
            assert!(st.residual <= crate::geom::tol::RESIDUAL_REL);
        }
        // Accelerations against central differences of the exact velocities.
        for st in &states[1..] {
            let (r, l, w) = (1.0_f64, 3.0_f64, 2.0_f64);
            let vel = |t: f64| {
                let phi = 0.3 + 2.0 * t;
                let root = (l * l - (r * phi.sin()).powi(2)).sqrt();
                -r * w * phi.sin() - r * r * w * phi.sin() * phi.cos() / root
            };
            let h = 1e-5;
            let a = (vel(st.t + h) - vel(st.t - h)) / (2.0 * h);
            assert!((st.acceleration(slider).x - a).abs() < 1e-6, "t={}", st.t);
        }
    }

    #[test]
    fn counts_degrees_of_freedom_before_solving() {
        let mut m = slider_crank("t");
        m.drivers.clear();
        let e = Solver::new(m).unwrap_err();
        assert!(matches!(e, LinkageError::DofMismatch { dof: 1, drivers: 0, .. }), "{e}");
        assert!(e.to_string().contains("add 1 driver"), "{e}");
    }

    #[test]
    fn dead_point_is_reported_as_singular() {
        // Rod as long as... a slider-crank with r = l reaches a singular position at φ = 90°.
        let mut m = slider_crank("0.3 + t");
        let l = 1.0;
        if let JointKind::Revolute { a, .. } = &mut m.joints[2].kind {
            a.local = Vector::new(l, 0.0);
        }
        m.bodies[1].points[1].1 = Vector::new(l, 0.0);
        let a0 = Vector::new(0.3f64.cos(), 0.3f64.sin());
        m.bodies[1].angle = -0.3;
        m.bodies[2].at = Point::new(2.0 * a0.x, 0.0);
        let mut s = Solver::new(m).unwrap();
        let times: Vec<f64> = (0..=100).map(|k| k as f64 * (std::f64::consts::FRAC_PI_2 - 0.3) / 100.0).collect();
        let e = s.run(&times).unwrap_err();
        match &e {
            LinkageError::Singular { t, constraints, drivers } => {
                assert!((t - times[100]).abs() < 1e-12, "{e}");
                assert!(drivers.contains("driver `crank` = 90.0000°"), "{e}");
                assert!(constraints.contains("joint"), "{e}");
            }
            other => panic!("expected a singularity, got {other}"),
        }
    }

    #[test]
    fn constraints_of_a_non_finite_jacobian_are_not_determined_rather_than_looping() {
        // nalgebra's SVD never returns on NaN entries; a driver far out of range (a scene
        // with time.to = 1e200) used to hang the run here.
        let mut s = Solver::new(slider_crank("0.3 + t")).unwrap();
        s.q.iter_mut().for_each(|v| *v = f64::NAN);
        assert!(s.singular_constraints().contains("not determined"));
        s.q.iter_mut().for_each(|v| *v = 1e200);
        let names = s.singular_constraints();
        assert!(!names.is_empty());
    }

    #[test]
    fn cannot_assemble_is_reported() {
        let mut m = slider_crank("0.3");
        // Guide far above the reach of crank + rod.
        if let JointKind::Prismatic { q1, q2, .. } = &mut m.joints[3].kind {
            q1.local.y = 10.0;
            q2.local.y = 10.0;
        }
        let mut s = Solver::new(m).unwrap();
        let e = s.assemble(0.0).unwrap_err();
        assert!(matches!(e, LinkageError::CannotAssemble { .. }), "{e}");
    }

    #[test]
    fn drag_moves_the_point_as_close_as_the_joints_allow() {
        let mut s = Solver::new(slider_crank("0.3")).unwrap();
        let st = s.assemble(0.0).unwrap();
        let a = Anchor { body: Attach::Body(0), local: Vector::new(1.0, 0.0) };
        // Crank pin A dragged towards (0, 5): it can only reach (0, 1).
        let d = s.drag(&st, a, Point::new(0.0, 5.0)).unwrap();
        let p = d.point(a);
        assert!((p - Point::new(0.0, 1.0)).norm() < 1e-9, "{p:?}");
        let res = s.residuals(&d).unwrap();
        assert!(res[..7].iter().all(|r| r.abs() <= 1e-12), "{res:?}");
    }
}
