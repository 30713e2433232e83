//! Stability of the general Newton solver where it breaks: a Jacobian that turns singular
//! (a four-bar driven by its rocker through the rocker's extreme), redundant constraints
//! (a parallelogram with a redundant link), and a start far from the solution.

mod common;

use mechdraw::geom::{CircleIntersection, Point, Side, circle_circle, polar};
use mechdraw::scene::{self, Override, Scene};
use mechdraw::solve::linkage::{LinkageError, Solver};

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
/// never a state past t*. (`Singular` is accepted too, should a step land on t*: see the
/// next test.)
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

/// The same rocker-driven four-bar with its last time step exactly on the dead point t*,
/// where the configuration exists but the constraint Jacobian is singular in exact
/// arithmetic (crank and coupler in line). Observed: the solver is not refused there (the
/// equilibrated Jacobian's smallest pivot at the computed q stays above
/// `SINGULAR_PIVOT_REL`); it returns the dead-point position — tested: B within 1e-7 m of
/// the exact B = (0.1, √0.0096) (observed 1e-15) with every coordinate, velocity and
/// acceleration finite. The velocities there are those of a nearly singular system (crank
/// ω ≈ 1.6e6 rad/s observed, printed by the test): finite, but not flagged — a known gap,
/// left to the solver's owner. The next step past t* fails by name (previous test).
#[test]
fn landing_exactly_on_the_dead_point_gives_the_dead_point_position() {
    let theta_min = (0.0096f64).sqrt().atan2(0.02);
    let t_star = (1.7722121 - theta_min) / 0.6;
    let text = FOURBAR.replace("body = \"crank\"\nlaw = \"20*t\"", "body = \"rocker\"\nlaw = \"1.7722121 - 0.6*t\"");
    let s = linkage(&text, &[&format!("time.to={t_star:.17}"), "time.steps=40"]);
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
            assert!(message.contains("0 degree(s) of freedom") && message.contains("1 driver(s)"), "{message}");
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
