//! Kineto-statics of general linkages (issue 15 §1) against independent routes: the
//! four-bar kind's closed-form dyad route on the Chebyshev four-bar (seed 003), a
//! Newton–Euler written here body by body for the slider-crank, a static case by hand,
//! zero masses, a mm scene against its SI twin, the virtual-power balance on every
//! template with forces.

#![allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the library calls"
)]

mod common;

use mechdraw::geom::{Point, Vector, cross, perp};
use mechdraw::scene::linkage::LinkageScene;
use mechdraw::scene::{self, Scene};
use mechdraw::solve::fourbar::solve_motion;
use mechdraw::solve::linkage::{Forces, Solver, State};

fn linkage(text: &str) -> LinkageScene {
    match scene::parse(text, "test.toml", &[]).unwrap() {
        Scene::Linkage(s) => s,
        other => panic!("not a linkage scene: {}", other.kind()),
    }
}

fn template(name: &str) -> String {
    std::fs::read_to_string(common::root().join("templates").join(name)).unwrap()
}

/// Replaces `from` by `to`, which must occur exactly once.
fn edit(text: &str, from: &str, to: &str) -> String {
    assert_eq!(text.matches(from).count(), 1, "`{from}` should occur once");
    text.replacen(from, to, 1)
}

fn solve(s: &LinkageScene) -> (Vec<State>, Vec<Forces>) {
    let d = s.dynamics.as_ref().expect("the scene has forces");
    Solver::new(s.mechanism.clone()).unwrap().run_kinetostatics(&s.times, d).unwrap()
}

fn joint(s: &LinkageScene, name: &str) -> usize {
    s.mechanism.joints.iter().position(|j| j.name == name).unwrap()
}

fn driver(s: &LinkageScene, name: &str) -> usize {
    s.mechanism.drivers.iter().position(|d| d.name == name).unwrap()
}

/// |got − want| ≤ rel · max(|want|, floor).
fn close(got: Vector, want: Vector, rel: f64, floor: f64) -> bool {
    (got - want).norm() <= rel * want.norm().max(floor)
}

/// templates/fourbar-linkage.toml with seed 003's masses, gravity and force (design.md §3):
/// crank 0.05 kg, coupler AB + BM 0.125 + 0.125 kg (one body: centroid at B, J of a
/// homogeneous 0.2 m bar about its middle), rocker 0.125 kg, g = 9.8 m/s² along −y,
/// F = 50 N along −y at M for φ1 ∈ [80°, 280°] (t = φ1 / 20 rad/s).
fn chebyshev_with_masses() -> String {
    let t = template("fourbar-linkage.toml");
    let t = edit(
        &t,
        "points = { O1 = [0.0, 0.0], A = [0.04, 0.0] }\n",
        "points = { O1 = [0.0, 0.0], A = [0.04, 0.0] }\nmass = 0.05\n",
    );
    let t = edit(
        &t,
        "angle_deg = 78.46                         # B above the ground line at phi1 = 0\n",
        "angle_deg = 78.46\nmass = 0.25\ninertia = 0.0008333333333333334\n",
    );
    let t = edit(&t, "angle_deg = 101.54\n", "angle_deg = 101.54\nmass = 0.125\n");
    let window = format!("t = [{:?}, {:?}]", 80f64.to_radians() / 20.0, 280f64.to_radians() / 20.0);
    edit(
        &t,
        "[[driver]]",
        &format!(
            "[dynamics]\ng = [0.0, -9.8]\n\n[[load]]\nat = \"coupler.M\"\nforce = [0.0, -50.0]\n{window}\n\n[[driver]]"
        ),
    )
}

#[test]
fn chebyshev_linkage_with_seed_003_masses_reproduces_the_fourbar_kind() {
    let s = linkage(&chebyshev_with_masses());
    let (states, forces) = solve(&s);
    let Scene::Fourbar(fb) = scene::load(&common::root().join("templates/fourbar-chebyshev.toml"), &[]).unwrap().scene
    else {
        panic!()
    };
    let motion = solve_motion(&fb.spec).unwrap();
    assert_eq!(motion.positions.len(), 360);
    let (ja, jb, jc, jo) = (joint(&s, "A"), joint(&s, "B"), joint(&s, "C"), joint(&s, "O1"));
    let crank = driver(&s, "crank");
    // Me1 changes sign over the turn: compare it relative to its largest magnitude.
    let me1_scale = motion.forces.iter().map(|f| f.me1.abs()).fold(0.0, f64::max);
    let rel = 1e-9;
    for (k, (p, f)) in motion.positions.iter().zip(&motion.forces).enumerate() {
        assert!((p.phi1.to_degrees() - k as f64).abs() < 1e-9);
        assert!((20.0 * states[k].t - p.phi1).abs() < 1e-12, "k = {k}");
        let r = &forces[k].reactions;
        // Which body on which: A = crank on coupler = R_A; B = coupler on rocker = −R_B
        // (R_B is the rocker on the coupler); C = ground on rocker = R_C; O1 = ground on
        // crank = R_O; the crank driver's force = Me1.
        assert!(close(r[ja].force, f.r_a, rel, 0.0), "φ1 = {k}°: R_A {:?} vs {:?}", r[ja].force, f.r_a);
        assert!(close(r[jb].force, -f.r_b, rel, 0.0), "φ1 = {k}°: R_B {:?} vs {:?}", r[jb].force, -f.r_b);
        assert!(close(r[jc].force, f.r_c, rel, 0.0), "φ1 = {k}°: R_C {:?} vs {:?}", r[jc].force, f.r_c);
        assert!(close(r[jo].force, f.r_o, rel, 0.0), "φ1 = {k}°: R_O {:?} vs {:?}", r[jo].force, f.r_o);
        let me1 = forces[k].drivers[crank];
        assert!((me1 - f.me1).abs() <= rel * me1_scale, "φ1 = {k}°: Me1 {me1} vs {}", f.me1);
        assert!(r.iter().all(|x| x.torque == 0.0));
    }
}

#[test]
fn virtual_power_balances_on_every_template_with_forces() {
    let mut with_forces = Vec::new();
    for entry in std::fs::read_dir(common::root().join("templates")).unwrap() {
        let path = entry.unwrap().path();
        let Scene::Linkage(s) = scene::load(&path, &[]).unwrap().scene else { continue };
        if s.dynamics.is_none() {
            continue;
        }
        let (_, forces) = solve(&s);
        for (k, f) in forces.iter().enumerate() {
            assert!(f.power_residual <= 1e-9, "{}: sample {k}: residual {:e}", s.name, f.power_residual);
        }
        with_forces.push(s.name.clone());
    }
    with_forces.sort();
    assert_eq!(with_forces, ["shaper-forces", "slider-crank"]);
}

/// The slider-crank template's data, SI, written out here.
const R: f64 = 0.110;
const L: f64 = 0.495;
const C: f64 = 0.170; // rod centroid from the crank pin A
const M_ROD: f64 = 50.0;
const J_ROD: f64 = 50.0 * 0.148 * 0.148;
const M_PISTON: f64 = 30.0;
const G: Vector = Vector::new(0.0, -9.81);
const HALF_TURN: f64 = 0.09375; // s at 320 rpm

fn omega() -> f64 {
    320.0 * std::f64::consts::TAU / 60.0
}

fn gas(t: f64) -> Vector {
    let on = (0.0..=HALF_TURN).contains(&t);
    let p = 2.5e6 * (1.0 - t / HALF_TURN);
    Vector::new(if on { -p * std::f64::consts::PI * 0.125 * 0.125 / 4.0 } else { 0.0 }, 0.0)
}

/// Newton–Euler of the slider-crank body by body, with its closed-form kinematics:
/// returns (R_O ground on crank, R_A crank on rod, R_B rod on piston, N ground on
/// piston, T driving torque on the crank).
fn newton_euler(t: f64) -> (Vector, Vector, Vector, Vector, f64) {
    let w = omega();
    let th = w * t;
    let a = Vector::new(R * th.cos(), R * th.sin());
    // Rod angle β: A.y + L·sin β = 0, B on the x axis right of A.
    let sb = -a.y / L;
    let cb = (1.0 - sb * sb).sqrt();
    let e = Vector::new(cb, sb);
    let bd = -R * w * th.cos() / (L * cb);
    let bdd = (R * w * w * th.sin() + L * sb * bd * bd) / (L * cb);
    let acc_a = -a * (w * w);
    let acc_rel = |d: f64| (perp(e) * bdd - e * (bd * bd)) * d;
    let acc_g = acc_a + acc_rel(C);
    let acc_b = acc_a + acc_rel(L);
    assert!(acc_b.y.abs() < 1e-9 * acc_b.norm().max(1.0));
    let f = gas(t);
    // Piston, x: R_B.x + F.x + m·g.x = m·a_B.x.
    let rbx = M_PISTON * acc_b.x - f.x - M_PISTON * G.x;
    // Rod, moments about A: (B − A) × (−R_B) + (G − A) × (m·g − m·a_G) − J·β̈ = 0.
    let d = e * L;
    let k = cross(e * C, (G - acc_g) * M_ROD) - J_ROD * bdd;
    let rby = (d.y * rbx + k) / d.x;
    let rb = Vector::new(rbx, rby);
    // Rod, forces: R_A − R_B + m·g = m·a_G.
    let ra = rb - (G - acc_g) * M_ROD;
    // Piston, y: R_B.y + N + m·g.y = m·a_B.y.
    let n = Vector::new(0.0, M_PISTON * acc_b.y - rb.y - M_PISTON * G.y - f.y);
    // Crank (massless): R_O − R_A = 0; about O: T + A × (−R_A) = 0.
    (ra, ra, rb, n, cross(a, ra))
}

#[test]
fn slider_crank_matches_a_newton_euler_written_body_by_body() {
    let s = linkage(&template("slider-crank.toml"));
    let (states, forces) = solve(&s);
    let (jo, ja, jb, jc) = (joint(&s, "O"), joint(&s, "A"), joint(&s, "B"), joint(&s, "cylinder"));
    let o = driver(&s, "O");
    let rel = 1e-8;
    let t_scale = forces.iter().map(|f| f.drivers[o].abs()).fold(0.0, f64::max);
    let mut gas_on = 0;
    for (st, f) in states.iter().zip(&forces) {
        let (r_o, r_a, r_b, n, torque) = newton_euler(st.t);
        gas_on += usize::from(gas(st.t).x < 0.0);
        let r = &f.reactions;
        let t = st.t;
        assert!(close(r[jo].force, r_o, rel, 0.0), "t = {t}: O {:?} vs {r_o:?}", r[jo].force);
        assert!(close(r[ja].force, r_a, rel, 0.0), "t = {t}: A {:?} vs {r_a:?}", r[ja].force);
        assert!(close(r[jb].force, r_b, rel, 0.0), "t = {t}: B {:?} vs {r_b:?}", r[jb].force);
        assert!(close(r[jc].force, n, rel, 0.0), "t = {t}: cylinder {:?} vs {n:?}", r[jc].force);
        // The piston is one point: every force on it passes through B, no couple.
        assert!(r[jc].torque.abs() <= rel * n.norm(), "t = {t}: couple {}", r[jc].torque);
        assert!(
            (f.drivers[o] - torque).abs() <= rel * torque.abs().max(1e-3 * t_scale),
            "t = {t}: T {} vs {torque}",
            f.drivers[o]
        );
    }
    // Over the expansion stroke, 0° to 180°, falling to zero at its end.
    assert_eq!(gas_on, 180);
}

#[test]
fn static_slider_crank_by_hand() {
    // At rest (constant crank angle 60°), gravity on a 2 kg crank, a 100 N push on the
    // piston towards the crank; rod and piston massless. By hand:
    // A = r(cos 60°, sin 60°) = (0.05, 0.0866025); the rod A→B has sin β = −A.y/l;
    // the massless rod carries s·e (e = (cos β, sin β)) and the piston's x balance gives
    // s·cos β = 100 N; the ground pushes the piston up with N = −s·sin β; the crank:
    // R_O = R_A − m·g, T = A × R_A − G1 × m·g with G1 = A/2.
    let text = r#"
kind = "linkage"
name = "static"
units = "SI"
time = { from = 0.0, to = 1.0, steps = 4 }
[ground]
points = { O = [0.0, 0.0], G1 = [0.0, 0.0], G2 = [1.0, 0.0] }
[[body]]
name = "crank"
points = { O = [0.0, 0.0], A = [0.1, 0.0] }
angle_deg = 60.0
mass = 2.0
[[body]]
name = "rod"
points = { A = [0.0, 0.0], B = [0.3, 0.0] }
at = [0.05, 0.0866]
angle_deg = -16.8
[[body]]
name = "piston"
points = { B = [0.0, 0.0] }
at = [0.337, 0.0]
[[joint]]
name = "O"
revolute = ["ground.O", "crank.O"]
[[joint]]
name = "A"
revolute = ["crank.A", "rod.A"]
[[joint]]
name = "B"
revolute = ["rod.B", "piston.B"]
[[joint]]
name = "cylinder"
prismatic = { point = "piston.B", line = ["ground.G1", "ground.G2"] }
[[driver]]
body = "crank"
law = "pi/3"
[dynamics]
g = [0.0, -9.81]
[[load]]
at = "piston.B"
force = [-100.0, 0.0]
"#;
    let s = linkage(text);
    let (states, forces) = solve(&s);
    let a = Vector::new(0.05, 0.1 * 60f64.to_radians().sin());
    let sb = -a.y / 0.3;
    let cb = (1.0 - sb * sb).sqrt();
    let s_rod = 100.0 / cb;
    let r_a = Vector::new(cb, sb) * s_rod;
    let w = Vector::new(0.0, -2.0 * 9.81);
    let r_o = r_a - w;
    let n = Vector::new(0.0, -s_rod * sb);
    let torque = cross(a, r_a) - cross(a / 2.0, w);
    // The same numbers, rounded, as worked on paper.
    assert!((r_a - Vector::new(100.0, -30.1511)).norm() < 1e-4, "{r_a:?}");
    assert!((torque - -9.6773).abs() < 1e-4, "{torque}");
    for (st, f) in states.iter().zip(&forces) {
        assert!(st.qd.iter().chain(&st.qdd).all(|v| v.abs() < 1e-12), "not at rest");
        let r = &f.reactions;
        assert!(close(r[joint(&s, "O")].force, r_o, 1e-10, 0.0), "{:?} vs {r_o:?}", r[0].force);
        assert!(close(r[joint(&s, "A")].force, r_a, 1e-10, 0.0));
        assert!(close(r[joint(&s, "B")].force, r_a, 1e-10, 0.0));
        assert!(close(r[joint(&s, "cylinder")].force, n, 1e-10, 0.0));
        assert!(r[joint(&s, "cylinder")].torque.abs() < 1e-10);
        assert!((f.drivers[0] - torque).abs() < 1e-10 * torque.abs(), "{} vs {torque}", f.drivers[0]);
        // Nothing moves: no power at all, residual 0 by definition.
        assert_eq!(f.power_residual, 0.0);
    }
}

#[test]
fn zero_masses_and_no_loads_give_zero_reactions() {
    let mut text = template("shaper.toml");
    for body in ["crank", "block", "rocker", "link", "ram"] {
        let at = text.find(&format!("name = \"{body}\"\n")).unwrap();
        text.insert_str(at, "mass = 0.0\n");
    }
    // Each insertion lands right after its body's [[body]] header.
    let s = linkage(&text);
    assert!(s.dynamics.is_some());
    let (_, forces) = solve(&s);
    for f in &forces {
        assert!(f.reactions.iter().all(|r| r.force == Vector::zeros() && r.torque == 0.0));
        assert!(f.drivers.iter().all(|d| *d == 0.0));
        assert_eq!(f.power_residual, 0.0);
    }
    // And a scene with neither masses nor loads computes no forces at all.
    assert!(linkage(&template("shaper.toml")).dynamics.is_none());
}

#[test]
fn a_mm_scene_and_its_si_twin_give_the_same_forces_in_newtons() {
    let mm = template("slider-crank.toml");
    let si = [
        ("units = \"mm\"", "units = \"SI\""),
        ("G2 = [1000.0, 0.0]", "G2 = [1.0, 0.0]"),
        ("A = [110.0, 0.0] }", "A = [0.110, 0.0] }"),
        ("B = [495.0, 0.0] }", "B = [0.495, 0.0] }"),
        ("at = [110.0, 0.0]", "at = [0.110, 0.0]"),
        ("centroid = [170.0, 0.0]", "centroid = [0.170, 0.0]"),
        ("at = [605.0, 0.0]", "at = [0.605, 0.0]"),
    ]
    .iter()
    .fold(mm.clone(), |t, (a, b)| edit(&t, a, b));
    let (mm, si) = (linkage(&mm), linkage(&si));
    let (_, f_mm) = solve(&mm);
    let (_, f_si) = solve(&si);
    for (a, b) in f_mm.iter().zip(&f_si) {
        for (ra, rb) in a.reactions.iter().zip(&b.reactions) {
            assert!(close(ra.force, rb.force, 1e-12, 1e-9), "{ra:?} vs {rb:?}");
            assert!((ra.torque - rb.torque).abs() <= 1e-12 * rb.torque.abs().max(1e-6));
        }
        assert!((a.drivers[0] - b.drivers[0]).abs() <= 1e-12 * b.drivers[0].abs().max(1.0));
    }
}

#[test]
fn a_prismatic_joint_reports_the_couple_about_its_point() {
    // The shaper's ram: the cutting force at the tool T, 200 mm below the guide, is
    // balanced about E by the guide's couple (the ram only translates, its weight and
    // inertia act at its centroid). Moments about E on the ram:
    // M + (T − E) × F_cut + (G − E) × (m·g − m·a) = 0, with the link's force through E.
    let s = linkage(&template("shaper-forces.toml"));
    let (states, forces) = solve(&s);
    let guide = joint(&s, "ram-guide");
    let e = s.anchor("ram.E").unwrap();
    let tool = s.anchor("ram.T").unwrap();
    let mut cutting = 0;
    for (st, f) in states.iter().zip(&forces) {
        let on = (0.0..=0.568).contains(&st.t) || (0.932..=1.0).contains(&st.t);
        cutting += usize::from(on);
        let cut = if on { Vector::new(3000.0, 0.0) } else { Vector::zeros() };
        let pe: Point = st.point(e);
        let arm_t = (st.point(tool) - pe) * 1e-3;
        let arm_g = arm_t / 2.0;
        let a_ram = st.acceleration(e) * 1e-3;
        let m = 45.0;
        let want = -(cross(arm_t, cut) + cross(arm_g, (Vector::new(0.0, -9.81) - a_ram) * m));
        let got = f.reactions[guide].torque;
        assert!((got - want).abs() <= 1e-9 * want.abs().max(1.0), "t = {}: {got} vs {want}", st.t);
    }
    assert!(cutting > 200);
}

/// The static slider-crank of `static_slider_crank_by_hand` the other way round: the
/// piston held by a distance driver, the crank loaded by a torque.
fn piston_driven(law: &str, crank_load: &str, units: &str, scale: f64) -> String {
    let l = |v: f64| format!("{:?}", v * scale);
    format!(
        r#"
kind = "linkage"
name = "piston-driven"
units = "{units}"
time = {{ from = 0.0, to = 0.2, steps = 20 }}
[ground]
points = {{ O = [0.0, 0.0], G1 = [0.0, 0.0], G2 = [{g2}, 0.0] }}
[[body]]
name = "crank"
points = {{ O = [0.0, 0.0], A = [{r}, 0.0] }}
angle_deg = 60.0
mass = 2.0
[[body]]
name = "rod"
points = {{ A = [0.0, 0.0], B = [{rod}, 0.0] }}
at = [{ax}, {ay}]
angle_deg = -16.8
mass = 1.5
[[body]]
name = "piston"
points = {{ B = [0.0, 0.0] }}
at = [{bx}, 0.0]
mass = 0.8
[[joint]]
name = "O"
revolute = ["ground.O", "crank.O"]
[[joint]]
name = "A"
revolute = ["crank.A", "rod.A"]
[[joint]]
name = "B"
revolute = ["rod.B", "piston.B"]
[[joint]]
name = "cylinder"
prismatic = {{ point = "piston.B", line = ["ground.G1", "ground.G2"] }}
[[driver]]
joint = "cylinder"
law = "{law}"
[dynamics]
g = [0.0, -9.81]
[[load]]
body = "crank"
torque = {crank_load}
"#,
        g2 = l(1.0),
        r = l(0.1),
        rod = l(0.3),
        ax = l(0.05),
        ay = l(0.0866),
        bx = l(0.337),
    )
}

#[test]
fn a_distance_driver_holds_the_piston_against_a_crank_torque() {
    // At rest at crank 60°, with masses: drive the crank and push the piston with
    // −100 N; the crank driver's torque holds it. Then swap: put that torque on the crank
    // as a load and hold the piston with a distance driver: it must push with −100 N.
    let a = Vector::new(0.05, 0.1 * 60f64.to_radians().sin());
    let sb = -a.y / 0.3;
    let x_b = a.x + 0.3 * (1.0 - sb * sb).sqrt();
    // The torque on the crank that balances a −100 N push on the piston with these masses,
    // from the crank-driven route of the same scene (its driver torque).
    let crank_driven = piston_driven(&format!("{x_b:?}"), "0.0", "SI", 1.0)
        .replace("joint = \"cylinder\"\nlaw", "body = \"crank\"\nlaw")
        .replace(&format!("law = \"{x_b:?}\""), "law = \"pi/3\"")
        + "[[load]]\nat = \"piston.B\"\nforce = [-100.0, 0.0]\n";
    let s = linkage(&crank_driven);
    assert!(matches!(s.mechanism.drivers[0].target, mechdraw::solve::linkage::DriverTarget::BodyAngle(0)));
    let (_, f) = solve(&s);
    let holding = f[0].drivers[0];
    let s = linkage(&piston_driven(&format!("{x_b:?}"), &format!("{holding:?}"), "SI", 1.0));
    let (states, f) = solve(&s);
    assert!((states[0].angular(mechdraw::solve::linkage::Attach::Body(0)).0 - 60f64.to_radians()).abs() < 1e-12);
    for x in &f {
        assert!((x.drivers[0] - -100.0).abs() < 1e-9, "{}", x.drivers[0]);
    }
}

#[test]
fn a_moving_distance_driver_balances_the_virtual_power_in_mm_and_in_si() {
    // The piston driven by x(t) = 0.33 − 0.1·t (m) while the crank carries a torque: the
    // driver's power is force × ḟ with ḟ in length units/s, so a unit slip would show.
    let law = |scale: f64| format!("{:?} - {:?}*t", 0.33 * scale, 0.1 * scale);
    let si = linkage(&piston_driven(&law(1.0), "\"5*sin(10*t)\"", "SI", 1.0));
    let mm = linkage(&piston_driven(&law(1000.0), "\"5*sin(10*t)\"", "mm", 1000.0));
    let (_, f_si) = solve(&si);
    let (_, f_mm) = solve(&mm);
    for (a, b) in f_si.iter().zip(&f_mm) {
        assert!(a.power_residual <= 1e-12 && b.power_residual <= 1e-12, "{} {}", a.power_residual, b.power_residual);
        assert!((a.drivers[0] - b.drivers[0]).abs() <= 1e-10 * a.drivers[0].abs().max(1.0));
        for (ra, rb) in a.reactions.iter().zip(&b.reactions) {
            assert!(close(ra.force, rb.force, 1e-10, 1.0));
        }
    }
}
