//! Stroke H and time ratio K of a point that slides on a ground guide (the shaper's ram
//! point E), from a solved motion of the general linkage solver.
//!
//! The point's displacement along the guide's unit direction u, d(t) = u·(r(t) − r(t₀)),
//! has its extremes where the velocity along the guide, u·v, changes sign. The sampled
//! extremes are refined by Newton's method on u·v(t) = 0 (derivative u·a, exact from the
//! solver), solving the mechanism at the trial times, so H does not depend on the sampling.
//!
//! - **H** = max d − min d over the motion (length units).
//! - **K** = working-stroke time / return-stroke time ≥ 1, over one period of the single
//!   angular driver (one turn, |Δφ| = 2π, with the driver turning one way throughout): the
//!   times of the two extremes split the period into the two strokes; the longer is the
//!   working stroke. K is not found (and [`NoCycle`] says why) when the mechanism has no
//!   single angular driver, the driver turns back, the motion covers less than one turn,
//!   or the point reverses more than twice in the period.
//!
//! The displacement of the textbook diagram, s, is measured from the extreme where the
//! working stroke starts, positive along the working stroke, so 0 ≤ s ≤ H; without K, from
//! the extreme at the guide's negative end, positive along u.

use crate::geom::{Point, Vector};
use crate::solve::expr::Expr;
use crate::solve::linkage::{Anchor, LinkageError, Mechanism, Solver, State};

/// Newton iterations allowed to refine one extreme.
const MAX_REFINE_ITERATIONS: usize = 30;
/// Relative change of t at which a refinement stops.
const REFINE_TOL_REL: f64 = 1e-15;
/// Relative slack allowed when checking that the displacement is monotonic between the
/// extremes (samples may repeat a value to roundoff near an extreme).
const MONOTONE_SLACK_REL: f64 = 1e-9;

/// One extreme position of the point.
#[derive(Debug, Clone, PartialEq)]
pub struct Extreme {
    /// Time, s (refined where the point turns back between samples).
    pub t: f64,
    /// The point there (global).
    pub at: Point,
    /// The driver's value there (its law at t), radians for an angular driver; `None`
    /// with several drivers.
    pub driver: Option<f64>,
}

/// One period of the motion, split into the working and the return stroke.
#[derive(Debug, Clone, PartialEq)]
pub struct Cycle {
    /// Time ratio: working-stroke time / return-stroke time (≥ 1).
    pub k: f64,
    /// Duration of the working stroke (the longer), s.
    pub working_time: f64,
    /// Duration of the return stroke, s.
    pub return_time: f64,
    /// The driver's period (time of one turn), s.
    pub period: f64,
}

/// Why K is not reported.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NoCycle {
    /// The mechanism has no single angular driver (several drivers, or a distance driver):
    /// no period to take the strokes' times over.
    NoAngularDriver,
    /// The driver's law turns back (its rate changes sign) or stands still within the motion.
    DriverNotMonotonic,
    /// The motion covers less than one turn of the driver.
    LessThanOneTurn,
    /// The point reverses more than twice in one period.
    MoreThanTwoReversals,
    /// The point does not move along its guide.
    NoMotion,
}

impl NoCycle {
    /// What the reason says, for reports and the JSON summary.
    pub fn text(self) -> &'static str {
        match self {
            NoCycle::NoAngularDriver => "the mechanism has no single angular driver, so no period",
            NoCycle::DriverNotMonotonic => "the driver turns back within the motion",
            NoCycle::LessThanOneTurn => "the motion covers less than one turn of the driver",
            NoCycle::MoreThanTwoReversals => "the point reverses more than twice in one period",
            NoCycle::NoMotion => "the point does not move along its guide",
        }
    }
}

/// The stroke of a guided point.
#[derive(Debug, Clone, PartialEq)]
pub struct Stroke {
    /// H: extent of the displacement along the guide over the motion (length units).
    pub h: f64,
    /// Unit direction in which s grows: along the working stroke when K is found, else the
    /// guide's q1 → q2.
    pub direction: Vector,
    /// The extreme where s = 0 (the working stroke starts there when K is found).
    pub start: Extreme,
    /// The other extreme, s = H.
    pub end: Extreme,
    /// The period's split into strokes, or why there is none.
    pub cycle: Result<Cycle, NoCycle>,
}

impl Stroke {
    /// s at `p`: the displacement from the start extreme along [`Stroke::direction`].
    pub fn s(&self, p: Point) -> f64 {
        (p - self.start.at).dot(&self.direction)
    }
}

/// The time `t₁ > t₀` at which the single angular driver has turned once from `times[0]`
/// (|φ(t₁) − φ(t₀)| = 2π), or why there is none within `times`.
pub fn driver_turn(mech: &Mechanism, times: &[f64]) -> Result<(f64, f64), NoCycle> {
    let (driver, _) = mech.angular_driver().ok_or(NoCycle::NoAngularDriver)?;
    let law = &driver.law;
    if !one_way(law, times) {
        return Err(NoCycle::DriverNotMonotonic);
    }
    let t0 = times[0];
    let phi0 = law.eval(t0).value;
    let sign = (law.eval(times[times.len() - 1]).value - phi0).signum();
    let turned = |t: f64| (law.eval(t).value - phi0) * sign - std::f64::consts::TAU;
    let k = times.iter().position(|&t| turned(t) >= 0.0).ok_or(NoCycle::LessThanOneTurn)?;
    // Bisection, then Newton, on [times[k−1], times[k]] (turned is increasing there).
    let (mut lo, mut hi) = (times[k.saturating_sub(1)], times[k]);
    if turned(hi) == 0.0 || k == 0 {
        return Ok((t0, hi));
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if turned(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let mut t = hi;
    for _ in 0..5 {
        let j = law.eval(t);
        let f = turned(t);
        if j.d1 == 0.0 {
            break;
        }
        let next = t - f / (j.d1 * sign);
        if !(next.is_finite() && (lo..=hi).contains(&next)) {
            break;
        }
        t = next;
    }
    Ok((t0, t))
}

/// Whether `law` turns one way over `times` (two or more): its values at the samples
/// strictly monotonic and its rate never of the other sign (it may start or pause at rest).
pub fn one_way(law: &Expr, times: &[f64]) -> bool {
    let values: Vec<f64> = times.iter().map(|&t| law.eval(t).value).collect();
    let Some((first, last)) = values.first().zip(values.last()) else { return false };
    let sign = (last - first).signum();
    sign != 0.0
        && values.windows(2).all(|w| (w[1] - w[0]) * sign > 0.0)
        && times.iter().all(|&t| law.eval(t).d1 * sign >= 0.0)
}

/// The stroke of `point` moving along the unit direction `u` (its ground guide), from the
/// solved `states` (at least one). `solver` solves the mechanism between samples to refine
/// the extremes (it is left at the last refined state).
pub fn stroke(solver: &mut Solver, states: &[State], point: Anchor, u: Vector) -> Result<Stroke, LinkageError> {
    let r0 = states[0].point(point);
    let d: Vec<f64> = states.iter().map(|s| (s.point(point) - r0).dot(&u)).collect();
    let (imin, imax) = arg_extremes(&d);
    let lo = refine(solver, states, imin, point, u)?;
    let hi = refine(solver, states, imax, point, u)?;
    let driver_value =
        |t: f64| (solver.mechanism().drivers.len() == 1).then(|| solver.mechanism().drivers[0].law.eval(t).value);
    let extreme = |s: &State| Extreme { t: s.t, at: s.point(point), driver: driver_value(s.t) };
    let (lo, hi) = (extreme(&lo), extreme(&hi));
    let h = (hi.at - lo.at).dot(&u);
    let times: Vec<f64> = states.iter().map(|s| s.t).collect();
    let cycle = if h <= 0.0 {
        Err(NoCycle::NoMotion)
    } else {
        driver_turn(solver.mechanism(), &times).and_then(|(t0, t1)| cycle(&times, &d, (t0, t1), &lo, &hi))
    };
    // The working stroke starts at the extreme after which the longer stroke follows.
    let (start, end, direction) = match &cycle {
        Ok(c) if c.1 => (hi, lo, -u),
        _ => (lo, hi, u),
    };
    Ok(Stroke { h, direction, start, end, cycle: cycle.map(|c| c.0) })
}

/// Indices of the first smallest and the first largest value.
fn arg_extremes(d: &[f64]) -> (usize, usize) {
    let (mut imin, mut imax) = (0, 0);
    for (k, v) in d.iter().enumerate() {
        if *v < d[imin] {
            imin = k;
        }
        if *v > d[imax] {
            imax = k;
        }
    }
    (imin, imax)
}

/// The extreme near sample `k`: where u·v changes sign within one sample step of it, found
/// by Newton's method on u·v(t) = 0 (slope u·a); the sample itself when the point does
/// not turn there (an end of the motion) or the iteration leaves the step.
fn refine(solver: &mut Solver, states: &[State], k: usize, point: Anchor, u: Vector) -> Result<State, LinkageError> {
    let sample = &states[k];
    let f = |s: &State| s.velocity(point).dot(&u);
    let before = k.checked_sub(1).map(|i| &states[i]);
    let after = states.get(k + 1);
    let turns = |a: Option<&State>, b: Option<&State>| match (a, b) {
        (Some(a), Some(b)) => f(a) * f(b) <= 0.0,
        _ => false,
    };
    if !(turns(before, Some(sample)) || turns(Some(sample), after)) {
        return Ok(sample.clone());
    }
    let lo = before.map_or(sample.t, |s| s.t);
    let hi = after.map_or(sample.t, |s| s.t);
    let mut s = sample.clone();
    for _ in 0..MAX_REFINE_ITERATIONS {
        let slope = s.acceleration(point).dot(&u);
        if slope == 0.0 || !slope.is_finite() {
            break;
        }
        let t = s.t - f(&s) / slope;
        if !(lo..=hi).contains(&t) {
            return Ok(sample.clone());
        }
        let dt = t - s.t;
        solver.resume(&s);
        solver.step(t)?;
        s = solver.state();
        if dt.abs() <= REFINE_TOL_REL * t.abs().max(1.0) {
            break;
        }
    }
    Ok(s)
}

/// The split of one period `(t0, t1)` into strokes, with whether the working stroke runs
/// from `hi` to `lo` (against u): the displacement `d` at the samples up to t1 must rise
/// from its minimum to its maximum and fall back (cyclically) with no other turn.
fn cycle(times: &[f64], d: &[f64], (t0, t1): (f64, f64), lo: &Extreme, hi: &Extreme) -> Result<(Cycle, bool), NoCycle> {
    let period = t1 - t0;
    let n = times.iter().take_while(|&&t| t < t1 - 1e-12 * period).count();
    if n < 3 {
        return Err(NoCycle::LessThanOneTurn);
    }
    let one = &d[..n];
    let (imin, imax) = arg_extremes(one);
    let span = one[imax] - one[imin];
    let slack = MONOTONE_SLACK_REL * span;
    let monotone = |from: usize, to: usize, rising: bool| {
        let mut k = from;
        while k != to {
            let next = (k + 1) % n;
            let step = one[next] - one[k];
            if (rising && step < -slack) || (!rising && step > slack) {
                return false;
            }
            k = next;
        }
        true
    };
    if !(monotone(imin, imax, true) && monotone(imax, imin, false)) {
        return Err(NoCycle::MoreThanTwoReversals);
    }
    let rising = (hi.t - lo.t).rem_euclid(period);
    let falling = period - rising;
    let (working_time, return_time) = (rising.max(falling), rising.min(falling));
    let k = working_time / return_time;
    Ok((Cycle { k, working_time, return_time, period }, falling > rising))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::linkage::{Body, Driver, DriverTarget};

    /// One body turned by `law` (no joints: `driver_turn` looks at the driver only).
    fn turned_by(law: &str) -> Mechanism {
        Mechanism {
            bodies: vec![Body {
                name: "crank".into(),
                points: vec![("A".into(), Vector::new(1.0, 0.0))],
                at: Point::origin(),
                angle: 0.0,
            }],
            joints: Vec::new(),
            drivers: vec![Driver {
                name: "crank".into(),
                target: DriverTarget::BodyAngle(0),
                law: Expr::parse(law).unwrap(),
            }],
            length_scale: 1.0,
        }
    }

    fn times(to: f64, steps: u32) -> Vec<f64> {
        (0..=steps).map(|k| to * f64::from(k) / f64::from(steps)).collect()
    }

    #[test]
    fn one_turn_of_a_non_uniform_or_clockwise_driver_is_found_on_its_law() {
        // φ = π·t² turns once at t = √2, between samples.
        let (t0, t1) = driver_turn(&turned_by("pi*t^2"), &times(2.0, 20)).unwrap();
        assert_eq!(t0, 0.0);
        assert!((t1 - 2f64.sqrt()).abs() < 1e-14, "{t1}");
        // Clockwise: |Δφ| = 2π at t = 1.
        let (_, t1) = driver_turn(&turned_by("-2*pi*t"), &times(1.5, 7)).unwrap();
        assert!((t1 - 1.0).abs() < 1e-15, "{t1}");
    }

    #[test]
    fn no_turn_says_why() {
        assert_eq!(driver_turn(&turned_by("t"), &times(1.0, 10)), Err(NoCycle::LessThanOneTurn));
        assert_eq!(driver_turn(&turned_by("8*sin(t)"), &times(3.0, 30)), Err(NoCycle::DriverNotMonotonic));
        let mut two = turned_by("t");
        two.drivers.push(two.drivers[0].clone());
        assert_eq!(driver_turn(&two, &times(10.0, 10)), Err(NoCycle::NoAngularDriver));
    }
}
