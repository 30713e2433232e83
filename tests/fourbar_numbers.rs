//! Four-bar kinematics checked against independent routes: the loop-closure equation in
//! angles, central finite differences of positions (Richardson-extrapolated), the instant
//! centre of the coupler, the acceleration polygon's closure, the law of cosines for the
//! limit angles, rigid-motion invariance.

#![allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the library calls"
)]

use mechdraw::geom::{self, Point, Side, Vector, cross, perp};
use mechdraw::scene::{self, Scene};
use mechdraw::solve::fourbar::{
    self, DeadPointKind, FourbarError, GapReason, Geometry, Grashof, MotionSpec, Outputs, Position, Reach, Sweep,
    position, solve_motion,
};

const TEMPLATE: &str = include_str!("../templates/fourbar-chebyshev.toml");

fn template_spec() -> MotionSpec {
    match scene::parse(TEMPLATE, "fourbar-chebyshev.toml", &[]).unwrap() {
        Scene::Fourbar(s) => s.spec,
        other => panic!("not a fourbar scene: {}", other.kind()),
    }
}

fn spec_from(text: &str) -> Result<MotionSpec, scene::SceneError> {
    match scene::parse(text, "test.toml", &[])? {
        Scene::Fourbar(s) => Ok(s.spec),
        other => panic!("not a fourbar scene: {}", other.kind()),
    }
}

/// A small scene: pivots on the x axis, lengths given, kinematics only.
fn scene_text(l1: f64, d: f64, l_ab: f64, l_bc: f64, outputs: &str, step: f64) -> String {
    format!(
        "kind = \"fourbar\"\nname = \"t\"\nunits = \"SI\"\no1 = [0.0, 0.0]\nc = [{d}, 0.0]\nl1 = {l1}\nl_ab = {l_ab}\n\
         l_bm = 0.05\nalpha_deg = 150.0\nl_bc = {l_bc}\nomega1 = 10.0\n\
         phi1_deg = {{ from = 0.0, to = 359.0, step = {step} }}\noutputs = [{outputs}]\n"
    )
}

fn side_of(g: &Geometry, p: &Position) -> Side {
    p.side(g).expect("B off the line AC")
}

/// Richardson-extrapolated central differences of f at x: first and second derivatives,
/// error O(h⁴). h = 1e-2 rad: truncation ≈ h⁴·|f⁽⁶⁾| ≈ 1e-11 relative to the largest
/// acceleration, rounding ≈ 1e-16·|f|/h² ≈ 1e-12 (a smaller h lets rounding win where
/// |a_M| is nearly zero, on the lambda's straight stretch).
fn derivs<T, F>(f: F, x: f64) -> (T, T)
where
    F: Fn(f64) -> T,
    T: std::ops::Sub<Output = T> + std::ops::Add<Output = T> + std::ops::Mul<f64, Output = T> + Copy,
{
    let h = 1e-2;
    let d1 = |h: f64| (f(x + h) - f(x - h)) * (1.0 / (2.0 * h));
    let d2 = |h: f64| (f(x + h) - f(x) * 2.0 + f(x - h)) * (1.0 / (h * h));
    let first = (d1(h / 2.0) * 4.0 - d1(h)) * (1.0 / 3.0);
    let second = (d2(h / 2.0) * 4.0 - d2(h)) * (1.0 / 3.0);
    (first, second)
}

/// `|a − b| ≤ rel·|b| + floor`.
fn vclose(a: Vector, b: Vector, rel: f64, floor: f64) -> bool {
    (a - b).norm() <= rel * b.norm() + floor
}

#[test]
fn loop_closure_holds_at_every_position() {
    let spec = template_spec();
    let g = spec.geometry;
    let motion = solve_motion(&spec).unwrap();
    assert_eq!(motion.positions.len(), 360);
    assert!(motion.gaps.is_empty(), "{:?}", motion.gaps);
    let scale = g.l1.max(g.l_ab).max(g.l_bc).max(g.ground());
    for p in &motion.positions {
        // The vector loop in angles (independent of the points B was computed as):
        // l1·e^{iφ1} + l_ab·e^{iφ2} − l_bc·e^{iφ3} − (C − O1) = 0.
        let e = |phi: f64| Vector::new(phi.cos(), phi.sin());
        let residual = e(p.phi1) * g.l1 + e(p.phi2()) * g.l_ab - e(p.phi3()) * g.l_bc - (g.c - g.o1);
        assert!(residual.norm() <= 1e-12 * scale, "phi1 = {}: loop residual {}", p.phi1, residual.norm());
        // The points lie on their circles; M is rigidly attached (|BM|, angle ABM = alpha).
        assert!(((p.a - g.o1).norm() - g.l1).abs() <= 1e-12 * scale);
        assert!(((p.b - p.a).norm() - g.l_ab).abs() <= 1e-12 * scale);
        assert!(((p.b - g.c).norm() - g.l_bc).abs() <= 1e-12 * scale);
        assert!(((p.m - p.b).norm() - g.l_bm).abs() <= 1e-12 * scale);
        let ang = geom::angle_of(p.m - p.b) - geom::angle_of(p.a - p.b);
        assert!(geom::wrap_pi(ang - g.alpha).abs() <= 1e-12, "angle ABM");
        // Transmission angle by the law of cosines in triangle ABC.
        let ac2 = (g.c - p.a).norm_squared();
        let cos_t = (g.l_ab * g.l_ab + g.l_bc * g.l_bc - ac2) / (2.0 * g.l_ab * g.l_bc);
        assert!((p.transmission().cos() - cos_t).abs() <= 1e-12);
    }
}

#[test]
fn velocities_and_accelerations_match_finite_differences() {
    let spec = template_spec();
    let g = spec.geometry;
    let w1 = spec.omega1;
    let motion = solve_motion(&spec).unwrap();
    // Floors: 1e-9 of the largest value over the motion (relative error is meaningless
    // where a velocity passes through zero).
    let vmax = motion.positions.iter().map(|p| p.kin.unwrap().v_m.norm()).fold(0.0, f64::max);
    let amax = motion.positions.iter().map(|p| p.kin.unwrap().a_m.norm()).fold(0.0, f64::max);
    let (wmax, emax) = motion.positions.iter().fold((0.0f64, 0.0f64), |(w, e), p| {
        let k = p.kin.unwrap();
        (w.max(k.omega2.abs()).max(k.omega3.abs()), e.max(k.eps2.abs()).max(k.eps3.abs()))
    });
    let mut worst = 0.0f64;
    for p in &motion.positions {
        let k = p.kin.unwrap();
        let side = side_of(&g, p);
        let at = |phi: f64| position(&g, phi, side).unwrap();
        // dP/dt = ω1·dP/dφ1, d²P/dt² = ω1²·d²P/dφ1² (ε1 = 0).
        for (name, get, v, a) in [
            ("A", (|q: &Position| q.a.coords) as fn(&Position) -> Vector, k.v_a, k.a_a),
            ("B", |q: &Position| q.b.coords, k.v_b, k.a_b),
            ("M", |q: &Position| q.m.coords, k.v_m, k.a_m),
        ] {
            let (d1, d2) = derivs(|phi| get(&at(phi)), p.phi1);
            let (vf, af) = (d1 * w1, d2 * (w1 * w1));
            assert!(vclose(v, vf, 1e-6, 1e-9 * vmax), "v{name} at {}: {v:?} vs FD {vf:?}", p.phi1);
            assert!(vclose(a, af, 1e-6, 1e-9 * amax), "a{name} at {}: {a:?} vs FD {af:?}", p.phi1);
            // Reported: error relative to the value, floored at 1e-3 of the largest value.
            worst = worst.max((v - vf).norm() / vf.norm().max(1e-3 * vmax));
            worst = worst.max((a - af).norm() / af.norm().max(1e-3 * amax));
        }
        // Link angles, unwrapped around the current value.
        let phi2 = |phi: f64| geom::wrap_pi(at(phi).phi2() - p.phi2());
        let phi3 = |phi: f64| geom::wrap_pi(at(phi).phi3() - p.phi3());
        let (d2_1, d2_2) = derivs(phi2, p.phi1);
        let (d3_1, d3_2) = derivs(phi3, p.phi1);
        let pairs = [
            ("omega2", k.omega2, d2_1 * w1, wmax),
            ("omega3", k.omega3, d3_1 * w1, wmax),
            ("eps2", k.eps2, d2_2 * w1 * w1, emax),
            ("eps3", k.eps3, d3_2 * w1 * w1, emax),
        ];
        for (name, x, fd, big) in pairs {
            assert!((x - fd).abs() <= 1e-6 * fd.abs() + 1e-9 * big, "{name} at {}: {x} vs FD {fd}", p.phi1);
        }
    }
    eprintln!("worst FD error of v, a relative to max(|value|, 1e-3·max): {worst:e}");
}

#[test]
fn velocity_and_acceleration_polygons_close_by_a_second_route() {
    let spec = template_spec();
    let g = spec.geometry;
    let motion = solve_motion(&spec).unwrap();
    let mut checked_ic = 0;
    for p in &motion.positions {
        let k = p.kin.unwrap();
        let (r2, r3) = (p.b - p.a, p.b - g.c);
        let vs = k.v_b.norm().max(k.v_a.norm());
        let as_ = k.a_b.norm().max(k.a_a.norm());
        // Velocity polygon: pb = pa + ab, with ab ⊥ AB and pb ⊥ CB (v_B = ω3 × CB).
        assert!((k.v_a + k.v_ba - k.v_b).norm() <= 1e-14 * vs);
        assert!((perp(r3) * k.omega3 - k.v_b).norm() <= 1e-12 * vs, "v_B ≠ ω3 × CB at {}", p.phi1);
        assert!(k.v_ba.dot(&r2).abs() <= 1e-12 * vs * g.l_ab);
        // Velocity image of M: v_M − v_B ⊥ BM, |v_MB| = |ω2|·BM.
        let vmb = k.v_m - k.v_b;
        assert!(vmb.dot(&(p.m - p.b)).abs() <= 1e-12 * vs * g.l_bm);
        assert!((vmb.norm() - k.omega2.abs() * g.l_bm).abs() <= 1e-12 * vs);
        // Acceleration polygon: a_A + a_BA^n + a_BA^t = a_BC^n + a_BC^t, components in
        // their drawn directions: a^n towards the centre with ω²·l, a^t ⊥ the bar.
        assert!((k.a_a + k.a_ba_n + k.a_ba_t - (k.a_bc_n + k.a_bc_t)).norm() <= 1e-12 * as_, "at {}", p.phi1);
        assert!((k.a_bc_n + k.a_bc_t - k.a_b).norm() <= 1e-12 * as_);
        assert!((k.a_ba_n.norm() - k.omega2 * k.omega2 * g.l_ab).abs() <= 1e-12 * as_);
        assert!(k.a_ba_n.dot(&(p.a - p.b)) >= 0.0);
        assert!((k.a_bc_n.norm() - k.omega3 * k.omega3 * g.l_bc).abs() <= 1e-12 * as_);
        assert!(k.a_bc_n.dot(&(g.c - p.b)) >= 0.0);
        assert!(k.a_ba_t.dot(&r2).abs() <= 1e-12 * as_ * g.l_ab);
        assert!(k.a_bc_t.dot(&r3).abs() <= 1e-12 * as_ * g.l_bc);
        // Centroids: the middles of the bars, accelerations by rigid-body kinematics
        // a_G = a_P + ε × (G−P) − ω²·(G−P), written from the other end.
        let mid = |p: Point, q: Point| p + (q - p) * 0.5;
        let rigid =
            |a_p: Vector, at: Point, g_pt: Point, w: f64, e: f64| a_p + perp(g_pt - at) * e - (g_pt - at) * (w * w);
        assert!(vclose(k.a_g1, rigid(Vector::zeros(), g.o1, mid(g.o1, p.a), spec.omega1, 0.0), 1e-12, 1e-15));
        assert!(vclose(k.a_g21, rigid(k.a_b, p.b, mid(p.a, p.b), k.omega2, k.eps2), 1e-12, 1e-15));
        assert!(vclose(k.a_g22, rigid(k.a_b, p.b, mid(p.b, p.m), k.omega2, k.eps2), 1e-12, 1e-15));
        assert!(vclose(k.a_g3, rigid(Vector::zeros(), g.c, mid(g.c, p.b), k.omega3, k.eps3), 1e-12, 1e-15));
        // Instant centre P of the coupler = intersection of lines O1A and CB (Kennedy):
        // v_A = ω2 × (A − P) and v_B = ω2 × (B − P) = ω3 × (B − C).
        let (u, w) = (p.a - g.o1, p.b - g.c);
        let den = cross(u, w);
        if den.abs() > 0.05 * u.norm() * w.norm() {
            let t = cross(g.c - g.o1, w) / den;
            let ic = g.o1 + u * t;
            let omega2 = cross(p.a - ic, k.v_a) / (p.a - ic).norm_squared();
            assert!((omega2 - k.omega2).abs() <= 1e-10 * k.omega2.abs().max(1e-3), "ω2 by IC at {}", p.phi1);
            let vb = perp(p.b - ic) * omega2;
            let omega3 = cross(p.b - g.c, vb) / g.l_bc.powi(2);
            assert!((omega3 - k.omega3).abs() <= 1e-10 * k.omega3.abs().max(1e-3), "ω3 by IC at {}", p.phi1);
            checked_ic += 1;
        }
    }
    assert!(checked_ic > 300, "instant centre checked at only {checked_ic} positions");
}

/// The crank angles (degrees in [0, 360)) where |AC| = len, by the law of cosines in
/// O1AC with O1 = (0,0), C = (d, 0): cos φ = (l1² + d² − len²) / (2·l1·d).
fn hand_limits(l1: f64, d: f64, len: f64) -> (f64, f64) {
    let phi = ((l1 * l1 + d * d - len * len) / (2.0 * l1 * d)).acos().to_degrees();
    (phi, 360.0 - phi)
}

#[test]
fn non_grashof_gap_matches_the_analytic_limit_angles() {
    // s + l = 0.04 + 0.08 > p + q = 0.05 + 0.06: a triple rocker; |AC| ∈ [0.03, 0.13]
    // exceeds l_ab + l_bc = 0.10 around phi1 = 180°.
    let (l1, d, l_ab, l_bc) = (0.05, 0.08, 0.06, 0.04);
    let spec = spec_from(&scene_text(l1, d, l_ab, l_bc, "\"position\", \"velocity\"", 1.0)).unwrap();
    let motion = solve_motion(&spec).unwrap();
    assert_eq!(motion.grashof, Grashof::NonGrashof);
    let (lo, hi) = hand_limits(l1, d, l_ab + l_bc);
    assert_eq!(motion.gaps.len(), 1, "{:?}", motion.gaps);
    let gap = motion.gaps[0];
    assert_eq!(gap.reason, GapReason::Unassemblable(Reach::TooFar));
    assert!((gap.from_deg - lo).abs() < 1e-9 && (gap.to_deg - hi).abs() < 1e-9, "{gap:?} vs ({lo}, {hi})");
    // Skipped: exactly the integer angles strictly inside (lo, hi).
    let inside: Vec<f64> = (0..360).map(f64::from).filter(|&x| x > lo && x < hi).collect();
    assert_eq!(gap.skipped, inside.len());
    assert_eq!(gap.first_skipped_deg, inside[0]);
    assert_eq!(gap.last_skipped_deg, *inside.last().unwrap());
    assert_eq!(motion.positions.len(), 360 - inside.len());
    // At the limit angles the dyad is stretched: |AC| = l_ab + l_bc.
    for x in [gap.from_deg, gap.to_deg] {
        let a = Point::new(l1 * x.to_radians().cos(), l1 * x.to_radians().sin());
        assert!(((Point::new(d, 0.0) - a).norm() - (l_ab + l_bc)).abs() < 1e-14);
    }
    // Dead points: those two angles, transmission 180°, limits of assembly.
    assert_eq!(motion.dead_points.len(), 2);
    for (dp, x) in motion.dead_points.iter().zip([lo, hi]) {
        assert!((dp.phi1_deg - x).abs() < 1e-9);
        assert_eq!(dp.transmission_deg, 180.0);
        assert_eq!(dp.kind, DeadPointKind::Limit);
    }
    // No NaN anywhere, and the last position before the gap is nearly stretched.
    for p in &motion.positions {
        let k = p.kin.unwrap();
        assert!([p.b.x, p.b.y, p.m.x, p.m.y, k.omega2, k.eps3, k.a_m.x].iter().all(|v| v.is_finite()));
    }
    let before = motion.positions.iter().rfind(|p| p.phi1.to_degrees() < lo).unwrap();
    assert!(before.transmission().to_degrees() > 150.0);
    // The single-angle API names the failure with the angle.
    match position(&spec.geometry, 180f64.to_radians(), Side::Left) {
        Err(FourbarError::Unassemblable { phi1_deg, reach: Reach::TooFar, .. }) => {
            assert!((phi1_deg - 180.0).abs() < 1e-12)
        }
        other => panic!("expected Unassemblable, got {other:?}"),
    }
}

#[test]
fn too_close_gap_around_the_ground_direction() {
    // l_ab − l_bc = 0.05 > min |AC| = 0.03: the dyad cannot fold short enough around
    // phi1 = 0; l_ab + l_bc = 0.09 < max |AC| = 0.13: nor stretch around 180°.
    let (l1, d, l_ab, l_bc) = (0.05, 0.08, 0.07, 0.02);
    let spec = spec_from(&scene_text(l1, d, l_ab, l_bc, "\"position\"", 0.5)).unwrap();
    let motion = solve_motion(&spec).unwrap();
    let (near_lo, near_hi) = hand_limits(l1, d, l_ab - l_bc); // gap (−near_lo, near_lo) around 0
    let (far_lo, far_hi) = hand_limits(l1, d, l_ab + l_bc);
    let reasons: Vec<GapReason> = motion.gaps.iter().map(|g| g.reason).collect();
    assert_eq!(
        reasons,
        [
            GapReason::Unassemblable(Reach::TooClose),
            GapReason::Unassemblable(Reach::TooFar),
            GapReason::Unassemblable(Reach::TooClose)
        ]
    );
    let [g0, g1, g2] = [motion.gaps[0], motion.gaps[1], motion.gaps[2]];
    assert_eq!(g0.from_deg, 0.0, "a gap that starts the sweep starts at its first angle");
    assert!((g0.to_deg - near_lo).abs() < 1e-9);
    assert!((g1.from_deg - far_lo).abs() < 1e-9 && (g1.to_deg - far_hi).abs() < 1e-9);
    assert!((g2.from_deg - near_hi).abs() < 1e-9);
    assert_eq!(g2.to_deg, 359.0);
    let zeros: Vec<f64> = motion.dead_points.iter().filter(|d| d.transmission_deg == 0.0).map(|d| d.phi1_deg).collect();
    assert_eq!(zeros.len(), 2);
    assert!((zeros[0] - near_lo).abs() < 1e-9 && (zeros[1] - near_hi).abs() < 1e-9);
}

#[test]
fn change_point_linkage_passes_its_flat_position_smoothly() {
    // l1 + d = l_ab + l_bc: at phi1 = 180° all four joints are on the x axis (a touch,
    // transmission 180°). The smooth continuation crosses the line AC there.
    let (l1, d, l_ab, l_bc) = (0.04, 0.08, 0.07, 0.05);
    let spec = spec_from(&scene_text(l1, d, l_ab, l_bc, "\"position\"", 1.0)).unwrap();
    let g = spec.geometry;
    let motion = solve_motion(&spec).unwrap();
    assert_eq!(motion.grashof, Grashof::ChangePoint);
    assert!(motion.gaps.is_empty(), "{:?}", motion.gaps);
    assert_eq!(motion.dead_points.len(), 1);
    let dp = motion.dead_points[0];
    assert!((dp.phi1_deg - 180.0).abs() < 1e-6 && dp.kind == DeadPointKind::Touch && dp.transmission_deg == 180.0);
    assert_eq!(motion.positions.len(), 360);
    let flat = &motion.positions[180];
    assert!(flat.b.y.abs() < 1e-6, "B on the axis at 180°: {:?}", flat.b);
    // Branch continuity: B moves by bounded steps and without a kink (second differences
    // as small as elsewhere): the side switches at the flat position.
    let b: Vec<Point> = motion.positions.iter().map(|p| p.b).collect();
    let max_step = b.windows(2).map(|w| (w[1] - w[0]).norm()).fold(0.0, f64::max);
    assert!(max_step < 0.04 * 2.0 * std::f64::consts::PI / 360.0 * 3.0, "B jumps by {max_step}");
    let kink = |i: usize| (b[i + 1].coords - b[i].coords * 2.0 + b[i - 1].coords).norm();
    let typical = (10..170).map(kink).fold(0.0, f64::max);
    for i in 175..185 {
        assert!(kink(i) < 3.0 * typical, "kink at {i}°: {} vs {typical}", kink(i));
    }
    assert_eq!(side_of(&g, &motion.positions[170]), Side::Left);
    assert_eq!(side_of(&g, &motion.positions[190]), Side::Right);
    // With kinematics asked for, the flat grid position is skipped by name.
    let spec = spec_from(&scene_text(l1, d, l_ab, l_bc, "\"velocity\"", 1.0)).unwrap();
    let motion = solve_motion(&spec).unwrap();
    assert_eq!(motion.gaps.len(), 1);
    assert_eq!(motion.gaps[0].reason, GapReason::Singular);
    assert_eq!(motion.gaps[0].from_deg, 180.0);
    assert!(motion.warnings().iter().any(|w| w.contains("phi1 = 180°") && w.contains("singular")));
    let p = position(&g, std::f64::consts::PI, Side::Left).unwrap();
    assert!(matches!(fourbar::kinematics(&g, &p, 1.0), Err(FourbarError::Singular { .. })));
}

#[test]
fn template_branch_is_kept_and_continuous() {
    let spec = template_spec();
    let g = spec.geometry;
    let motion = solve_motion(&spec).unwrap();
    // design.md: B above the ground line at phi1 = 0.
    assert!(motion.positions[0].b.y > 0.0);
    assert!(motion.positions.iter().all(|p| side_of(&g, p) == Side::Left));
    assert!(motion.dead_points.is_empty());
    assert_eq!(motion.grashof, Grashof::Grashof);
    // Continuity: |ΔB| ≤ max|v_B|/ω1 · Δφ (1 % margin).
    let vb = motion.positions.iter().map(|p| p.kin.unwrap().v_b.norm()).fold(0.0, f64::max);
    let bound = vb / spec.omega1 * 1f64.to_radians() * 1.01;
    for w in motion.positions.windows(2) {
        assert!((w[1].b - w[0].b).norm() <= bound);
    }
    // The other assembly mode is the mirror image of B across A→C.
    let mut other = spec.clone();
    other.geometry.branch = Side::Right;
    let m2 = solve_motion(&other).unwrap();
    for (p, q) in motion.positions.iter().zip(&m2.positions) {
        assert_eq!(side_of(&g, q), Side::Right);
        let u = (g.c - p.a).normalize();
        let rel = p.b - p.a;
        let mirror = p.a + u * (2.0 * rel.dot(&u)) - rel;
        assert!((mirror - q.b).norm() < 1e-13);
    }
}

#[test]
fn positions_only_scene_computes_no_kinematics() {
    let text = TEMPLATE.replace(
        "outputs = [\"position\", \"velocity\", \"acceleration\", \"forces\", \"centres\"]",
        "outputs = [\"position\"]",
    );
    assert_ne!(text, TEMPLATE);
    let spec = spec_from(&text).unwrap();
    assert_eq!(spec.outputs, Outputs::POSITIONS);
    let motion = solve_motion(&spec).unwrap();
    assert_eq!(motion.positions.len(), 360);
    assert!(motion.positions.iter().all(|p| p.kin.is_none()));
    assert!(motion.forces.is_empty());
    // ... and the full template computes both.
    let full = solve_motion(&template_spec()).unwrap();
    assert!(full.positions.iter().all(|p| p.kin.is_some()));
    assert_eq!(full.forces.len(), 360);
}

#[test]
fn rotating_and_translating_the_mechanism_changes_no_magnitude() {
    let spec = template_spec();
    let beta = 37.0f64; // degrees
    let t = Vector::new(1.5, -0.7);
    let rot = |p: Point| Point::from(geom::rotate(p.coords, beta.to_radians()) + t);
    let mut moved = spec.clone();
    moved.geometry.o1 = rot(spec.geometry.o1);
    moved.geometry.c = rot(spec.geometry.c);
    moved.sweep = Sweep { from_deg: spec.sweep.from_deg + beta, to_deg: spec.sweep.to_deg + beta, ..spec.sweep };
    let m0 = solve_motion(&spec).unwrap();
    let m1 = solve_motion(&moved).unwrap();
    assert_eq!(m0.positions.len(), m1.positions.len());
    for (p, q) in m0.positions.iter().zip(&m1.positions) {
        let (k, l) = (p.kin.unwrap(), q.kin.unwrap());
        assert!((rot(p.m) - q.m).norm() < 1e-13);
        // Floors: 1e-12 of the typical size (ω2 passes through zero).
        let same = |a: f64, b: f64, what: &str| {
            assert!((a - b).abs() <= 1e-10 * a.abs() + 1e-12 * 100.0, "{what}: {a} vs {b}")
        };
        same(k.omega2, l.omega2, "omega2");
        same(k.omega3, l.omega3, "omega3");
        same(k.eps2, l.eps2, "eps2");
        same(k.eps3, l.eps3, "eps3");
        same(k.v_m.norm(), l.v_m.norm(), "|vM|");
        same(k.a_m.norm(), l.a_m.norm(), "|aM|");
        same(k.a_b.norm(), l.a_b.norm(), "|aB|");
        same(p.transmission(), q.transmission(), "transmission");
        // Vectors rotate with the mechanism.
        assert!((geom::rotate(k.v_m, beta.to_radians()) - l.v_m).norm() <= 1e-10 * k.v_m.norm());
    }
}

#[test]
fn scene_fields_are_checked_by_name() {
    let bad = |from: &str, to: &str, field: &str| {
        let text = TEMPLATE.replace(from, to);
        assert_ne!(text, TEMPLATE, "{from}");
        match spec_from(&text) {
            Err(scene::SceneError::Field { field: f, message, .. }) => assert_eq!(f, field, "{message}"),
            other => panic!("{to}: expected a field error on {field}, got {other:?}"),
        }
    };
    bad("l_bc = 0.10", "l_bc = -0.10", "l_bc");
    bad("step = 1.0", "step = 0.0", "phi1_deg.step");
    bad("to = 359.0", "to = -1.0", "phi1_deg.to");
    bad("\"forces\",", "\"force\",", "outputs[3]");
    bad("\"centres\"]", "\"centers\"]", "outputs[4]");
    bad("at = \"M\"", "at = \"Q\"", "dynamics.force[0].at");
    bad("m3 = 0.125", "m3 = -0.125", "dynamics.m3");
    bad("branch = \"left\"", "branch = \"up\"", "branch");
    bad("c = [0.08, 0.0]", "c = [0.0, 0.0]", "c");
    // forces without [dynamics]
    let cut = TEMPLATE.find("[dynamics]").unwrap();
    match spec_from(&TEMPLATE[..cut]) {
        Err(scene::SceneError::Field { field, .. }) => assert_eq!(field, "outputs"),
        other => panic!("expected outputs error, got {other:?}"),
    }
    // Defaults: branch left, outputs without forces when there is no [dynamics].
    let text = TEMPLATE[..cut]
        .replace("branch = \"left\"", "")
        .replace("outputs = [\"position\", \"velocity\", \"acceleration\", \"forces\", \"centres\"]", "");
    let spec = spec_from(&text).unwrap();
    assert_eq!(spec.geometry.branch, Side::Left);
    assert_eq!(spec.outputs, Outputs { velocity: true, acceleration: true, forces: false });
}

#[test]
fn a_scene_that_never_assembles_is_a_named_error() {
    let spec = spec_from(&scene_text(0.01, 0.5, 0.1, 0.1, "\"position\"", 1.0)).unwrap();
    assert!(matches!(solve_motion(&spec), Err(FourbarError::NeverAssembled { .. })));
}
