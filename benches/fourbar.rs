//! Four-bar solver speed (issue targets): positions only ≤ 40 ns per crank angle;
//! positions + velocities + accelerations ≤ 80 ns per angle (360 angles ≤ 30 µs);
//! kineto-statics for 360 positions adds ≤ 100 µs.
//!
//! "Positions" are the joints A, B and the coupler point M (what the kinematics, the
//! drawings and the closure checks use); the link angles φ2, φ3 are derived on demand
//! (`Position::phi2`), and `positions_with_link_angles` measures them on top.
//!
//! Every benchmark runs over the template's 360 crank angles (throughput: 360 elements, so
//! criterion's elem/s gives the per-angle figure). Two clocks: wall time, and this
//! thread's CPU time (`*_cpu`, via `clock_gettime(CLOCK_THREAD_CPUTIME_ID)`), which on a
//! shared, overloaded machine leaves out the time the thread waits for a core.
//!
//! Run: `cargo bench --bench fourbar` (add `-- --quick` for a short run).

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkGroup, Criterion, Throughput, criterion_group, criterion_main, measurement::WallTime};
use mechdraw::scene::{self, Scene};
use mechdraw::solve::fourbar::forces;
use mechdraw::solve::fourbar::{MotionSpec, Outputs, Prepared, kinematics, solve_motion};

fn template() -> MotionSpec {
    match scene::parse(include_str!("../templates/fourbar-chebyshev.toml"), "template", &[]) {
        Ok(Scene::Fourbar(s)) => s.spec,
        _ => panic!("the four-bar template does not load"),
    }
}

/// This thread's CPU time.
fn thread_cpu() -> Duration {
    let mut ts = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: `ts` is a valid, writable timespec; the clock id is a constant Linux provides.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    assert_eq!(rc, 0, "clock_gettime(CLOCK_THREAD_CPUTIME_ID) failed");
    Duration::new(ts.tv_sec as u64, ts.tv_nsec as u32)
}

/// Benchmarks `f` under `name` (wall time) and `name_cpu` (thread CPU time).
fn both<R>(group: &mut BenchmarkGroup<'_, WallTime>, name: &str, f: impl Fn() -> R) {
    group.bench_function(name, |b| b.iter(&f));
    group.bench_function(format!("{name}_cpu"), |b| {
        b.iter_custom(|iters| {
            let t0 = thread_cpu();
            for _ in 0..iters {
                black_box(f());
            }
            thread_cpu() - t0
        })
    });
}

fn bench(c: &mut Criterion) {
    let spec = template();
    let g = spec.geometry;
    let prepared = Prepared::new(&g);
    let angles: Vec<f64> = (0..360).map(|k| f64::from(k).to_radians()).collect();
    let mut kin_only = spec.clone();
    kin_only.outputs = Outputs { forces: false, ..Outputs::ALL };
    let mut pos_only = spec.clone();
    pos_only.outputs = Outputs::POSITIONS;
    let motion = solve_motion(&kin_only).expect("template solves");
    let dynamics = spec.dynamics.clone().expect("template has dynamics");

    let mut group = c.benchmark_group("fourbar_360_angles");
    group.throughput(Throughput::Elements(360));
    // Calibration: the libm calls a position needs at the least (one sincos of phi1, two
    // atan2 for phi2 and phi3).
    both(&mut group, "calibration_sincos_2atan2", || {
        let mut acc = 0.0;
        for &phi in &angles {
            let (s, c) = libm::sincos(black_box(phi));
            acc += libm::atan2(s, c) + libm::atan2(c, s);
        }
        acc
    });
    both(&mut group, "positions", || {
        let mut acc = 0.0;
        for &phi in &angles {
            if let Ok(p) = prepared.position(black_box(phi), g.branch) {
                acc += p.m.x;
            }
        }
        acc
    });
    // The joint positions and, on top, the link angles φ2, φ3 that a position derives on
    // demand (two atan2): what the CSV and the diagrams read.
    both(&mut group, "positions_with_link_angles", || {
        let mut acc = 0.0;
        for &phi in &angles {
            if let Ok(p) = prepared.position(black_box(phi), g.branch) {
                acc += p.phi2() + p.phi3();
            }
        }
        acc
    });
    both(&mut group, "positions_velocities_accelerations", || {
        let mut acc = 0.0;
        for &phi in &angles {
            if let Ok(p) = prepared.position(black_box(phi), g.branch)
                && let Ok(k) = kinematics(&g, &p, spec.omega1)
            {
                acc += k.a_m.x;
            }
        }
        acc
    });
    both(&mut group, "solve_motion_positions", || solve_motion(black_box(&pos_only)));
    both(&mut group, "solve_motion_kinematics", || solve_motion(black_box(&kin_only)));
    both(&mut group, "solve_motion_with_forces", || solve_motion(black_box(&spec)));
    both(&mut group, "kinetostatics_only", || {
        let mut acc = 0.0;
        for p in &motion.positions {
            if let Some(k) = &p.kin
                && let Ok(f) = forces(&g, p, k, black_box(&dynamics))
            {
                acc += f.me1;
            }
        }
        acc
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
