//! The Assur route's sweep: each group solved over every time step of a motion before the
//! next group ([`AssurSolver::positions_into`], [`AssurSolver::motion_into`]). A group needs
//! only the groups before it at the same step, its own last two positions (its prediction)
//! and its branch, so a sweep holds each group's constants across the steps and gives the
//! bits of stepping: the closed forms are the step's own, read and written through a
//! [`Lane`] instead of the live solver.

use super::*;

/// Step `k` of a sweep ([`AssurSolver::positions_into`], [`AssurSolver::motion_into`]):
/// the sweep's poses, body by body (body b's pose at step k at `b·stride + k + 2`; the two
/// entries before step 0 hold the step before the last and the last), the laws' values
/// (and rates) at each step, the steps' predictions, the bodies' rates (body b's at step k at
/// `b·rstride + k + 2`, the entry before step 0 the last step's: a sweep of positions only
/// keeps that entry alone, `rstride` 2).
struct Lane<'a> {
    poses: &'a mut [Pose],
    stride: usize,
    k: usize,
    laws: &'a [(f64, f64, f64)],
    nd: usize,
    how: Extrapolation,
    rates: &'a mut [Rates],
    rstride: usize,
    /// The motion's rows from the sweep's first step (q, and with the rates q̇, q̈; `n`
    /// values a step), written as the poses and rates are.
    q: &'a mut [f64],
    qd: &'a mut [f64],
    qdd: &'a mut [f64],
    n: usize,
}

impl Poses for Lane<'_> {
    #[inline(always)]
    fn pose(&self, b: usize) -> Pose {
        self.poses[b * self.stride + self.k + 2]
    }
}

impl Lane<'_> {
    /// The prediction of coordinate `j` (0: x, 1: y, 2: φ) of body `b`, as
    /// [`Predictor::at`] gives it (the two entries before step 0 hold the q of the step
    /// before the last and of the last; Taylor's rates are the last step's).
    #[inline(always)]
    fn predicted(&self, b: usize, j: usize) -> f64 {
        let coordinate = |p: Pose| match j {
            0 => p.r.x,
            1 => p.r.y,
            _ => p.phi,
        };
        let at = b * self.stride + self.k;
        let now = coordinate(self.poses[at + 1]);
        match self.how {
            Extrapolation::Hold => now,
            Extrapolation::Linear(f) => now + (now - coordinate(self.poses[at])) * f,
            Extrapolation::Taylor(dt) => {
                let r = self.rates[b * self.rstride + self.k + 1];
                now + r.qd[j] * dt + 0.5 * r.qdd[j] * dt * dt
            }
        }
    }
}

impl Frame for Lane<'_> {
    #[inline(always)]
    fn last(&self, b: usize) -> Pose {
        self.poses[b * self.stride + self.k + 1]
    }
    #[inline(always)]
    fn law(&self, d: usize) -> f64 {
        self.laws[self.k * self.nd + d].0
    }
    #[inline(always)]
    fn predicted_phi(&self, b: usize) -> f64 {
        self.predicted(b, 2)
    }
    #[inline(always)]
    fn predicted_r(&self, b: usize) -> Vector {
        Vector::new(self.predicted(b, 0), self.predicted(b, 1))
    }
    #[inline(always)]
    fn put(&mut self, b: usize, r: Vector, phi: f64, cs: (f64, f64)) {
        self.poses[b * self.stride + self.k + 2] = Pose { r, phi, c: cs.0, s: cs.1 };
        let at = self.k * self.n + 3 * b;
        self.q[at..at + 3].copy_from_slice(&[r.x, r.y, phi]);
    }
}

impl RateFrame for Lane<'_> {
    #[inline(always)]
    fn rates(&self, b: usize) -> Rates {
        self.rates[b * self.rstride + self.k + 2]
    }
    #[inline(always)]
    fn jet(&self, d: usize) -> (f64, f64, f64) {
        self.laws[self.k * self.nd + d]
    }
    #[inline(always)]
    fn put_rates(&mut self, b: usize, r: Rates) {
        self.rates[b * self.rstride + self.k + 2] = r;
        let at = self.k * self.n + 3 * b;
        self.qd[at..at + 3].copy_from_slice(&r.qd);
        self.qdd[at..at + 3].copy_from_slice(&r.qdd);
    }
}

/// A sweep's buffers (kept between sweeps): every body's poses and rates over the steps
/// (see [`Lane`]), the laws' values (and rates) and the prediction of each step, each
/// group's branch and (with rates) the conditioning of its rates after each step.
#[derive(Debug, Clone, Default)]
pub(super) struct Sweep {
    poses: Vec<Pose>,
    rates: Vec<Rates>,
    laws: Vec<(f64, f64, f64)>,
    how: Vec<Extrapolation>,
    sides: Vec<f64>,
    pivots: Vec<f64>,
}

/// One group over the sweep's steps `0..end`, its kind's closed form `K` at each (and, with
/// `RATES`, its rates, whose conditioning goes into `pivots`), its position's constants
/// and branch held across the steps: the first step it cannot solve (stepped alone
/// afterwards, which says why: a position that cannot be assembled, rates at a dead
/// point).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn sweep_group<const RATES: bool, K: Kernel>(
    op: &mut Op,
    mut lane: Lane<'_>,
    how: &[Extrapolation],
    sides: &mut [f64],
    pivots: &mut [f64],
    end: usize,
    slack: f64,
) -> Option<usize> {
    let position = op.position.clone();
    let mut side = op.side;
    for (k, (&how, after)) in how[..end].iter().zip(&mut sides[..end]).enumerate() {
        lane.k = k;
        lane.how = how;
        if K::position(&mut lane, &position, &mut side, slack).is_err() {
            op.side = side;
            return Some(k);
        }
        *after = side;
        if RATES {
            match K::rates(&mut lane, &position) {
                Some(rho) if !(rho.is_nan() || rho <= super::super::SINGULAR_PIVOT_REL) => pivots[k] = rho,
                _ => {
                    op.side = side;
                    return Some(k);
                }
            }
        }
    }
    op.side = side;
    None
}

/// A kind's closed forms for a sweep's loop: its position and its rates at a step (static
/// calls, inlined into the loop of each kind).
trait Kernel {
    /// The group's position at the lane's step.
    fn position(lane: &mut Lane<'_>, position: &Position, side: &mut f64, slack: f64) -> Result<(), Why>;
    /// The group's rates at the lane's step: ρ, the conditioning of its 2×2.
    fn rates(lane: &mut Lane<'_>, position: &Position) -> Option<f64>;
}

/// The [`Kernel`] of each kind: `Name => position's closed form, rates' closed form`.
macro_rules! kernels {
    ($($name:ident => $position:ident, $rates:ident;)*) => {$(
        struct $name;
        impl Kernel for $name {
            #[inline(always)]
            fn position(lane: &mut Lane<'_>, position: &Position, side: &mut f64, slack: f64) -> Result<(), Why> {
                $position(lane, position, side, slack)
            }
            #[inline(always)]
            fn rates(lane: &mut Lane<'_>, position: &Position) -> Option<f64> {
                $rates(lane, position)
            }
        }
    )*};
}

kernels! {
    DrivenAngleK => driven_angle, driven_angle_rates;
    DrivenDistanceK => driven_distance, driven_distance_rates;
    RrrK => rrr, rrr_rates;
    RrpK => rrp, rrp_rates;
    RprK => rpr, rpr_rates;
    PrpK => prp, prp_rates;
    RppK => rpp, rpp_rates;
}

/// One group swept by its kind's closed form (see [`sweep_group`]).
fn sweep_kind<const RATES: bool>(
    op: &mut Op,
    lane: Lane<'_>,
    how: &[Extrapolation],
    sides: &mut [f64],
    pivots: &mut [f64],
    end: usize,
    slack: f64,
) -> Option<usize> {
    match op.position {
        Position::DrivenAngle { .. } => sweep_group::<RATES, DrivenAngleK>(op, lane, how, sides, pivots, end, slack),
        Position::DrivenDistance { .. } => {
            sweep_group::<RATES, DrivenDistanceK>(op, lane, how, sides, pivots, end, slack)
        }
        Position::Rrr { .. } => sweep_group::<RATES, RrrK>(op, lane, how, sides, pivots, end, slack),
        Position::Rrp { .. } => sweep_group::<RATES, RrpK>(op, lane, how, sides, pivots, end, slack),
        Position::Rpr { .. } => sweep_group::<RATES, RprK>(op, lane, how, sides, pivots, end, slack),
        Position::Prp { .. } => sweep_group::<RATES, PrpK>(op, lane, how, sides, pivots, end, slack),
        Position::Rpp { .. } => sweep_group::<RATES, RppK>(op, lane, how, sides, pivots, end, slack),
        // Not swept (a scene with these is stepped).
        Position::Triad(_) | Position::Newton => Some(0),
    }
}

impl AssurSolver {
    /// Positions (and with `rates`, velocities and accelerations) at `times` by a sweep
    /// (see [`AssurSolver::positions_into`], [`AssurSolver::motion_into`]) from the last
    /// step solved, each step appended to `out`: the number of steps solved, all of them
    /// unless one cannot be (the solver then stands after the step before it).
    pub(super) fn sweep(&mut self, times: &[f64], out: &mut Motion, rates: bool) -> usize {
        let Some(t_last) = self.inner.t else { return 0 };
        let (nb, nd) = (self.inner.poses.len(), self.inner.laws.len());
        let sw = &mut self.sweep;
        // The laws' values (and rates) and each step's prediction, as the steps would set
        // them.
        sw.laws.clear();
        sw.how.clear();
        let (mut rates_valid, mut dt_prev, mut t0) = (self.rates_valid, self.dt_prev, t_last);
        let mut end = times.len();
        'steps: for (k, &t) in times.iter().enumerate() {
            for d in &self.inner.mech.drivers {
                let jet = if rates {
                    d.law.eval(t).finite()
                } else {
                    match d.law.value(t) {
                        Some(v) if v.is_finite() => Some((v, 0.0, 0.0)),
                        _ => whole_law(d, t).ok(),
                    }
                };
                let Some(jet) = jet else {
                    sw.laws.truncate(k * nd);
                    end = k;
                    break 'steps;
                };
                sw.laws.push(jet);
            }
            let dt = t - t0;
            sw.how.push(Extrapolation::of(rates_valid, dt_prev, dt));
            (rates_valid, dt_prev, t0) = (rates, Some(dt), t);
        }
        if end == 0 {
            return 0;
        }
        // Body by body: the step before the last (its q: what the prediction reads), the
        // last (its cached pose, whose origin and angle are its q: what a group reads as
        // its bodies' last), then the steps; the rates likewise (the last step's, what
        // Taylor's prediction reads; with `rates`, then the steps').
        let steps = end;
        let stride = steps + 2;
        let rstride = if rates { stride } else { 2 };
        // Not cleared: a group reads only what this sweep has written (the first two
        // entries of each body, the steps the groups before it solved, its own last
        // steps), so the buffers only grow.
        if sw.poses.len() < nb * stride {
            sw.poses.resize(nb * stride, GROUND_POSE);
        }
        if sw.rates.len() < nb * rstride {
            sw.rates.resize(nb * rstride, Rates::default());
        }
        for (b, &p) in self.inner.poses.iter().enumerate() {
            let q = &self.q_prev[3 * b..3 * b + 3];
            sw.poses[b * stride] = Pose { r: Vector::new(q[0], q[1]), phi: q[2], ..GROUND_POSE };
            sw.poses[b * stride + 1] = p;
            sw.rates[b * rstride + 1] = Rates { qd: coords(&self.inner.qd, b), qdd: coords(&self.inner.qdd, b) };
        }
        let groups = self.ops.len();
        sw.sides.clear();
        sw.sides.resize(groups * steps, 0.0);
        sw.pivots.clear();
        if rates {
            sw.pivots.resize(groups * steps, 1.0);
        }
        let slack = crate::geom::tol::RESIDUAL_REL * self.inner.mech.length_scale;
        // The motion's rows, written by the groups as they sweep (cut back to the steps
        // every group solved).
        let n = 3 * nb;
        let first = out.q.len();
        out.q.resize(first + steps * n, 0.0);
        if rates {
            out.qd.resize(first + steps * n, 0.0);
            out.qdd.resize(first + steps * n, 0.0);
        }
        let mut branches = Vec::with_capacity(groups);
        for (gi, op) in self.ops.iter_mut().enumerate() {
            branches.push(op.side);
            let lane = Lane {
                poses: &mut sw.poses,
                stride,
                k: 0,
                laws: &sw.laws,
                nd,
                how: Extrapolation::Hold,
                rates: &mut sw.rates,
                rstride,
                q: &mut out.q[first..],
                qd: if rates { &mut out.qd[first..] } else { &mut [] },
                qdd: if rates { &mut out.qdd[first..] } else { &mut [] },
                n,
            };
            let (how, sides) = (&sw.how[..], &mut sw.sides[gi * steps..(gi + 1) * steps]);
            let stop = if rates {
                sweep_kind::<true>(op, lane, how, sides, &mut sw.pivots[gi * steps..(gi + 1) * steps], end, slack)
            } else {
                sweep_kind::<false>(op, lane, how, sides, &mut [], end, slack)
            };
            if let Some(k) = stop {
                end = end.min(k);
            }
        }
        if end < steps {
            // Every group's branch after the last step solved (a group swept further than a
            // later group could follow is taken back).
            for (gi, op) in self.ops.iter_mut().enumerate() {
                op.side = if end == 0 { branches[gi] } else { sw.sides[gi * steps + end - 1] };
            }
        }
        out.q.truncate(first + end * n);
        if rates {
            out.qd.truncate(first + end * n);
            out.qdd.truncate(first + end * n);
        }
        if end == 0 {
            return 0;
        }
        // Every step solved, then the solver as stepping would leave it: q and the poses of
        // the last step, the step before it for the next prediction, the time, the laws,
        // the rates and their state.
        if end >= 2 {
            let before = out.q.len() - 2 * n;
            self.q_prev.copy_from_slice(&out.q[before..before + n]);
        } else {
            self.q_prev.copy_from_slice(&self.inner.q);
        }
        self.inner.q.copy_from_slice(&out.q[out.q.len() - n..]);
        for (b, p) in self.inner.poses.iter_mut().enumerate() {
            *p = sw.poses[b * stride + end + 1];
        }
        let t = times[end - 1];
        if rates {
            // The rates of the step before the last (what stepping leaves swapped out),
            // and of the last.
            let before = if end >= 2 { end } else { 1 };
            for b in 0..nb {
                let r = sw.rates[b * rstride + before];
                self.qd_prev[3 * b..3 * b + 3].copy_from_slice(&r.qd);
                self.qdd_prev[3 * b..3 * b + 3].copy_from_slice(&r.qdd);
            }
            self.inner.qd.copy_from_slice(&out.qd[out.qd.len() - n..]);
            self.inner.qdd.copy_from_slice(&out.qdd[out.qdd.len() - n..]);
            // Each step's near-singular report: the group whose rates are the worst
            // conditioned, as a step finds it.
            let first_step = out.iterations.len();
            out.iterations.extend(std::iter::repeat_n(0, end));
            self.inner.near = None;
            for (k, &tk) in times[..end].iter().enumerate() {
                let mut worst: Option<(f64, usize)> = None;
                for gi in 0..groups {
                    let rho = sw.pivots[gi * steps + k];
                    if worst.is_none_or(|(p, _)| rho < p) {
                        worst = Some((rho, gi));
                    }
                }
                if let Some((pivot, gi)) = worst.filter(|&(pivot, _)| pivot < NEAR_SINGULAR_PIVOT_REL) {
                    let _ = self.inner.eval_law_values(tk);
                    let near = NearSingular {
                        t: tk,
                        pivot,
                        drivers: self.inner.driver_values(),
                        constraints: self.plans[gi].constraint_names(&self.inner),
                    };
                    if k + 1 == end {
                        // The last step's, as a step leaves it.
                        self.inner.near = Some(near.clone());
                    }
                    out.near.push((first_step + k, near));
                }
            }
            for (gi, plan) in self.plans.iter_mut().enumerate() {
                plan.pivot = sw.pivots[gi * steps + end - 1];
            }
            // Sets the laws and their rates as the step did; it succeeded there.
            let _ = self.inner.eval_laws(t);
        } else {
            if self.rates_valid {
                // A positions-only step keeps the rates it predicted from.
                self.qd_prev.copy_from_slice(&self.inner.qd);
                self.qdd_prev.copy_from_slice(&self.inner.qdd);
            }
            // Sets the laws' values (and any whole jet) as the step did; it succeeded there.
            let _ = self.inner.eval_law_values(t);
        }
        self.dt_prev = Some(t - if end >= 2 { times[end - 2] } else { t_last });
        self.how = sw.how[end - 1];
        self.rates_valid = rates;
        self.fallback = None;
        self.inner.t = Some(t);
        end
    }
}
