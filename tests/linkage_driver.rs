//! A driver law with non-constant speed: the shaper's crank driven by
//! φ1 = 0.3·sin(4t) + t². The solver's velocities and accelerations (from the exact
//! derivatives of the law) are checked against central finite differences of its own
//! positions and velocities at nearby times, solved separately.

#![allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the library calls"
)]

mod common;

use mechdraw::scene::{self, Scene};
use mechdraw::solve::linkage::{Attach, Solver};

const LAW: &str = "0.3*sin(4*t) + t^2";

#[test]
fn non_constant_speed_law_agrees_with_finite_differences() {
    let text = std::fs::read_to_string(common::root().join("templates/shaper.toml")).unwrap();
    assert!(text.contains("law = \"2*pi*t\""));
    let text = text.replace("law = \"2*pi*t\"", &format!("law = \"{LAW}\""));
    let Scene::Linkage(s) = scene::parse(&text, "shaper-sin.toml", &[]).unwrap() else { panic!() };
    let h = 1e-4;
    let centres: Vec<f64> = (1..40).map(|k| k as f64 * 0.05).collect();
    let times: Vec<f64> = centres.iter().flat_map(|&t| [t - h, t, t + h]).collect();
    let states = Solver::new(s.mechanism.clone()).unwrap().run(&times).unwrap();
    let e = s.anchor("ram.E").unwrap();
    let crank = Attach::Body(0);
    for w in states.chunks(3) {
        let (m, c, p) = (&w[0], &w[1], &w[2]);
        let t = c.t;
        // The crank follows the law, its speed and acceleration exactly.
        let (phi, omega, eps) = c.angular(crank);
        assert!((phi - (0.3 * (4.0 * t).sin() + t * t)).abs() < 1e-12);
        assert!((omega - (1.2 * (4.0 * t).cos() + 2.0 * t)).abs() < 1e-12, "t = {t}: omega {omega}");
        assert!((eps - (-4.8 * (4.0 * t).sin() + 2.0)).abs() < 1e-11, "t = {t}: eps {eps}");
        let fd_v = (p.point(e) - m.point(e)) / (2.0 * h);
        let fd_a = (p.velocity(e) - m.velocity(e)) / (2.0 * h);
        let (v, a) = (c.velocity(e), c.acceleration(e));
        // Scale floors: the ram's speed and acceleration over this motion are O(100)–O(1000).
        assert!((fd_v - v).norm() <= 1e-6 * v.norm().max(100.0), "t = {t}: v {v:?} vs fd {fd_v:?}");
        assert!((fd_a - a).norm() <= 1e-6 * a.norm().max(1000.0), "t = {t}: a {a:?} vs fd {fd_a:?}");
        let fd_w = (p.angular(Attach::Body(2)).0 - m.angular(Attach::Body(2)).0) / (2.0 * h);
        assert!((fd_w - c.angular(Attach::Body(2)).1).abs() <= 1e-6 * fd_w.abs().max(1.0), "t = {t}: rocker omega");
    }
}

/// A distance driver along a prismatic joint whose guide moves: the shaper driven by the
/// block's distance from O3 along the rocker, s(t) = 325 + 30·sin(3t) (the crank follows).
/// The block's distance and its rates equal the law's; the ram's velocity and acceleration
/// equal finite differences of separately solved positions and velocities.
#[test]
fn distance_driver_on_a_moving_guide_agrees_with_finite_differences() {
    let text = std::fs::read_to_string(common::root().join("templates/shaper.toml")).unwrap();
    let text = text
        .replace("joint = \"O1\"               # crank angle relative to the ground, rad", "joint = \"slide\"")
        .replace("law = \"2*pi*t\"", "law = \"325 + 30*sin(3*t)\"");
    assert!(text.contains("joint = \"slide\""));
    let Scene::Linkage(s) = scene::parse(&text, "shaper-slide.toml", &[]).unwrap() else { panic!() };
    let h = 1e-4;
    let centres: Vec<f64> = (1..20).map(|k| k as f64 * 0.1).collect();
    let times: Vec<f64> = centres.iter().flat_map(|&t| [t - h, t, t + h]).collect();
    let states = Solver::new(s.mechanism.clone()).unwrap().run(&times).unwrap();
    let (a, o3, b) = (s.anchor("block.A").unwrap(), s.anchor("rocker.O3").unwrap(), s.anchor("rocker.B").unwrap());
    let e = s.anchor("ram.E").unwrap();
    for w in states.chunks(3) {
        let (m, c, p) = (&w[0], &w[1], &w[2]);
        let t = c.t;
        // The block's distance from O3 along O3→B, and its rate, from the solver's own points.
        let u = (c.point(b) - c.point(o3)).normalize();
        let dist = u.dot(&(c.point(a) - c.point(o3)));
        assert!((dist - (325.0 + 30.0 * (3.0 * t).sin())).abs() < 1e-9, "t = {t}: {dist}");
        let fd_v = (p.point(e) - m.point(e)) / (2.0 * h);
        let fd_a = (p.velocity(e) - m.velocity(e)) / (2.0 * h);
        let (v, acc) = (c.velocity(e), c.acceleration(e));
        assert!((fd_v - v).norm() <= 1e-6 * v.norm().max(100.0), "t = {t}: v {v:?} vs fd {fd_v:?}");
        assert!((fd_a - acc).norm() <= 1e-6 * acc.norm().max(1000.0), "t = {t}: a {acc:?} vs fd {fd_a:?}");
        // The crank angle's rate against finite differences too.
        let fd_w = (p.angular(Attach::Body(0)).0 - m.angular(Attach::Body(0)).0) / (2.0 * h);
        assert!((fd_w - c.angular(Attach::Body(0)).1).abs() <= 1e-6 * fd_w.abs().max(1.0), "t = {t}: crank omega");
        assert!(c.residual <= 1e-12);
    }
}
