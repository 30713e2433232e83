//! The methods of `mechdraw bench` under criterion, at the settings that reach 1e-12 (the
//! chart's headline) and at one loose setting each: triad pattern method and Newton–Raphson,
//! all modes, the closed-form four-bar dyad, and the general Newton solver per time step on
//! the same four-bar and on the shaper (a whole 361-step motion per iteration).

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use mechdraw::bench::suite::{FOURBAR_LINKAGE, SHAPER, chebyshev_geometry, popa_triad};
use mechdraw::geom::{angle_of, rad};
use mechdraw::scene::{self, Scene};
use mechdraw::solve::fourbar::Prepared;
use mechdraw::solve::linkage::Solver;
use mechdraw::solve::triad::{NewtonOptions, PatternOptions, all_modes, newton_to, pattern, pattern::construct};

fn triad(c: &mut Criterion) {
    let t = popa_triad().expect("the seed's triad");
    let mut g = c.benchmark_group("methods/triad");
    for eps in [1e-6, 1e-12] {
        let o = PatternOptions { tol: eps, ..Default::default() };
        g.bench_function(format!("pattern eps={eps:e}"), |b| b.iter(|| pattern(black_box(&t), black_box(&o))));
    }
    let o = PatternOptions::default();
    let a = construct(&t, o.phi1_start, o.a2, o.orientation).expect("start triangle");
    let start = [0, 1, 2].map(|i| angle_of(a[i] - t.o[i]));
    let n = NewtonOptions { start, max_iterations: 50 };
    for tol in [1e-6, 1e-15] {
        g.bench_function(format!("newton tol={tol:e}"), |b| b.iter(|| newton_to(black_box(&t), black_box(&n), tol)));
    }
    g.bench_function("all modes", |b| b.iter(|| all_modes(black_box(&t), None)));
    g.finish();
}

fn fourbar_and_linkages(c: &mut Criterion) {
    let geom = chebyshev_geometry().expect("the Chebyshev four-bar");
    let p = Prepared::new(&geom);
    let mut k = 0usize;
    c.bench_function("methods/fourbar/closed-form dyad (one position)", |b| {
        b.iter(|| {
            k = (k + 7) % 360;
            p.position(black_box(rad(k as f64)), geom.branch)
        })
    });
    let mut g = c.benchmark_group("methods/general newton (361-step motion)");
    g.sample_size(20);
    for (name, text) in [("fourbar", FOURBAR_LINKAGE), ("shaper", SHAPER)] {
        let Ok(Scene::Linkage(s)) = scene::parse(text, name, &[]) else { panic!("{name} is a linkage scene") };
        for tol in [1e-6, 1e-14] {
            let mut solver = Solver::new(s.mechanism.clone()).expect("compiles");
            solver.set_newton_tolerance(tol);
            g.bench_function(format!("{name} tol={tol:e}"), |b| b.iter(|| solver.clone().run(black_box(&s.times))));
        }
    }
    g.finish();
}

criterion_group!(benches, triad, fourbar_and_linkages);
criterion_main!(benches);
