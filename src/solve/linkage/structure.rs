//! Structural analysis of a linkage, as a mechanism course writes it: the mobility by the
//! Chebyshev–Grübler–Kutzbach formula M = 3n − 2p₅ − p₄ (n moving links, p₅ lower pairs:
//! revolute and prismatic joints, one degree of freedom each; p₄ higher pairs: cams and
//! gear teeth, none in a mechdraw scene), the mobility the joints really leave at a
//! placement, 3n − rank Φq (it exceeds the formula's by the number of redundant joint
//! equations: a passive link, such as a third crank parallel to two of a parallelogram),
//! and the decomposition into the driver (a class I mechanism: the driven link and the
//! frame) and Assur groups, each with its class and order.
//!
//! Class and order (Artobolevsky's convention): a group's *order* is the number of its
//! outer pairs (the joints by which it is attached to the links before it: 2 for a dyad,
//! 3 for the 6R triad); its *class* is the most inner pairs of one of its links, or the
//! most links of a closed contour of inner pairs, whichever is larger, and at least II: II
//! for a dyad, III for the 6R triad (its ternary link has three inner pairs), IV for a
//! group closing a four-link contour. The mechanism's class is its groups' highest.
//!
//! The groups are the solver's ([`decompose`]): the report draws what the solver solves by.

use nalgebra::DMatrix;

use super::assur::{Group, GroupKind, decompose};
use super::{Attach, JointKind, Mechanism};
use crate::geom::{Point, Vector, perp, rotate};

/// Relative size (to the largest singular value of the scaled Φq) under which a singular
/// value counts as zero when the rank is taken: roundoff of the placement is ~1e-15
/// relative, a genuinely independent equation is far above 1e-9.
pub const RANK_TOL_REL: f64 = 1e-9;

/// The mobility by the formula and by the rank of the joint equations.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Mobility {
    /// n: the moving links (bodies).
    pub links: usize,
    /// Revolute joints (lower pairs, class 5).
    pub revolute: usize,
    /// Prismatic joints (lower pairs, class 5).
    pub prismatic: usize,
    /// p₄: higher pairs (class 4): always 0 in a mechdraw scene.
    pub higher: usize,
    /// M = 3n − 2p₅ − p₄.
    pub formula: i64,
    /// 3n − rank Φq at the placement examined: the degrees of freedom the joints leave
    /// there (`None` when no placement was given).
    pub actual: Option<i64>,
}

impl Mobility {
    /// p₅ = revolute + prismatic joints.
    pub fn lower(&self) -> usize {
        self.revolute + self.prismatic
    }

    /// The joint equations that repeat others at the placement examined (actual − formula;
    /// 0 when unknown).
    pub fn redundant(&self) -> usize {
        self.actual.map_or(0, |a| (a - self.formula).max(0) as usize)
    }

    /// The formula written out with the numbers: `M = 3·5 − 2·7 − 0 = 1`.
    pub fn worked(&self) -> String {
        format!("M = 3·{} − 2·{} − {} = {}", self.links, self.lower(), self.higher, self.formula)
    }
}

/// One group of the structure: the solver's group, with its class and order.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct GroupStructure {
    /// The group as the solver solves it.
    pub group: Group,
    /// Class: 1 for the driver (the primary mechanism), else II, III, IV, … (≥ 2).
    pub class: u32,
    /// Order: outer pairs (joints to links before the group, the frame included).
    pub order: usize,
    /// The group's joints to links before it (indices into [`Mechanism::joints`]).
    pub outer: Vec<usize>,
    /// Its joints between its own links.
    pub inner: Vec<usize>,
    /// Its own degrees of freedom, W = 3·links − 2·joints: 0 for an Assur group, 1 for the
    /// driver (its one degree of freedom, the one its driver takes).
    pub mobility: i64,
}

impl GroupStructure {
    /// Whether it is the driver (a class I primary mechanism).
    pub fn is_driver(&self) -> bool {
        matches!(self.group.kind, GroupKind::Driven(_))
    }

    /// Whether it is a passive (redundant) link rather than an Assur group: what is left once
    /// the groups are taken, with more joint equations than coordinates (W < 0), e.g. a
    /// parallelogram's third crank. It has no class.
    pub fn is_passive(&self) -> bool {
        !self.is_driver() && self.mobility < 0
    }
}

/// The structure of a mechanism: its mobility and its groups in solving order.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Structure {
    /// The mobility, by formula and at the placement.
    pub mobility: Mobility,
    /// Drivers given in the scene.
    pub drivers: usize,
    /// The driver(s) and the Assur groups, in the order the solver solves them.
    pub groups: Vec<GroupStructure>,
}

impl Structure {
    /// The structure of `mech`: the groups of [`decompose`], the formula's mobility and,
    /// when `q` (x, y, φ per body) is given, the rank's.
    pub fn of(mech: &Mechanism, q: Option<&[f64]>) -> Structure {
        let revolute = mech.joints.iter().filter(|j| matches!(j.kind, JointKind::Revolute { .. })).count();
        let prismatic = mech.joints.len() - revolute;
        let n = mech.bodies.len();
        let formula = 3 * n as i64 - 2 * (revolute + prismatic) as i64;
        let actual = q.filter(|q| q.len() == 3 * n).map(|q| 3 * n as i64 - joint_rank(mech, q) as i64);
        let mobility = Mobility { links: n, revolute, prismatic, higher: 0, formula, actual };
        let groups = decompose(mech).into_iter().map(|g| group_structure(mech, g)).collect();
        Structure { mobility, drivers: mech.drivers.len(), groups }
    }

    /// The mechanism's class: its groups' highest (I with no Assur group; a passive link
    /// has no class).
    pub fn class(&self) -> u32 {
        self.groups.iter().filter(|g| !g.is_passive()).map(|g| g.class).max().unwrap_or(1)
    }

    /// The formula of the structure as a course writes it: `I(0,1) → II(2,3) → II(4,5)`
    /// (the driver with the frame 0), the links of each group numbered as `number` gives them.
    pub fn formula(&self, number: impl Fn(usize) -> usize) -> String {
        self.groups
            .iter()
            .map(|g| {
                let mut numbers: Vec<usize> = g.group.bodies.iter().map(|&b| number(b)).collect();
                numbers.sort_unstable();
                let mut links: Vec<String> = numbers.iter().map(usize::to_string).collect();
                if g.is_driver() {
                    links.insert(0, "0".into());
                }
                if g.is_passive() {
                    return format!("passive({})", links.join(","));
                }
                format!("{}({})", roman(g.class), links.join(","))
            })
            .collect::<Vec<_>>()
            .join(" → ")
    }
}

/// A class in Roman numerals (I … X; larger as digits).
pub fn roman(n: u32) -> String {
    const R: [&str; 11] = ["0", "I", "II", "III", "IV", "V", "VI", "VII", "VIII", "IX", "X"];
    R.get(n as usize).map_or_else(|| n.to_string(), |s| s.to_string())
}

/// The bodies a joint ties together.
fn joint_ends(kind: &JointKind) -> (Attach, Attach) {
    match *kind {
        JointKind::Revolute { a, b } => (a.body, b.body),
        JointKind::Prismatic { point, q1, .. } => (point.body, q1.body),
    }
}

/// Class, order, outer and inner joints of `group`.
fn group_structure(mech: &Mechanism, group: Group) -> GroupStructure {
    let inside = |a: Attach| matches!(a, Attach::Body(b) if group.bodies.contains(&b));
    let (mut outer, mut inner) = (Vec::new(), Vec::new());
    for &j in &group.joints {
        let (x, y) = joint_ends(&mech.joints[j].kind);
        if inside(x) && inside(y) { inner.push(j) } else { outer.push(j) }
    }
    let mobility = 3 * group.bodies.len() as i64 - 2 * group.joints.len() as i64;
    let class = if matches!(group.kind, GroupKind::Driven(_)) {
        1
    } else {
        let most_pairs = group
            .bodies
            .iter()
            .map(|&b| {
                inner
                    .iter()
                    .filter(|&&j| {
                        let (x, y) = joint_ends(&mech.joints[j].kind);
                        x == Attach::Body(b) || y == Attach::Body(b)
                    })
                    .count()
            })
            .max()
            .unwrap_or(0);
        let edges: Vec<(usize, usize)> = inner
            .iter()
            .filter_map(|&j| match joint_ends(&mech.joints[j].kind) {
                (Attach::Body(x), Attach::Body(y)) => Some((x, y)),
                _ => None,
            })
            .collect();
        (most_pairs.max(longest_cycle(&group.bodies, &edges)).max(2)) as u32
    };
    let order = outer.len();
    GroupStructure { group, class, order, outer, inner, mobility }
}

/// The most links of a simple closed contour of `edges` over `nodes` (0 without one; a
/// group has at most a handful of links, so every path is tried).
fn longest_cycle(nodes: &[usize], edges: &[(usize, usize)]) -> usize {
    fn walk(
        start: usize,
        at: usize,
        path: &mut Vec<usize>,
        used: &mut Vec<bool>,
        edges: &[(usize, usize)],
        best: &mut usize,
    ) {
        for (e, &(x, y)) in edges.iter().enumerate() {
            if used[e] {
                continue;
            }
            let next = if x == at {
                y
            } else if y == at {
                x
            } else {
                continue;
            };
            if next == start {
                *best = (*best).max(path.len());
                continue;
            }
            if path.contains(&next) {
                continue;
            }
            used[e] = true;
            path.push(next);
            walk(start, next, path, used, edges, best);
            path.pop();
            used[e] = false;
        }
    }
    let mut best = 0;
    for &s in nodes {
        let mut used = vec![false; edges.len()];
        walk(s, s, &mut vec![s], &mut used, edges, &mut best);
    }
    // Two joints between the same two links close a "contour" of two: not a contour of links.
    if best < 3 { 0 } else { best }
}

/// The rank of the joint equations' Jacobian Φq at `q` (x, y, φ per body), the φ columns
/// scaled by the mechanism's size so that every column is a length, by the singular values
/// above [`RANK_TOL_REL`] of the largest.
pub fn joint_rank(mech: &Mechanism, q: &[f64]) -> usize {
    let n = mech.bodies.len();
    let rows = 2 * mech.joints.len();
    if rows == 0 || n == 0 {
        return 0;
    }
    let mut j = DMatrix::<f64>::zeros(rows, 3 * n);
    let l = mech.length_scale.max(f64::MIN_POSITIVE);
    let pose = |a: Attach| match a {
        Attach::Ground => (Point::origin(), 0.0),
        Attach::Body(b) => (Point::new(q[3 * b], q[3 * b + 1]), q[3 * b + 2]),
    };
    // Adds to row `r` the derivative of a point `s` (body coordinates) of body `a`, times
    // `w` (a row vector the point's motion is read through).
    let put = |j: &mut DMatrix<f64>, r: usize, a: Attach, s: Vector, w: Vector, sign: f64| {
        if let Attach::Body(b) = a {
            let (_, phi) = pose(a);
            let turn = perp(rotate(s, phi));
            j[(r, 3 * b)] += sign * w.x;
            j[(r, 3 * b + 1)] += sign * w.y;
            j[(r, 3 * b + 2)] += sign * w.dot(&turn) / l;
        }
    };
    let place = |a: Attach, s: Vector| {
        let (at, phi) = pose(a);
        at + rotate(s, phi)
    };
    for (k, joint) in mech.joints.iter().enumerate() {
        let (r0, r1) = (2 * k, 2 * k + 1);
        match joint.kind {
            JointKind::Revolute { a, b } => {
                for (r, w) in [(r0, Vector::new(1.0, 0.0)), (r1, Vector::new(0.0, 1.0))] {
                    put(&mut j, r, a.body, a.local, w, 1.0);
                    put(&mut j, r, b.body, b.local, w, -1.0);
                }
            }
            JointKind::Prismatic { point, q1, q2, .. } => {
                // Φ1 = d × (p − q1) / |d|, d = q2 − q1 (global): the point's distance from
                // the line; Φ2 = φ_point − φ_line − angle (scaled by the size, a length).
                let (p, a1, a2) = (place(point.body, point.local), place(q1.body, q1.local), place(q2.body, q2.local));
                let d = a2 - a1;
                let dn = d.norm().max(f64::MIN_POSITIVE);
                let u = d / dn;
                // d × w = (perp-of-d)ᵀ w with perp(d) = (−d.y, d.x): the normal.
                let normal = perp(u);
                put(&mut j, r0, point.body, point.local, normal, 1.0);
                put(&mut j, r0, q1.body, q1.local, normal, -1.0);
                // The line turns with its body: d rotates, changing d × (p − q1).
                if let Attach::Body(g) = q1.body {
                    let w = p - a1;
                    j[(r0, 3 * g + 2)] += crate::geom::cross(perp(u), w) / l;
                }
                for (body, sign) in [(point.body, 1.0), (q1.body, -1.0)] {
                    if let Attach::Body(b) = body {
                        j[(r1, 3 * b + 2)] += sign;
                    }
                }
            }
        }
    }
    let sv = j.singular_values();
    let top = sv.iter().copied().fold(0.0, f64::max);
    if !(top > 0.0 && top.is_finite()) {
        return 0;
    }
    sv.iter().filter(|&&s| s > RANK_TOL_REL * top).count()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::expr::Expr;
    use crate::solve::linkage::{Anchor, Body, Driver, DriverTarget, Joint};

    fn body(name: &str, points: &[(&str, [f64; 2])], at: [f64; 2], angle: f64) -> Body {
        Body {
            name: name.into(),
            points: points.iter().map(|(n, p)| (n.to_string(), Vector::new(p[0], p[1]))).collect(),
            at: Point::new(at[0], at[1]),
            angle,
        }
    }
    fn pin(name: &str, a: Attach, la: [f64; 2], b: Attach, lb: [f64; 2]) -> Joint {
        Joint {
            name: name.into(),
            kind: JointKind::Revolute {
                a: Anchor { body: a, local: Vector::new(la[0], la[1]) },
                b: Anchor { body: b, local: Vector::new(lb[0], lb[1]) },
            },
        }
    }
    fn q_of(m: &Mechanism) -> Vec<f64> {
        m.bodies.iter().flat_map(|b| [b.at.x, b.at.y, b.angle]).collect()
    }

    /// A parallelogram O1ABC (crank 1, coupler 2, rocker 3, all 40/100 long) with, when
    /// `passive`, a third crank 4 from O4 to the coupler's middle, parallel to the others.
    fn parallelogram(passive: bool) -> Mechanism {
        let g = Attach::Ground;
        let up = std::f64::consts::FRAC_PI_2;
        let mut bodies = vec![
            body("crank", &[("O1", [0.0, 0.0]), ("A", [40.0, 0.0])], [0.0, 0.0], up),
            body("coupler", &[("A", [0.0, 0.0]), ("E", [50.0, 0.0]), ("B", [100.0, 0.0])], [0.0, 40.0], 0.0),
            body("rocker", &[("C", [0.0, 0.0]), ("B", [40.0, 0.0])], [100.0, 0.0], up),
        ];
        let mut joints = vec![
            pin("O1", g, [0.0, 0.0], Attach::Body(0), [0.0, 0.0]),
            pin("A", Attach::Body(0), [40.0, 0.0], Attach::Body(1), [0.0, 0.0]),
            pin("B", Attach::Body(1), [100.0, 0.0], Attach::Body(2), [40.0, 0.0]),
            pin("C", g, [100.0, 0.0], Attach::Body(2), [0.0, 0.0]),
        ];
        if passive {
            bodies.push(body("passive", &[("O4", [0.0, 0.0]), ("E", [40.0, 0.0])], [50.0, 0.0], up));
            joints.push(pin("O4", g, [50.0, 0.0], Attach::Body(3), [0.0, 0.0]));
            joints.push(pin("E", Attach::Body(1), [50.0, 0.0], Attach::Body(3), [40.0, 0.0]));
        }
        let law = Expr::parse("pi/2 + t").unwrap();
        Mechanism {
            bodies,
            joints,
            drivers: vec![Driver { name: "O1".into(), target: DriverTarget::BodyAngle(0), law }],
            length_scale: 100.0,
        }
    }

    #[test]
    fn a_four_bar_has_mobility_one_a_driver_and_one_rrr_dyad() {
        let m = parallelogram(false);
        let s = Structure::of(&m, Some(&q_of(&m)));
        assert_eq!(s.mobility.formula, 1);
        assert_eq!(s.mobility.actual, Some(1));
        assert_eq!(s.mobility.worked(), "M = 3·3 − 2·4 − 0 = 1");
        assert_eq!(s.groups.len(), 2);
        assert_eq!((s.groups[0].class, s.groups[0].order, s.groups[0].is_driver()), (1, 1, true));
        assert_eq!((s.groups[1].class, s.groups[1].order, s.groups[1].mobility), (2, 2, 0));
        assert_eq!(s.groups[1].inner.len(), 1);
        assert_eq!(s.class(), 2);
        assert_eq!(s.formula(|b| b + 1), "I(0,1) → II(2,3)");
    }

    #[test]
    fn a_passive_link_is_found_by_the_rank_not_by_the_formula() {
        let m = parallelogram(true);
        let s = Structure::of(&m, Some(&q_of(&m)));
        assert_eq!(s.mobility.formula, 0, "3·4 − 2·6");
        assert_eq!(s.mobility.actual, Some(1), "the parallel link repeats one equation");
        assert_eq!(s.mobility.redundant(), 1);
        // Moved off parallel, the same link locks the mechanism: the rank is full.
        let mut q = q_of(&m);
        q[3 * 3 + 2] += 0.1;
        q[3 * 3] -= 2.0;
        assert_eq!(joint_rank(&m, &q), 12);
    }

    #[test]
    fn classes_count_inner_pairs_and_contours() {
        assert_eq!(longest_cycle(&[0, 1], &[(0, 1)]), 0);
        assert_eq!(longest_cycle(&[0, 1, 2, 3], &[(0, 1), (1, 2), (2, 3), (3, 0)]), 4);
        assert_eq!(longest_cycle(&[0, 1, 2, 3], &[(0, 1), (0, 2), (0, 3)]), 0);
        assert_eq!(roman(3), "III");
        assert_eq!(roman(12), "12");
    }
}
