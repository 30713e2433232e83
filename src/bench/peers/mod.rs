//! Peers' cold sweeps beside mechdraw's "Assur groups (cold)" rows (issue 34): the same two
//! problems solved by another tool from nothing, every position of a whole turn of the crank,
//! timed per position and measured against the same independent references as mechdraw's
//! rows ([`super::reference`]).
//!
//! - the `four-bar` crate (KmolYuan's closed-form four-bar; only with the `peers` feature):
//!   `fourbar_crate`;
//! - pylinkage (Python; its numba path when numba is installed), run as a child process:
//!   [`pylinkage`].
//!
//! A peer that is not there gives a note (one line: which peer, why, how to add it) instead
//! of a row; the bench goes on.

#[cfg(feature = "peers")]
pub mod fourbar_crate;
pub mod pylinkage;

use super::Measurement;
use super::reference::{self, shaper};
use crate::geom::{Point, Vector, angle_of, cross, polar};
use crate::solve::fourbar::Geometry;

/// Crank angles of a peer's sweep: 0°, 1°, …, 359°.
pub const POSITIONS: usize = 360;

/// The problem names of mechdraw's own rows, so that a peer's row sits beside them.
pub const FOURBAR_PROBLEM: &str = "four-bar (seed 003)";
/// See [`FOURBAR_PROBLEM`].
pub const SHAPER_PROBLEM: &str = "shaper (seed 002)";

/// What the peers gave: rows, and a line for each peer that is not there.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PeerReport {
    /// One row per peer and problem (method `<peer> (cold)`), ns per position.
    pub rows: Vec<Measurement>,
    /// One line per peer that was not measured: which, why, how to add it.
    pub notes: Vec<String>,
}

/// Where pylinkage is looked for.
#[derive(Debug, Clone, PartialEq)]
pub struct PeerOptions {
    /// The Python that runs the pylinkage script (`python3` on the PATH when `None`).
    pub python: Option<std::path::PathBuf>,
    /// A smoke run: fewer, shorter batches.
    pub quick: bool,
}

/// Every peer this build can measure: the `four-bar` crate (feature `peers`) and pylinkage.
pub fn run(budget: super::timing::Budget, opts: &PeerOptions) -> PeerReport {
    let mut report = PeerReport::default();
    match super::suite::chebyshev_geometry() {
        Ok(g) => fourbar_crate_rows(budget, &g, &mut report),
        Err(e) => report.notes.push(format!("four-bar crate: the Chebyshev template did not load: {e}")),
    }
    match pylinkage::run(opts) {
        Ok(rows) => report.rows.extend(rows),
        Err(e) => report.notes.push(format!("pylinkage (cold): not measured: {e}")),
    }
    report
}

#[cfg(feature = "peers")]
fn fourbar_crate_rows(budget: super::timing::Budget, g: &Geometry, report: &mut PeerReport) {
    report.rows.push(fourbar_crate::cold(budget, g));
}

#[cfg(not(feature = "peers"))]
fn fourbar_crate_rows(_: super::timing::Budget, _: &Geometry, report: &mut PeerReport) {
    report.notes.push(
        "four-bar crate (cold): not built in (a build with the `peers` feature measures it: \
         cargo run --release --features peers -- bench)"
            .into(),
    );
}

/// The crank angle of position `k` of a peer's sweep, radians (`k`°).
pub fn angle(k: usize) -> f64 {
    crate::geom::rad(k as f64)
}

/// The four-bar's coupler point M where the coupler's A and B are: B→M is B→A turned by
/// `alpha` and scaled by l_bm/l_ab (the geometry's convention).
pub fn coupler_point(g: &Geometry, a: Point, b: Point) -> Point {
    let (s, c) = libm::sincos(g.alpha);
    let ba = (a - b) * (g.l_bm / g.l_ab);
    b + Vector::new(c * ba.x - s * ba.y, s * ba.x + c * ba.y)
}

/// M relative to the coupler: |AM| and the angle from A→B to A→M (radians), what a peer that
/// places M by distance and angle from A is given.
pub fn coupler_point_polar(g: &Geometry) -> (f64, f64) {
    let m = coupler_point(g, Point::origin(), Point::new(g.l_ab, 0.0));
    (m.coords.norm(), angle_of(m.coords))
}

/// A four-bar peer's sweep scored as mechdraw's four-bar rows are: the residual of the loop
/// closure (|O1A| − l1, |AB| − l_ab, |CB| − l_bc, and A's distance from where the crank puts
/// it) and the distance of B and M to the second route's ([`reference::fourbar_b`], M from it),
/// both over the longest link. `points[k]` = (A, B, M) at [`angle`]`(k)`; `None` (a position
/// the peer did not assemble) scores infinite.
pub fn fourbar_error(g: &Geometry, points: &[Option<[Point; 3]>]) -> (f64, f64) {
    let scale = g.l1.max(g.l_ab).max(g.l_bc).max(g.ground());
    let (mut res, mut dist) = (0.0_f64, 0.0_f64);
    for (k, p) in points.iter().enumerate() {
        let Some([a, b, m]) = *p else { return (f64::INFINITY, f64::INFINITY) };
        let phi1 = angle(k);
        let a_exact = polar(g.o1, g.l1, phi1);
        res = res.max(reference::fourbar_residual(g, a, b)).max((a - a_exact).norm() / scale);
        let Some(b_ref) = reference::fourbar_b(g, phi1) else { continue };
        let m_ref = coupler_point(g, a_exact, b_ref);
        dist = dist.max((b - b_ref).norm() / scale).max((m - m_ref).norm() / scale);
    }
    (res, dist)
}

/// A shaper peer's sweep scored as mechdraw's shaper rows are: the residual of its
/// constraints (|O1A| − R, |O3B| − L, |BE| − l_BE, A's distance from the rocker's line O3B,
/// E's from the ram's line) over L, and the distance to the closed form
/// ([`shaper::closed_form`]: |Δx_E| / L and the rocker angle's difference, radians).
/// `points[k]` = (A, B, E) at [`angle`]`(k)`, time k/360 s.
pub fn shaper_error(points: &[Option<[Point; 3]>]) -> (f64, f64) {
    let (o1, o3) = (Point::new(0.0, shaper::H_PIVOT), Point::origin());
    let (mut res, mut dist) = (0.0_f64, 0.0_f64);
    for (k, p) in points.iter().enumerate() {
        let Some([a, b, e]) = *p else { return (f64::INFINITY, f64::INFINITY) };
        let (ob, ab) = (b - o3, a - o3);
        let r = [
            (a - o1).norm() - shaper::R,
            ob.norm() - shaper::L,
            (e - b).norm() - shaper::LBE,
            cross(ob, ab) / ob.norm(),
            e.y - shaper::Y_RAM,
        ];
        res = r.iter().fold(res, |m, v| m.max(v.abs() / shaper::L));
        let t = angle(k) / shaper::OMEGA;
        let ([x_e, ..], [theta, ..]) = shaper::closed_form(t);
        dist = dist.max((e.x - x_e).abs() / shaper::L).max(reference::angle_distance(angle_of(ob), theta));
    }
    (res, dist)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Side;
    use crate::solve::fourbar::Prepared;

    #[test]
    fn mechdraws_own_four_bar_scores_at_rounding_and_a_moved_m_does_not() {
        let g = super::super::suite::chebyshev_geometry().unwrap();
        let prepared = Prepared::new(&g);
        let mut points: Vec<Option<[Point; 3]>> =
            (0..POSITIONS).map(|k| prepared.position(angle(k), Side::Left).ok().map(|p| [p.a, p.b, p.m])).collect();
        let (res, dist) = fourbar_error(&g, &points);
        assert!(res < 1e-15 && dist < 1e-15, "{res:e} {dist:e}");
        // The polar form of M gives the same M (a peer placing M by |AM| and an angle).
        let (l_am, ang) = coupler_point_polar(&g);
        for p in points.iter().flatten() {
            let m = polar(p[0], l_am, angle_of(p[1] - p[0]) + ang);
            assert!((m - p[2]).norm() < 1e-15, "{m:?} {:?}", p[2]);
        }
        if let Some(p) = points[90].as_mut() {
            p[2].x += 1e-9;
        }
        let (_, dist) = fourbar_error(&g, &points);
        assert!((dist - 1e-9 / 0.1).abs() < 1e-12, "{dist:e}");
        points[3] = None;
        assert_eq!(fourbar_error(&g, &points), (f64::INFINITY, f64::INFINITY));
    }

    #[test]
    fn the_shapers_closed_form_scores_at_rounding() {
        let points: Vec<Option<[Point; 3]>> = (0..POSITIONS)
            .map(|k| {
                let phi = angle(k);
                let a = polar(Point::new(0.0, shaper::H_PIVOT), shaper::R, phi);
                let ([x_e, ..], [theta, ..]) = shaper::closed_form(phi / shaper::OMEGA);
                Some([a, polar(Point::origin(), shaper::L, theta), Point::new(x_e, shaper::Y_RAM)])
            })
            .collect();
        let (res, dist) = shaper_error(&points);
        assert!(res < 1e-15 && dist < 1e-15, "{res:e} {dist:e}");
    }
}
