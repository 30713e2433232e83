//! The measurements of `mechdraw bench`: every method on its problem, timed and compared
//! with the independent references of [`super::reference`].

use super::reference::{self, shaper};
use super::timing::{Budget, ns_per_call};
use super::{Measurement, RunCost};
use crate::error::Error;
use crate::geom::{Side, angle_of, rad};
use crate::scene::linkage::LinkageScene;
use crate::scene::{self, Loaded, Override, Scene};
use crate::solve::fourbar::{Geometry, Prepared};
use crate::solve::linkage::{AssurSolver, Motion, Solver, State};
use crate::solve::triad::{NewtonOptions, PatternOptions, Triad, all_modes, newton_to, pattern, pattern::construct};
use std::path::Path;

/// The templates the bench solves (embedded, so the command works from any directory).
pub const TRIAD_POPA: &str = include_str!("../../templates/triad-popa.toml");
/// The closed-form four-bar scene.
pub const FOURBAR_CHEBYSHEV: &str = include_str!("../../templates/fourbar-chebyshev.toml");
/// The same four-bar as a general linkage.
pub const FOURBAR_LINKAGE: &str = include_str!("../../templates/fourbar-linkage.toml");
/// The shaper as a general linkage.
pub const SHAPER: &str = include_str!("../../templates/shaper.toml");

/// The pattern method's ε (model units, mm here).
pub const PATTERN_EPS: [f64; 6] = [1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12];
/// Triad Newton–Raphson goals (relative residual).
pub const TRIAD_NEWTON_TOL: [f64; 5] = [1e-3, 1e-6, 1e-9, 1e-12, 1e-15];
/// General-solver Newton goals (relative residual).
pub const LINKAGE_NEWTON_TOL: [f64; 5] = [1e-4, 1e-6, 1e-8, 1e-10, 1e-14];

fn parse(text: &str, name: &str, overrides: &[Override]) -> Result<Scene, Error> {
    Ok(scene::parse(text, name, overrides)?)
}

fn solve_err(file: &str, e: impl Into<crate::solve::SolveError>) -> Error {
    Error::Solve { file: file.into(), source: e.into() }
}

/// The seed's triad (templates/triad-popa.toml).
pub fn popa_triad() -> Result<Triad, Error> {
    let Scene::Triad(s) = parse(TRIAD_POPA, "triad-popa.toml", &[])? else {
        unreachable!("triad-popa.toml is a triad scene")
    };
    Triad::new(s.o, s.r, s.l12, s.l23, s.l13).map_err(|e| solve_err("triad-popa.toml", e))
}

/// The Chebyshev four-bar's geometry (templates/fourbar-chebyshev.toml).
pub fn chebyshev_geometry() -> Result<Geometry, Error> {
    let Scene::Fourbar(s) = parse(FOURBAR_CHEBYSHEV, "fourbar-chebyshev.toml", &[])? else {
        unreachable!("fourbar-chebyshev.toml is a four-bar scene")
    };
    Ok(s.spec.geometry)
}

fn fmt_e(v: f64) -> String {
    let k = libm::log10(v).round() as i32;
    format!("1e{k}")
}

/// The triad: pattern method at every ε, Newton–Raphson at every goal (from the pattern
/// method's start triangle), the all-modes enumeration. Error: the larger of the residual
/// of the six constraints and the distance to the nearest polished mode (both relative to
/// [`Triad::scale`]).
pub fn triad(budget: Budget) -> Result<Vec<Measurement>, Error> {
    let t = popa_triad()?;
    let modes = reference::triad_modes(&t).map_err(|e| solve_err("triad-popa.toml", e))?;
    let score = |a: &[crate::geom::Point; 3]| {
        let dist = reference::nearest_mode(&t, &modes, a).map_or(f64::INFINITY, |(_, d)| d);
        (t.residual(a), dist)
    };
    let mut out = Vec::new();
    let problem = "triad (seed 000)";
    for eps in PATTERN_EPS {
        let o = PatternOptions { tol: eps, ..Default::default() };
        let Ok(s) = pattern(&t, &o) else { continue };
        let (res, dist) = score(&s.configuration.a);
        let ns = ns_per_call(budget, || pattern(&t, &o).is_ok());
        out.push(Measurement::new(problem, "pattern (secant)", &format!("ε={}", fmt_e(eps)), ns, res, dist));
    }
    let o = PatternOptions::default();
    let start_a = construct(&t, o.phi1_start, o.a2, o.orientation)
        .ok_or_else(|| solve_err("triad-popa.toml", crate::solve::triad::TriadError::Movable))?;
    let start = [0, 1, 2].map(|i| angle_of(start_a[i] - t.o[i]));
    let nopts = NewtonOptions { start, max_iterations: 50 };
    for tol in TRIAD_NEWTON_TOL {
        let Ok(s) = newton_to(&t, &nopts, tol) else { continue };
        let (res, dist) = score(&s.configuration.a);
        let ns = ns_per_call(budget, || newton_to(&t, &nopts, tol).is_ok());
        out.push(Measurement::new(problem, "Newton–Raphson", &format!("tol={}", fmt_e(tol)), ns, res, dist));
    }
    if let Ok(all) = all_modes(&t, None) {
        let (mut res, mut dist) = (0.0_f64, 0.0_f64);
        for m in &all {
            let (r, d) = score(&m.a);
            res = res.max(r);
            dist = dist.max(d);
        }
        let ns = ns_per_call(budget, || all_modes(&t, None).map(|v| v.len()).unwrap_or(0));
        out.push(Measurement::new(problem, "all modes (degree 6)", &format!("{} modes", all.len()), ns, res, dist));
    }
    Ok(out)
}

/// The four-bar: the closed-form dyad per crank angle (B and M; and with the two link
/// angles, what a run of the four-bar kind writes), and the general Newton solver on
/// the same four-bar (templates/fourbar-linkage.toml) per time step at every goal. Error:
/// the larger of the loop-closure residual and the distance of B to the second-route B of
/// [`reference::fourbar_b`], relative to the longest link.
pub fn fourbar(budget: Budget) -> Result<Vec<Measurement>, Error> {
    let g = chebyshev_geometry()?;
    let scale = g.l1.max(g.l_ab).max(g.l_bc).max(g.ground());
    let prepared = Prepared::new(&g);
    let problem = "four-bar (seed 003)";
    let angles: Vec<f64> = (0..360).map(|k| rad(k as f64)).collect();
    // Errors of B (and, for the row with the link angles, of φ2 and φ3 too, in radians)
    // against the second route's.
    let (mut res, mut dist, mut dist_angles) = (0.0_f64, 0.0_f64, 0.0_f64);
    for &phi1 in &angles {
        let p = prepared.position(phi1, g.branch).map_err(|e| solve_err("fourbar-chebyshev.toml", e))?;
        res = res.max(reference::fourbar_residual(&g, p.a, p.b));
        if let Some(b) = reference::fourbar_b(&g, phi1) {
            dist = dist.max((b - p.b).norm() / scale);
            let (ab, cb) = (b - p.a, b - g.c);
            let d2 = crate::geom::wrap_pi(libm::atan2(ab.y, ab.x) - p.phi2()).abs();
            let d3 = crate::geom::wrap_pi(libm::atan2(cb.y, cb.x) - p.phi3()).abs();
            dist_angles = dist_angles.max(d2).max(d3);
        }
    }
    let dist_angles = dist.max(dist_angles);
    // B and M; then with the two link angles a run writes (φ2 of A→B, φ3 of C→B, `atan2`
    // each): the four-bar kind giving per position what the four-bar as a linkage gives per
    // step (its bodies' poses).
    let mut out = vec![
        Measurement::new(
            problem,
            "closed-form dyad",
            "exact",
            per_angle(budget, &prepared, &angles, |p| p.b.x),
            res,
            dist,
        ),
        Measurement::new(
            problem,
            "closed-form dyad",
            "+ link angles",
            per_angle(budget, &prepared, &angles, |p| p.b.x + p.phi2() + p.phi3()),
            res,
            dist_angles,
        ),
    ];

    let Scene::Linkage(s) = parse(FOURBAR_LINKAGE, "fourbar-linkage.toml", &[])? else {
        unreachable!("fourbar-linkage.toml is a linkage scene")
    };
    let file = "fourbar-linkage.toml";
    let anchor = |spec: &str| s.anchor(spec).map_err(|m| solve_err(file, scene_msg(m)));
    let (b_an, a_an) = (anchor("coupler.B")?, anchor("coupler.A")?);
    let omega1 = 20.0; // the template's driver law 20*t
    for tol in LINKAGE_NEWTON_TOL {
        let mut solver = Solver::new(s.mechanism.clone()).map_err(|e| solve_err(file, e))?;
        solver.set_newton_tolerance(tol);
        let Ok(states) = solver.clone().run(&s.times) else { continue };
        let (mut res, mut dist) = (0.0_f64, 0.0_f64);
        for st in &states {
            let phi1 = omega1 * st.t;
            let (a, b) = (st.point(a_an), st.point(b_an));
            // A from the driver: where the crank pin must be at this time.
            let a_exact = crate::geom::polar(g.o1, g.l1, phi1);
            res = res.max(reference::fourbar_residual(&g, a, b)).max((a - a_exact).norm() / scale);
            if let Some(bref) = reference::fourbar_b(&g, phi1) {
                dist = dist.max((bref - b).norm() / scale);
            }
        }
        let ns = per_step(budget, &solver, &s.times);
        out.push(Measurement::new(problem, "general Newton", &format!("tol={}", fmt_e(tol)), ns, res, dist));
    }
    let score = |st: &State| {
        let phi1 = omega1 * st.t;
        let (a, b) = (st.point(a_an), st.point(b_an));
        let a_exact = crate::geom::polar(g.o1, g.l1, phi1);
        let res = reference::fourbar_residual(&g, a, b).max((a - a_exact).norm() / scale);
        let dist = reference::fourbar_b(&g, phi1).map_or(0.0, |bref| (bref - b).norm() / scale);
        (res, dist)
    };
    out.extend(assur(budget, problem, file, &s, score)?);
    Ok(out)
}

/// Nanoseconds per position of the closed-form dyad, cycling through `angles` (B on the
/// left): `read` takes what a caller reads of the position (statically, so inlined as a
/// caller's own code would be).
fn per_angle(
    budget: Budget,
    prepared: &Prepared,
    angles: &[f64],
    read: impl Fn(&crate::solve::fourbar::Position) -> f64,
) -> f64 {
    let mut k = 0usize;
    ns_per_call(budget, || {
        k = if k + 1 == angles.len() { 0 } else { k + 1 };
        prepared.position(angles[k], Side::Left).map(|p| read(&p)).unwrap_or(0.0)
    })
}

/// The Assur-group route on a linkage scene (solve::linkage::assur), nanoseconds per time
/// step over the whole motion after the first (assembled) position: positions only (the
/// sweep, [`AssurSolver::positions_into`], as a run asking for positions solves them), and
/// positions with velocities and accelerations (the sweep with rates,
/// [`AssurSolver::motion_into`], as a run asking for them solves them). Error: the worst
/// `score` (residual, distance) over the motion, each row on its own answers.
fn assur(
    budget: Budget,
    problem: &str,
    file: &str,
    s: &LinkageScene,
    score: impl Fn(&State) -> (f64, f64),
) -> Result<Vec<Measurement>, Error> {
    let mut solver = AssurSolver::new(s.mechanism.clone()).map_err(|e| solve_err(file, e))?;
    let states = solver.clone().run(&s.times).map_err(|e| solve_err(file, e))?;
    let positions = solver.clone().run_positions(&s.times).map_err(|e| solve_err(file, e))?;
    let worst =
        |it: &mut dyn Iterator<Item = (f64, f64)>| it.fold((0.0_f64, 0.0_f64), |m, v| (m.0.max(v.0), m.1.max(v.1)));
    let full = worst(&mut states.iter().map(&score));
    let pos = worst(&mut states.iter().zip(&positions).map(|(st, q)| score(&State { q: q.clone(), ..st.clone() })));
    let start = states[0].clone();
    let rest = &s.times[1..];
    let steps = rest.len().max(1) as f64;
    let mut q = Vec::with_capacity(rest.len() * solver.q().len());
    let ns_pos = ns_per_call(budget, || {
        solver.resume(&start);
        q.clear();
        let _ = solver.positions_into(rest, &mut q);
        q.first().copied().unwrap_or(0.0)
    }) / steps;
    let mut motion = Motion::default();
    let ns_full = ns_per_call(budget, || {
        solver.resume(&start);
        motion.clear();
        let _ = solver.motion_into(rest, &mut motion);
        motion.qd.first().copied().unwrap_or(0.0)
    }) / steps;
    let mut rows = vec![
        Measurement::new(problem, "Assur groups", "positions", ns_pos, pos.0, pos.1),
        Measurement::new(problem, "Assur groups", "pos+vel+acc", ns_full, full.0, full.1),
    ];
    rows.extend(cold(budget, problem, s, &start, &score));
    Ok(rows)
}

/// A cold sweep, nanoseconds per position over the whole motion (its first position
/// included), positions only: a fresh solver (`cold, new`: the mechanism copied and
/// decomposed, the first position assembled by the general solver from the scene's
/// placement, as a run starts), and a solver refitted to the mechanism's numbers and resumed
/// from a known state (`cold, refit`: [`AssurSolver::refit`], the first position by the
/// groups' closed forms; what each tolerance sample costs). Error as [`assur`]'s, on each
/// route's own answers.
fn cold(
    budget: Budget,
    problem: &str,
    s: &LinkageScene,
    start: &State,
    score: &impl Fn(&State) -> (f64, f64),
) -> Vec<Measurement> {
    let n = s.times.len().max(1) as f64;
    let worst = |qs: &[f64]| {
        let nq = start.q.len().max(1);
        qs.chunks_exact(nq).zip(&s.times).fold((0.0_f64, 0.0_f64), |m, (q, &t)| {
            let v = score(&State { t, q: q.to_vec(), ..start.clone() });
            (m.0.max(v.0), m.1.max(v.1))
        })
    };
    let mut q = Vec::new();
    let ns_new = ns_per_call(budget, || {
        q.clear();
        AssurSolver::new(s.mechanism.clone()).map(|mut a| a.positions_into(&s.times, &mut q)).is_ok() as usize as f64
    }) / n;
    let fresh = worst(&q);
    let Ok(mut solver) = AssurSolver::new(s.mechanism.clone()) else { return Vec::new() };
    let ns_refit = ns_per_call(budget, || {
        q.clear();
        if solver.refit(|_| {}).is_err() {
            return 0.0;
        }
        solver.resume(start);
        solver.positions_into(&s.times, &mut q).is_ok() as usize as f64
    }) / n;
    let refit = worst(&q);
    vec![
        Measurement::new(problem, "Assur groups (cold)", "new", ns_new, fresh.0, fresh.1),
        Measurement::new(problem, "Assur groups (cold)", "refit", ns_refit, refit.0, refit.1),
    ]
}

fn scene_msg(m: String) -> crate::solve::linkage::LinkageError {
    crate::solve::linkage::LinkageError::Drag { what: m }
}

/// Median time of one whole motion divided by its steps, nanoseconds per solve.
fn per_step(budget: Budget, solver: &Solver, times: &[f64]) -> f64 {
    ns_per_call(budget, || solver.clone().run(times).map(|v| v.len()).unwrap_or(0)) / times.len() as f64
}

/// The shaper through the general solver at every goal. Error: the larger of the relative
/// constraint residual and the distance to the closed form of [`shaper::closed_form`]
/// (|Δx_E|, |Δy_E| over the rocker length, and the rocker angle's difference in radians).
pub fn shaper(budget: Budget) -> Result<Vec<Measurement>, Error> {
    let file = "shaper.toml";
    let Scene::Linkage(s) = parse(SHAPER, file, &[])? else { unreachable!("shaper.toml is a linkage scene") };
    let e = s.anchor("ram.E").map_err(|m| solve_err(file, scene_msg(m)))?;
    let rocker = crate::solve::linkage::Attach::Body(
        s.mechanism.bodies.iter().position(|b| b.name == "rocker").unwrap_or_default(),
    );
    let mut out = Vec::new();
    for tol in LINKAGE_NEWTON_TOL {
        let mut solver = Solver::new(s.mechanism.clone()).map_err(|e| solve_err(file, e))?;
        solver.set_newton_tolerance(tol);
        let mut check = solver.clone();
        let Ok(states) = check.run(&s.times) else { continue };
        let (mut res, mut dist) = (0.0_f64, 0.0_f64);
        for st in &states {
            res = res.max(residual_of(&mut check, st));
            let ([xe, _, _], [th, _, _]) = shaper::closed_form(st.t);
            let p = st.point(e);
            let (phi, _, _) = st.angular(rocker);
            dist = dist
                .max((p.x - xe).abs() / shaper::L)
                .max((p.y - shaper::Y_RAM).abs() / shaper::L)
                .max(reference::angle_distance(phi, th));
        }
        let ns = per_step(budget, &solver, &s.times);
        out.push(Measurement::new(
            "shaper (seed 002)",
            "general Newton",
            &format!("tol={}", fmt_e(tol)),
            ns,
            res,
            dist,
        ));
    }
    let check = std::cell::RefCell::new(Solver::new(s.mechanism.clone()).map_err(|e| solve_err(file, e))?);
    let score = |st: &State| {
        let res = residual_of(&mut check.borrow_mut(), st);
        let ([xe, _, _], [th, _, _]) = shaper::closed_form(st.t);
        let p = st.point(e);
        let (phi, _, _) = st.angular(rocker);
        let dist = ((p.x - xe).abs() / shaper::L)
            .max((p.y - shaper::Y_RAM).abs() / shaper::L)
            .max(reference::angle_distance(phi, th));
        (res, dist)
    };
    out.extend(assur(budget, "shaper (seed 002)", file, &s, score)?);
    Ok(out)
}

fn residual_of(solver: &mut Solver, st: &State) -> f64 {
    solver.residuals(st).map_or(f64::INFINITY, |r| r.iter().fold(0.0_f64, |m, v| m.max(v.abs())))
}

/// What a four-bar scene's `outputs` cost: the whole `run::run` (solve, figures, files)
/// into a scratch directory under `scratch`, for positions only, with kinematics, with
/// kineto-statics, each with and without frames. Milliseconds per run (median of `runs`).
pub fn outputs_cost(scratch: &Path, runs: usize) -> Result<Vec<RunCost>, Error> {
    let cases: [(&str, &str); 3] = [
        ("positions", r#"outputs=["position"]"#),
        ("kinematics", r#"outputs=["position","velocity","acceleration"]"#),
        ("kineto-statics", r#"outputs=["position","velocity","acceleration","forces"]"#),
    ];
    let mut out = Vec::new();
    for (name, set) in cases {
        let ov: Override = set.parse().map_err(Error::from)?;
        let scene = parse(FOURBAR_CHEBYSHEV, "fourbar-chebyshev.toml", &[ov])?;
        let loaded = Loaded { path: "fourbar-chebyshev.toml".into(), scene, text: FOURBAR_CHEBYSHEV.to_string() };
        for frames in [false, true] {
            let mut times = Vec::new();
            let mut files = 0;
            for r in 0..runs.max(1) {
                let dir = scratch.join(format!("run-{name}-{frames}-{r}"));
                let opts =
                    crate::run::RunOptions { out_dir: Some(dir.clone()), no_frames: !frames, ..Default::default() };
                let t0 = std::time::Instant::now();
                let outcome = crate::run::run(&loaded, &opts)?;
                times.push(t0.elapsed().as_secs_f64() * 1e3);
                files = outcome.written.len();
                std::fs::remove_dir_all(&dir).map_err(|e| Error::Io { path: dir.display().to_string(), source: e })?;
            }
            times.sort_by(f64::total_cmp);
            out.push(RunCost {
                scene: "fourbar-chebyshev (360 positions)".into(),
                outputs: name.into(),
                frames,
                files,
                ms_per_run: times[times.len() / 2],
            });
        }
    }
    Ok(out)
}
