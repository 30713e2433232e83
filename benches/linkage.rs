//! Speed of the general linkage solver on the shaper (templates/shaper.toml): one time
//! step (positions by Newton–Raphson from the extrapolated previous step, then velocities
//! and accelerations) and a whole turn of 360 steps. Targets: ≤ 5 µs per step, ≤ 2 ms
//! per 360 steps.

use std::hint::black_box;

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use mechdraw::scene::{self, Scene};
use mechdraw::solve::linkage::Solver;

fn shaper_solver() -> Solver {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("templates/shaper.toml");
    let Ok(loaded) = scene::load(&path, &[]) else { panic!("templates/shaper.toml does not load") };
    let Scene::Linkage(s) = loaded.scene else { panic!("not a linkage scene") };
    let Ok(mut solver) = Solver::new(s.mechanism) else { panic!("shaper does not compile") };
    if solver.assemble(0.0).is_err() {
        panic!("shaper does not assemble");
    }
    solver
}

fn bench(c: &mut Criterion) {
    let dt = 1.0 / 360.0;
    let mut solver = shaper_solver();
    let mut t = 0.0;
    c.bench_function("linkage/shaper step (pos+vel+acc)", |b| {
        b.iter(|| {
            t += dt;
            black_box(solver.step(black_box(t)).ok())
        })
    });
    let start = shaper_solver();
    c.bench_function("linkage/shaper 360 steps", |b| {
        b.iter_batched(
            || start.clone(),
            |mut s| {
                for k in 1..=360 {
                    black_box(s.step(k as f64 * dt).ok());
                }
                s
            },
            BatchSize::SmallInput,
        )
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
