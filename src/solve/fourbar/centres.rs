//! Instantaneous centres of velocity of the four-bar, and Kennedy's theorem.
//!
//! Links: 0 ground, 1 crank O1A, 2 coupler A–B–M, 3 rocker BC. Four of the six centres are
//! the joints: I10 = O1, I30 = C, I12 = A, I23 = B. The other two follow from Kennedy's
//! theorem (the three centres of any three links lie on one line):
//! - I20 (the coupler's centre relative to the ground) on the lines I10 I12 = O1A and
//!   I30 I23 = CB: their intersection;
//! - I13 (crank relative to rocker) on the lines I12 I23 = AB and I10 I30 = O1C.
//!
//! Parallel lines meet at infinity: such a centre is [`Centre::AtInfinity`] with the lines'
//! direction (the coupler then translates: ω2 = 0), never a point with NaN or huge
//! coordinates. The four Kennedy lines are the lines of the four links
//! ([`Centres::kennedy_lines`]).

use super::Geometry;
use super::kinematics::Position;
use crate::geom::{Point, Vector, cross};

/// `|sin|` of the angle between two lines at or below which they count as parallel (their
/// intersection at infinity): the intersection would lie more than ~10¹² times the links'
/// length away.
pub const PARALLEL_SIN: f64 = 1e-12;

/// An instantaneous centre: a point, or a direction at infinity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Centre {
    /// A finite point.
    At(Point),
    /// At infinity in this direction (a unit vector; its opposite names the same point).
    AtInfinity(Vector),
}

impl Centre {
    /// The point, when finite.
    pub fn point(&self) -> Option<Point> {
        match self {
            Centre::At(p) => Some(*p),
            Centre::AtInfinity(_) => None,
        }
    }
}

/// Intersection of the line through `p` along `u` with the line through `q` along `v`.
pub fn intersect(p: Point, u: Vector, q: Point, v: Vector) -> Centre {
    let s = cross(u, v);
    let (nu, nv) = (u.norm(), v.norm());
    if s.abs() <= PARALLEL_SIN * nu * nv || nu == 0.0 || nv == 0.0 {
        let dir = if nu > 0.0 { u / nu } else { v / nv.max(f64::MIN_POSITIVE) };
        return Centre::AtInfinity(dir);
    }
    Centre::At(p + u * (cross(q - p, v) / s))
}

/// A line of Kennedy's construction: the three centres of three links lie on it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KennedyLine {
    /// The three centres' names, the two joints first (`["I10", "I12", "I20"]`).
    pub names: [&'static str; 3],
    /// A point of the line (the first joint).
    pub through: Point,
    /// Its direction (the link's direction).
    pub direction: Vector,
}

/// The six instantaneous centres of the four-bar at one position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Centres {
    /// I10 = O1 (crank–ground).
    pub i10: Point,
    /// I30 = C (rocker–ground).
    pub i30: Point,
    /// I12 = A (crank–coupler).
    pub i12: Point,
    /// I23 = B (coupler–rocker).
    pub i23: Point,
    /// I20 = O1A ∩ CB: the coupler's instantaneous centre of velocity.
    pub i20: Centre,
    /// I13 = AB ∩ O1C: crank and rocker have the same velocity there.
    pub i13: Centre,
}

impl Centres {
    /// Every centre with its name, in the order I10, I30, I12, I23, I20, I13.
    pub fn named(&self) -> [(&'static str, Centre); 6] {
        [
            ("I10", Centre::At(self.i10)),
            ("I30", Centre::At(self.i30)),
            ("I12", Centre::At(self.i12)),
            ("I23", Centre::At(self.i23)),
            ("I20", self.i20),
            ("I13", self.i13),
        ]
    }

    /// The four Kennedy lines, one per triple of links: {1,2,0} on O1A, {3,2,0} on CB,
    /// {1,2,3} on AB, {1,0,3} on O1C.
    pub fn kennedy_lines(&self) -> [KennedyLine; 4] {
        let line = |names, a: Point, b: Point| KennedyLine { names, through: a, direction: b - a };
        [
            line(["I10", "I12", "I20"], self.i10, self.i12),
            line(["I30", "I23", "I20"], self.i30, self.i23),
            line(["I12", "I23", "I13"], self.i12, self.i23),
            line(["I10", "I30", "I13"], self.i10, self.i30),
        ]
    }

    /// The coupler's angular velocity read off its centre: v_A = ω2 × (A − I20), so
    /// ω2 = (A − I20) × v_A / |A − I20|² (CCW positive); 0 when I20 is at infinity (the
    /// coupler translates); `None` when A is I20 (ω2 is not determined by v_A there).
    pub fn omega2(&self, v_a: Vector) -> Option<f64> {
        match self.i20 {
            Centre::AtInfinity(_) => Some(0.0),
            Centre::At(i) => {
                let r = self.i12 - i;
                let r2 = r.norm_squared();
                (r2 > 0.0).then(|| cross(r, v_a) / r2)
            }
        }
    }
}

/// The six instantaneous centres at `pos`.
pub fn centres(geom: &Geometry, pos: &Position) -> Centres {
    Centres {
        i10: geom.o1,
        i30: geom.c,
        i12: pos.a,
        i23: pos.b,
        i20: intersect(geom.o1, pos.a - geom.o1, geom.c, pos.b - geom.c),
        i13: intersect(pos.a, pos.b - pos.a, geom.o1, geom.c - geom.o1),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Side, perp};
    use crate::solve::fourbar::{kinematics, position};

    fn template() -> Geometry {
        super::super::test_template()
    }

    #[test]
    fn the_coupler_turns_about_i20_at_the_solvers_omega2() {
        // Skip 0° and 180°: there I20 = C lies on O1A and I13 = A (degenerate but finite).
        let g = template();
        let mut checked = 0;
        for k in 0..360 {
            let phi1 = f64::from(k).to_radians();
            let mut p = position(&g, phi1, Side::Left).unwrap();
            let kin = kinematics(&g, &p, 20.0).unwrap();
            p.kin = Some(kin);
            let c = centres(&g, &p);
            let Centre::At(i20) = c.i20 else {
                // At infinity only where the coupler translates.
                assert!(kin.omega2.abs() < 1e-9, "{k}°");
                continue;
            };
            // |ω2| = v_A / |A I20|, and the sign from the turning sense.
            let w2 = kin.v_a.norm() / (p.a - i20).norm();
            assert!((w2 - kin.omega2.abs()).abs() <= 1e-9 * w2.max(1.0), "{k}°: {w2} vs {}", kin.omega2);
            let w2s = c.omega2(kin.v_a).unwrap();
            assert!((w2s - kin.omega2).abs() <= 1e-9 * w2.max(1.0), "{k}°");
            // v_M ⊥ I20 M and |v_M| = |ω2|·|I20 M|; the same for B.
            for (pt, v) in [(p.m, kin.v_m), (p.b, kin.v_b)] {
                let r = pt - i20;
                assert!(v.dot(&r).abs() <= 1e-9 * v.norm().max(1e-3) * r.norm(), "{k}°");
                assert!((v.norm() - kin.omega2.abs() * r.norm()).abs() <= 1e-9 * v.norm().max(1.0), "{k}°");
                assert!((v - perp(r) * kin.omega2).norm() <= 1e-9 * v.norm().max(1.0), "{k}°");
            }
            checked += 1;
        }
        assert!(checked >= 358, "{checked}");
    }

    #[test]
    fn crank_and_rocker_move_alike_at_i13() {
        // At I13 the crank (turning about O1 at ω1) and the rocker (about C at ω3) have the
        // same velocity: ω1 × (I13 − O1) = ω3 × (I13 − C).
        let g = template();
        for k in [10, 45, 90, 135, 200, 300] {
            let phi1 = f64::from(k).to_radians();
            let p = position(&g, phi1, Side::Left).unwrap();
            let kin = kinematics(&g, &p, 20.0).unwrap();
            let Centre::At(i13) = centres(&g, &p).i13 else { panic!("{k}°: I13 at infinity") };
            let v1 = perp(i13 - g.o1) * 20.0;
            let v3 = perp(i13 - g.c) * kin.omega3;
            assert!((v1 - v3).norm() <= 1e-9 * v1.norm().max(1.0), "{k}°: {v1:?} {v3:?}");
        }
    }

    #[test]
    fn parallel_lines_give_a_centre_at_infinity_not_nan() {
        // A parallelogram O1ABC: O1A ∥ CB at every angle, so I20 is at infinity and the
        // coupler translates.
        let g = Geometry { l1: 0.05, l_ab: 0.08, l_bc: 0.05, l_bm: 0.05, ..template() };
        let p = position(&g, 1.0, Side::Left).unwrap();
        let c = centres(&g, &p);
        match c.i20 {
            Centre::AtInfinity(u) => {
                assert!((u.norm() - 1.0).abs() < 1e-12);
                assert!(cross(u, p.a - g.o1).abs() < 1e-12);
            }
            Centre::At(x) => panic!("I20 should be at infinity, got {x:?}"),
        }
        assert_eq!(c.omega2(Vector::new(1.0, 2.0)), Some(0.0));
        for (_, centre) in c.named() {
            if let Centre::At(x) = centre {
                assert!(x.x.is_finite() && x.y.is_finite());
            }
        }
        assert!(
            matches!(intersect(Point::origin(), Vector::zeros(), Point::origin(), Vector::zeros()), Centre::AtInfinity(u) if u.x.is_finite())
        );
    }

    #[test]
    fn each_kennedy_line_holds_its_three_centres() {
        let g = template();
        for k in [30, 120, 250] {
            let p = position(&g, f64::from(k).to_radians(), Side::Left).unwrap();
            let c = centres(&g, &p);
            let named = c.named();
            for line in c.kennedy_lines() {
                for n in line.names {
                    let centre = named.iter().find(|(m, _)| *m == n).unwrap().1;
                    let Centre::At(x) = centre else { continue };
                    let off = cross(line.direction, x - line.through) / line.direction.norm();
                    assert!(off.abs() < 1e-12, "{k}°: {n} is {off} off {:?}", line.names);
                }
            }
        }
    }
}
