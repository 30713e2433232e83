//! Stability of the closed-form four-bar where it breaks: the edge of the assembly range of
//! a non-Grashof linkage (a dead point for the crank: A, B, C collinear), and branch
//! continuity through near-singular positions. Expected behaviour is written on each test.

#![allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the library calls"
)]

use mechdraw::geom::{Point, Side, deg, polar, rad};
use mechdraw::solve::fourbar::{
    FourbarError, Geometry, Grashof, MotionSpec, Outputs, Reach, Sweep, kinematics, position, solve_motion,
};

/// A non-Grashof triple rocker: ground 1.0, crank 0.8, coupler 0.5, rocker 0.6
/// (s + l = 1.5 > p + q = 1.4). |AC| reaches l_ab + l_bc = 1.1 at phi1 = ±acos(0.43/1.6).
fn triple_rocker() -> Geometry {
    Geometry {
        o1: Point::new(0.0, 0.0),
        c: Point::new(1.0, 0.0),
        l1: 0.8,
        l_ab: 0.5,
        l_bm: 0.3,
        alpha: std::f64::consts::PI,
        l_bc: 0.6,
        branch: Side::Left,
    }
}

/// The limit crank angle from the law of cosines in triangle O1 A C (independent of the
/// solver): |AC|² = g² + l1² − 2·g·l1·cos phi1 = (l_ab + l_bc)².
fn edge(g: &Geometry) -> f64 {
    let (gr, l1, reach) = (g.ground(), g.l1, g.l_ab + g.l_bc);
    ((gr * gr + l1 * l1 - reach * reach) / (2.0 * gr * l1)).acos()
}

/// Approaching the edge of the assembly range (transmission → 180°) from inside, the
/// position exists and is finite for every gap 1e-2 … 1e-12 rad, the transmission angle
/// tends to 180°, and the velocities are finite and grow like 1/√gap — until the gap is
/// so small that `kinematics` answers `Singular` naming the angle (never an infinite or
/// NaN velocity). Just past the edge, `position` answers `Unassemblable` with
/// `Reach::TooFar` and the angle asked for.
#[test]
fn edge_of_the_assembly_range() {
    let g = triple_rocker();
    assert_eq!(g.grashof(), Grashof::NonGrashof);
    let star = edge(&g);
    let limits = g.limit_angles();
    assert!(
        limits.iter().any(|l| (mechdraw::geom::wrap_pi(l.phi1 - star)).abs() < 1e-12 && l.reach == Reach::TooFar),
        "{limits:?} vs {star}"
    );
    let mut last_omega = 0.0;
    let mut singular_seen = false;
    for k in 2..=12 {
        let gap = 10f64.powi(-k);
        let p = position(&g, star - gap, Side::Left).unwrap();
        assert!(p.b.x.is_finite() && p.b.y.is_finite() && p.transmission().is_finite());
        // 180° − transmission shrinks like √gap.
        let miss = 180.0 - deg(p.transmission());
        assert!(miss >= 0.0 && miss <= 200.0 * gap.sqrt(), "gap {gap}: transmission {}°", deg(p.transmission()));
        match kinematics(&g, &p, 1.0) {
            Ok(kin) => {
                assert!(!singular_seen, "finite velocities after a Singular at a larger gap");
                assert!(kin.omega3.is_finite() && kin.omega2.is_finite());
                assert!(kin.omega3.abs() > last_omega, "gap {gap}: |omega3| {} not growing", kin.omega3);
                // |omega3| · √gap stays bounded (square-root singularity).
                assert!(kin.omega3.abs() * gap.sqrt() < 10.0, "gap {gap}: omega3 {}", kin.omega3);
                last_omega = kin.omega3.abs();
            }
            Err(FourbarError::Singular { phi1_deg, transmission_deg }) => {
                assert!((phi1_deg - deg(star - gap)).abs() < 1e-9 && transmission_deg > 179.9);
                singular_seen = true;
            }
            Err(e) => panic!("gap {gap}: unexpected {e}"),
        }
        match position(&g, star + gap.max(1e-10), Side::Left) {
            Err(FourbarError::Unassemblable { phi1_deg, reach: Reach::TooFar, .. }) => {
                assert!((phi1_deg - deg(star + gap.max(1e-10))).abs() < 1e-9)
            }
            other => panic!("gap {gap} past the edge: expected Unassemblable, got {other:?}"),
        }
    }
    assert!(singular_seen, "the exactly-collinear limit must be named Singular by kinematics");
}

/// Branch continuity through near-singular positions: sweeping the triple rocker over its
/// whole assembly range (−phi* … phi*, step 0.01°, grid landing within 1e-6° of both
/// limits), B stays on its branch (left of A→C) at every position, and no step moves B
/// further than the motion allows: |ΔB| ≤ 1.5 · max |ω3|·l_bc/ω1 · Δphi1 over the two ends,
/// plus the √ growth allowed at the last step onto the limit. A sweep past both limits
/// skips the angles outside (two gaps) and reports dead points exactly at ±phi*.
#[test]
fn branch_is_kept_through_near_singular_positions() {
    let g = triple_rocker();
    let star = deg(edge(&g));
    let from = -star + 1e-6;
    let step = 0.01;
    let n = ((2.0 * star - 2e-6) / step).floor();
    let spec = MotionSpec {
        geometry: g,
        omega1: 1.0,
        epsilon1: 0.0,
        sweep: Sweep { from_deg: from, to_deg: from + n * step, step_deg: step },
        outputs: Outputs { velocity: true, acceleration: false, forces: false },
        dynamics: None,
    };
    let motion = solve_motion(&spec).unwrap();
    assert!(motion.gaps.is_empty(), "{:?}", motion.gaps);
    assert_eq!(motion.positions.len() as f64, n + 1.0);
    for p in &motion.positions {
        assert_eq!(p.side(&g), Some(Side::Left), "phi1 = {}°", deg(p.phi1));
    }
    let dphi = rad(step);
    for w in motion.positions.windows(2) {
        let db = (w[1].b - w[0].b).norm();
        let vmax =
            [w[0], w[1]].iter().map(|p| p.kin.map_or(f64::INFINITY, |k| k.omega3.abs() * g.l_bc)).fold(0.0, f64::max);
        // Near the limit B moves like √(phi* − phi1): allow the √ step as well.
        let allowed = 1.5 * vmax * dphi + 2.0 * g.l_bc * dphi.sqrt() * 0.01;
        assert!(db <= allowed, "phi1 = {}°: |ΔB| = {db} > {allowed}", deg(w[0].phi1));
    }
    // A sweep past both limits: skipped angles outside, dead points exactly at ±phi*.
    let wide = MotionSpec { sweep: Sweep { from_deg: -90.0, to_deg: 90.0, step_deg: 1.0 }, ..spec };
    let motion = solve_motion(&wide).unwrap();
    assert_eq!(motion.gaps.len(), 2, "{:?}", motion.gaps);
    let dead: Vec<f64> = motion.dead_points.iter().map(|d| d.phi1_deg).collect();
    assert_eq!(dead.len(), 2, "{dead:?}");
    assert!((dead[0] + star).abs() < 1e-9 && (dead[1] - star).abs() < 1e-9, "{dead:?} vs ±{star}");
    let _ = polar;
}

/// Magnitudes beyond double precision: a scene whose lengths square to infinity, or whose
/// crank speed does, is refused with `NonFinite` naming the quantity and the first angle
/// (never NaN carried into a drawing, never blamed on the file writer); the same scene at
/// magnitudes that fit solves.
#[test]
fn overflowing_magnitudes_are_refused_by_name() {
    let base = triple_rocker();
    let spec = |scale: f64, omega1: f64| MotionSpec {
        geometry: Geometry {
            o1: Point::new(0.0, 0.0),
            c: Point::new(base.c.x * scale, 0.0),
            l1: base.l1 * scale,
            l_ab: base.l_ab * scale,
            l_bm: base.l_bm * scale,
            l_bc: base.l_bc * scale,
            ..base
        },
        omega1,
        epsilon1: 0.0,
        sweep: Sweep { from_deg: 0.0, to_deg: 10.0, step_deg: 1.0 },
        outputs: Outputs { velocity: true, acceleration: true, forces: false },
        dynamics: None,
    };
    // |AC|² overflows for lengths of 1e160 (the square of 1e160 is beyond 1.8e308).
    match solve_motion(&spec(1e160, 1.0)) {
        Err(FourbarError::NonFinite { phi1_deg, quantity }) => {
            assert_eq!((phi1_deg, quantity), (0.0, "positions"));
        }
        other => panic!("expected NonFinite positions, got {other:?}"),
    }
    // Accelerations ω²·l overflow for omega1 = 1e200.
    match solve_motion(&spec(1.0, 1e200)) {
        Err(FourbarError::NonFinite { phi1_deg, quantity }) => {
            assert_eq!((phi1_deg, quantity), (0.0, "velocities and accelerations"));
        }
        other => panic!("expected NonFinite kinematics, got {other:?}"),
    }
    // Large but representable: solves, every number finite.
    let motion = solve_motion(&spec(1e100, 1e50)).unwrap();
    assert_eq!(motion.positions.len(), 11);
    assert!(motion.positions.iter().all(|p| p.kin.is_some_and(|k| k.is_finite())));
}
