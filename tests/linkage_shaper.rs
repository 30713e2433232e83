//! The shaper (seed 002, design.md §3) through the general linkage solver, against a
//! closed-form solution of the same mechanism (mechdraw::bench::reference::shaper, shared
//! with `mechdraw bench`), and its stroke H and quick-return ratio K against the closed
//! form; the relative motion at its prismatic joints (sliding velocity, relative and
//! Coriolis accelerations).

#![allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the library calls"
)]

mod common;

use mechdraw::geom::Vector;
use mechdraw::scene::{self, Scene};
use mechdraw::solve::linkage::{Attach, Solver, State};

use mechdraw::bench::reference::shaper::{H_PIVOT, R, Y_RAM, closed_form};

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

/// The shaper's stroke H and time ratio K as the run reports them (JSON `strokes.E`),
/// against the closed form. The rocker O3B is at a limit where it is tangent to the crank
/// circle (crank ⟂ rocker): its angle from the vertical O3O1 is ±α, α = asin(l1/O1O3), with
/// the crank at φ1 = 180° + α and 360° − α; the crank angle between the limit positions is
/// θ = 2α, so K = (180° + θ)/(180° − θ). B = l3·(cos ψ, sin ψ) has the same height at both
/// limits (ψ = 90° ∓ α), so x_E − x_B is the same there; when x_E is monotonic in ψ over the
/// swing (checked below for the template), E's extremes are the rocker's and
/// H = x_B(90° − α) − x_B(90° + α) = 2·l3·sin α = 2·l3·l1/O1O3 = 500 mm.
#[test]
fn stroke_and_time_ratio_match_the_closed_form() {
    use mechdraw::bench::reference::shaper::{L, LBE};
    let loaded = scene::load(&common::root().join("templates/shaper.toml"), &[]).unwrap();
    let p = mechdraw::run::products(&loaded, &mechdraw::run::RunOptions::default()).unwrap();
    let e = &p.summary["strokes"]["E"];
    let num = |v: &serde_json::Value| v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"));

    let alpha = (R / H_PIVOT).asin();
    // x_E is monotonic in the rocker angle ψ over [90° − α, 90° + α] (the guide is far
    // enough from B's arc): dx_E/dψ = −l3·sin ψ + (y_ram − y_B)·l3·cos ψ / √(l4² − (y_ram − y_B)²) < 0.
    for i in 0..=1000 {
        let psi = std::f64::consts::FRAC_PI_2 - alpha + 2.0 * alpha * f64::from(i) / 1000.0;
        let dy = Y_RAM - L * psi.sin();
        let slope = -L * psi.sin() + dy * L * psi.cos() / (LBE * LBE - dy * dy).sqrt();
        assert!(slope < 0.0, "x_E not monotonic in the rocker angle at ψ = {}°", psi.to_degrees());
    }
    let h = 2.0 * L * R / H_PIVOT;
    let theta = 2.0 * alpha.to_degrees();
    let k = (180.0 + theta) / (180.0 - theta);
    eprintln!(
        "shaper stroke: H = {} mm (closed form {h}), K = {} (closed form {k}, θ = {theta:.6}°)",
        num(&e["H"]),
        num(&e["K"])
    );
    assert!((num(&e["H"]) - h).abs() <= 1e-9, "H {} vs {h}", e["H"]);
    assert!((num(&e["K"]) - k).abs() <= 1e-9, "K {} vs {k}", e["K"]);
    // The working stroke (the slower, crank turning 180° + θ) starts at the right extreme,
    // crank at 360° − α, and runs towards −x to the left extreme, crank at 180° + α.
    let (start, end) = (360.0 - alpha.to_degrees(), 180.0 + alpha.to_degrees());
    assert!((num(&e["start"]["driver_deg"]) - start).abs() <= 1e-9, "{}", e["start"]);
    assert!((num(&e["end"]["driver_deg"]) - end).abs() <= 1e-9, "{}", e["end"]);
    assert!((num(&e["start"]["t"]) - start / 360.0).abs() <= 1e-9 && (num(&e["end"]["t"]) - end / 360.0).abs() <= 1e-9);
    assert_eq!(e["direction"], serde_json::json!([-1.0, 0.0]));
    // The extremes are where the closed form puts E at those times.
    let (x_start, x_end) = (closed_form(start / 360.0).0[0], closed_form(end / 360.0).0[0]);
    assert!((num(&e["start"]["at"][0]) - x_start).abs() <= 1e-9 && (num(&e["end"]["at"][0]) - x_end).abs() <= 1e-9);
    assert!((x_start - x_end - h).abs() <= 1e-9);
    // The strokes' times: (180° ± θ)/360° of the 1 s turn.
    assert!((num(&e["working_time"]) - (180.0 + theta) / 360.0).abs() <= 1e-9);
    assert!((num(&e["return_time"]) - (180.0 - theta) / 360.0).abs() <= 1e-9);
    assert_eq!(num(&e["period"]), 1.0);
    // The report says it too.
    assert!(p.report.contains("stroke of E: H = 500.0000 mm, K = 1.7533"), "{}", p.report);
}

#[test]
fn sliding_velocity_relative_acceleration_and_coriolis_at_the_block() {
    // The block's point A slides on the rocker O3B (O3 fixed at the origin). With d = A − O3,
    // the distance along the rocker is s = |d|, so independently of the solver's split:
    // ṡ = d·v/|d| and s̈ = (v·v + d·a)/|d| − (d·v)²/|d|³; the rocker turns at ω3.
    let (scene, states) = shaper();
    let slide = scene.mechanism.joints.iter().find(|j| j.name == "slide").unwrap();
    let a = scene.anchor("block.A").unwrap();
    let rocker = Attach::Body(scene.mechanism.bodies.iter().position(|b| b.name == "rocker").unwrap());
    let amp_v = states.iter().map(|s| s.velocity(a).norm()).fold(0.0, f64::max);
    let amp_a = states.iter().map(|s| s.acceleration(a).norm()).fold(0.0, f64::max);
    for st in &states {
        let sl = st.sliding(&slide.kind).unwrap();
        let d = st.point(a).coords;
        let (v, acc) = (st.velocity(a), st.acceleration(a));
        let u = d / d.norm();
        let s_dot = d.dot(&v) / d.norm();
        let s_ddot = (v.dot(&v) + d.dot(&acc)) / d.norm() - d.dot(&v).powi(2) / d.norm().powi(3);
        let (_, w3, _) = st.angular(rocker);
        let t = st.t;
        assert!((sl.v_rel - u * s_dot).norm() <= 1e-12 * amp_v, "t = {t}: v_rel {:?}", sl.v_rel);
        assert!((sl.a_rel - u * s_ddot).norm() <= 1e-11 * amp_a, "t = {t}: a_rel {:?} vs {:?}", sl.a_rel, u * s_ddot);
        // Coriolis: 2·ω3·|v_rel| in magnitude, v_rel turned 90° the way the rocker turns.
        assert!((sl.a_cor.norm() - 2.0 * w3.abs() * sl.v_rel.norm()).abs() <= 1e-12 * amp_a, "t = {t}");
        let turned = Vector::new(-sl.v_rel.y, sl.v_rel.x) * w3.signum();
        assert!(sl.a_cor.dot(&turned) >= -1e-12 * amp_a * amp_v, "t = {t}: direction");
        assert!(sl.a_cor.dot(&sl.v_rel).abs() <= 1e-9 * amp_a * amp_v, "t = {t}: across the guide");
    }
    // The ram slides on a fixed guide: no Coriolis component there.
    let guide = scene.mechanism.joints.iter().find(|j| j.name == "ram-guide").unwrap();
    assert!(states.iter().all(|s| s.sliding(&guide.kind).unwrap().a_cor == Vector::zeros()));
    assert!(
        scene
            .mechanism
            .joints
            .iter()
            .filter(|j| j.name != "slide" && j.name != "ram-guide")
            .all(|j| states[0].sliding(&j.kind).is_none())
    );
}
