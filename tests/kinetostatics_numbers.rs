//! Kineto-statics of the four-bar checked against independent routes: the virtual-power
//! balance, the Newton–Euler linear system, each link's free-body equilibrium, a static
//! configuration solved by hand, virtual work with finite-difference velocity ratios.

#![allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the library calls"
)]

use mechdraw::geom::{Point, Side, Vector, cross};
use mechdraw::scene::{self, Scene};
use mechdraw::solve::fourbar::{CrankRange, Dynamics, Forces, forces_newton_euler};
use mechdraw::solve::fourbar::{Kinematics, MotionSpec, Position, position, solve_motion};

const TEMPLATE: &str = include_str!("../templates/fourbar-chebyshev.toml");

fn spec_from(text: &str) -> MotionSpec {
    match scene::parse(text, "test.toml", &[]).unwrap() {
        Scene::Fourbar(s) => s.spec,
        other => panic!("not a fourbar scene: {}", other.kind()),
    }
}

fn template_spec() -> MotionSpec {
    spec_from(TEMPLATE)
}

/// Loads recomputed here from the kinematics (not taken from `Forces`): weights and
/// inertia torsors of the homogeneous bars, J = m·l²/12 about the middle.
struct Loads {
    at: [Point; 4],     // G1, G21, G22, G3
    force: [Vector; 4], // weight + inertia force
    v: [Vector; 4],     // centroid velocities
    moment: [f64; 4],   // inertia moments −J·eps (crank: 0)
}

fn loads(spec: &MotionSpec, p: &Position, k: &Kinematics) -> Loads {
    let g = &spec.geometry;
    let d = spec.dynamics.as_ref().unwrap();
    let mid = |a: Point, b: Point| Point::from((a.coords + b.coords) / 2.0);
    let down = d.gravity;
    let a_g = [k.a_a / 2.0, (k.a_a + k.a_b) / 2.0, (k.a_b + k.a_m) / 2.0, k.a_b / 2.0];
    let m = [d.m1, d.m21, d.m22, d.m3];
    let l = [g.l1, g.l_ab, g.l_bm, g.l_bc];
    let eps = [0.0, k.eps2, k.eps2, k.eps3];
    Loads {
        at: [mid(g.o1, p.a), mid(p.a, p.b), mid(p.b, p.m), mid(g.c, p.b)],
        force: std::array::from_fn(|i| down * m[i] - a_g[i] * m[i]),
        v: [k.v_a / 2.0, (k.v_a + k.v_b) / 2.0, (k.v_b + k.v_m) / 2.0, k.v_b / 2.0],
        moment: std::array::from_fn(|i| -m[i] * l[i] * l[i] / 12.0 * eps[i]),
    }
}

/// The external forces acting at `p` (point, value, velocity of the point).
fn external(d: &Dynamics, p: &Position, k: &Kinematics) -> Vec<(Point, Vector, Vector)> {
    use mechdraw::solve::fourbar::ForcePoint;
    d.forces
        .iter()
        .filter(|f| f.range.is_none_or(|r| r.contains_deg(p.phi1.to_degrees())))
        .map(|f| match f.at {
            ForcePoint::A => (p.a, f.value, k.v_a),
            ForcePoint::B => (p.b, f.value, k.v_b),
            ForcePoint::M => (p.m, f.value, k.v_m),
        })
        .collect()
}

#[test]
fn virtual_power_balances_at_every_position() {
    let spec = template_spec();
    let motion = solve_motion(&spec).unwrap();
    assert_eq!(motion.forces.len(), 360);
    let d = spec.dynamics.as_ref().unwrap();
    let mut worst = 0.0f64;
    for (p, f) in motion.positions.iter().zip(&motion.forces) {
        let k = p.kin.unwrap();
        let l = loads(&spec, p, &k);
        // Me1·ω1 + Σ (G + F_i)·v_G + Σ M_i·ω + Σ F·v = 0 (ideal joints: reactions do no work).
        let omegas = [spec.omega1, k.omega2, k.omega2, k.omega3];
        let mut terms = vec![f.me1 * spec.omega1];
        terms.extend((0..4).map(|i| l.force[i].dot(&l.v[i])));
        terms.extend((0..4).map(|i| l.moment[i] * omegas[i]));
        terms.extend(external(d, p, &k).iter().map(|(_, fv, v)| fv.dot(v)));
        let sum: f64 = terms.iter().sum();
        let size: f64 = terms.iter().map(|t| t.abs()).sum();
        let rel = sum.abs() / size;
        worst = worst.max(rel);
        assert!(rel <= 1e-9, "phi1 = {}°: power residual {sum} of {size}", p.phi1.to_degrees());
    }
    eprintln!("worst relative virtual-power residual: {worst:e}");
}

fn vclose(a: Vector, b: Vector, rel: f64, floor: f64) -> bool {
    (a - b).norm() <= rel * a.norm().max(b.norm()) + floor
}

#[test]
fn seed_route_and_newton_euler_agree() {
    for omega1 in [20.0, -35.0, 0.0] {
        let mut spec = template_spec();
        spec.omega1 = omega1;
        let motion = solve_motion(&spec).unwrap();
        let d = spec.dynamics.as_ref().unwrap();
        let rmax = motion.forces.iter().map(|f| f.r_a.norm()).fold(0.0, f64::max);
        let floor = 1e-13 * rmax;
        for (p, f) in motion.positions.iter().zip(&motion.forces) {
            let k = p.kin.unwrap();
            let ne = forces_newton_euler(&spec.geometry, p, &k, d).unwrap();
            let at = p.phi1.to_degrees();
            assert!(vclose(f.r_a, ne.r_a, 1e-9, floor), "R_A at {at}: {:?} vs {:?}", f.r_a, ne.r_a);
            assert!(vclose(f.r_b, ne.r_b, 1e-9, floor), "R_B at {at}");
            assert!(vclose(f.r_c, ne.r_c, 1e-9, floor), "R_C at {at}");
            assert!(vclose(f.r_o, ne.r_o, 1e-9, floor), "R_O at {at}");
            assert!((f.me1 - ne.me1).abs() <= 1e-9 * f.me1.abs().max(ne.me1.abs()) + floor * spec.geometry.l1);
        }
    }
}

#[test]
fn every_link_is_in_equilibrium_with_equal_and_opposite_joint_forces() {
    // How "R_A on link 1 vs on link 2" is checked: link 2 is balanced with +R_A and +R_B
    // (forces and moments about M), link 1 with −R_A (the reaction of link 2 on link 1),
    // R_O and Me1 (moments about A), link 3 with −R_B and R_C (moments about its
    // centroid). None of these points is one the solver takes moments about (B, O1), and
    // the loads are recomputed here, so the three balances hold only if R_A and R_B enter
    // the neighbouring links equal and opposite.
    let spec = template_spec();
    let g = spec.geometry;
    let motion = solve_motion(&spec).unwrap();
    let d = spec.dynamics.as_ref().unwrap();
    let fmax = motion.forces.iter().map(|f| f.r_a.norm().max(f.r_o.norm())).fold(0.0, f64::max);
    let tol_f = 1e-12 * fmax;
    let tol_m = 1e-12 * fmax * 0.3;
    for (p, f) in motion.positions.iter().zip(&motion.forces) {
        let k = p.kin.unwrap();
        let l = loads(&spec, p, &k);
        let ext = external(d, p, &k);
        // Link 2.
        let sum2 = f.r_a + f.r_b + l.force[1] + l.force[2] + ext.iter().map(|e| e.1).sum::<Vector>();
        let mom2 = cross(p.a - p.m, f.r_a)
            + cross(p.b - p.m, f.r_b)
            + cross(l.at[1] - p.m, l.force[1])
            + cross(l.at[2] - p.m, l.force[2])
            + l.moment[1]
            + l.moment[2]
            + ext.iter().map(|(at, fv, _)| cross(at - p.m, *fv)).sum::<f64>();
        assert!(sum2.norm() <= tol_f && mom2.abs() <= tol_m, "link 2 at {}: {sum2:?} {mom2}", p.phi1);
        // Link 1 (about A).
        let sum1 = f.r_o - f.r_a + l.force[0];
        let mom1 = f.me1 + cross(g.o1 - p.a, f.r_o) + cross(l.at[0] - p.a, l.force[0]) + l.moment[0];
        assert!(sum1.norm() <= tol_f && mom1.abs() <= tol_m, "link 1 at {}: {sum1:?} {mom1}", p.phi1);
        // Link 3 (about G3).
        let sum3 = f.r_c - f.r_b + l.force[3];
        let mom3 = cross(g.c - l.at[3], f.r_c) + cross(p.b - l.at[3], -f.r_b) + l.moment[3];
        assert!(sum3.norm() <= tol_f && mom3.abs() <= tol_m, "link 3 at {}: {sum3:?} {mom3}", p.phi1);
        // The seed's decomposition: R^n ⊥ bar, R^t ∥ bar, R = R^n + R^t.
        let (u2, u3) = ((p.b - p.a) / g.l_ab, (p.b - g.c) / g.l_bc);
        assert!(f.r_a_n.dot(&u2).abs() <= tol_f && cross(u2, f.r_a_t).abs() <= tol_f);
        assert!(f.r_c_n.dot(&u3).abs() <= tol_f && cross(u3, f.r_c_t).abs() <= tol_f);
        assert!((f.r_a_n + f.r_a_t - f.r_a).norm() <= tol_f && (f.r_c_n + f.r_c_t - f.r_c).norm() <= tol_f);
        // The inertia forces drawn are the ones recomputed here.
        assert!(vclose(f.fi21 + f.g21, l.force[1], 1e-12, 1e-15));
        assert!(vclose(f.fi3 + f.g3, l.force[3], 1e-12, 1e-15));
        assert!((f.mi21 + f.mi22 - l.moment[1] - l.moment[2]).abs() <= 1e-12 * fmax);
    }
}

#[test]
fn no_masses_and_no_force_give_no_reactions() {
    let text = TEMPLATE
        .replace("m1 = 0.05", "m1 = 0.0")
        .replace("m21 = 0.125", "m21 = 0.0")
        .replace("m22 = 0.125", "m22 = 0.0")
        .replace("m3 = 0.125", "m3 = 0.0")
        .replace("value = [0.0, -50.0]", "value = [0.0, 0.0]");
    let spec = spec_from(&text);
    assert_eq!(spec.dynamics.as_ref().unwrap().m3, 0.0);
    let motion = solve_motion(&spec).unwrap();
    assert_eq!(motion.forces.len(), 360);
    for f in &motion.forces {
        for v in [f.r_a, f.r_b, f.r_c, f.r_o, f.r_a_n, f.r_a_t, f.r_c_n, f.r_c_t] {
            assert_eq!(v.norm(), 0.0);
        }
        assert_eq!(f.me1, 0.0);
    }
}

/// Static scene: O1 = (0,0), crank along +x at phi1 = 0 (A = (0.04, 0)), coupler AB
/// vertical up to B = (0.04, 0.10), M above B (alpha = 180°), rocker BC horizontal to
/// C = (0.10, 0.10).
fn static_scene(force: &str) -> String {
    format!(
        "kind = \"fourbar\"\nname = \"static\"\nunits = \"SI\"\no1 = [0.0, 0.0]\nc = [0.10, 0.10]\nl1 = 0.04\n\
         l_ab = 0.10\nl_bm = 0.05\nalpha_deg = 180.0\nl_bc = 0.06\nomega1 = 0.0\n\
         phi1_deg = {{ from = 0.0, to = 0.0, step = 1.0 }}\nbranch = \"left\"\n\
         [dynamics]\ng = 9.8\nm1 = 0.05\nm21 = 0.125\nm22 = 0.125\nm3 = 0.2\n{force}"
    )
}

#[test]
fn static_moment_by_hand() {
    // By hand (omega1 = 0: no inertia). The rocker BC is horizontal, loaded by its weight
    // m3·g at the middle: moments about B give the ground's vertical pull at C,
    // R_C = (0, m3·g/2). Link 2 (AB vertical, M straight above B) has all its weights on
    // the line AB, so its moment about A, (B−A) × R_B = −0.1·R_Bx, forces R_Bx = 0; link 3's
    // forces then give R_B = R_C + G3 = (0, −m3·g/2) (the rocker pushes the coupler down
    // by half its weight). Link 2's forces: R_A = (0, (m21 + m22 + m3/2)·g); link 1:
    // R_O = R_A − G1 = (0, (m1 + m21 + m22 + m3/2)·g) and, about O1, with A = (l1, 0),
    // Me1 = (A−O1) × R_A − (G1−O1) × G1 = l1·(m21 + m22 + m3/2)·g + (l1/2)·m1·g.
    // The same by virtual work: v_A = (0, ω1·l1) vertical along AB and v_B ⊥ BC also
    // vertical, so link 2 translates with v_A, G1 and G3 move at half of it:
    // Me1·ω1 = g·ω1·l1·(m1/2 + m21 + m22 + m3/2).
    let (g, l1, m1, m21, m22, m3) = (9.8, 0.04, 0.05, 0.125, 0.125, 0.2);
    let spec = spec_from(&static_scene(""));
    let motion = solve_motion(&spec).unwrap();
    let p = motion.positions[0];
    assert!((p.b - Point::new(0.04, 0.10)).norm() < 1e-15, "{:?}", p.b);
    let f = motion.forces[0];
    let me1 = g * l1 * (m1 / 2.0 + m21 + m22 + m3 / 2.0);
    assert!((f.me1 - me1).abs() <= 1e-12 * me1, "Me1 = {} vs {me1} by hand", f.me1);
    let close =
        |a: Vector, b: Vector, what: &str| assert!((a - b).norm() <= 1e-12 * b.norm(), "{what}: {a:?} vs {b:?}");
    close(f.r_c, Vector::new(0.0, m3 * g / 2.0), "R_C");
    close(f.r_b, Vector::new(0.0, -m3 * g / 2.0), "R_B");
    close(f.r_a, Vector::new(0.0, (m21 + m22 + m3 / 2.0) * g), "R_A");
    close(f.r_o, Vector::new(0.0, (m1 + m21 + m22 + m3 / 2.0) * g), "R_O");
    // A 50 N load pulling M down adds 50·l1 to the driving moment.
    let spec = spec_from(&static_scene("[[dynamics.force]]\nat = \"M\"\nvalue = [0.0, -50.0]\n"));
    let f = solve_motion(&spec).unwrap().forces[0];
    assert!((f.me1 - (me1 + 50.0 * l1)).abs() <= 1e-12 * me1);
}

#[test]
fn static_moment_by_virtual_work_at_every_angle() {
    // omega1 = 0: Me1 = −Σ G·dP_G/dφ1 − F·dM/dφ1, with the velocity ratios dP/dφ1 from
    // Richardson-extrapolated central differences of the solver's positions.
    let mut spec = template_spec();
    spec.omega1 = 0.0;
    let g = spec.geometry;
    let d = spec.dynamics.clone().unwrap();
    let motion = solve_motion(&spec).unwrap();
    let down = d.gravity;
    for (p, f) in motion.positions.iter().zip(&motion.forces) {
        let at = |phi: f64| position(&g, phi, Side::Left).unwrap();
        let ddphi = |get: &dyn Fn(&Position) -> Vector| {
            // First derivatives only: a small step (rounding ≈ 1e-16·|P|/h ≈ 1e-14).
            let h = 2e-3;
            let d1 = |h: f64| (get(&at(p.phi1 + h)) - get(&at(p.phi1 - h))) / (2.0 * h);
            (d1(h / 2.0) * 4.0 - d1(h)) / 3.0
        };
        let va = ddphi(&|q| q.a.coords);
        let vb = ddphi(&|q| q.b.coords);
        let vm = ddphi(&|q| q.m.coords);
        let mut work = down.dot(&(va / 2.0)) * d.m1
            + down.dot(&((va + vb) / 2.0)) * d.m21
            + down.dot(&((vb + vm) / 2.0)) * d.m22
            + down.dot(&(vb / 2.0)) * d.m3;
        let zero_kin = p.kin.unwrap();
        for (_, fv, _) in external(&d, p, &zero_kin) {
            work += fv.dot(&vm); // every template force acts at M
        }
        let me1 = -work;
        assert!(
            (f.me1 - me1).abs() <= 1e-8 * me1.abs().max(1e-3),
            "phi1 = {}°: {} vs {me1}",
            p.phi1.to_degrees(),
            f.me1
        );
    }
}

#[test]
fn force_acts_on_its_closed_range_only() {
    let spec = template_spec();
    let motion = solve_motion(&spec).unwrap();
    let f_at = |deg: usize| -> Forces {
        let i = motion.positions.iter().position(|p| (p.phi1.to_degrees() - deg as f64).abs() < 1e-9).unwrap();
        motion.forces[i]
    };
    let f = Vector::new(0.0, -50.0);
    assert_eq!(f_at(80).f_ext, f);
    assert_eq!(f_at(280).f_ext, f);
    assert_eq!(f_at(180).f_ext, f);
    assert_eq!(f_at(79).f_ext, Vector::zeros());
    assert_eq!(f_at(281).f_ext, Vector::zeros());
    assert_eq!(f_at(0).f_ext, Vector::zeros());
    // The rule itself: counter-clockwise from `from` to `to`, both ends included,
    // modulo 360°.
    let r = |a: f64, b: f64| CrankRange { from_deg: a, to_deg: b };
    assert!(r(80.0, 280.0).contains_deg(80.0) && r(80.0, 280.0).contains_deg(280.0));
    assert!(!r(80.0, 280.0).contains_deg(79.999) && !r(80.0, 280.0).contains_deg(280.001));
    assert!(r(80.0, 280.0).contains_deg(80.0 + 360.0) && r(80.0, 280.0).contains_deg(-80.0));
    assert!(r(80.0, 280.0).contains_deg(80f64.to_radians().to_degrees()));
    assert!(
        r(300.0, 60.0).contains_deg(0.0) && r(300.0, 60.0).contains_deg(330.0) && r(300.0, 60.0).contains_deg(60.0)
    );
    assert!(!r(300.0, 60.0).contains_deg(61.0) && !r(300.0, 60.0).contains_deg(180.0));
    assert!(r(0.0, 360.0).contains_deg(123.4) && r(-10.0, 350.0).contains_deg(200.0));
    assert!(r(45.0, 45.0).contains_deg(45.0) && !r(45.0, 45.0).contains_deg(45.1));
}

#[test]
fn inertia_of_the_rocker_includes_its_mass() {
    // The seed's J3 line forgets m3; here M_i3 = −m3·l_bc²/12·eps3.
    let spec = template_spec();
    let motion = solve_motion(&spec).unwrap();
    let d = spec.dynamics.as_ref().unwrap();
    for (p, f) in motion.positions.iter().zip(&motion.forces) {
        let k = p.kin.unwrap();
        let j3 = d.m3 * spec.geometry.l_bc.powi(2) / 12.0;
        assert!((f.mi3 + j3 * k.eps3).abs() <= 1e-12 * (j3 * k.eps3).abs().max(1e-12));
        // and the crank's inertia force points against its centripetal acceleration.
        assert!(f.fi1.dot(&(p.a - spec.geometry.o1)) >= 0.0);
    }
}

/// Issue 14 (units): the template written in millimetres gives the same reactions in N as
/// the SI template (forces are N and masses kg in every scene; g is m/s²), and its moments
/// are the SI ones in N·mm (×1000). Before, a mm scene's forces came out in mN labelled N.
#[test]
fn a_mm_scene_gives_the_si_scenes_forces_in_newtons() {
    let si = solve_motion(&template_spec()).unwrap();
    let mm_text = TEMPLATE
        .replace("units = \"SI\"", "units = \"mm\"")
        .replace("c = [0.08, 0.0]", "c = [80.0, 0.0]")
        .replace("l1 = 0.04", "l1 = 40.0")
        .replace("l_ab = 0.10", "l_ab = 100.0")
        .replace("l_bm = 0.10", "l_bm = 100.0")
        .replace("l_bc = 0.10", "l_bc = 100.0");
    assert!(mm_text.contains("units = \"mm\"") && mm_text.contains("l_bc = 100.0"), "template changed: {mm_text}");
    let mm = solve_motion(&spec_from(&mm_text)).unwrap();
    assert_eq!(si.forces.len(), 360);
    assert_eq!(mm.forces.len(), si.forces.len());
    let rel = |a: f64, b: f64, scale: f64| (a - b).abs() <= 1e-9 * scale;
    let mut max_force: f64 = 0.0;
    for (s, m) in si.forces.iter().zip(&mm.forces) {
        let scale = s.r_a.norm().max(s.r_c.norm()).max(1.0);
        max_force = max_force.max(m.r_a.norm());
        for (a, b, what) in [(s.r_a, m.r_a, "R_A"), (s.r_b, m.r_b, "R_B"), (s.r_c, m.r_c, "R_C"), (s.r_o, m.r_o, "R_O")]
        {
            assert!(rel(a.x, b.x, scale) && rel(a.y, b.y, scale), "{what}: SI {a:?} N vs mm {b:?} N");
        }
        assert!(rel(s.fi21.x, m.fi21.x, scale) && rel(s.g3.y, m.g3.y, scale), "loads in N");
        // Moments: N·m in the SI scene, N·mm in the mm scene.
        let me_scale = s.me1.abs().max(1e-3) * 1000.0;
        assert!(rel(1000.0 * s.me1, m.me1, me_scale), "Me1: SI {} N·m vs mm {} N·mm", s.me1, m.me1);
        assert!(rel(1000.0 * s.mi21, m.mi21, me_scale.max(1.0)), "Mi21");
    }
    // The 50 N load is felt as 50 N (tens of newtons of reaction), not as 50 mN.
    assert!(max_force > 20.0, "largest |R_A| {max_force} N");
}

/// A mm scene's g in mm/s² (as written before forces were N everywhere) is refused by name.
#[test]
fn a_mm_scenes_g_in_mm_per_s2_is_refused_by_name() {
    let text = TEMPLATE.replace("units = \"SI\"", "units = \"mm\"").replace("g = 9.8", "g = 9806.65");
    assert!(text.contains("g = 9806.65"), "template changed");
    let err = scene::parse(&text, "old.toml", &[]).unwrap_err().to_string();
    assert!(err.contains("old.toml") && err.contains("dynamics.g") && err.contains("m/s²"), "{err}");
}
