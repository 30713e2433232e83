//! A crank-rocker four-bar for a rocker swing ψ and a time ratio K, by the textbook's
//! construction (e.g. Shigley & Uicker, *Theory of Machines and Mechanisms*, §"quick-return
//! four-bar"; 孙桓, 机械原理, §8-5 "按行程速比系数设计"):
//!
//! 1. θ = 180°·(K − 1)/(K + 1);
//! 2. the rocker CB of length c drawn in its two extremes CB1, CB2, ψ apart;
//! 3. the circle k through B1 and B2 on which the chord B1B2 is seen under θ (B2P ⊥ B1B2,
//!    ∠B2B1P = 90° − θ, B1P a diameter); the crank pivot O1 anywhere on its arc — there are
//!    two such circles, one on each side of the chord, and on the one away from C the arc
//!    FG between the rocker lines CB1, CB2 produced is forbidden (there the crank would pass
//!    the two extremes on different assembly modes);
//! 4. at the extremes crank and coupler are in line: O1B1 = b − a (folded), O1B2 = b + a
//!    (stretched), so a = (O1B2 − O1B1)/2, b = (O1B2 + O1B1)/2 (the textbook swings O1B1
//!    onto O1B2 about O1 to E: B2E = 2a).
//!
//! The free choice is the crank pivot's place on the arc. Up to a mirror image it is set by
//! the ground length d = O1C (d < c on the circle towards C, d > c on the other), so the
//! family is one curve of designs over d: [`Choice::Ground`] takes one, [`Choice::ExtremeToGround`]
//! the designs whose ground line makes a given angle with the rocker in an extreme
//! (the usual textbook problem: "∠C1DA = 90°"), [`Choice::BestTransmission`] the one with the
//! largest smallest transmission angle γ_min.
//!
//! The design is returned in the `fourbar` scene's frame: O1 at the origin, C on +x.

use std::f64::consts::{FRAC_PI_2, PI};

use super::{
    FourbarClass, Frame, SynthesisError, best_of, excess_angle, fourbar_class, gamma_min_crank, on_seeing_arc,
    positive, seeing_circle, swing, unit,
};
use crate::geom::{Point, Side, Vector, angle_of, circle_circle, cross, normalize_angle};

/// What the design must do.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Requirement {
    /// Rocker swing ψ, radians in (0, π).
    pub psi: f64,
    /// Time ratio K > 1: working-stroke time over return-stroke time at a constant crank speed.
    pub time_ratio: f64,
    /// Rocker length c = CB (> 0).
    pub rocker: f64,
    /// The free choice.
    pub choice: Choice,
}

/// The free choice of the crank pivot on its circle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Choice {
    /// The ground length d = O1C.
    Ground(f64),
    /// The angle at C between the ground line CO1 and the rocker in one of its extremes,
    /// radians in (0, π).
    ExtremeToGround(f64),
    /// The design of the family with the largest γ_min.
    BestTransmission,
}

/// Which of the two circles through B1 and B2 carries the crank pivot.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Circle {
    /// The circle on the side of the chord B1B2 away from C (d > c); its arc FG is forbidden.
    Far,
    /// The circle on the side of C (d < c).
    Near,
}

/// One crank-rocker that meets the requirement, with its construction (design frame:
/// O1 at the origin, C on +x; lengths in the requirement's unit, angles radians).
#[derive(Debug, Clone, PartialEq)]
pub struct Design {
    /// Crank O1A.
    pub a: f64,
    /// Coupler AB.
    pub b: f64,
    /// Rocker CB.
    pub c: f64,
    /// Ground O1C.
    pub d: f64,
    /// Crank pivot (the origin).
    pub o1: Point,
    /// Rocker pivot (d, 0).
    pub pivot_c: Point,
    /// The rocker's extreme where crank and coupler are folded: O1B1 = b − a.
    pub b1: Point,
    /// The rocker's extreme where crank and coupler are stretched: O1B2 = b + a.
    pub b2: Point,
    /// The crank pin at the folded extreme (A1 on B1O1 produced beyond O1).
    pub a1: Point,
    /// The crank pin at the stretched extreme (A2 on O1B2).
    pub a2: Point,
    /// O1B1 swung onto O1B2 about O1: B2E = 2a.
    pub e: Point,
    /// Centre of the circle k.
    pub centre: Point,
    /// Radius of the circle k.
    pub radius: f64,
    /// The end of the diameter from B1 (the textbook's P: B2P ⊥ B1B2).
    pub p: Point,
    /// Which circle O1 is on.
    pub circle: Circle,
    /// On the far circle, the ends F, G of the forbidden arc (CB1 and CB2 produced).
    pub forbidden: Option<(Point, Point)>,
    /// Excess angle θ.
    pub theta: f64,
    /// Rocker swing ψ.
    pub psi: f64,
    /// Grashof class (a crank-rocker when the design is valid).
    pub class: FourbarClass,
    /// Smallest transmission angle, radians (0…π/2).
    pub gamma_min: f64,
    /// The side of B relative to the directed line A → C throughout the motion (the
    /// `fourbar` scene's `branch`).
    pub branch: Side,
    /// Crank angles at the folded and the stretched extreme, radians.
    pub crank_at: (f64, f64),
    /// Whether, with the crank turning counter-clockwise, the working (longer) stroke runs
    /// from B1 to B2.
    pub working_from_b1: bool,
}

/// The family of designs over the ground length d.
#[derive(Debug, Clone, PartialEq)]
pub struct Family {
    /// Samples (d, γ_min in radians) of valid designs, in increasing d; `None` where d
    /// gives none.
    pub samples: Vec<(f64, Option<f64>)>,
    /// The stretches of d that give a design, (from, to), increasing.
    pub valid: Vec<(f64, f64)>,
    /// The design with the largest γ_min: (d, γ_min).
    pub best: (f64, f64),
}

/// A synthesis: the design proposed, the others the choice allows, and the family.
#[derive(Debug, Clone, PartialEq)]
pub struct Synthesis {
    /// The design proposed (the best γ_min among those the choice allows).
    pub design: Design,
    /// The other designs the choice allows (e.g. the second ground line of an angle).
    pub others: Vec<Design>,
    /// The whole family over d, with its best.
    pub family: Family,
}

/// Samples of d charted over the family.
pub const FAMILY_SAMPLES: usize = 401;

/// The construction in the local frame: C at the origin, the swing's bisector along +y, L
/// and R the rocker's extremes left and right of it.
#[derive(Debug, Clone, Copy)]
struct Local {
    c: f64,
    psi: f64,
    theta: f64,
    left: Point,
    right: Point,
    far: (Point, f64),
    near: (Point, f64),
}

impl Local {
    fn new(psi: f64, theta: f64, c: f64) -> Local {
        let left = Point::origin() + unit(FRAC_PI_2 + 0.5 * psi) * c;
        let right = Point::origin() + unit(FRAC_PI_2 - 0.5 * psi) * c;
        // The chord L → R runs along +x: its left side is away from C.
        let far = seeing_circle(left, right, theta, Side::Left);
        let near = seeing_circle(left, right, theta, Side::Right);
        Local { c, psi, theta, left, right, far, near }
    }

    /// The crank pivot at ground length `d`, on the left of the bisector (x < 0), on its
    /// circle's arc, if any.
    fn pivot(&self, d: f64) -> Option<(Point, Circle)> {
        let (circle, (m, r), side) =
            if d > self.c { (Circle::Far, self.far, Side::Left) } else { (Circle::Near, self.near, Side::Right) };
        let x = match circle_circle(Point::origin(), d, m, r) {
            crate::geom::CircleIntersection::Two { left, right } => {
                if left.x < right.x {
                    left
                } else {
                    right
                }
            }
            crate::geom::CircleIntersection::Tangent(p) => p,
            crate::geom::CircleIntersection::None => return None,
        };
        (x.x < 0.0 && on_seeing_arc(self.left, self.right, x, side)).then_some((x, circle))
    }

    /// The design with its crank pivot at `o1` (local), on `circle`, if it is a valid
    /// crank-rocker: both extremes on one assembly mode and the crank the shortest link of
    /// a Grashof chain.
    fn design(&self, o1: Point, circle: Circle) -> Option<Design> {
        let (rl, rr) = ((self.left - o1).norm(), (self.right - o1).norm());
        // The nearer extreme is the folded one.
        let (b1, b2, r1, r2) = if rl <= rr { (self.left, self.right, rl, rr) } else { (self.right, self.left, rr, rl) };
        let a = 0.5 * (r2 - r1);
        let b = 0.5 * (r2 + r1);
        let d = (o1 - Point::origin()).norm();
        if !(a > 0.0 && r1 > 0.0 && d > 0.0) {
            return None;
        }
        let u1 = (b1 - o1) / r1;
        let u2 = (b2 - o1) / r2;
        let a1 = o1 - u1 * a;
        let a2 = o1 + u2 * a;
        let cpt = Point::origin();
        let s1 = cross(cpt - a1, b1 - a1);
        let s2 = cross(cpt - a2, b2 - a2);
        if s1 * s2 <= 0.0 {
            return None;
        }
        let class = fourbar_class(a, b, self.c, d);
        if class != FourbarClass::CrankRocker {
            return None;
        }
        let (m, radius) = match circle {
            Circle::Far => self.far,
            Circle::Near => self.near,
        };
        let forbidden = (circle == Circle::Far).then(|| {
            // The second intersection of the ray C → B with the circle: t·t' = |CM|² − R².
            let power = (m - cpt).norm_squared() - radius * radius;
            let end = |bx: Point| cpt + (bx - cpt) * (power / (self.c * self.c));
            (end(self.left), end(self.right))
        });
        let frame = Frame::along(o1, cpt);
        let e = o1 + u2 * r1;
        let p = Point::origin() + (m - Point::origin()) * 2.0 - (b1 - Point::origin());
        let crank_at = (frame.angle(angle_of(a1 - o1)), frame.angle(angle_of(a2 - o1)));
        // Counter-clockwise from the folded to the stretched extreme: the working stroke when
        // it is the longer.
        let forward = normalize_angle(crank_at.1 - crank_at.0);
        Some(Design {
            a,
            b,
            c: self.c,
            d,
            // Exactly on the axis: the frame's rotation would leave 1e-15 of noise in C's y.
            o1: Point::origin(),
            pivot_c: Point::new(d, 0.0),
            b1: frame.point(b1),
            b2: frame.point(b2),
            a1: frame.point(a1),
            a2: frame.point(a2),
            e: frame.point(e),
            centre: frame.point(m),
            radius,
            p: frame.point(p),
            circle,
            forbidden: forbidden.map(|(f, g)| (frame.point(f), frame.point(g))),
            theta: self.theta,
            psi: self.psi,
            class,
            gamma_min: gamma_min_crank(a, b, self.c, d),
            branch: if s2 > 0.0 { Side::Left } else { Side::Right },
            crank_at,
            working_from_b1: forward > PI,
        })
    }

    /// The valid design at ground length `d`, if any.
    fn at(&self, d: f64) -> Option<Design> {
        let (o1, circle) = self.pivot(d)?;
        self.design(o1, circle)
    }

    /// The ground lengths the two circles reach: (smallest, largest).
    fn reach(&self) -> (f64, f64) {
        let lo = ((self.near.0 - Point::origin()).norm() - self.near.1).abs();
        let hi = (self.far.0 - Point::origin()).norm() + self.far.1;
        (lo, hi)
    }
}

/// The edge between a valid and an invalid d, by bisection (`good` valid, `bad` not).
fn edge(l: &Local, mut good: f64, mut bad: f64) -> f64 {
    for _ in 0..200 {
        let mid = 0.5 * (good + bad);
        if mid == good || mid == bad {
            break;
        }
        if l.at(mid).is_some() {
            good = mid;
        } else {
            bad = mid;
        }
    }
    good
}

/// The family over d: samples, valid stretches (edges found by bisection) and the best.
fn family(l: &Local) -> Option<Family> {
    let (lo, hi) = l.reach();
    let n = FAMILY_SAMPLES;
    let ds: Vec<f64> = (0..n).map(|k| lo + (hi - lo) * k as f64 / (n - 1) as f64).collect();
    let samples: Vec<(f64, Option<f64>)> = ds.iter().map(|&d| (d, l.at(d).map(|x| x.gamma_min))).collect();
    let mut valid = Vec::new();
    let mut start: Option<f64> = None;
    for k in 0..n {
        let ok = samples[k].1.is_some();
        match (ok, start) {
            (true, None) => start = Some(if k == 0 { ds[0] } else { edge(l, ds[k], ds[k - 1]) }),
            (false, Some(s)) => {
                valid.push((s, edge(l, ds[k - 1], ds[k])));
                start = None;
            }
            _ => {}
        }
    }
    if let Some(s) = start {
        valid.push((s, ds[n - 1]));
    }
    let gamma = |d: f64| l.at(d).map_or(f64::NEG_INFINITY, |x| x.gamma_min);
    let best = valid
        .iter()
        .map(|&(a, b)| best_of(&gamma, a, b, 64))
        .filter(|(_, g)| g.is_finite())
        .max_by(|x, y| x.1.total_cmp(&y.1))?;
    Some(Family { samples, valid, best })
}

/// The points where the ray from the origin along `u` meets the circle (`m`, `r`), ahead.
fn ray_circle(u: Vector, m: Point, r: f64) -> Vec<Point> {
    let mc = m - Point::origin();
    let (bq, cq) = (u.dot(&mc), mc.norm_squared() - r * r);
    let disc = bq * bq - cq;
    if disc < 0.0 {
        return Vec::new();
    }
    let s = disc.sqrt();
    [bq - s, bq + s].into_iter().filter(|t| *t > 0.0).map(|t| Point::origin() + u * t).collect()
}

/// Synthesises the crank-rocker.
pub fn synthesise(req: &Requirement) -> Result<Synthesis, SynthesisError> {
    let psi = swing(req.psi)?;
    let theta = excess_angle(req.time_ratio)?;
    let c = positive("the rocker length c", req.rocker)?;
    let l = Local::new(psi, theta, c);
    let fam = family(&l).ok_or_else(|| SynthesisError::OutOfFamily {
        what: "the requirement",
        value: req.time_ratio,
        why: "no crank pivot on either circle gives a crank-rocker".into(),
        valid: "a smaller ψ or K".into(),
    })?;
    let valid_text = || fam.valid.iter().map(|(a, b)| format!("{a:.6}…{b:.6}")).collect::<Vec<_>>().join(" or ");
    let mut designs: Vec<Design> = match req.choice {
        Choice::Ground(d) => {
            let d = positive("the ground length d", d)?;
            vec![l.at(d).ok_or_else(|| SynthesisError::OutOfFamily {
                what: "the ground length d",
                value: d,
                why: if (d - c).abs() <= 1e-12 * c {
                    "d = c puts the crank pivot on an extreme of the rocker".into()
                } else {
                    "the crank pivot at this distance from C passes the rocker's extremes on different assembly modes, or there is none".into()
                },
                valid: format!("d in {} (the rocker is {c})", valid_text()),
            })?]
        }
        Choice::ExtremeToGround(delta) => {
            if !(delta.is_finite() && delta > 0.0 && delta < PI) {
                return Err(SynthesisError::OutOfFamily {
                    what: "the angle between the ground line and an extreme of the rocker (degrees)",
                    value: delta.to_degrees(),
                    why: "it must lie strictly between 0° and 180°".into(),
                    valid: "0 < angle < 180".into(),
                });
            }
            let mut out: Vec<Design> = Vec::new();
            for b in [l.left, l.right] {
                for sense in [1.0, -1.0] {
                    let u = unit(angle_of(b - Point::origin()) + sense * delta);
                    for (m, r) in [l.far, l.near] {
                        for x in ray_circle(u, m, r) {
                            let d = (x - Point::origin()).norm();
                            if let Some(des) = l.at(d)
                                && !out.iter().any(|o| (o.d - d).abs() <= 1e-9 * c)
                            {
                                out.push(des);
                            }
                        }
                    }
                }
            }
            if out.is_empty() {
                return Err(SynthesisError::OutOfFamily {
                    what: "the angle between the ground line and an extreme of the rocker (degrees)",
                    value: delta.to_degrees(),
                    why: "no ground line at this angle to CB1 or CB2 meets an arc that gives a crank-rocker".into(),
                    valid: format!("an angle whose ground line gives d in {}", valid_text()),
                });
            }
            out
        }
        Choice::BestTransmission => l.at(fam.best.0).into_iter().collect(),
    };
    designs.sort_by(|x, y| y.gamma_min.total_cmp(&x.gamma_min).then(x.d.total_cmp(&y.d)));
    let mut it = designs.into_iter();
    let design = it.next().ok_or_else(|| SynthesisError::OutOfFamily {
        what: "the best design",
        value: fam.best.0,
        why: "the family's best could not be built".into(),
        valid: valid_text(),
    })?;
    Ok(Synthesis { design, others: it.collect(), family: fam })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn req(choice: Choice) -> Requirement {
        Requirement { psi: 40f64.to_radians(), time_ratio: 1.5, rocker: 80.0, choice }
    }

    /// The rocker angle at crank angle φ by the loop closure (law of cosines, no circles).
    fn rocker_angle(d: &Design, phi: f64) -> f64 {
        let a = d.o1 + unit(phi) * d.a;
        let ac = d.pivot_c - a;
        let l = ac.norm();
        // The angle at C between CA and CB.
        let at_c = libm::acos(((d.c * d.c + l * l - d.b * d.b) / (2.0 * d.c * l)).clamp(-1.0, 1.0));
        let ca = angle_of(-ac);
        match d.branch {
            // B left of A → C: B is clockwise of CA seen from C.
            Side::Left => ca - at_c,
            Side::Right => ca + at_c,
        }
    }

    #[test]
    fn the_construction_gives_back_psi_and_k_by_the_loop_closure() {
        for choice in [Choice::Ground(60.0), Choice::Ground(120.0), Choice::BestTransmission] {
            let s = synthesise(&req(choice)).unwrap();
            let d = &s.design;
            // Extremes: the crank along B1O1 produced and along O1B2.
            let (p1, p2) = d.crank_at;
            let (r1, r2) = (rocker_angle(d, p1), rocker_angle(d, p2));
            assert!(crate::geom::wrap_pi(angle_of(d.b1 - d.pivot_c) - r1).abs() < 1e-9, "{choice:?}");
            let psi = crate::geom::wrap_pi(r2 - r1).abs();
            assert!((psi - 40f64.to_radians()).abs() < 1e-12, "{choice:?}: ψ = {}", psi.to_degrees());
            let fwd = normalize_angle(p2 - p1);
            let k = fwd.max(2.0 * PI - fwd) / fwd.min(2.0 * PI - fwd);
            assert!((k - 1.5).abs() < 1e-12, "{choice:?}: K = {k}");
        }
    }

    #[test]
    fn a_ground_line_at_right_angles_to_an_extreme_gives_two_designs() {
        // The textbook problem (c = 80, ψ = 40°, K = 1.5, ∠C1DA = 90°): both crank pivots
        // lie on the circle towards C, at d = 17.569 and 43.231.
        let s = synthesise(&req(Choice::ExtremeToGround(FRAC_PI_2))).unwrap();
        let mut ds: Vec<f64> = std::iter::once(&s.design).chain(&s.others).map(|d| d.d).collect();
        ds.sort_by(f64::total_cmp);
        assert_eq!(ds.len(), 2, "{ds:?}");
        assert!((ds[0] - 17.569).abs() < 1e-3 && (ds[1] - 43.231).abs() < 1e-3, "{ds:?}");
        for d in std::iter::once(&s.design).chain(&s.others) {
            let to_ground = |b: Point| libm::acos((b - d.pivot_c).normalize().dot(&(d.o1 - d.pivot_c).normalize()));
            let right = [d.b1, d.b2].iter().any(|b| (to_ground(*b) - FRAC_PI_2).abs() < 1e-12);
            assert!(right, "d = {}", d.d);
        }
    }

    #[test]
    fn the_forbidden_arc_and_a_ground_beyond_it_are_refused() {
        let s = synthesise(&req(Choice::Ground(100.0))).unwrap();
        assert_eq!(s.design.circle, Circle::Far);
        assert!(s.design.forbidden.is_some());
        // F is 132.06 from C: a crank pivot between F and G is refused, by name.
        assert!(matches!(synthesise(&req(Choice::Ground(140.0))), Err(SynthesisError::OutOfFamily { .. })));
        assert!(matches!(synthesise(&req(Choice::Ground(80.0))), Err(SynthesisError::OutOfFamily { .. })));
        let far = s.family.valid.iter().find(|(a, b)| *a < 100.0 && *b > 100.0).unwrap();
        assert!((far.1 - 132.06).abs() < 0.01, "{far:?}");
    }

    #[test]
    fn impossible_requirements_are_named() {
        let mut r = req(Choice::BestTransmission);
        r.time_ratio = 1.0;
        assert!(matches!(synthesise(&r), Err(SynthesisError::TimeRatio { .. })));
        r.time_ratio = 1.5;
        r.psi = PI;
        assert!(matches!(synthesise(&r), Err(SynthesisError::Swing { .. })));
    }
}
