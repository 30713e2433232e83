//! Stability of the triad's methods where they break (seed 000's triad and families of it).
//! Every case states what must happen: the right mode, or a named failure saying where —
//! never NaN, never a silent jump to another assembly mode.

use mechdraw::bench::basins::{Basin, triad_basins};
use mechdraw::bench::reference::{nearest_mode, triad_modes};
use mechdraw::geom::{Side, angle_of, deg, polar, rad};
use mechdraw::solve::triad::{
    NewtonOptions, Orientation, PatternOptions, Triad, TriadError, all_modes, newton, pattern, pattern::construct,
};

mod common;

use common::seed_triad as seed;

fn with_r3(r3: f64) -> Triad {
    let t = seed();
    Triad::new(t.o, [t.r[0], t.r[1], r3], t.l12, t.l23, t.l13).unwrap()
}

/// |A1(phi1) O2| − (l12 + R2): positive where circle (A1, l12) misses circle (O2, R2)
/// from outside (the dyad A1–A2–O2 cannot reach).
fn reach_gap(t: &Triad, phi1: f64) -> f64 {
    (polar(t.o[0], t.r[0], phi1) - t.o[1]).norm() - (t.l12 + t.r[1])
}

/// The start angle where the dyad's two circles become tangent, between `inside` (they
/// meet) and `outside` (they miss), by bisection to the last bit.
fn tangency(t: &Triad, mut inside: f64, mut outside: f64) -> f64 {
    assert!(reach_gap(t, inside) < 0.0 && reach_gap(t, outside) > 0.0);
    for _ in 0..200 {
        let mid = 0.5 * (inside + outside);
        if mid == inside || mid == outside {
            break;
        }
        if reach_gap(t, mid) < 0.0 { inside = mid } else { outside = mid }
    }
    inside
}

/// Tangent circles, discriminant → 0 from both sides: starting the pattern method at
/// phi1 approaching the edge of the dyad's reach (the seed's phi1 = 90° is inside, 180° is
/// outside). Inside, however close (1e-3 … 1e-12 rad), the start triangle exists with
/// finite coordinates and the method converges to a reference mode or fails by name; just
/// past the edge it fails with `PatternNoIntersection` at iteration 0 naming that angle.
#[test]
fn pattern_start_at_the_edge_of_the_dyads_reach() {
    let t = seed();
    let modes = triad_modes(&t).unwrap();
    let edge = tangency(&t, rad(90.0), rad(180.0));
    for delta in [1e-3, 1e-6, 1e-9, 1e-12] {
        let inside = edge - delta;
        let a = construct(&t, inside, Side::Right, Orientation::Ccw).expect("start triangle inside the reach");
        assert!(a.iter().all(|p| p.x.is_finite() && p.y.is_finite()));
        let o = PatternOptions { phi1_start: inside, ..Default::default() };
        match pattern(&t, &o) {
            Ok(s) => {
                let (_, d) = nearest_mode(&t, &modes, &s.configuration.a).unwrap();
                assert!(d < 1e-5, "δ = {delta}: converged to no mode (distance {d})");
            }
            Err(e) => assert!(
                matches!(
                    e,
                    TriadError::PatternNoIntersection { .. }
                        | TriadError::PatternStalled { .. }
                        | TriadError::PatternNotConverged { .. }
                ),
                "δ = {delta}: {e}"
            ),
        }
        let outside = edge + delta;
        let o = PatternOptions { phi1_start: outside, ..Default::default() };
        if construct(&t, outside, Side::Right, Orientation::Ccw).is_some() {
            // Within the circle intersection's tangency tolerance: the start is the tangent
            // point; only allowed for the smallest step past the edge.
            assert!(delta < 1e-9, "δ = {delta}: a start triangle past the edge");
            assert!(pattern(&t, &o).is_ok_and(|s| s.configuration.residual < 1e-9) || pattern(&t, &o).is_err());
            continue;
        }
        match pattern(&t, &o) {
            Err(TriadError::PatternNoIntersection { phi1_deg, iteration: 0 }) => {
                assert!((phi1_deg - deg(outside)).abs() < 1e-9, "{phi1_deg} vs {}", deg(outside));
            }
            other => panic!("δ = {delta} past the edge: expected PatternNoIntersection, got {other:?}"),
        }
    }
}

/// Number of modes of the seed's triad with R3 = r3 (0 when there is no configuration).
fn count(r3: f64) -> usize {
    match all_modes(&with_r3(r3), None) {
        Ok(m) => m.len(),
        Err(TriadError::NoConfiguration { .. } | TriadError::CannotJoin { .. }) => 0,
        Err(e) => panic!("R3 = {r3}: {e}"),
    }
}

/// Two assembly modes merging (a double root): the largest R3 for which the seed's triad
/// still assembles is where its last two modes merge. Approaching it from below
/// (relative distance 1e-4 … 1e-9) both modes are still found, distinct, each with a
/// residual below 1e-9, and their distance shrinks with the gap; just past it the
/// enumeration answers `NoConfiguration`, naming the closest miss.
#[test]
fn two_modes_merge_at_the_largest_r3() {
    // Bracket the edge: modes exist at 84, none at 400.
    let (mut lo, mut hi) = (84.0, 400.0);
    assert!(count(lo) > 0 && count(hi) == 0);
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        if count(mid) > 0 { lo = mid } else { hi = mid }
    }
    let edge = lo;
    let mut last_gap = f64::INFINITY;
    for rel in [1e-4, 1e-6, 1e-8] {
        let t = with_r3(edge * (1.0 - rel));
        let modes = all_modes(&t, None).unwrap();
        assert_eq!(modes.len(), 2, "R3 = edge·(1 − {rel}): {modes:?}");
        for m in &modes {
            assert!(m.residual < 1e-9 && m.phi.iter().all(|p| p.is_finite()), "{m:?}");
        }
        let gap = (0..3).map(|i| (modes[0].a[i] - modes[1].a[i]).norm()).fold(0.0, f64::max);
        assert!(gap > 0.0 && gap < last_gap, "rel {rel}: gap {gap} (before {last_gap})");
        last_gap = gap;
    }
    let past = with_r3(edge * (1.0 + 1e-6));
    match all_modes(&past, None) {
        Err(TriadError::NoConfiguration { closest_miss, at_phi1_deg, .. }) => {
            assert!(closest_miss.is_finite() && at_phi1_deg.is_finite());
            assert!(closest_miss.abs() < 1e-3 * edge, "closest miss {closest_miss}");
        }
        other => panic!("past the edge: expected NoConfiguration, got {other:?}"),
    }
}

/// The secant stalling: a first step Δφ below the resolution of phi1 makes d2 = d1; the
/// pattern method must say `PatternStalled` with the angle and the step, not divide by zero.
#[test]
fn secant_stalls_by_name() {
    let t = seed();
    let o = PatternOptions { step: 1e-30, tol: 1e-12, ..Default::default() };
    match pattern(&t, &o) {
        Err(TriadError::PatternStalled { phi1_deg, iteration: 1, step_deg, residual }) => {
            assert!((phi1_deg - 90.0).abs() < 1e-12, "{phi1_deg}");
            assert!(step_deg > 0.0 && step_deg < 1e-20 && residual.is_finite() && residual > 0.0);
        }
        other => panic!("expected PatternStalled at iteration 1, got {other:?}"),
    }
}

/// Newton started far away: from every start on a 30° grid of (phi1, phi2, phi3), Newton
/// converges to one of the reference modes (within 1e-9 of it) or fails by name
/// (`NewtonSingular` with finite angles, `NewtonNotConverged` with a residual that is not
/// NaN). Both outcomes occur.
#[test]
fn newton_from_anywhere_converges_to_a_mode_or_fails_by_name() {
    let t = seed();
    let modes = triad_modes(&t).unwrap();
    let (mut ok, mut failed) = (0, 0);
    for i in 0..12 {
        for j in 0..12 {
            for k in 0..12 {
                let start = [rad(30.0 * i as f64), rad(30.0 * j as f64), rad(30.0 * k as f64)];
                match newton(&t, &NewtonOptions { start, max_iterations: 50 }) {
                    Ok(s) => {
                        let (_, d) = nearest_mode(&t, &modes, &s.configuration.a).unwrap();
                        assert!(d < 1e-9, "start {start:?}: converged {d} away from every mode");
                        ok += 1;
                    }
                    Err(TriadError::NewtonSingular { phi_deg, .. }) => {
                        assert!(phi_deg.iter().all(|p| p.is_finite()));
                        failed += 1;
                    }
                    Err(TriadError::NewtonNotConverged { residual, .. }) => {
                        assert!(!residual.is_nan());
                        failed += 1;
                    }
                    Err(e) => panic!("start {start:?}: unexpected error {e}"),
                }
            }
        }
    }
    assert!(ok > 0, "no start converged");
    eprintln!("Newton from a 30° grid: {ok} converged to a mode, {failed} failed by name");
}

/// The basins (as charted by `mechdraw bench`): every start phi1 of every strip ends in a
/// reference mode, in a missing start triangle, or in a named failure — never in a
/// configuration that is no mode. The pattern method keeps its orientation: it only ever
/// lands on counter-clockwise modes.
#[test]
fn basins_hold_only_modes_and_named_failures() {
    let t = seed();
    let modes = triad_modes(&t).unwrap();
    let strips = triad_basins(&t, &modes, 90);
    assert_eq!(strips.len(), 4);
    for s in &strips {
        assert!(!s.outcomes.contains(&Basin::Stray), "{}: {:?}", s.method, s.outcomes);
        assert!(s.outcomes.iter().any(|b| matches!(b, Basin::Mode(_))), "{}", s.method);
        if s.method.starts_with("pattern") {
            for b in &s.outcomes {
                if let Basin::Mode(k) = b {
                    assert_eq!(modes[*k].orientation, Orientation::Ccw, "{}", s.method);
                }
            }
        }
    }
    // Where the start triangle is missing, the dyad's circles really miss.
    let right = &strips[0];
    for (k, b) in right.outcomes.iter().enumerate() {
        let phi1 = rad(4.0 * k as f64);
        assert_eq!(*b == Basin::NoStart, construct(&t, phi1, Side::Right, Orientation::Ccw).is_none());
        if *b == Basin::NoStart {
            let a1 = polar(t.o[0], t.r[0], phi1);
            let d = (a1 - t.o[1]).norm();
            assert!(d > t.l12 + t.r[1] || d < (t.l12 - t.r[1]).abs(), "phi1 = {}°", deg(phi1));
        }
    }
    let _ = angle_of;
}
