//! The shaper (seed 002, design.md §3) through the general linkage solver, against a
//! closed-form solution of the same mechanism written here, and its quick-return ratio
//! against the analytic one.

mod common;

use mechdraw::scene::{self, Scene};
use mechdraw::solve::linkage::{Attach, Solver, State};

const H_PIVOT: f64 = 300.0; // O1 above O3
const R: f64 = 125.0; // crank
const L: f64 = 600.0; // rocker O3B
const LBE: f64 = 150.0; // link BE
const Y_RAM: f64 = 600.0; // the ram's line
const OMEGA: f64 = std::f64::consts::TAU; // 360°/s

/// Closed form: (x_E, v_E, a_E) and (theta, theta', theta'') of the rocker at time t.
fn closed_form(t: f64) -> ([f64; 3], [f64; 3]) {
    let phi = OMEGA * t;
    let (s, c) = phi.sin_cos();
    let a = [R * c, H_PIVOT + R * s];
    let ad = [-R * OMEGA * s, R * OMEGA * c];
    let add = [-R * OMEGA * OMEGA * c, -R * OMEGA * OMEGA * s];
    let n2 = a[0] * a[0] + a[1] * a[1];
    let cross = |u: [f64; 2], v: [f64; 2]| u[0] * v[1] - u[1] * v[0];
    let dot = |u: [f64; 2], v: [f64; 2]| u[0] * v[0] + u[1] * v[1];
    let th = a[1].atan2(a[0]);
    let thd = cross(a, ad) / n2;
    let thdd = cross(a, add) / n2 - 2.0 * cross(a, ad) * dot(a, ad) / (n2 * n2);
    let (st, ct) = th.sin_cos();
    let b = [L * ct, L * st];
    let bd = [-L * thd * st, L * thd * ct];
    let bdd = [-L * thdd * st - L * thd * thd * ct, L * thdd * ct - L * thd * thd * st];
    let dy = Y_RAM - b[1];
    let root = (LBE * LBE - dy * dy).sqrt();
    let xe = b[0] + root;
    let ve = bd[0] + dy * bd[1] / root;
    let ae = bdd[0] + (dy * bdd[1] - bd[1] * bd[1]) / root - (dy * bd[1]).powi(2) / root.powi(3);
    ([xe, ve, ae], [th, thd, thdd])
}

fn shaper() -> (mechdraw::scene::linkage::LinkageScene, Vec<State>) {
    let path = common::root().join("templates/shaper.toml");
    let loaded = scene::load(&path, &[]).unwrap();
    let Scene::Linkage(s) = loaded.scene else { panic!("not a linkage scene") };
    let states = Solver::new(s.mechanism.clone()).unwrap().run(&s.times).unwrap();
    (s, states)
}

#[test]
fn shaper_matches_the_closed_form_at_every_step() {
    let (scene, states) = shaper();
    assert_eq!(states.len(), 361);
    let e = scene.anchor("ram.E").unwrap();
    let rocker = Attach::Body(scene.mechanism.bodies.iter().position(|b| b.name == "rocker").unwrap());
    let (mut worst_x, mut worst_v, mut worst_a) = (0.0f64, 0.0f64, 0.0f64);
    for st in &states {
        let ([xe, ve, ae], [th, thd, thdd]) = closed_form(st.t);
        let p = st.point(e);
        let v = st.velocity(e);
        let a = st.acceleration(e);
        worst_x = worst_x.max((p.x - xe).abs());
        // Relative to the quantity's amplitude over the cycle (it crosses zero).
        worst_v = worst_v.max((v.x - ve).abs() / 2000.0);
        worst_a = worst_a.max((a.x - ae).abs() / 30000.0);
        assert!((p.x - xe).abs() <= 1e-8, "t = {}: x_E {} vs closed form {xe}", st.t, p.x);
        assert!((p.y - Y_RAM).abs() <= 1e-8);
        assert!(common::rel_close(v.x, ve, 1e-6, 1.0), "t = {}: v_E {} vs {ve}", st.t, v.x);
        assert!(v.y.abs() <= 1e-8 && a.y.abs() <= 1e-6);
        assert!(common::rel_close(a.x, ae, 1e-6, 1.0), "t = {}: a_E {} vs {ae}", st.t, a.x);
        let (phi, w, eps) = st.angular(rocker);
        assert!((phi - th).abs() <= 1e-12, "t = {}: rocker angle", st.t);
        assert!(common::rel_close(w, thd, 1e-9, 1e-3), "t = {}: rocker omega {w} vs {thd}", st.t);
        assert!(common::rel_close(eps, thdd, 1e-9, 1e-2), "t = {}: rocker eps {eps} vs {thdd}", st.t);
        assert!(st.residual <= 1e-12, "t = {}: residual {}", st.t, st.residual);
    }
    eprintln!(
        "shaper vs closed form: |Δx_E| ≤ {worst_x:.2e} mm, |Δv_E|/2000 ≤ {worst_v:.2e}, |Δa_E|/30000 ≤ {worst_a:.2e}"
    );
}

#[test]
fn quick_return_ratio_matches_the_analytic_one() {
    let (scene, states) = shaper();
    let e = scene.anchor("ram.E").unwrap();
    // Times where v_E changes sign (the stroke ends), by linear interpolation of samples.
    let mut reversals = Vec::new();
    for w in states.windows(2) {
        let (v0, v1) = (w[0].velocity(e).x, w[1].velocity(e).x);
        if v0 * v1 < 0.0 {
            reversals.push(w[0].t + (w[1].t - w[0].t) * v0 / (v0 - v1));
        }
    }
    assert_eq!(reversals.len(), 2, "{reversals:?}");
    let first = reversals[1] - reversals[0];
    let second = 1.0 - first;
    let ratio = first.max(second) / first.min(second);
    // Analytic: the rocker's limits are where it touches the crank circle, alpha = asin(r/h);
    // the crank turns 180° + 2α on one stroke and 180° − 2α on the other.
    let alpha = (R / H_PIVOT).asin().to_degrees();
    let analytic = (180.0 + 2.0 * alpha) / (180.0 - 2.0 * alpha);
    eprintln!("quick-return ratio: from the motion {ratio:.5}, analytic {analytic:.5} (alpha = {alpha:.4}°)");
    assert!((ratio - analytic).abs() <= 1e-3 * analytic, "{ratio} vs {analytic}");
    // The strokes start where the crank is perpendicular to the rocker: t = −α and 180° + α.
    let t_right = (360.0 - alpha) / 360.0;
    let t_left = (180.0 + alpha) / 360.0;
    let near = |t: f64| reversals.iter().any(|r| (r - t).abs() < 1e-4);
    assert!(near(t_right) && near(t_left), "{reversals:?} vs {t_left}, {t_right}");
}
