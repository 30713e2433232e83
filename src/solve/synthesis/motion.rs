//! Motion generation: a four-bar whose coupler line passes two or three given positions
//! (each a point P and an angle), by the perpendicular-bisector construction for chosen
//! moving pivots (e.g. Norton, *Design of Machinery*, §3.4 and §5.5; Erdman & Sandor,
//! *Mechanism Design*, §3.5).
//!
//! The moving pivots A and B are chosen on the coupler in the first position (A1, B1); the
//! coupler carries them to A_i, B_i in position i. A fixed pivot is a point equidistant from
//! a moving pivot's positions: on the perpendicular bisector of A1A2 for two positions (a
//! free choice along it), the centre of the circle through A1A2A3 for three (where the
//! bisectors of A1A2 and A2A3 meet). A is the input's crank pin, B the rocker's.
//!
//! A design through the positions can still fail to move through them: the classic defects,
//! checked and reported by name ([`Defect`]) — the positions on different assembly modes
//! (branch defect: the input cannot drive from one to the other without a dead point or
//! taking the linkage apart), reached in the wrong order as the input turns (order defect),
//! and an input that is not a crank where one is asked.

use std::f64::consts::TAU;

use super::{FourbarClass, SynthesisError, fourbar_class, gamma_min_crank};
use crate::geom::{Point, Side, Vector, angle_of, cross, normalize_angle, perp, rotate};

/// A position of the coupler line: its point P and its direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// The coupler's point P.
    pub at: Point,
    /// The coupler line's direction, radians.
    pub angle: f64,
}

/// The way the input must turn through the positions 1 → 2 → 3.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Turning {
    /// Either way (the input's motor can turn either way).
    Either,
    /// Counter-clockwise.
    Ccw,
    /// Clockwise.
    Cw,
}

/// What the design must do.
#[derive(Debug, Clone, PartialEq)]
pub struct Requirement {
    /// Two or three positions of the coupler line.
    pub poses: Vec<Pose>,
    /// The moving pivots A (input) and B (output) in the first position, global.
    pub a1: Point,
    /// See `a1`.
    pub b1: Point,
    /// With two positions: each fixed pivot's signed distance along its bisector from the
    /// chord's middle (positive to the left of A1 → A2, resp. B1 → B2).
    pub bisector_distance: [f64; 2],
    /// Whether the input must be a crank (turn fully).
    pub crank: bool,
    /// How the input must turn through the positions.
    pub turning: Turning,
}

/// A defect of a design that passes the positions.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[serde(tag = "defect", rename_all = "snake_case")]
pub enum Defect {
    /// The positions are on different assembly modes (B on different sides of A → C):
    /// the input cannot drive through them without passing a dead point.
    Branch {
        /// The side of B relative to A → C in each position.
        sides: Vec<Side>,
    },
    /// The input reaches the positions in another order than 1 → 2 → 3.
    Order {
        /// Why, in words.
        why: String,
    },
    /// A crank is asked for but the input does not turn fully.
    NotACrank {
        /// The linkage's class.
        class: FourbarClass,
    },
}

impl Defect {
    /// The defect's name (`branch`, `order`, `not a crank`).
    pub fn name(&self) -> &'static str {
        match self {
            Defect::Branch { .. } => "branch defect",
            Defect::Order { .. } => "order defect",
            Defect::NotACrank { .. } => "not a crank",
        }
    }

    /// The defect in words.
    pub fn describe(&self) -> String {
        match self {
            Defect::Branch { sides } => format!(
                "branch defect: B lies {} of A → C in positions 1…{}: the positions are on different assembly modes, so the input cannot drive through them without passing a dead point",
                sides.iter().map(|s| format!("{s:?}").to_lowercase()).collect::<Vec<_>>().join(", "),
                sides.len()
            ),
            Defect::Order { why } => format!("order defect: {why}"),
            Defect::NotACrank { class } => {
                format!("not a crank: a crank is asked for, the linkage is a {}", class.describe())
            }
        }
    }
}

/// A perpendicular bisector drawn by the construction: the chord's middle and the line's
/// direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bisector {
    /// The chord's ends.
    pub chord: (Point, Point),
    /// The chord's middle (on the bisector).
    pub mid: Point,
    /// The bisector's unit direction (the chord's turned +90°).
    pub dir: Vector,
}

/// The four-bar through the positions, with its construction and defects.
#[derive(Debug, Clone, PartialEq)]
pub struct Design {
    /// The fixed pivot of A (the crank's pivot, the `fourbar` scene's O1).
    pub o_a: Point,
    /// The fixed pivot of B (the rocker's pivot, the `fourbar` scene's C).
    pub o_b: Point,
    /// A in each position.
    pub a: Vec<Point>,
    /// B in each position.
    pub b: Vec<Point>,
    /// The positions.
    pub poses: Vec<Pose>,
    /// Input O_A A.
    pub l_in: f64,
    /// Coupler AB.
    pub l_ab: f64,
    /// Output O_B B.
    pub l_out: f64,
    /// Ground O_A O_B.
    pub ground: f64,
    /// B to the coupler's point P.
    pub l_bp: f64,
    /// The angle from the ray B → A to the ray B → P, counter-clockwise, radians.
    pub alpha: f64,
    /// The coupler line's direction less the direction A → B (a constant of the coupler).
    pub line_offset: f64,
    /// Input angles in each position (direction O_A → A_i), radians.
    pub input: Vec<f64>,
    /// The sides of B relative to A → O_B in each position.
    pub sides: Vec<Side>,
    /// The bisectors drawn for A (one for two positions, two for three) and for B.
    pub bisectors: [Vec<Bisector>; 2],
    /// The linkage's class.
    pub class: FourbarClass,
    /// The smallest transmission angle over a turn of the input, radians (a crank input),
    /// else `None`.
    pub gamma_min: Option<f64>,
    /// Whether the input must turn counter-clockwise to pass 1 → 2 → 3 (`None` when the
    /// order cannot be kept).
    pub ccw: Option<bool>,
    /// The defects found.
    pub defects: Vec<Defect>,
}

/// The point on the coupler at `p1` in position 1 carried to position `pose`.
fn carried(first: &Pose, pose: &Pose, p1: Point) -> Point {
    pose.at + rotate(p1 - first.at, pose.angle - first.angle)
}

/// The perpendicular bisector of `p`–`q`.
fn bisector(p: Point, q: Point, pivot: &'static str, i: usize, j: usize) -> Result<Bisector, SynthesisError> {
    let chord = q - p;
    let scale = p.coords.norm().max(q.coords.norm()).max(1.0);
    if chord.norm() <= 1e-12 * scale {
        return Err(SynthesisError::CoincidentPositions { pivot, first: i, second: j, x: p.x, y: p.y });
    }
    Ok(Bisector { chord: (p, q), mid: p + 0.5 * chord, dir: perp(chord.normalize()) })
}

/// The fixed pivot of a moving pivot's positions `ps` (2 or 3), with the bisectors drawn.
fn fixed_pivot(ps: &[Point], pivot: &'static str, along: f64) -> Result<(Point, Vec<Bisector>), SynthesisError> {
    let b12 = bisector(ps[0], ps[1], pivot, 1, 2)?;
    if ps.len() == 2 {
        return Ok((b12.mid + b12.dir * along, vec![b12]));
    }
    let b23 = bisector(ps[1], ps[2], pivot, 2, 3)?;
    bisector(ps[0], ps[2], pivot, 1, 3)?;
    // Where the bisectors meet: mid12 + s·dir12 = mid23 + t·dir23.
    let det = cross(b12.dir, b23.dir);
    let (c1, c2) = (ps[1] - ps[0], ps[2] - ps[1]);
    // Collinear positions: the chords are parallel (relative to their lengths).
    if cross(c1, c2).abs() <= 1e-12 * c1.norm() * c2.norm() || det == 0.0 {
        return Err(SynthesisError::ParallelBisectors { pivot });
    }
    let s = cross(b23.mid - b12.mid, b23.dir) / det;
    Ok((b12.mid + b12.dir * s, vec![b12, b23]))
}

/// The side of `b` relative to the directed line `a` → `c`.
fn side(a: Point, b: Point, c: Point) -> Side {
    if cross(c - a, b - a) > 0.0 { Side::Left } else { Side::Right }
}

/// Synthesises the four-bar through the positions.
pub fn synthesise(req: &Requirement) -> Result<Design, SynthesisError> {
    let n = req.poses.len();
    if !(2..=3).contains(&n) {
        return Err(SynthesisError::Degenerate {
            what: format!("{n} positions given: motion generation takes 2 or 3"),
        });
    }
    let first = &req.poses[0];
    let a: Vec<Point> = req.poses.iter().map(|p| carried(first, p, req.a1)).collect();
    let b: Vec<Point> = req.poses.iter().map(|p| carried(first, p, req.b1)).collect();
    let (o_a, bis_a) = fixed_pivot(&a, "A", req.bisector_distance[0])?;
    let (o_b, bis_b) = fixed_pivot(&b, "B", req.bisector_distance[1])?;
    let scale = (a[0] - b[0]).norm().max((o_a - o_b).norm());
    let tiny = 1e-12 * scale.max(f64::MIN_POSITIVE);
    let degenerate = |what: &str| Err(SynthesisError::Degenerate { what: what.to_string() });
    if (a[0] - b[0]).norm() <= tiny {
        return degenerate("the moving pivots A1 and B1 coincide: choose two points of the coupler");
    }
    if (o_a - o_b).norm() <= tiny {
        return degenerate(
            "the fixed pivots of A and B coincide: the ground link has no length; choose other moving pivots",
        );
    }
    if (a[0] - o_a).norm() <= tiny || (b[0] - o_b).norm() <= tiny {
        return degenerate(
            "a moving pivot lies on its fixed pivot: the link has no length; choose another moving pivot",
        );
    }
    if (first.at - b[0]).norm() <= tiny {
        return degenerate(
            "the coupler's point P is the moving pivot B: the four-bar scene needs P off B (choose B elsewhere, or P)",
        );
    }
    let (l_in, l_ab, l_out, ground) =
        ((a[0] - o_a).norm(), (b[0] - a[0]).norm(), (b[0] - o_b).norm(), (o_b - o_a).norm());
    let l_bp = (first.at - b[0]).norm();
    let alpha = normalize_angle(angle_of(first.at - b[0]) - angle_of(a[0] - b[0]));
    let line_offset = first.angle - angle_of(b[0] - a[0]);
    let input: Vec<f64> = a.iter().map(|p| angle_of(p - o_a)).collect();
    let sides: Vec<Side> = (0..n).map(|i| side(a[i], b[i], o_b)).collect();
    let class = fourbar_class(l_in, l_ab, l_out, ground);
    let gamma_min = class.input_turns().then(|| gamma_min_crank(l_in, l_ab, l_out, ground));
    let mut defects = Vec::new();
    if sides.iter().any(|s| *s != sides[0]) {
        defects.push(Defect::Branch { sides: sides.clone() });
    }
    let ccw = order(&input, class, &Limits { o_a, o_b, l_in, l_ab, l_out }, req.turning, &mut defects);
    if req.crank && !class.input_turns() {
        defects.push(Defect::NotACrank { class });
    }
    Ok(Design {
        o_a,
        o_b,
        a,
        b,
        poses: req.poses.clone(),
        l_in,
        l_ab,
        l_out,
        ground,
        l_bp,
        alpha,
        line_offset,
        input,
        sides,
        bisectors: [bis_a, bis_b],
        class,
        gamma_min,
        ccw,
        defects,
    })
}

/// What the input's dead points depend on.
struct Limits {
    o_a: Point,
    o_b: Point,
    l_in: f64,
    l_ab: f64,
    l_out: f64,
}

impl Limits {
    /// The input angles where coupler and output fold or stretch (|A O_B| = |b ∓ c|).
    fn angles(&self) -> Vec<f64> {
        let g = self.o_b - self.o_a;
        let (d, towards) = (g.norm(), angle_of(g));
        let mut out = Vec::new();
        for len in [self.l_ab + self.l_out, (self.l_ab - self.l_out).abs()] {
            let cos = (self.l_in * self.l_in + d * d - len * len) / (2.0 * self.l_in * d);
            if cos.abs() < 1.0 {
                let half = libm::acos(cos);
                out.extend([normalize_angle(towards - half), normalize_angle(towards + half)]);
            }
        }
        out.sort_by(f64::total_cmp);
        out
    }
}

/// Checks the order 1 → 2 → 3 of the input angles; returns whether the input turns
/// counter-clockwise through them (`None` when no direction keeps the order).
fn order(
    input: &[f64],
    class: FourbarClass,
    lim: &Limits,
    turning: Turning,
    defects: &mut Vec<Defect>,
) -> Option<bool> {
    let ccw_from_first = |k: usize| normalize_angle(input[k] - input[0]);
    if input.len() < 3 {
        let ccw = ccw_from_first(1) <= std::f64::consts::PI;
        return Some(match turning {
            Turning::Cw => false,
            Turning::Ccw => true,
            Turning::Either => ccw,
        });
    }
    let ccw_order = ccw_from_first(1) < ccw_from_first(2);
    if class.input_turns() {
        return match (turning, ccw_order) {
            (Turning::Either, o) => Some(o),
            (Turning::Ccw, true) => Some(true),
            (Turning::Cw, false) => Some(false),
            (t, _) => {
                let way = if t == Turning::Ccw { "counter-clockwise" } else { "clockwise" };
                defects.push(Defect::Order {
                    why: format!("the crank, turning {way} as asked, meets position 3 before position 2"),
                });
                None
            }
        };
    }
    // An input that rocks: the positions must lie on one stretch between dead points, in
    // order along it.
    let limits = lim.angles();
    let start = limits.iter().rev().find(|&&l| l <= input[0]).or(limits.last()).copied();
    let Some(lo) = start else { return Some(ccw_order) };
    let along = |k: usize| normalize_angle(input[k] - lo);
    let stretch = limits.iter().map(|l| normalize_angle(l - lo)).filter(|s| *s > 0.0).fold(TAU, f64::min);
    if (0..3).any(|k| along(k) > stretch) {
        defects.push(Defect::Order {
            why: "the rocking input cannot reach every position without passing a dead point".into(),
        });
        return None;
    }
    let (s1, s2, s3) = (along(0), along(1), along(2));
    let in_order = (s1 < s2 && s2 < s3) || (s1 > s2 && s2 > s3);
    let ccw = s3 > s1;
    if !in_order {
        defects.push(Defect::Order {
            why: "the rocking input meets position 3 between positions 1 and 2: it would have to turn back".into(),
        });
        return None;
    }
    match turning {
        Turning::Ccw if !ccw => {
            defects.push(Defect::Order {
                why: "the input must turn clockwise to pass 1 → 2 → 3, counter-clockwise is asked".into(),
            });
            None
        }
        Turning::Cw if ccw => {
            defects.push(Defect::Order {
                why: "the input must turn counter-clockwise to pass 1 → 2 → 3, clockwise is asked".into(),
            });
            None
        }
        _ => Some(ccw),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pose(x: f64, y: f64, deg: f64) -> Pose {
        Pose { at: Point::new(x, y), angle: deg.to_radians() }
    }

    fn three(a1: Point, b1: Point) -> Requirement {
        Requirement {
            poses: vec![pose(0.0, 0.0, 0.0), pose(1.0, 0.6, 20.0), pose(2.2, 0.7, 45.0)],
            a1,
            b1,
            bisector_distance: [0.0, 0.0],
            crank: false,
            turning: Turning::Either,
        }
    }

    #[test]
    fn the_fixed_pivots_are_equidistant_from_the_moving_pivots_positions() {
        let d = synthesise(&three(Point::new(-0.5, -0.3), Point::new(0.8, -0.2))).unwrap();
        for i in 0..3 {
            assert!(((d.a[i] - d.o_a).norm() - d.l_in).abs() < 1e-12);
            assert!(((d.b[i] - d.o_b).norm() - d.l_out).abs() < 1e-12);
            assert!(((d.b[i] - d.a[i]).norm() - d.l_ab).abs() < 1e-12);
        }
    }

    #[test]
    fn collinear_positions_of_a_pivot_are_refused_by_name() {
        // Three positions that translate the coupler along a line: every pivot moves on a
        // line, so the bisectors are parallel.
        let r = Requirement {
            poses: vec![pose(0.0, 0.0, 10.0), pose(1.0, 0.5, 10.0), pose(3.0, 1.5, 10.0)],
            ..three(Point::new(0.0, -1.0), Point::new(1.0, -1.0))
        };
        assert_eq!(synthesise(&r), Err(SynthesisError::ParallelBisectors { pivot: "A" }));
        let r = Requirement {
            poses: vec![pose(0.0, 0.0, 0.0), pose(0.0, 0.0, 30.0)],
            ..three(Point::new(0.0, 0.0), Point::new(1.0, 0.0))
        };
        assert!(matches!(synthesise(&r), Err(SynthesisError::CoincidentPositions { pivot: "A", .. })));
    }
}
