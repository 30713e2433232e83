//! The `four-bar` crate (KmolYuan's; feature `peers`) on the Chebyshev four-bar: its coupler
//! curve over the sweep's 360 crank angles, a fresh linkage each sweep.
//!
//! The crate solves each angle in closed form from the link lengths alone (a circle
//! intersection, M by distance and angle from A), with no state carried from one angle to the
//! next: its "cold" sweep is a `FourBar` built from nine numbers and `curve_by` over the
//! angles, which returns a new `Vec` of coupler points, as a caller of the crate gets it.

use super::{FOURBAR_PROBLEM, POSITIONS, angle, coupler_point_polar, fourbar_error};
use crate::bench::Measurement;
use crate::bench::timing::{Budget, ns_per_call};
use crate::geom::{Point, Side, angle_of};
use crate::solve::fourbar::Geometry;
use four_bar::FourBar;
use four_bar::mech::fb::UnNorm;
use four_bar::mech::{CurveGen, NormFourBar, Stat, Statable};

/// The crate's four-bar for mechdraw's geometry: driver pivot O1, ground angle of O1→C,
/// ground |O1C|, driver l1, coupler l_ab, follower l_bc, coupler point M at |AM| and the angle
/// from A→B; B left of A→C is the crate's first circuit (`C1B1`, no inversion).
pub fn fourbar(g: &Geometry) -> FourBar {
    let (l5, angle_am) = coupler_point_polar(g);
    let stat = if g.branch == Side::Left { Stat::C1B1 } else { Stat::C2B1 };
    let norm = NormFourBar { l1: g.ground(), l3: g.l_ab, l4: g.l_bc, l5, g: angle_am, stat };
    let unnorm = UnNorm { p1x: g.o1.x, p1y: g.o1.y, a: angle_of(g.c - g.o1), l2: g.l1 };
    FourBar::new(unnorm, norm)
}

/// The crate's crank angles for mechdraw's 0°, 1°, …, 359° (the crate measures the driver's
/// angle from the ground line O1→C).
fn crate_angles(g: &Geometry) -> Vec<f64> {
    let a = angle_of(g.c - g.o1);
    (0..POSITIONS).map(|k| angle(k) - a).collect()
}

/// (A, B, M) at every angle of the sweep, from the crate's own joints (`None` where it
/// assembles nothing).
pub fn points(g: &Geometry) -> Vec<Option<[Point; 3]>> {
    let fb = fourbar(g);
    let inv = fb.inv();
    crate_angles(g)
        .into_iter()
        .map(|t| fb.pos_s(t, inv).map(|[_, _, a, b, m]: [[f64; 2]; 5]| [a, b, m].map(|p| Point::new(p[0], p[1]))))
        .collect()
}

/// The row "four-bar crate (cold)": nanoseconds per position of a fresh `FourBar` and its
/// `curve_by` over the 360 angles; error as mechdraw's four-bar rows
/// ([`super::fourbar_error`]: B and M against the second route).
pub fn cold(budget: Budget, g: &Geometry) -> Measurement {
    let angles = crate_angles(g);
    let ns = ns_per_call(budget, || {
        let curve: Vec<[f64; 2]> = fourbar(std::hint::black_box(g)).curve_by(&angles);
        curve.len()
    }) / POSITIONS as f64;
    let (res, dist) = fourbar_error(g, &points(g));
    Measurement::new(FOURBAR_PROBLEM, "four-bar crate (cold)", "curve_by, 360 angles", ns, res, dist)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::fourbar::Prepared;

    /// The crate's A, B and M equal mechdraw's closed-form dyad's to 1e-9 of the longest link,
    /// on both assembly modes, at angles around the turn (so the row's error column compares
    /// the same mechanism).
    #[test]
    fn the_crates_coupler_point_equals_mechdraws() {
        let mut g = crate::bench::suite::chebyshev_geometry().unwrap();
        for branch in [Side::Left, Side::Right] {
            g.branch = branch;
            let prepared = Prepared::new(&g);
            let pts = points(&g);
            for k in [0, 37, 90, 179, 180, 271, 359] {
                let ours = prepared.position(angle(k), branch).unwrap();
                let [a, b, m] = pts[k].unwrap();
                for (p, q, name) in [(a, ours.a, "A"), (b, ours.b, "B"), (m, ours.m, "M")] {
                    assert!((p - q).norm() <= 1e-9 * 0.1, "{branch:?} {k}°: {name} {p:?} vs {q:?}");
                }
            }
        }
        g.branch = Side::Left;
        let (res, dist) = fourbar_error(&g, &points(&g));
        assert!(res < 1e-14 && dist < 1e-14, "{res:e} {dist:e}");
    }
}
