//! Forces drawn on a printed sheet's mechanism clear of it (issue 33, the report's position
//! pages): a force acts at a joint drawn as a symbol (a joint's circle, a slider's block, a
//! pivot's ground symbol) on links and guides; drawn from the joint's centre it runs over
//! the symbol and out across whatever passes through the joint (the shaper's R32 from A's
//! centre over the slider's block and the rocker). Each force is placed at the first of
//! these that crosses no stroke of the mechanism and no force placed before it:
//! 1. from the joint: its tail where its line of action leaves the symbol, plus
//!    [`SYMBOL_GAP`] arrowheads;
//! 2. onto the joint: its tip there (the line of action through the joint, pointing at it);
//! 3. as [`forces::arrows_on_mechanism`] placed it (moved beside a link it would lie on,
//!    with a connector);
//!
//! and when none is clear, the one crossing fewest strokes (the first on a tie). The force's
//! length and direction are kept (measured × k_f it is the force), and in 1 and 2 its line
//! of action runs through the joint.

use crate::figure::shared::forces::{self, ForceArrow, runs_over};
use crate::figure::shared::vocab::Sizes;
use crate::geom::{Point, Vector, cross, perp};

/// Gap between a joint's symbol and the end of a force drawn from or onto it, in
/// arrowheads.
pub const SYMBOL_GAP: f64 = 0.3;

/// A symbol drawn at a joint, which a force acting there starts (or ends) outside of.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Symbol {
    /// A joint's circle at `at`, radius `r`.
    Circle {
        /// Its centre.
        at: Point,
        /// Its radius.
        r: f64,
    },
    /// A box (a slider's block, a ground symbol) around the joint at `at`: `centre`, its
    /// unit direction `dir` and its half sizes along and across it.
    Block {
        /// The joint it is drawn at.
        at: Point,
        /// The box's centre.
        centre: Point,
        /// Its unit direction.
        dir: Vector,
        /// Half its length along `dir`, half its height across.
        half: (f64, f64),
    },
}

impl Symbol {
    /// The joint it is drawn at.
    pub fn at(&self) -> Point {
        match *self {
            Symbol::Circle { at, .. } | Symbol::Block { at, .. } => at,
        }
    }

    /// How far from its joint along the unit direction `u` the symbol reaches (0 when the
    /// ray misses it).
    pub fn reach(&self, u: Vector) -> f64 {
        match *self {
            Symbol::Circle { r, .. } => r,
            Symbol::Block { at, centre, dir, half } => {
                // The ray at + t·u in the box's frame, where the box is |x| ≤ hl, |y| ≤ hh.
                let n = perp(dir);
                let p = at - centre;
                let (p, d) = (Vector::new(p.dot(&dir), p.dot(&n)), Vector::new(u.dot(&dir), u.dot(&n)));
                let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
                for (pi, di, h) in [(p.x, d.x, half.0), (p.y, d.y, half.1)] {
                    if di.abs() < 1e-15 {
                        if pi.abs() > h {
                            return 0.0;
                        }
                    } else {
                        let (a, b) = ((-h - pi) / di, (h - pi) / di);
                        t0 = t0.max(a.min(b));
                        t1 = t1.min(a.max(b));
                    }
                }
                if t1 >= t0 && t1.is_finite() { t1 } else { 0.0 }
            }
        }
    }

    /// Its outline as segments (a circle is left out: a force from its joint starts outside
    /// it, and a force passing it elsewhere is judged by the links).
    pub fn outline(&self) -> Vec<(Point, Point)> {
        match *self {
            Symbol::Circle { .. } => Vec::new(),
            Symbol::Block { centre, dir, half, .. } => {
                let n = perp(dir);
                let c = [
                    centre - dir * half.0 - n * half.1,
                    centre + dir * half.0 - n * half.1,
                    centre + dir * half.0 + n * half.1,
                    centre - dir * half.0 + n * half.1,
                ];
                (0..4).map(|i| (c[i], c[(i + 1) % 4])).collect()
            }
        }
    }
}

/// The ground symbol under a pivot at `p` ([`crate::figure::shared::vocab::ground`]) as a
/// box, hatch included.
pub fn ground_block(p: Point, s: Sizes) -> Symbol {
    let b = crate::figure::shared::vocab::ground_extent(p, s);
    let centre = Point::new(0.5 * (b.min.x + b.max.x), 0.5 * (b.min.y + b.max.y));
    Symbol::Block {
        at: p,
        centre,
        dir: Vector::new(1.0, 0.0),
        half: (0.5 * (b.max.x - b.min.x), 0.5 * (b.max.y - b.min.y)),
    }
}

/// A ground guide from `a` to `b` ([`crate::figure::shared::vocab::guide`]) as segments:
/// its line and its hatch's two edges.
pub fn guide_strokes(a: Point, b: Point, s: Sizes) -> Vec<(Point, Point)> {
    let len = (b - a).norm();
    if len.is_nan() || len <= 0.0 {
        return Vec::new();
    }
    let u = (b - a) / len;
    let down = -perp(u);
    let off = down * (0.5 * s.slider_height);
    let far = off + (down - u) * (0.6 * s.ground);
    vec![(a, b), (a + off, b + off), (a + far, b + far)]
}

/// Whether segments `a` and `b` cross (a point inside both).
fn crosses(a: (Point, Point), b: (Point, Point)) -> bool {
    let (u, w) = (a.1 - a.0, b.1 - b.0);
    let den = cross(u, w);
    if den.abs() <= 1e-12 * u.norm() * w.norm() {
        return false;
    }
    let d = b.0 - a.0;
    let (t, k) = (cross(d, w) / den, cross(d, u) / den);
    (0.0..=1.0).contains(&t) && (0.0..=1.0).contains(&k)
}

/// Places `arrows` (from [`forces::arrows_on_mechanism`], paper mm) clear of the mechanism's
/// `strokes` (links, guides), its `symbols` and each other (see the module's text); with
/// `within` (a box, lower-left and upper-right corners), a placement leaving it comes after
/// every one inside it.
pub fn place(
    arrows: &mut [ForceArrow],
    strokes: &[(Point, Point)],
    symbols: &[Symbol],
    within: Option<(Point, Point)>,
    s: Sizes,
) {
    let band = s.link + 2.0 * crate::draw::parts::ARROW_HALF_WIDTH * s.head;
    let mut obstacles: Vec<(Point, Point)> = strokes.to_vec();
    obstacles.extend(symbols.iter().flat_map(Symbol::outline));
    let near = |p: Point, q: Point| (p - q).norm() <= 1e-9 * (1.0 + p.coords.norm());
    let reach = |p: Point, u: Vector| {
        symbols.iter().filter(|x| near(x.at(), p)).map(|x| x.reach(u)).fold(s.joint, f64::max) + SYMBOL_GAP * s.head
    };
    let mut placed: Vec<(Point, Point)> = Vec::new();
    for a in arrows.iter_mut() {
        let v = a.arrow.1 - a.arrow.0;
        let len = v.norm();
        if len.is_nan() || len <= 0.0 {
            continue;
        }
        let (p, u) = (a.at, v / len);
        let from = p + u * reach(p, u);
        let onto = p - u * reach(p, -u);
        let candidates = [(from, (from, from + v)), (onto - v, (onto - v, onto)), (a.at, a.arrow)];
        let outside = |p: Point| within.is_some_and(|(lo, hi)| p.x < lo.x || p.y < lo.y || p.x > hi.x || p.y > hi.y);
        let count = |seg: (Point, Point)| {
            usize::from(outside(seg.0) || outside(seg.1)) * (obstacles.len() + placed.len() + 1)
                + obstacles.iter().filter(|o| crosses(seg, **o) || runs_over(seg, **o, band, s)).count()
                + placed.iter().filter(|o| crosses(seg, **o) || forces::on_one_line(seg, **o, s)).count()
        };
        let best = candidates
            .iter()
            .enumerate()
            .min_by_key(|(i, (_, seg))| (count(*seg), *i))
            .map(|(_, c)| *c)
            .unwrap_or((a.at, a.arrow));
        (a.at, a.arrow) = best;
        placed.push(a.arrow);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_force_at_a_slider_starts_outside_its_block_on_its_line_of_action() {
        let s = Sizes::for_length(100.0);
        let at = Point::new(50.0, 50.0);
        let block = Symbol::Block { at, centre: at, dir: Vector::new(1.0, 0.0), half: (4.0, 2.5) };
        // Straight up: leaves the block at 2.5; at 45°, at 2.5·√2 (the long side is 4).
        assert!((block.reach(Vector::new(0.0, 1.0)) - 2.5).abs() < 1e-12);
        let d = Vector::new(1.0, 1.0).normalize();
        assert!((block.reach(d) - 2.5 * 2f64.sqrt()).abs() < 1e-12);
        // A rocker through the joint, a force across it from the joint's centre.
        let rocker = (Point::new(40.0, 30.0), Point::new(60.0, 70.0));
        let f = forces::NamedVector::new("R32", Vector::new(20.0, -10.0));
        let mut a = vec![ForceArrow { at, force: f, arrow: (at, at + Vector::new(20.0, -10.0)) }];
        assert!(crosses(a[0].arrow, block.outline()[1]) || crosses(a[0].arrow, block.outline()[0]));
        place(&mut a, &[rocker], &[block], None, s);
        let (t, tip) = a[0].arrow;
        assert!((tip - t - Vector::new(20.0, -10.0)).norm() < 1e-12, "its vector kept");
        assert!(cross(tip - t, at - t).abs() < 1e-9, "its line of action through the joint");
        assert!(!block.outline().iter().any(|o| crosses(a[0].arrow, *o)) && !crosses(a[0].arrow, rocker));
        assert_eq!(a[0].at, t, "no connector");
    }

    #[test]
    fn a_force_that_would_cross_a_link_from_the_joint_points_onto_it() {
        let s = Sizes::for_length(100.0);
        let at = Point::new(0.0, 0.0);
        // A link from the joint up to the right, another one across the force's way out.
        let other = (Point::new(5.0, -5.0), Point::new(5.0, 5.0));
        let f = forces::NamedVector::new("RB", Vector::new(10.0, 0.0));
        let mut a = vec![ForceArrow { at, force: f, arrow: (at, Point::new(10.0, 0.0)) }];
        place(&mut a, &[other], &[Symbol::Circle { at, r: s.joint }], None, s);
        assert!(a[0].arrow.1.x < 0.0 && (a[0].arrow.1 - a[0].arrow.0 - Vector::new(10.0, 0.0)).norm() < 1e-12);
        assert!(!crosses(a[0].arrow, other));
    }
}
