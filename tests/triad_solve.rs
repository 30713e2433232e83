//! The triad solver's numbers against independent routes: the seed's published result,
//! the six constraint equations, a dense scan of phi1 written here from scratch, poses
//! built backwards, a tangent and a singular (double-root) pose, and invariance.

#![allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the library calls"
)]

use mechdraw::geom::{Point, Vector, deg, rad, rotate};
use mechdraw::solve::triad::{
    Configuration, NewtonOptions, Orientation, PatternOptions, Triad, TriadError, all_modes, newton, pattern,
};
use rand::{RngExt, SeedableRng};

mod common;

use common::seed_triad as seed;

/// The six constraint errors (absolute, model units).
fn equations(t: &Triad, a: &[Point; 3]) -> [f64; 6] {
    [
        (a[0] - t.o[0]).norm() - t.r[0],
        (a[1] - t.o[1]).norm() - t.r[1],
        (a[2] - t.o[2]).norm() - t.r[2],
        (a[1] - a[0]).norm() - t.l12,
        (a[2] - a[1]).norm() - t.l23,
        (a[2] - a[0]).norm() - t.l13,
    ]
}

fn assert_all_equations(t: &Triad, modes: &[Configuration], tol: f64) {
    for c in modes {
        for (k, e) in equations(t, &c.a).iter().enumerate() {
            assert!(e.abs() <= tol, "equation {k} off by {e} in {c:?}");
        }
        // The angles are the directions O_i → A_i.
        for i in 0..3 {
            let dir = c.a[i] - t.o[i];
            let back = Vector::new(c.phi[i].cos(), c.phi[i].sin()) * t.r[i];
            assert!((dir - back).norm() <= tol, "phi{} does not point at A{}", i + 1, i + 1);
        }
        let cross = (c.a[1] - c.a[0]).perp(&(c.a[2] - c.a[0]));
        match c.orientation {
            Orientation::Ccw => assert!(cross > 0.0),
            Orientation::Cw => assert!(cross < 0.0),
            Orientation::Collinear => {}
        }
    }
}

// ---------------------------------------------------------------------------------------
// An independent route: a dense scan of phi1 on both A2 branches, written from scratch.

/// A2 candidates for A1: intersections of circle (A1, l12) and circle (O2, R2), by the
/// law of cosines in the triangle A1–O2–A2 (a different formula from the library's).
fn a2_of(t: &Triad, a1: Point, branch: usize) -> Option<Point> {
    let v = t.o[1] - a1;
    let d = v.norm();
    let cos = (t.l12 * t.l12 + d * d - t.r[1] * t.r[1]) / (2.0 * t.l12 * d);
    if !(-1.0..=1.0).contains(&cos) {
        return None;
    }
    let ang = cos.acos() * if branch == 0 { 1.0 } else { -1.0 };
    Some(a1 + rotate(v / d, ang) * t.l12)
}

/// |O3A3| − R3 for phi1 on a branch, A3 placed by the triangle's angle at A1.
fn miss(t: &Triad, phi1: f64, branch: usize, ccw: bool) -> Option<f64> {
    let a1 = t.o[0] + Vector::new(phi1.cos(), phi1.sin()) * t.r[0];
    let a2 = a2_of(t, a1, branch)?;
    let cos_a = (t.l12 * t.l12 + t.l13 * t.l13 - t.l23 * t.l23) / (2.0 * t.l12 * t.l13);
    let alpha = cos_a.clamp(-1.0, 1.0).acos() * if ccw { 1.0 } else { -1.0 };
    let a3 = a1 + rotate((a2 - a1) / t.l12, alpha) * t.l13;
    Some((a3 - t.o[2]).norm() - t.r[2])
}

/// Roots phi1 (radians) of one orientation by sign changes on a dense grid, bisected; the
/// ends of each branch's interval of existence are located by bisection and included.
fn scan(t: &Triad, ccw: bool, steps: usize) -> Vec<f64> {
    let mut roots = Vec::new();
    for branch in 0..2 {
        let f = |phi: f64| miss(t, phi, branch, ccw);
        let mut samples: Vec<(f64, f64)> = Vec::new();
        let push_run = |samples: &mut Vec<(f64, f64)>, roots: &mut Vec<f64>| {
            for w in samples.windows(2) {
                let ((x0, y0), (x1, y1)) = (w[0], w[1]);
                if (y0 < 0.0) != (y1 < 0.0) {
                    let (mut lo, mut hi, neg_lo) = (x0, x1, y0 < 0.0);
                    for _ in 0..80 {
                        let mid = 0.5 * (lo + hi);
                        match f(mid) {
                            Some(v) if (v < 0.0) == neg_lo => lo = mid,
                            _ => hi = mid,
                        }
                    }
                    roots.push(0.5 * (lo + hi));
                }
            }
            samples.clear();
        };
        let h = std::f64::consts::TAU / steps as f64;
        let mut prev: Option<(f64, Option<f64>)> = None;
        for i in 0..=steps {
            let x = i as f64 * h;
            let y = f(x);
            if let Some((px, py)) = prev
                && py.is_some() != y.is_some()
            {
                // Interval end between px and x: bisect to its last existing point.
                let (mut inside, mut outside) = if py.is_some() { (px, x) } else { (x, px) };
                for _ in 0..80 {
                    let mid = 0.5 * (inside + outside);
                    if f(mid).is_some() { inside = mid } else { outside = mid }
                }
                if let Some(v) = f(inside) {
                    if py.is_some() {
                        samples.push((inside, v));
                        push_run(&mut samples, &mut roots);
                    } else {
                        samples.push((inside, v));
                    }
                }
            }
            if let Some(v) = y {
                samples.push((x, v));
            }
            prev = Some((x, y));
        }
        push_run(&mut samples, &mut roots);
    }
    roots.sort_by(f64::total_cmp);
    // 0 and 2π are the same angle.
    roots.dedup_by(|a, b| (*a - *b).abs() < 1e-9 || (*a - *b - std::f64::consts::TAU).abs() < 1e-9);
    roots
}

fn phi1_matches(a: f64, b: f64, tol: f64) -> bool {
    mechdraw::geom::wrap_pi(a - b).abs() <= tol
}

fn assert_scan_agrees(t: &Triad, label: &str) -> usize {
    let modes = all_modes(t, None).unwrap_or_default();
    for (ccw, o) in [(true, Orientation::Ccw), (false, Orientation::Cw)] {
        let ours: Vec<f64> = modes.iter().filter(|c| c.orientation == o).map(|c| c.phi[0]).collect();
        let theirs = scan(t, ccw, 20_000);
        assert_eq!(
            ours.len(),
            theirs.len(),
            "{label} {o}: solver {:?}° vs scan {:?}°",
            ours.iter().map(|x| deg(*x)).collect::<Vec<_>>(),
            theirs.iter().map(|x| deg(*x)).collect::<Vec<_>>()
        );
        for x in &theirs {
            assert!(ours.iter().any(|y| phi1_matches(*x, *y, 1e-8)), "{label} {o}: scan root {}° not found", deg(*x));
        }
    }
    modes.len()
}

// ---------------------------------------------------------------------------------------

#[test]
fn pattern_method_reaches_the_seeds_75_77_degrees() {
    let t = seed();
    let s = pattern(&t, &PatternOptions::default()).unwrap();
    let phi1 = s.configuration.phi_deg()[0];
    assert!((phi1 - 75.77).abs() <= 0.005, "phi1 = {phi1}°");
    // Its stopping rule, eq. (3), with the seed's ε.
    assert!(s.residual < 1e-5, "{}", s.residual);
    assert!(((s.configuration.a[2] - t.o[2]).norm() - 84.0).abs() < 1e-5);
    eprintln!("pattern method: phi1 = {phi1:.6}° after {} iterations, |R3 − d| = {:.3e}", s.iterations, s.residual);
    assert!((1..=8).contains(&s.iterations));
}

#[test]
fn newton_from_the_seeds_start_agrees_with_the_pattern_method() {
    let t = seed();
    let p = pattern(&t, &PatternOptions::default()).unwrap();
    let [a1, a2, a3] = p.start;
    let start = [a1 - t.o[0], a2 - t.o[1], a3 - t.o[2]].map(|v| v.y.atan2(v.x));
    let n = newton(&t, &NewtonOptions { start, max_iterations: 50 }).unwrap();
    assert!((n.configuration.phi_deg()[0] - 75.77).abs() <= 0.005);
    assert_all_equations(&t, &[n.configuration], 1e-10);
    // The pattern's ε = 1e-5 on |O3A3| bounds its distance to the exact root.
    for i in 0..3 {
        assert!((n.configuration.a[i] - p.configuration.a[i]).norm() < 1e-4);
    }
}

#[test]
fn every_seed_mode_satisfies_the_six_equations_and_the_scan_finds_the_same_modes() {
    let t = seed();
    let modes = all_modes(&t, None).unwrap();
    assert_all_equations(&t, &modes, 1e-9);
    for c in &modes {
        assert!(c.residual <= 1e-10);
    }
    assert_eq!(assert_scan_agrees(&t, "seed"), modes.len());
    assert!(modes.iter().any(|c| (c.phi_deg()[0] - 75.77).abs() <= 0.005 && c.orientation == Orientation::Ccw));
}

/// A random triangle pose and pivots; radii and sides measured from the pose.
fn random_pose(rng: &mut rand_chacha::ChaCha8Rng) -> (Triad, [Point; 3]) {
    loop {
        let mut p = || Point::new(rng.random_range(-100.0..100.0), rng.random_range(-100.0..100.0));
        let a = [p(), p(), p()];
        let o = [p(), p(), p()];
        let l12 = (a[1] - a[0]).norm();
        let l23 = (a[2] - a[1]).norm();
        let l13 = (a[2] - a[0]).norm();
        let r = [0, 1, 2].map(|i| (a[i] - o[i]).norm());
        let area = (a[1] - a[0]).perp(&(a[2] - a[0])).abs();
        // Keep well-shaped data (no needle triangles, no pivot on its vertex).
        if area > 0.05 * l12.max(l23).max(l13).powi(2) && r.iter().all(|x| *x > 5.0) {
            return (Triad::new(o, r, l12, l23, l13).unwrap(), a);
        }
    }
}

#[test]
fn random_triads_built_backwards_contain_their_pose_and_agree_with_the_scan() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(20261121);
    let mut total = 0;
    for k in 0..12 {
        let (t, pose) = random_pose(&mut rng);
        let modes = all_modes(&t, None).unwrap();
        assert_all_equations(&t, &modes, 1e-9);
        let found = modes.iter().any(|c| (0..3).all(|i| (c.a[i] - pose[i]).norm() <= 1e-7 * t.scale()));
        assert!(found, "triad {k}: pose {pose:?} not among {modes:#?}");
        total += assert_scan_agrees(&t, &format!("random triad {k}"));
        assert!(modes.iter().filter(|c| c.orientation == Orientation::Ccw).count() <= 6);
        assert!(modes.iter().filter(|c| c.orientation == Orientation::Cw).count() <= 6);
    }
    eprintln!("{total} modes in 12 random triads");
}

#[test]
#[ignore = "stress run: cargo test --release --test triad_solve -- --ignored"]
fn stress_many_random_triads_agree_with_the_scan() {
    let n: usize = std::env::var("TRIAD_STRESS").ok().and_then(|v| v.parse().ok()).unwrap_or(300);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(99);
    for k in 0..n {
        let (t, pose) = random_pose(&mut rng);
        let modes = all_modes(&t, None).unwrap();
        assert!(modes.iter().any(|c| (0..3).all(|i| (c.a[i] - pose[i]).norm() <= 1e-7 * t.scale())), "{k}");
        assert_scan_agrees(&t, &format!("stress triad {k}"));
    }
}

#[test]
fn six_modes_of_one_orientation_are_all_found() {
    // A class-III triad reaches its bound of 6 configurations: search random poses for
    // one whose scan shows 6 roots, then the solver must find all 6.
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(6);
    for _ in 0..400 {
        let (t, _) = random_pose(&mut rng);
        for (ccw, o) in [(true, Orientation::Ccw), (false, Orientation::Cw)] {
            if scan(&t, ccw, 4000).len() == 6 {
                let modes = all_modes(&t, Some(o)).unwrap();
                assert_eq!(modes.len(), 6, "{modes:#?}");
                assert_all_equations(&t, &modes, 1e-9);
                return;
            }
        }
    }
    panic!("no six-mode triad in 400 random poses");
}

#[test]
fn a_tangent_dyad_pose_is_found_once_without_nan() {
    // A1, A2, O2 collinear with A2 between: circle (A1, l12) touches circle (O2, R2).
    let a = [Point::new(0.0, 0.0), Point::new(40.0, 10.0), Point::new(15.0, 45.0)];
    let u = (a[1] - a[0]).normalize();
    let o = [Point::new(-30.0, -25.0), a[1] + u * 35.0, Point::new(70.0, 80.0)];
    let r = [0, 1, 2].map(|i| (a[i] - o[i]).norm());
    let t = Triad::new(o, r, (a[1] - a[0]).norm(), (a[2] - a[1]).norm(), (a[2] - a[0]).norm()).unwrap();
    let modes = all_modes(&t, None).unwrap();
    assert!(modes.iter().all(|c| c.phi.iter().all(|p| p.is_finite())));
    let hits = modes.iter().filter(|c| (0..3).all(|i| (c.a[i] - a[i]).norm() <= 1e-6 * t.scale())).count();
    assert_eq!(hits, 1, "{modes:#?}");
    assert_all_equations(&t, &modes, 1e-9);
    // The pattern method started there sees the single (tangent) A2 and stops at once.
    let phi1 = (a[0] - o[0]).y.atan2((a[0] - o[0]).x);
    for side in [mechdraw::geom::Side::Left, mechdraw::geom::Side::Right] {
        let p = pattern(&t, &PatternOptions { phi1_start: phi1, a2: side, ..Default::default() }).unwrap();
        assert_eq!(p.iterations, 0);
        assert!((p.configuration.a[1] - a[1]).norm() < 1e-6);
    }
}

/// A singular pose: the lines O1A1, O2A2, O3A3 meet in one point P. Two assembly modes
/// merge there (a double root of the closure equation).
fn singular_triad(r3_delta: f64) -> (Triad, [Point; 3]) {
    let a = [Point::new(0.0, 0.0), Point::new(60.0, 0.0), Point::new(20.0, 45.0)];
    let p = Point::new(25.0, 15.0);
    let k = [1.6, 0.9, 1.3];
    let o = [0, 1, 2].map(|i| a[i] + (a[i] - p) * k[i]);
    let mut r = [0, 1, 2].map(|i| (a[i] - o[i]).norm());
    r[2] += r3_delta;
    (Triad::new(o, r, 60.0, (a[2] - a[1]).norm(), (a[2] - a[0]).norm()).unwrap(), a)
}

#[test]
fn a_double_root_where_two_modes_merge_is_found() {
    let (t, a) = singular_triad(0.0);
    let near = |modes: &[Configuration], tol: f64| {
        modes.iter().filter(|c| (0..3).all(|i| (c.a[i] - a[i]).norm() <= tol)).count()
    };
    let modes = all_modes(&t, Some(Orientation::Ccw)).unwrap();
    assert_all_equations(&t, &modes, 1e-9);
    // A double root is known to ~sqrt(machine epsilon): found once.
    assert_eq!(near(&modes, 1e-5 * t.scale()), 1, "{modes:#?}");
    // Perturbing R3 either way splits it into two modes or removes both: it is double.
    let h = 1e-3;
    let counts: Vec<usize> = [-h, h]
        .iter()
        .map(|d| {
            let (t2, _) = singular_triad(*d);
            near(&all_modes(&t2, Some(Orientation::Ccw)).unwrap_or_default(), 0.05 * t.scale())
        })
        .collect();
    assert!(counts.contains(&2) && counts.contains(&0), "near-pose modes for R3 ∓ {h}: {counts:?}");
    // On both sides the independent scan agrees (the close pair is two modes, then none).
    for d in [-h, h] {
        assert_scan_agrees(&singular_triad(d).0, &format!("singular pose, R3 {d:+}"));
    }
}

#[test]
fn translating_and_rotating_the_triad_changes_nothing_but_the_angles() {
    let t = seed();
    let theta = rad(37.0);
    let shift = Vector::new(1234.5, -567.8);
    let moved = |p: Point| Point::from(rotate(p.coords, theta)) + shift;
    let t2 = Triad::new(t.o.map(moved), t.r, t.l12, t.l23, t.l13).unwrap();
    let m1 = all_modes(&t, None).unwrap();
    let m2 = all_modes(&t2, None).unwrap();
    assert_eq!(m1.len(), m2.len());
    for c in &m1 {
        let twin = m2
            .iter()
            .find(|d| d.orientation == c.orientation && (0..3).all(|i| phi1_matches(d.phi[i] - theta, c.phi[i], 1e-9)));
        let twin = twin.unwrap_or_else(|| panic!("no rotated twin of {c:?}"));
        for i in 0..3 {
            assert!((twin.a[i] - moved(c.a[i])).norm() < 1e-9 * t2.scale());
        }
    }
    // The pattern method is invariant too when its start angle turns with the triad.
    let p1 = pattern(&t, &PatternOptions::default()).unwrap();
    let o2 = PatternOptions { phi1_start: rad(90.0) + theta, ..Default::default() };
    let p2 = pattern(&t2, &o2).unwrap();
    assert!(phi1_matches(p2.configuration.phi[0] - theta, p1.configuration.phi[0], 1e-6));
}

#[test]
fn impossible_data_is_named() {
    let t = seed();
    // Pivots too far apart for A1 and A2 to be l12 apart.
    let far = Triad::new([t.o[0], Point::new(400.0, 20.0), t.o[2]], t.r, 50.0, 50.0, 92.0).unwrap();
    let e = all_modes(&far, None).unwrap_err();
    assert!(matches!(e, TriadError::CannotJoin { pair: [0, 1], .. }), "{e}");
    assert!(e.to_string().contains("l12"), "{e}");
    // Every pair can be joined but not all three: R3 too small for A3 to reach.
    let short = Triad::new(t.o, [50.0, 60.0, 8.0], 50.0, 50.0, 92.0).unwrap();
    assert!(scan(&short, true, 20_000).is_empty() && scan(&short, false, 20_000).is_empty());
    match all_modes(&short, None) {
        Err(TriadError::NoConfiguration { closest_miss, .. }) => assert!(closest_miss.abs() > 1.0),
        other => panic!("expected NoConfiguration, got {other:?}"),
    }
    assert!(matches!(
        Triad::new(t.o, t.r, 50.0, 50.0, 101.0),
        Err(TriadError::TriangleInequality { longest: "l13", .. })
    ));
    assert!(matches!(
        Triad::new(t.o, [50.0, -60.0, 84.0], 50.0, 50.0, 92.0),
        Err(TriadError::InvalidLength { name: "r[1]", .. })
    ));
}

#[test]
fn one_orientation_only_and_a_flat_triangle() {
    let t = seed();
    let ccw = all_modes(&t, Some(Orientation::Ccw)).unwrap();
    assert!(ccw.iter().all(|c| c.orientation == Orientation::Ccw));
    assert_eq!(ccw.len(), 4);
    // A flat triangle (l13 = l12 + l23): one orientation, collinear vertices.
    let flat = Triad::new(t.o, t.r, 50.0, 50.0, 100.0).unwrap();
    let modes = all_modes(&flat, None).unwrap();
    assert!(!modes.is_empty());
    assert!(modes.iter().all(|c| c.orientation == Orientation::Collinear));
    assert_all_equations(&flat, &modes, 1e-9);
}
