//! The Chebyshev four-bar written as a general linkage scene (templates/fourbar-linkage.toml)
//! against a closed-form four-bar (RRR dyad by circle intersection, velocities and
//! accelerations from the loop equations) written here: positions, velocities and
//! accelerations agree to 1e-9 relative at every one of the 361 crank angles.

#![allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the library calls"
)]

mod common;

use mechdraw::geom::{CircleIntersection, Point, Side, Vector, circle_circle, perp};
use mechdraw::scene::{self, Scene};
use mechdraw::solve::linkage::{Attach, Solver};

const L1: f64 = 0.04;
const OMEGA1: f64 = 20.0;

struct Closed {
    b: Point,
    m: Point,
    vb: Vector,
    vm: Vector,
    ab: Vector,
    am: Vector,
    phi2: f64,
    omega2: f64,
    eps2: f64,
    phi3: f64,
    omega3: f64,
    eps3: f64,
}

/// Solves a·x + b·y = r for the scalars x, y (2×2, Cramer).
fn solve2(a: Vector, b: Vector, r: Vector) -> (f64, f64) {
    let det = a.x * b.y - a.y * b.x;
    ((r.x * b.y - r.y * b.x) / det, (a.x * r.y - a.y * r.x) / det)
}

fn closed_form(phi1: f64) -> Closed {
    let c = Point::new(0.08, 0.0);
    let a = Point::new(L1 * phi1.cos(), L1 * phi1.sin());
    let b = match circle_circle(a, 0.10, c, 0.10) {
        CircleIntersection::Two { .. } => circle_circle(a, 0.10, c, 0.10).on(Side::Left).unwrap(),
        other => panic!("four-bar not assemblable at {phi1}: {other:?}"),
    };
    let m = a + (b - a) * 2.0;
    let va = perp(a.coords) * OMEGA1;
    let aa = -a.coords * (OMEGA1 * OMEGA1);
    // v_B = v_A + ω2 ⊥(B−A) = ω3 ⊥(B−C)
    let (omega2, omega3m) = solve2(perp(b - a), -perp(b - c), -va);
    let omega3 = omega3m;
    let vb = va + perp(b - a) * omega2;
    let rhs = -aa + (b - a) * omega2.powi(2) - (b - c) * omega3.powi(2);
    let (eps2, eps3) = solve2(perp(b - a), -perp(b - c), rhs);
    let ab = aa + perp(b - a) * eps2 - (b - a) * omega2.powi(2);
    let vm = va + perp(m - a) * omega2;
    let am = aa + perp(m - a) * eps2 - (m - a) * omega2.powi(2);
    let ang = |v: Vector| v.y.atan2(v.x);
    Closed { b, m, vb, vm, ab, am, phi2: ang(b - a), omega2, eps2, phi3: ang(b - c), omega3, eps3 }
}

/// |Δ| ≤ rel · max(|expected|, floor).
fn close_vec(got: Vector, want: Vector, rel: f64, floor: f64) -> bool {
    (got - want).norm() <= rel * want.norm().max(floor)
}

fn same_angle(a: f64, b: f64) -> bool {
    mechdraw::geom::wrap_pi(a - b).abs() <= 1e-12
}

#[test]
fn chebyshev_linkage_scene_equals_the_closed_form_four_bar() {
    let loaded = scene::load(&common::root().join("templates/fourbar-linkage.toml"), &[]).unwrap();
    let Scene::Linkage(s) = loaded.scene else { panic!("not a linkage scene") };
    let states = Solver::new(s.mechanism.clone()).unwrap().run(&s.times).unwrap();
    assert_eq!(states.len(), 361);
    let (b, m) = (s.anchor("coupler.B").unwrap(), s.anchor("coupler.M").unwrap());
    let coupler = Attach::Body(1);
    let rocker = Attach::Body(2);
    let rel = 1e-9;
    let (vs, as_) = (OMEGA1 * L1, OMEGA1 * OMEGA1 * L1);
    for st in &states {
        let phi1 = OMEGA1 * st.t;
        let cf = closed_form(phi1);
        let deg = phi1.to_degrees();
        assert!(close_vec(st.point(b).coords, cf.b.coords, rel, L1), "B at {deg}°");
        assert!(close_vec(st.point(m).coords, cf.m.coords, rel, L1), "M at {deg}°");
        assert!(close_vec(st.velocity(b), cf.vb, rel, vs), "vB at {deg}°: {:?} vs {:?}", st.velocity(b), cf.vb);
        assert!(close_vec(st.velocity(m), cf.vm, rel, vs), "vM at {deg}°");
        assert!(close_vec(st.acceleration(b), cf.ab, rel, as_), "aB at {deg}°");
        assert!(
            close_vec(st.acceleration(m), cf.am, rel, as_),
            "aM at {deg}°: {:?} vs {:?}",
            st.acceleration(m),
            cf.am
        );
        let (p2, w2, e2) = st.angular(coupler);
        let (p3, w3, e3) = st.angular(rocker);
        assert!(same_angle(p2, cf.phi2) && same_angle(p3, cf.phi3), "angles at {deg}°");
        assert!(common::rel_close(w2, cf.omega2, rel, OMEGA1), "omega2 at {deg}°: {w2} vs {}", cf.omega2);
        assert!(common::rel_close(w3, cf.omega3, rel, OMEGA1), "omega3 at {deg}°");
        assert!(common::rel_close(e2, cf.eps2, rel, OMEGA1 * OMEGA1), "eps2 at {deg}°: {e2} vs {}", cf.eps2);
        assert!(common::rel_close(e3, cf.eps3, rel, OMEGA1 * OMEGA1), "eps3 at {deg}°");
        assert!(st.residual <= 1e-12);
    }
}

/// The same scene against the project's closed-form four-bar solver (`solve::fourbar`,
/// written independently on its own branch): the second solver on the same mechanism.
#[test]
fn chebyshev_linkage_scene_equals_the_fourbar_solver() {
    use mechdraw::solve::fourbar::{Geometry, kinematics, position};
    let loaded = scene::load(&common::root().join("templates/fourbar-linkage.toml"), &[]).unwrap();
    let Scene::Linkage(s) = loaded.scene else { panic!("not a linkage scene") };
    let states = Solver::new(s.mechanism.clone()).unwrap().run(&s.times).unwrap();
    let geom = Geometry {
        o1: Point::new(0.0, 0.0),
        c: Point::new(0.08, 0.0),
        l1: L1,
        l_ab: 0.10,
        l_bm: 0.10,
        alpha: std::f64::consts::PI,
        l_bc: 0.10,
        branch: Side::Left,
    };
    let (b, m) = (s.anchor("coupler.B").unwrap(), s.anchor("coupler.M").unwrap());
    let rel = 1e-9;
    let (vs, as_) = (OMEGA1 * L1, OMEGA1 * OMEGA1 * L1);
    for st in &states {
        let phi1 = OMEGA1 * st.t;
        let pos = position(&geom, phi1, Side::Left).unwrap();
        let kin = kinematics(&geom, &pos, OMEGA1).unwrap();
        let deg = phi1.to_degrees();
        assert!(close_vec(st.point(b).coords, pos.b.coords, rel, L1), "B at {deg}°");
        assert!(close_vec(st.point(m).coords, pos.m.coords, rel, L1), "M at {deg}°");
        assert!(close_vec(st.velocity(b), kin.v_b, rel, vs), "vB at {deg}°");
        assert!(close_vec(st.velocity(m), kin.v_m, rel, vs), "vM at {deg}°");
        assert!(close_vec(st.acceleration(b), kin.a_b, rel, as_), "aB at {deg}°");
        assert!(close_vec(st.acceleration(m), kin.a_m, rel, as_), "aM at {deg}°");
        let (_, w2, e2) = st.angular(Attach::Body(1));
        let (_, w3, e3) = st.angular(Attach::Body(2));
        assert!(common::rel_close(w2, kin.omega2, rel, OMEGA1) && common::rel_close(w3, kin.omega3, rel, OMEGA1));
        assert!(common::rel_close(e2, kin.eps2, rel, OMEGA1 * OMEGA1), "eps2 at {deg}°");
        assert!(common::rel_close(e3, kin.eps3, rel, OMEGA1 * OMEGA1), "eps3 at {deg}°");
    }
}
