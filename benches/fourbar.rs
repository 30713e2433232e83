//! Four-bar solver speed (issue targets): positions only ≤ 40 ns per crank angle;
//! positions + velocities + accelerations ≤ 80 ns per angle (360 angles ≤ 30 µs);
//! kineto-statics for 360 positions adds ≤ 100 µs.
//!
//! Run: `cargo bench --bench fourbar` (add `-- --quick` for a short run).

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use mechdraw::scene::{self, Scene};
use mechdraw::solve::fourbar::{MotionSpec, Outputs, Prepared, kinematics, solve_motion};
use mechdraw::solve::kinetostatics::forces;

fn template() -> MotionSpec {
    match scene::parse(include_str!("../templates/fourbar-chebyshev.toml"), "template", &[]) {
        Ok(Scene::Fourbar(s)) => s.spec,
        _ => panic!("the four-bar template does not load"),
    }
}

fn bench(c: &mut Criterion) {
    let spec = template();
    let g = spec.geometry;
    let prepared = Prepared::new(&g);
    let angles: Vec<f64> = (0..360).map(|k| f64::from(k).to_radians()).collect();

    let mut group = c.benchmark_group("fourbar_360_angles");
    group.throughput(Throughput::Elements(360));
    // Calibration on a shared machine: the libm calls a position needs at the least
    // (one sin_cos of phi1, two atan2 for phi2 and phi3).
    group.bench_function("calibration_sincos_2atan2", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for &phi in &angles {
                let (s, c) = black_box(phi).sin_cos();
                acc += s.atan2(c) + c.atan2(s);
            }
            acc
        })
    });
    group.bench_function("positions", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for &phi in &angles {
                if let Ok(p) = prepared.position(black_box(phi), g.branch) {
                    acc += p.m.x;
                }
            }
            acc
        })
    });
    group.bench_function("positions_velocities_accelerations", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for &phi in &angles {
                if let Ok(p) = prepared.position(black_box(phi), g.branch)
                    && let Ok(k) = kinematics(&g, &p, spec.omega1)
                {
                    acc += k.a_m.x;
                }
            }
            acc
        })
    });
    let mut kin_only = spec.clone();
    kin_only.outputs = Outputs { forces: false, ..Outputs::ALL };
    group.bench_function("solve_motion_kinematics", |b| b.iter(|| solve_motion(black_box(&kin_only))));
    let mut pos_only = spec.clone();
    pos_only.outputs = Outputs::POSITIONS;
    group.bench_function("solve_motion_positions", |b| b.iter(|| solve_motion(black_box(&pos_only))));
    group.bench_function("solve_motion_with_forces", |b| b.iter(|| solve_motion(black_box(&spec))));
    let motion = solve_motion(&kin_only).expect("template solves");
    let dynamics = spec.dynamics.clone().expect("template has dynamics");
    group.bench_function("kinetostatics_only", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for p in &motion.positions {
                if let Some(k) = &p.kin
                    && let Ok(f) = forces(&g, p, k, black_box(&dynamics))
                {
                    acc += f.me1;
                }
            }
            acc
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
