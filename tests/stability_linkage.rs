//! Stability of the general Newton solver where it breaks: a Jacobian that turns singular
//! (a four-bar driven by its rocker through the rocker's extreme; a step landing on the
//! extreme itself is flagged near-singular, one near it is not), redundant constraints
//! (a parallelogram with a redundant link), and a start far from the solution.

#![allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the library calls"
)]

mod common;

use mechdraw::geom::{CircleIntersection, Point, Side, Vector, circle_circle, polar};
use mechdraw::scene::{self, Override, Scene};
use mechdraw::solve::linkage::{LinkageError, NEAR_SINGULAR_PIVOT_REL, SINGULAR_PIVOT_REL, Solver};

const FOURBAR: &str = include_str!("../templates/fourbar-linkage.toml");

fn linkage(text: &str, sets: &[&str]) -> mechdraw::scene::linkage::LinkageScene {
    let ov: Vec<Override> = sets.iter().map(|s| s.parse().unwrap()).collect();
    match scene::parse(text, "test.toml", &ov).unwrap() {
        Scene::Linkage(s) => s,
        _ => panic!("not a linkage scene"),
    }
}

/// The Chebyshev four-bar (O1 = 0, C = (0.08, 0), crank 0.04, coupler 0.10, rocker 0.10)
/// driven by its rocker's absolute angle, falling from 101.54° at 0.6 rad/s. The rocker's
/// smallest angle is reached with crank and coupler stretched out (|O1B| = 0.14): there
/// B = (0.1, √0.0096), rocker angle atan2(√0.0096, 0.02) = 78.463°, at
/// t* = (1.77221 − 1.369438)/0.6 ≈ 0.671 s. Expected (and observed): every step before t*
/// solves; at the first step past t* (t = 0.68) no configuration exists and Newton stops
/// with `NoConvergence` naming the time and the worst constraint — never a NaN state,
/// never a state past t*. (`Singular` is accepted too, should a step land close enough to
/// t*; a step exactly on t* is solved and flagged near-singular: see the tests below.)
#[test]
fn rocker_driven_through_its_extreme_fails_by_name_at_the_dead_point() {
    let text = FOURBAR.replace(
        "[[driver]]\nbody = \"crank\"\nlaw = \"20*t\"",
        "[[driver]]\nbody = \"rocker\"\nlaw = \"1.7722121\" \n",
    );
    assert_ne!(text, FOURBAR, "template changed: driver block not found");
    let text = text.replace("law = \"1.7722121\" \n", "law = \"1.7722121 - 0.6*t\"");
    let s = linkage(&text, &["time.to=1.0", "time.steps=100"]);
    let theta_min = (0.0096f64).sqrt().atan2(0.02);
    let t_star = (1.7722121 - theta_min) / 0.6;
    let mut solver = Solver::new(s.mechanism.clone()).unwrap();
    let mut solved_to = None;
    for &t in &s.times {
        match solver.step(t) {
            Ok(_) => {
                assert!(t < t_star, "solved at t = {t} past the dead point t* = {t_star}");
                assert!(solver.q().iter().all(|v| v.is_finite()));
                solved_to = Some(t);
            }
            Err(LinkageError::Singular { t: at, constraints, .. }) => {
                assert!(at >= t_star - 0.011 && at <= t_star + 0.011, "singular at {at}, t* = {t_star}");
                assert!(!constraints.is_empty());
                eprintln!("rocker through its extreme: Singular at t = {at} (t* = {t_star}): {constraints}");
                break;
            }
            Err(LinkageError::NoConvergence { t: at, residual, worst, .. }) => {
                assert!(at >= t_star && at <= t_star + 0.011, "no convergence at {at}, t* = {t_star}");
                assert!(!residual.is_nan());
                eprintln!("rocker through its extreme: NoConvergence at t = {at} (t* = {t_star})");
                assert!(!worst.is_empty());
                break;
            }
            Err(e) => panic!("t = {t}: unexpected {e}"),
        }
    }
    let last = solved_to.expect("the motion starts");
    assert!(last >= t_star - 0.011, "stopped early at {last}, t* = {t_star}");
}

/// The rocker-driven four-bar of the previous test with the rocker law in place of the
/// crank's (the template otherwise unchanged), run to `t_end` in 40 steps.
fn rocker_driven(t_end: f64) -> mechdraw::scene::linkage::LinkageScene {
    let text = FOURBAR.replace("body = \"crank\"\nlaw = \"20*t\"", "body = \"rocker\"\nlaw = \"1.7722121 - 0.6*t\"");
    assert_ne!(text, FOURBAR, "template changed: driver block not found");
    linkage(&text, &[&format!("time.to={t_end:.17}"), "time.steps=40"])
}

/// The dead point t* of the rocker-driven four-bar (rocker at its smallest angle).
fn t_star() -> f64 {
    let theta_min = (0.0096f64).sqrt().atan2(0.02);
    (1.7722121 - theta_min) / 0.6
}

/// Crank angular velocity of the rocker-driven four-bar at time t, closed form (rad/s):
/// B from the rocker law, A from the circle intersection on the branch nearest `a_near`,
/// and |B − A| = const differentiated: (B − A)·Ḃ = (B − A)·Ȧ with Ȧ = 0.04·ω·(−sin φ, cos φ).
fn crank_omega_closed_form(t: f64, a_near: Point) -> f64 {
    let theta = 1.7722121 - 0.6 * t;
    let b = Point::new(0.08 + 0.1 * theta.cos(), 0.1 * theta.sin());
    let b_dot = Vector::new(-0.1 * theta.sin(), 0.1 * theta.cos()) * -0.6;
    let a = match circle_circle(Point::new(0.0, 0.0), 0.04, b, 0.10) {
        ix @ CircleIntersection::Two { .. } => {
            let (l, r) = (ix.on(Side::Left).unwrap(), ix.on(Side::Right).unwrap());
            if (l - a_near).norm() < (r - a_near).norm() { l } else { r }
        }
        other => panic!("t = {t}: {other:?}"),
    };
    let phi = a.y.atan2(a.x);
    (b - a).dot(&b_dot) / (b - a).dot(&(Vector::new(-phi.sin(), phi.cos()) * 0.04))
}

/// The same rocker-driven four-bar with its last time step exactly on the dead point t*,
/// where the configuration exists but the constraint Jacobian is singular in exact
/// arithmetic (crank and coupler in line). The step is not refused: the equilibrated
/// Jacobian's smallest relative pivot at the computed q is ~1.2e-7, above
/// `SINGULAR_PIVOT_REL` (1e-10), and the dead-point position is right — tested: B within
/// 1e-7 m of the exact B = (0.1, √0.0096) (observed 1e-15), every coordinate, velocity and
/// acceleration finite. Its velocities are those of a nearly singular system (crank
/// ω ≈ 1.6e6 rad/s, set by where the roundoff of t put the step), so the step is flagged
/// near-singular (pivot below `NEAR_SINGULAR_PIVOT_REL`, 1e-5): at t = t*, with the rocker
/// driver at 78.4630° and the loop's joints named — and no step before it is flagged. The
/// next step past t* fails by name (previous test).
#[test]
fn landing_exactly_on_the_dead_point_is_reported_near_singular() {
    let t_star = t_star();
    let s = rocker_driven(t_star);
    assert!((s.times[s.times.len() - 1] - t_star).abs() < 1e-15);
    let b_anchor = s.anchor("coupler.B").unwrap();
    let mut solver = Solver::new(s.mechanism.clone()).unwrap();
    let states = solver.run(&s.times).unwrap();
    let last = states.last().unwrap();
    let b = last.point(b_anchor);
    let exact = Point::new(0.1, 0.0096f64.sqrt());
    eprintln!("dead point: |B − B*| = {:.3e} m, crank omega = {:.3e}", (b - exact).norm(), last.qd[2]);
    assert!((b - exact).norm() <= 1e-7, "B = {b:?} vs {exact:?}");
    assert!(last.q.iter().chain(&last.qd).chain(&last.qdd).all(|v| v.is_finite()));
    for st in &states[..states.len() - 1] {
        assert!(st.near_singular.is_none(), "t = {} flagged: {:?}", st.t, st.near_singular);
    }
    let ns = last.near_singular.as_ref().expect("the dead-point step is flagged near-singular");
    eprintln!("near-singular: {ns:?}");
    assert_eq!(ns.t, last.t);
    assert!(ns.pivot > SINGULAR_PIVOT_REL && ns.pivot < NEAR_SINGULAR_PIVOT_REL, "{ns:?}");
    assert!(ns.drivers.contains("driver `rocker` = 78.4630°"), "{ns:?}");
    // Crank and coupler in line: the joints at both ends of the crank and both of the
    // coupler take part.
    for joint in ["`O1`", "`A`", "`B`"] {
        assert!(ns.constraints.contains(&format!("revolute joint {joint}")), "{joint} missing: {ns:?}");
    }
}

/// A step near, but not at, the dead point: the rocker 1e-6 rad before its extreme
/// (t = t* − 1e-6/0.6 s). The smallest relative pivot there is ~3.6e-4 (ρ ≈ 0.36·√δθ),
/// above `NEAR_SINGULAR_PIVOT_REL`, so nothing is flagged — and rightly: the crank
/// velocity (≈ 547 rad/s) matches the closed form to 1e-8 relative (observed 3e-10) and
/// the crank acceleration (≈ 2.7e8 rad/s²) a central difference of the closed-form
/// velocity (step δt/100, whose own error is ~2e-4) to 1e-3.
#[test]
fn a_step_near_the_dead_point_is_not_flagged_and_its_speeds_are_right() {
    let t_end = t_star() - 1e-6 / 0.6;
    let s = rocker_driven(t_end);
    let a_anchor = s.anchor("crank.A").unwrap();
    let mut solver = Solver::new(s.mechanism.clone()).unwrap();
    let states = solver.run(&s.times).unwrap();
    assert!(solver.min_pivot_rel() > NEAR_SINGULAR_PIVOT_REL, "pivot {:.3e}", solver.min_pivot_rel());
    assert!(states.iter().all(|st| st.near_singular.is_none()));
    let last = states.last().unwrap();
    let a = last.point(a_anchor);
    let omega = crank_omega_closed_form(last.t, a);
    assert!(((last.qd[2] - omega) / omega).abs() < 1e-8, "omega {} vs {omega}", last.qd[2]);
    let h = (t_star() - t_end) / 100.0;
    let eps = (crank_omega_closed_form(last.t + h, a) - crank_omega_closed_form(last.t - h, a)) / (2.0 * h);
    assert!(((last.qdd[2] - eps) / eps).abs() < 1e-3, "eps {} vs {eps}", last.qdd[2]);
}

/// The bundled linkage templates run through no near-singular step (their smallest
/// relative pivots are 2e-2 and above).
#[test]
fn templates_have_no_near_singular_step() {
    for name in ["shaper", "fourbar-linkage", "triad-driven"] {
        let text = std::fs::read_to_string(common::root().join(format!("templates/{name}.toml"))).unwrap();
        let s = linkage(&text, &[]);
        let states = Solver::new(s.mechanism.clone()).unwrap().run(&s.times).unwrap();
        let flagged: Vec<f64> = states.iter().filter(|st| st.near_singular.is_some()).map(|st| st.t).collect();
        assert!(flagged.is_empty(), "{name}: near-singular at t = {flagged:?}");
    }
}

/// Redundant constraints: a parallelogram four-bar (crank 0.04, coupler 0.08 parallel to
/// the ground O1C) with a second crank between the coupler and the ground (the classical
/// redundant link). Counting gives 3·4 − 2·6 = 0 degrees of freedom against 1 driver:
/// refused before any solving, naming both numbers (the DOF mismatch; Grübler's count
/// cannot see that the link is redundant, so it is refused rather than solved).
#[test]
fn redundant_link_is_a_named_dof_mismatch() {
    let text = r#"
kind = "linkage"
name = "parallelogram"
units = "SI"
time = { from = 0.0, to = 0.1, steps = 10 }
[ground]
points = { O1 = [0.0, 0.0], C = [0.08, 0.0], D = [0.04, 0.0] }
[[body]]
name = "crank"
points = { O1 = [0.0, 0.0], A = [0.0, 0.04] }
[[body]]
name = "coupler"
points = { A = [0.0, 0.0], B = [0.08, 0.0], E = [0.04, 0.0] }
at = [0.0, 0.04]
[[body]]
name = "rocker"
points = { C = [0.0, 0.0], B = [0.0, 0.04] }
at = [0.08, 0.0]
[[body]]
name = "extra"
points = { D = [0.0, 0.0], E = [0.0, 0.04] }
at = [0.04, 0.0]
[[joint]]
revolute = ["ground.O1", "crank.O1"]
[[joint]]
revolute = ["crank.A", "coupler.A"]
[[joint]]
revolute = ["coupler.B", "rocker.B"]
[[joint]]
revolute = ["ground.C", "rocker.C"]
[[joint]]
revolute = ["ground.D", "extra.D"]
[[joint]]
revolute = ["coupler.E", "extra.E"]
[[driver]]
body = "crank"
law = "10*t"
"#;
    // The scene check counts before the solver is built: a field error on `driver`
    // carrying the solver's DofMismatch message.
    match scene::parse(text, "test.toml", &[]) {
        Err(mechdraw::scene::SceneError::Field { field, message, .. }) => {
            assert_eq!(field, "driver");
            assert!(message.contains("0 degrees of freedom") && message.contains("1 driver"), "{message}");
            assert!(message.contains("3 × 4 bodies") && message.contains("6 joints"), "{message}");
        }
        other => panic!("expected a field error on `driver`, got {other:?}"),
    }
}

/// B of the Chebyshev four-bar at crank angle `phi1` on both branches (circle
/// intersection, independent of the solver).
fn both_b(phi1: f64) -> (Point, Point) {
    let a = polar(Point::new(0.0, 0.0), 0.04, phi1);
    match circle_circle(a, 0.10, Point::new(0.08, 0.0), 0.10) {
        ix @ CircleIntersection::Two { .. } => (ix.on(Side::Left).unwrap(), ix.on(Side::Right).unwrap()),
        other => panic!("{other:?}"),
    }
}

/// A start far from the solution: the four-bar's coupler and rocker placed at wrong angles
/// and positions. Expected: assembly converges to one of the two true configurations (B
/// within 1e-9 of the closed form on one branch) or fails with `CannotAssemble` naming the
/// worst constraint — never a state that meets no configuration, never NaN.
#[test]
fn start_far_from_the_solution_converges_or_fails_by_name() {
    let mut converged = 0;
    for (coupler, rocker) in [(0.0, 0.0), (200.0, 30.0), (-120.0, 250.0), (45.0, -60.0), (300.0, 170.0)] {
        let sets = [
            format!("body[1].angle_deg={coupler}"),
            format!("body[2].angle_deg={rocker}"),
            "body[1].at=[0.3, -0.2]".to_string(),
        ];
        let refs: Vec<&str> = sets.iter().map(String::as_str).collect();
        let s = linkage(FOURBAR, &refs);
        let b_anchor = s.anchor("coupler.B").unwrap();
        let mut solver = Solver::new(s.mechanism.clone()).unwrap();
        match solver.assemble(0.0) {
            Ok(state) => {
                let b = state.point(b_anchor);
                let (left, right) = both_b(0.0);
                let d = (b - left).norm().min((b - right).norm());
                assert!(d < 1e-9, "coupler {coupler}°, rocker {rocker}°: B = {b:?} is no configuration ({d})");
                converged += 1;
            }
            Err(LinkageError::CannotAssemble { residual, worst, .. }) => {
                assert!(residual.is_finite() && !worst.is_empty());
            }
            Err(e) => panic!("coupler {coupler}°, rocker {rocker}°: unexpected {e}"),
        }
    }
    assert!(converged > 0);
}
