//! Tolerances of the rates (issue 34, "optionally velocity, acceleration"): the exact
//! sensitivities of a point's velocity and acceleration and of a link's ω and ε — the
//! four-bar's from its closed form differentiated, a linkage's from the velocity and
//! acceleration equations differentiated through the solver's Jacobian — against central
//! finite differences of the solver at 8 positions (1e-6 relative), the Monte Carlo's σ
//! (each sample's rates re-solved) against the linear σ at small tolerances, and the tables'
//! columns of a run.

mod common;

use common::tolerance::{assert_monte_carlo_sigma_is_linear, central_differences, scaled};

use mechdraw::geom::Side;
use mechdraw::scene::{Override, Scene};
use mechdraw::solve::fourbar::{Geometry, Position, kinematics_eps, solve_motion};
use mechdraw::solve::tolerance::Distribution;
use mechdraw::solve::tolerance::fourbar::{FourbarModel, FourbarOutput, FourbarParam, FourbarPoint};
use mechdraw::solve::tolerance::linkage::LinkageModel;
use mechdraw::solve::tolerance::monte_carlo::Model;

const TEMPLATE: &str = "fourbar-tolerances.toml";
/// The crank's state the four-bar's rates are taken at (an angular acceleration too, so
/// that its term is checked).
const OMEGA1: f64 = 20.0;
const EPS1: f64 = 150.0;

fn fourbar(sets: &[&str]) -> (mechdraw::scene::fourbar::FourbarScene, Vec<Position>) {
    let text = std::fs::read_to_string(common::root().join("templates").join(TEMPLATE)).unwrap();
    let overrides: Vec<Override> = sets.iter().map(|s| s.parse().unwrap()).collect();
    let Scene::Fourbar(s) = mechdraw::scene::parse(&text, TEMPLATE, &overrides).unwrap() else { panic!() };
    let motion = solve_motion(&s.spec).unwrap();
    (s, motion.positions)
}

/// Every rate of the four-bar, and one position output among them (the channels' layout
/// must not depend on the mix).
fn every_rate() -> Vec<FourbarOutput> {
    use FourbarPoint::{A, B, M};
    vec![
        FourbarOutput::Velocity(A),
        FourbarOutput::Velocity(B),
        FourbarOutput::Point(M),
        FourbarOutput::Velocity(M),
        FourbarOutput::Acceleration(A),
        FourbarOutput::Acceleration(B),
        FourbarOutput::Acceleration(M),
        FourbarOutput::Omega2,
        FourbarOutput::Omega3,
        FourbarOutput::Eps2,
        FourbarOutput::Eps3,
    ]
}

/// The channels of [`every_rate`] at `phi1` of geometry `g` on `side`, from the solver.
fn rate_channels(g: &Geometry, phi1: f64, side: Side) -> Vec<f64> {
    let p = mechdraw::solve::fourbar::position(g, phi1, side).unwrap();
    let k = kinematics_eps(g, &p, OMEGA1, EPS1).unwrap();
    let mut v = Vec::new();
    for x in [k.v_a, k.v_b, p.m.coords, k.v_m, k.a_a, k.a_b, k.a_m] {
        v.extend([x.x, x.y]);
    }
    v.extend([k.omega2, k.omega3, k.eps2, k.eps3]);
    v
}

#[test]
fn fourbar_rate_sensitivities_equal_central_differences_of_the_solver_at_eight_positions() {
    let (s, positions) = fourbar(&[]);
    let g = s.spec.geometry;
    let params = FourbarParam::ALL.to_vec();
    let model = FourbarModel::new(g, &positions, params.clone(), every_rate()).with_crank(OMEGA1, EPS1);
    let np = params.len();
    for k in (0..360).step_by(45) {
        let pos = &positions[k];
        let side = pos.side(&g).unwrap();
        let exact = model.sensitivities(k).unwrap();
        assert_eq!(exact.len(), rate_channels(&g, pos.phi1, side).len() * np);
        for (j, p) in params.iter().enumerate() {
            let h = if *p == FourbarParam::AlphaDeg { 1e-4 } else { 1e-7 };
            let (mut gp, mut gm) = (g, g);
            p.apply(&mut gp, h);
            p.apply(&mut gm, -h);
            let (cp, cm) = (rate_channels(&gp, pos.phi1, side), rate_channels(&gm, pos.phi1, side));
            for c in 0..cp.len() {
                let fd = (cp[c] - cm[c]) / (2.0 * h);
                let e = exact[c * np + j];
                let scale = (0..np).map(|i| exact[c * np + i].abs()).fold(0.0, f64::max);
                assert!(
                    common::rel_close(e, fd, 1e-6, scale),
                    "phi1 = {k}°, ∂channel {c}/∂{}: exact {e}, central difference {fd}",
                    p.field()
                );
            }
        }
    }
}

#[test]
fn fourbar_rates_monte_carlo_sigma_tends_to_the_linear_sigma() {
    // Eight positions, 1e5 samples, each sample's rates re-solved: σ's sampling error 0.22 %.
    let (s, positions) = fourbar(&["phi1_deg.step=45"]);
    let tol = s.tolerances.as_ref().unwrap();
    let dims = scaled(&tol.study.dims, 0.01, Distribution::Normal { k: 3.0 });
    let model =
        FourbarModel::new(s.spec.geometry, &positions, tol.study.params.clone(), every_rate()).with_crank(OMEGA1, EPS1);
    // A channel no toleranced field moves (at rounding level) is not compared.
    assert_monte_carlo_sigma_is_linear(&model, &dims, 100_000, 1e-12);
}

/// The slider-crank's tolerances watching the piston pin's velocity and acceleration and
/// the rod's ω and ε (and the pin's position, as a study would).
const SLIDER_CRANK: &str = r#"
[tolerances]
body = [{ points.A = [0.05, 0.05] }, { points.B = [0.1] }]
ground.points.O = [0.05, 0.05]
ground.points.G1 = [0.05, 0.05]
ground.points.G2 = [0.05, 0.05]

[tolerances.outputs]
points = ["piston.B"]
velocities = ["piston.B", "rod.B", "rod"]
accelerations = ["piston.B", "rod.B", "rod"]
"#;

/// The shaper's tolerances (tests/tolerance_linkage.rs's, the block's locked angle among
/// them) watching the ram's and the link's rates and the rocker's.
const SHAPER: &str = r#"
[tolerances]
"body[0].points.A" = [0.05, 0.05]
"ground.points.O3" = [0.05, 0.05]
"body[2].points.B" = [0.1, 0.1]
"body[3].points.E[0]" = 0.1
"ground.points.G1[1]" = 0.05
"ground.points.G2[1]" = 0.05
"joint[2].prismatic.angle_deg" = 0.02

[tolerances.outputs]
velocities = ["ram.E", "link.B", "rocker", "link"]
accelerations = ["ram.E", "link.B", "rocker", "link"]
"#;

/// A template with `tolerances` appended and `steps` positions.
fn linkage_scene(template: &str, tolerances: &str, steps: u32) -> mechdraw::scene::linkage::LinkageScene {
    let text = std::fs::read_to_string(common::root().join("templates").join(template)).unwrap();
    let mut out = String::new();
    for line in text.lines() {
        if line.starts_with("time = ") {
            let (head, tail) = line.split_once("steps = ").unwrap();
            let rest = tail.trim_start_matches(|c: char| c.is_ascii_digit());
            out.push_str(&format!("{head}steps = {steps}{rest}\n"));
        } else if !line.starts_with("[tolerances") {
            out.push_str(line);
            out.push('\n');
        } else {
            break;
        }
    }
    let text = format!("{out}\n{tolerances}");
    let Scene::Linkage(s) = mechdraw::scene::parse(&text, template, &[]).unwrap() else { panic!() };
    s
}

fn linkage_model(s: &mechdraw::scene::linkage::LinkageScene) -> LinkageModel {
    let tol = s.tolerances.as_ref().unwrap();
    LinkageModel::new(s.mechanism.clone(), &s.times, tol.study.params.clone(), tol.outputs.clone()).unwrap()
}

/// The rates' sensitivities against central differences of the samples' own route (the
/// Assur solver refitted and swept, its rates re-solved at each position), h = 1e-4 of the
/// field's unit (mm, °), at 8 positions spread over the motion; each entry to 1e-6 of its
/// channel's largest.
fn check_linkage_rates(template: &str, tolerances: &str) {
    let s = linkage_scene(template, tolerances, 72);
    let m = linkage_model(&s);
    let dims = &s.tolerances.as_ref().unwrap().study.dims;
    let (np, nc) = (dims.len(), m.channels());
    let fd = central_differences(&m, np, 1e-4);
    for k in (0..8).map(|i| 4 + 9 * i) {
        let exact = m.sensitivities(k).expect("a regular position");
        for c in 0..nc {
            let row = &exact[c * np..(c + 1) * np];
            let scale = row.iter().fold(0.0f64, |a, b| a.max(b.abs()));
            assert!(scale > 0.0, "{template} position {k}, channel {c}: no sensitivity");
            for (j, e) in row.iter().enumerate() {
                let f = fd[k][c * np + j];
                assert!(
                    (e - f).abs() <= 1e-6 * scale,
                    "{template} position {k}, channel {c}, field {}: exact {e} vs central difference {f}",
                    dims[j].name
                );
            }
        }
    }
}

#[test]
fn slider_crank_rate_sensitivities_equal_central_differences_at_eight_positions() {
    check_linkage_rates("slider-crank.toml", SLIDER_CRANK);
}

#[test]
fn shaper_rate_sensitivities_equal_central_differences_at_eight_positions() {
    check_linkage_rates("shaper.toml", SHAPER);
}

#[test]
fn linkage_rates_monte_carlo_sigma_tends_to_the_linear_sigma() {
    // 12 positions of the shaper, 1e5 samples (each sample's rates re-solved).
    let s = linkage_scene("shaper.toml", SHAPER, 11);
    let m = linkage_model(&s);
    let dims = scaled(&s.tolerances.as_ref().unwrap().study.dims, 0.1, Distribution::Normal { k: 3.0 });
    assert_monte_carlo_sigma_is_linear(&m, &dims, 100_000, 0.0);
}

fn run(args: &[&str]) -> std::process::Output {
    common::mechdraw().args(args).output().unwrap()
}

#[test]
fn a_fourbar_run_writes_the_rates_columns_json_and_diagrams() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let template = common::root().join("templates").join(TEMPLATE);
    let o = run(&[
        "run",
        template.to_str().unwrap(),
        "--no-frames",
        "-q",
        "--out",
        out.to_str().unwrap(),
        "--set",
        "phi1_deg.step=10",
        "--set",
        "tolerances.settings.samples=2000",
        "--set",
        "tolerances.outputs.velocities=[\"M\", \"rocker\"]",
        "--set",
        "tolerances.outputs.accelerations=[\"M\", \"coupler\"]",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read_to_string(out.join("fourbar-tolerances-tolerances.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    for col in
        ["vM.x.wc", "vM.along.rss", "vM.normal.mc_sigma", "aM.y.mc_p99.865", "omega3.value.nominal", "eps2.value.wc"]
    {
        assert!(header.contains(&col), "no column {col} in {header:?}");
    }
    assert!(!csv.contains("NaN") && !csv.contains("inf"));
    // The nominal rates are the run's own kinematics (ω1 = 20 rad/s): ω3 at φ1 = 0.
    let (s, positions) = fourbar(&["phi1_deg.step=10"]);
    let k0 = kinematics_eps(&s.spec.geometry, &positions[0], s.spec.omega1, s.spec.epsilon1).unwrap();
    let row: Vec<&str> = csv.lines().nth(1).unwrap().split(',').collect();
    let at = |c: &str| row[header.iter().position(|h| *h == c).unwrap()].parse::<f64>().unwrap();
    assert!(
        common::rel_close(at("omega3.value.nominal"), k0.omega3, 1e-3, 0.0),
        "{} vs {}",
        at("omega3.value.nominal"),
        k0.omega3
    );
    assert!(common::rel_close(at("vM.x.nominal"), k0.v_m.x, 1e-3, 0.0));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("fourbar-tolerances.json")).unwrap()).unwrap();
    let names: Vec<&str> =
        v["tolerances"]["components"].as_array().unwrap().iter().map(|c| c["name"].as_str().unwrap()).collect();
    for c in ["vM.x", "vM.y", "vM.normal", "vM.along", "omega3.value", "aM.along", "eps2.value"] {
        assert!(names.contains(&c), "no component {c} in {names:?}");
    }
    assert!(v["tolerances"]["positions"][3]["values"]["vM.along"]["rss"].as_f64().unwrap() > 0.0);
    // Their band diagrams and Pareto charts (the speed's and the tangential acceleration's).
    let diagrams = out.join("diagrams").join("fourbar-tolerances");
    for f in [
        "vM.along-band.svg",
        "omega3.value-band.svg",
        "vM.along-pareto.svg",
        "aM.along-pareto.svg",
        "eps2.value-pareto.svg",
    ] {
        assert!(diagrams.join(f).exists(), "{f}");
    }
    let band = std::fs::read_to_string(diagrams.join("vM.along-band.svg")).unwrap();
    assert!(band.contains("mm/s"), "the speed's deviations in mm/s");
    // The band drawing is the points' paths only.
    let drawing = std::fs::read_to_string(out.join("fourbar-tolerances-tolerance-band.svg")).unwrap();
    assert!(!drawing.contains("vM"));
}

#[test]
fn bad_rate_outputs_name_the_field_and_write_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let template = common::root().join("templates").join(TEMPLATE);
    for (set, field) in [
        ("tolerances.outputs.velocities=[\"Q\"]", "tolerances.outputs.velocities[0]"),
        ("tolerances.outputs.accelerations=[\"M\", \"crank\"]", "tolerances.outputs.accelerations[1]"),
        ("tolerances.outputs.velocities=[\"M\", \"M\"]", "tolerances.outputs"),
        ("tolerances.outputs.speeds=[\"M\"]", "tolerances.outputs.speeds"),
    ] {
        let out = tmp.path().join("out");
        let o = run(&["run", template.to_str().unwrap(), "--out", out.to_str().unwrap(), "--set", set]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{set}: {err}");
        assert!(err.contains(TEMPLATE) && err.contains(&format!("field `{field}`")), "{set}: {err}");
        assert!(!out.exists(), "{set}: something was written");
    }
}
