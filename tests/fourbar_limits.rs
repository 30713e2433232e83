//! Issue 15 §4: the four-bar kind's own limits lifted (a crank angular acceleration ε1,
//! offset centroids, given moments of inertia, loads at any point of any link, torques on
//! any link, gravity as a vector), checked against the linkage route on the same mechanism
//! and by a virtual-power balance of the four-bar kind's own result.

mod common;

use mechdraw::geom::{Point, Vector, cross, perp};
use mechdraw::scene::{self, Scene};
use mechdraw::solve::fourbar::{Link, MotionSpec, Sweep, forces_newton_euler, joukowski, loads, solve_motion};
use mechdraw::solve::linkage::Solver;

/// ω1 at t = 0 (rad/s) and the constant ε1 (rad/s²) of the linkage's crank law.
const OMEGA0: f64 = 20.0;
const EPS1: f64 = 150.0;

/// The Chebyshev four-bar as a `fourbar` scene with every new field. Masses and points in
/// link coordinates (origin at the link's first point, u towards its second point):
/// crank O1→A, AB A→B, BM B→M, rocker C→B.
const FOURBAR: &str = r#"
kind = "fourbar"
name = "limits"
units = "SI"
o1 = [0.0, 0.0]
c = [0.08, 0.0]
l1 = 0.04
l_ab = 0.10
l_bm = 0.10
alpha_deg = 180.0
l_bc = 0.10
omega1 = 20.0
epsilon1 = 150.0
phi1_deg = { from = 0.0, to = 359.0, step = 1.0 }
branch = "left"

[dynamics]
g = [3.0, -9.8]
m1 = 0.05
m21 = 0.25
m22 = 0.0
m3 = 0.125

[dynamics.crank]
centroid = [0.005, 0.002]
inertia = 2e-5

[dynamics.AB]
centroid = [0.01, 0.004]
inertia = 0.001

[dynamics.rocker]
centroid = [-0.01, 0.003]
inertia = 2e-4

[[dynamics.force]]
at = "M"
value = [0.0, -50.0]

[[dynamics.load]]
link = "rocker"
at = [0.07, 0.01]
force = [30.0, -20.0]

[[dynamics.load]]
link = "rocker"
torque = -4.0

[[dynamics.load]]
link = "BM"
at = [0.05, 0.01]
force = [-10.0, 15.0]

[[dynamics.load]]
link = "crank"
at = [0.03, 0.005]
force = [5.0, 5.0]
torque = 0.5
"#;

/// The same mechanism as a `linkage` scene: the body frames coincide with the link frames
/// (alpha = 180°: M on AB beyond B), so a centroid offset (dx, dy) from the middle of a bar
/// of length l is the body point (l/2 + dx, dy), and a load at link coordinates (x, y) of BM
/// is the coupler point (0.10 + x, y). Crank law φ1 = 20·t + ½·150·t².
const LINKAGE: &str = r#"
kind = "linkage"
name = "limits-linkage"
units = "SI"
time = { from = 0.0, to = 0.3, steps = 360 }

[ground]
points = { O1 = [0.0, 0.0], C = [0.08, 0.0] }

[[body]]
name = "crank"
points = { O1 = [0.0, 0.0], A = [0.04, 0.0], P = [0.03, 0.005] }
angle_deg = 0.0
mass = 0.05
centroid = [0.025, 0.002]
inertia = 2e-5

[[body]]
name = "coupler"
points = { A = [0.0, 0.0], B = [0.10, 0.0], M = [0.20, 0.0], Q = [0.15, 0.01] }
at = [0.04, 0.0]
angle_deg = 78.46
mass = 0.25
centroid = [0.06, 0.004]
inertia = 0.001

[[body]]
name = "rocker"
points = { C = [0.0, 0.0], B = [0.10, 0.0], P = [0.07, 0.01] }
at = [0.08, 0.0]
angle_deg = 101.54
mass = 0.125
centroid = [0.04, 0.003]
inertia = 2e-4

[[joint]]
name = "O1"
revolute = ["ground.O1", "crank.O1"]

[[joint]]
name = "A"
revolute = ["crank.A", "coupler.A"]

[[joint]]
name = "B"
revolute = ["coupler.B", "rocker.B"]

[[joint]]
name = "C"
revolute = ["ground.C", "rocker.C"]

[[driver]]
name = "crank"
body = "crank"
law = "20*t + 75*t^2"

[dynamics]
g = [3.0, -9.8]

[[load]]
at = "coupler.M"
force = [0.0, -50.0]

[[load]]
at = "rocker.P"
force = [30.0, -20.0]

[[load]]
body = "rocker"
torque = -4.0

[[load]]
at = "coupler.Q"
force = [-10.0, 15.0]

[[load]]
at = "crank.P"
force = [5.0, 5.0]

[[load]]
body = "crank"
torque = 0.5
"#;

fn fourbar_spec() -> MotionSpec {
    match scene::parse(FOURBAR, "limits.toml", &[]).unwrap() {
        Scene::Fourbar(s) => s.spec,
        other => panic!("not a four-bar scene: {}", other.kind()),
    }
}

/// The four-bar kind at one crank state (angle in degrees, ω1, ε1).
fn fourbar_at(spec: &MotionSpec, deg: f64, omega1: f64, eps1: f64) -> mechdraw::solve::fourbar::Motion {
    let spec = MotionSpec {
        omega1,
        epsilon1: eps1,
        sweep: Sweep { from_deg: deg, to_deg: deg, step_deg: 1.0 },
        ..spec.clone()
    };
    solve_motion(&spec).unwrap()
}

/// |got − want| ≤ rel · |want|.
fn close(got: Vector, want: Vector, rel: f64) -> bool {
    (got - want).norm() <= rel * want.norm()
}

#[test]
fn the_fourbar_kind_with_every_new_field_matches_the_linkage_route() {
    let spec = fourbar_spec();
    assert_eq!(spec.epsilon1, EPS1);
    let Scene::Linkage(s) = scene::parse(LINKAGE, "limits-linkage.toml", &[]).unwrap() else { panic!() };
    let d = s.dynamics.as_ref().unwrap();
    let (states, forces) = Solver::new(s.mechanism.clone()).unwrap().run_kinetostatics(&s.times, d).unwrap();
    assert_eq!(states.len(), 361);
    let joint = |name: &str| s.mechanism.joints.iter().position(|j| j.name == name).unwrap();
    let (ja, jb, jc, jo) = (joint("A"), joint("B"), joint("C"), joint("O1"));
    let rel = 1e-9;
    let mut me1_max = 0.0f64;
    for (state, lf) in states.iter().zip(&forces) {
        let t = state.t;
        let phi1 = OMEGA0 * t + 0.5 * EPS1 * t * t;
        let omega1 = OMEGA0 + EPS1 * t;
        let m = fourbar_at(&spec, phi1.to_degrees(), omega1, EPS1);
        assert_eq!(m.forces.len(), 1, "t = {t}");
        let f = &m.forces[0];
        let r = &lf.reactions;
        assert!(close(r[ja].force, f.r_a, rel), "t = {t}: R_A {:?} vs {:?}", r[ja].force, f.r_a);
        assert!(close(r[jb].force, -f.r_b, rel), "t = {t}: R_B {:?} vs {:?}", r[jb].force, -f.r_b);
        assert!(close(r[jc].force, f.r_c, rel), "t = {t}: R_C {:?} vs {:?}", r[jc].force, f.r_c);
        assert!(close(r[jo].force, f.r_o, rel), "t = {t}: R_O {:?} vs {:?}", r[jo].force, f.r_o);
        let me1 = lf.drivers[0];
        assert!((me1 - f.me1).abs() <= rel * me1.abs(), "t = {t}: Me1 {me1} vs {}", f.me1);
        me1_max = me1_max.max(me1.abs());
    }
    // The features matter: the same mechanism without ε1 gives another Me1.
    let plain = fourbar_at(&spec, 30.0, OMEGA0, 0.0).forces[0].me1;
    let accelerated = fourbar_at(&spec, 30.0, OMEGA0, EPS1).forces[0].me1;
    assert!((plain - accelerated).abs() > 1e-3 * me1_max, "{plain} vs {accelerated}");
}

#[test]
fn the_fourbar_kinds_own_result_balances_the_virtual_power() {
    let spec = fourbar_spec();
    let motion = solve_motion(&spec).unwrap();
    let d = spec.dynamics.as_ref().unwrap();
    let g = &spec.geometry;
    assert_eq!(motion.positions.len(), 360);
    let mut worst = 0.0f64;
    let mut lever_worst = 0.0f64;
    for (p, f) in motion.positions.iter().zip(&motion.forces) {
        let k = p.kin.unwrap();
        let l = loads(g, p, &k, d);
        // Velocity of a point `at` of a link turning at ω about its first point `o` moving at v_o.
        let v = |v_o: Vector, o: Point, w: f64, at: Point| v_o + perp(at - o) * w;
        let (w1, w2, w3) = (spec.omega1, k.omega2, k.omega3);
        let z = Vector::zeros();
        let mut terms = vec![
            f.me1 * w1,
            (l.w1 + l.fi1).dot(&v(z, g.o1, w1, l.g1_at)) + l.mi1 * w1,
            (l.w21 + l.fi21).dot(&v(k.v_a, p.a, w2, l.g21_at)) + l.mi21 * w2,
            (l.w22 + l.fi22).dot(&v(k.v_a, p.a, w2, l.g22_at)) + l.mi22 * w2,
            (l.w3 + l.fi3).dot(&v(z, g.c, w3, l.g3_at)) + l.mi3 * w3,
            Vector::new(0.0, -50.0).dot(&k.v_m),
        ];
        // The loads of the scene, their points written here from the link frames.
        let frame = |o: Point, q: Point, x: f64, y: f64| {
            let u = (q - o) / (q - o).norm();
            o + u * x + perp(u) * y
        };
        let rocker_p = frame(g.c, p.b, 0.07, 0.01);
        terms.push(Vector::new(30.0, -20.0).dot(&v(z, g.c, w3, rocker_p)));
        terms.push(-4.0 * w3);
        let bm_q = frame(p.b, p.m, 0.05, 0.01);
        terms.push(Vector::new(-10.0, 15.0).dot(&v(k.v_a, p.a, w2, bm_q)));
        let crank_p = frame(g.o1, p.a, 0.03, 0.005);
        terms.push(Vector::new(5.0, 5.0).dot(&v(z, g.o1, w1, crank_p)) + 0.5 * w1);
        let sum: f64 = terms.iter().sum();
        let scale: f64 = terms.iter().map(|x| x.abs()).sum();
        worst = worst.max(sum.abs() / scale);
        // The Newton–Euler route (one 9×9 system) reads the same loads.
        let ne = forces_newton_euler(g, p, &k, d).unwrap();
        for (x, y) in [(ne.r_a, f.r_a), (ne.r_b, f.r_b), (ne.r_c, f.r_c), (ne.r_o, f.r_o)] {
            assert!((x - y).norm() <= 1e-9 * y.norm().max(1.0), "{x:?} vs {y:?}");
        }
        assert!((ne.me1 - f.me1).abs() <= 1e-9 * f.me1.abs().max(1.0));
        // Joukowski's lever carries the same loads: its Me1 is the reactions route's.
        let lever = joukowski::lever(g, p, &k, d, spec.omega1).me1.unwrap();
        lever_worst = lever_worst.max((lever - f.me1).abs() / f.me1.abs().max(1e-3));
    }
    assert!(lever_worst <= 1e-9, "Joukowski's lever vs Me1: {lever_worst:e}");
    assert!(worst <= 1e-9, "virtual-power residual {worst:e}");
    // The centroids are where the scene puts them: crank G1 = O1 + u·0.025 + perp(u)·0.002.
    let p = &motion.positions[40];
    let l = loads(g, p, &p.kin.unwrap(), d);
    let u = (p.a - g.o1) / g.l1;
    assert!((l.g1_at - (g.o1 + u * 0.025 + perp(u) * 0.002)).norm() < 1e-15);
    assert!((Link::Rocker.to_world(g, p, Vector::new(1.0, 0.0)) - (p.b - g.c) / g.l_bc).norm() < 1e-15);
    assert!(cross(u, perp(u)) > 0.0);
}

#[test]
fn a_scalar_g_is_the_vector_along_minus_y_and_bad_fields_are_named() {
    let scalar = FOURBAR.replace("g = [3.0, -9.8]", "g = 9.8");
    let Scene::Fourbar(s) = scene::parse(&scalar, "s.toml", &[]).unwrap() else { panic!() };
    assert_eq!(s.spec.dynamics.unwrap().gravity, Vector::new(0.0, -9.8));
    for (from, to, field) in [
        ("link = \"rocker\"\ntorque", "link = \"frame\"\ntorque", "dynamics.load[1].link"),
        ("inertia = 2e-4", "inertia = -2e-4", "dynamics.rocker.inertia"),
        ("link = \"rocker\"\ntorque = -4.0", "link = \"rocker\"", "dynamics.load[1]"),
        ("epsilon1 = 150.0", "epsilon1 = nan", "epsilon1"),
    ] {
        assert_eq!(FOURBAR.matches(from).count(), 1, "{from}");
        let bad = FOURBAR.replacen(from, to, 1);
        let e = scene::parse(&bad, "bad.toml", &[]).unwrap_err().to_string();
        assert!(e.contains(field), "{field}: {e}");
    }
}

#[test]
fn the_force_polygons_close_with_loads_on_the_crank_and_the_rocker() {
    use mechdraw::figure::fourbar::{crank_polygon, dyad_polygon};
    let spec = fourbar_spec();
    for deg in [0.0, 30.0, 95.0, 200.0, 310.0] {
        let m = fourbar_at(&spec, deg, OMEGA0, EPS1);
        let f = &m.forces[0];
        assert!(f.f1_ext != Vector::zeros() && f.f3_ext != Vector::zeros(), "the scene loads crank and rocker");
        let dyad = dyad_polygon(f);
        let names: Vec<&str> = dyad.chain.iter().map(|v| v.name.as_str()).collect();
        assert!(names.contains(&"F3"), "{names:?}");
        // The dyad's chain closes (the link loads on the rocker in it), and its resultants
        // are the solver's reactions.
        let sum: Vector = dyad.chain.iter().map(|v| v.v).sum();
        let size: f64 = dyad.chain.iter().map(|v| v.v.norm()).sum();
        assert!(sum.norm() <= 1e-12 * size, "{deg}°: the dyad's polygon is open by {sum:?}");
        for (name, want) in [("RA", f.r_a), ("RB", f.r_b), ("RC", f.r_c)] {
            assert!(close(dyad.resultant(name).unwrap(), want, 1e-12), "{deg}°: {name}");
        }
        // The crank's: −RA, Fi1, G1, F1 closed by RO.
        let crank = crank_polygon(f);
        assert_eq!(crank.chain.last().unwrap().name, "F1");
        assert!(close(crank.resultant("RO").unwrap(), f.r_o, 1e-12), "{deg}°: RO");
    }
}
