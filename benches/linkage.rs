//! Speed of the general linkage solver on the shaper (templates/shaper.toml): one time
//! step (positions by Newton–Raphson from the extrapolated previous step, then velocities
//! and accelerations) and a whole turn of 360 steps. Targets: ≤ 5 µs per step, ≤ 2 ms
//! per 360 steps. Kineto-statics on templates/shaper-forces.toml: the forces of one
//! sample alone (the transposed solve on the step's LU, the generalised forces, the
//! reactions and the power balance: what forces add per sample, target ≤ 1 µs), and a
//! step with its forces. The Assur-group route on the shaper (issue 16: positions ≤ 5×
//! the four-bar's closed-form dyad, with velocities and accelerations ≤ 0.15 µs): one
//! step, one positions-only step, and the positions of the whole motion swept group by
//! group (what a positions-only run does).

use std::hint::black_box;

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use mechdraw::scene::linkage::LinkageScene;
use mechdraw::scene::{self, Scene};
use mechdraw::solve::linkage::{AssurSolver, Forces, Solver};

fn scene_of(template: &str) -> LinkageScene {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("templates").join(template);
    let Ok(loaded) = scene::load(&path, &[]) else { panic!("templates/{template} does not load") };
    let Scene::Linkage(s) = loaded.scene else { panic!("not a linkage scene") };
    s
}

fn solver_of(s: &LinkageScene) -> Solver {
    let Ok(mut solver) = Solver::new(s.mechanism.clone()) else { panic!("{} does not compile", s.name) };
    if solver.assemble(0.0).is_err() {
        panic!("{} does not assemble", s.name);
    }
    solver
}

fn shaper_solver() -> Solver {
    solver_of(&scene_of("shaper.toml"))
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
    let forces_scene = scene_of("shaper-forces.toml");
    let Some(dynamics) = forces_scene.dynamics.clone() else { panic!("shaper-forces has no forces") };
    let mut solver = solver_of(&forces_scene);
    if solver.step(0.3).is_err() {
        panic!("shaper-forces does not step");
    }
    let mut out = Forces::zeros(&forces_scene.mechanism);
    c.bench_function("linkage/shaper-forces kineto-statics of one sample", |b| {
        b.iter(|| black_box(solver.forces_into(black_box(&dynamics), &mut out).ok()))
    });
    let mut t = 0.3;
    c.bench_function("linkage/shaper-forces step + kineto-statics", |b| {
        b.iter(|| {
            t += dt;
            black_box(solver.step(black_box(t)).ok());
            black_box(solver.forces_into(&dynamics, &mut out).ok())
        })
    });
    // The Assur-group route (issue 16): the same shaper, group by group in closed form.
    let shaper = scene_of("shaper.toml");
    let Ok(mut assur) = AssurSolver::new(shaper.mechanism.clone()) else { panic!("shaper does not compile") };
    if assur.step(0.0).is_err() {
        panic!("shaper does not assemble");
    }
    let mut t = 0.0;
    c.bench_function("linkage/shaper Assur step (pos+vel+acc)", |b| {
        b.iter(|| {
            t += dt;
            black_box(assur.step(black_box(t)).ok())
        })
    });
    c.bench_function("linkage/shaper Assur step (positions)", |b| {
        b.iter(|| {
            t += dt;
            black_box(assur.step_positions(black_box(t)).ok())
        })
    });
    // The sweep a positions-only run uses: the whole motion after its first position.
    let Ok(start) = AssurSolver::new(shaper.mechanism.clone()).and_then(|mut a| a.run(&shaper.times[..1])) else {
        panic!("shaper does not assemble")
    };
    let rest = &shaper.times[1..];
    let mut q = Vec::with_capacity(rest.len() * 3 * shaper.mechanism.bodies.len());
    c.bench_function("linkage/shaper Assur sweep (positions, 360 steps)", |b| {
        b.iter(|| {
            assur.resume(&start[0]);
            q.clear();
            black_box(assur.positions_into(black_box(rest), &mut q).ok())
        })
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
