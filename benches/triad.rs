//! Triad solvers on the seed's data (templates/triad-popa.toml): the pattern method from
//! phi1 = 90°, Newton–Raphson from the pattern's start triangle, every assembly mode, and
//! the whole `mechdraw run` of the template (process wall time, SVG + JSON + DXF written).
//! Targets: Newton ≤ 1 µs, all modes ≤ 20 µs, whole run ≤ 20 ms.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use mechdraw::geom::{Point, angle_of};
use mechdraw::solve::triad::{NewtonOptions, PatternOptions, Triad, all_modes, newton, pattern};

fn seed() -> Triad {
    Triad::new(
        [Point::new(15.0, 30.0), Point::new(90.0, 20.0), Point::new(150.0, 40.0)],
        [50.0, 60.0, 84.0],
        50.0,
        50.0,
        92.0,
    )
    .expect("the seed's triad is valid")
}

fn solvers(c: &mut Criterion) {
    let t = seed();
    let popts = PatternOptions::default();
    c.bench_function("triad/pattern (seed, from 90°)", |b| b.iter(|| pattern(black_box(&t), black_box(&popts))));

    let start_triangle = pattern(&t, &popts).expect("seed converges").start;
    let start = [0, 1, 2].map(|i| angle_of(start_triangle[i] - t.o[i]));
    let nopts = NewtonOptions { start, max_iterations: 50 };
    c.bench_function("triad/newton (seed, from the start triangle)", |b| {
        b.iter(|| newton(black_box(&t), black_box(&nopts)))
    });

    c.bench_function("triad/all modes (seed, both orientations)", |b| b.iter(|| all_modes(black_box(&t), None)));
}

fn whole_run(c: &mut Criterion) {
    let root = env!("CARGO_MANIFEST_DIR");
    let out = std::env::temp_dir().join(format!("mechdraw-bench-triad-{}", std::process::id()));
    let mut g = c.benchmark_group("triad/run");
    g.sample_size(20);
    g.bench_function("mechdraw run templates/triad-popa.toml (wall)", |b| {
        b.iter(|| {
            let status = std::process::Command::new(env!("CARGO_BIN_EXE_mechdraw"))
                .args(["run", "templates/triad-popa.toml", "--quiet", "--out"])
                .arg(&out)
                .current_dir(root)
                .status()
                .expect("run mechdraw");
            assert!(status.success());
        })
    });
    g.finish();
    let _ = std::fs::remove_dir_all(&out);
}

criterion_group!(benches, solvers, whole_run);
criterion_main!(benches);
