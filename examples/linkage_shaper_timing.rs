//! Times the general linkage solver on the shaper (templates/shaper.toml) for the SolveSpace
//! comparison (benches/slvs_compare.py): one crank turn of 360 positions repeated, each
//! step solving positions (Newton–Raphson from the extrapolated previous step),
//! velocities and accelerations. Prints one JSON line:
//! `{"ns_per_step": …, "max_residual": …, "length_scale": …, "steps": …}`.
//!
//! Run with `cargo run --release --example linkage_shaper_timing`.

use std::time::Instant;

use mechdraw::scene::{self, Scene};
use mechdraw::solve::linkage::Solver;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("templates/shaper.toml");
    let Scene::Linkage(s) = scene::load(&path, &[])?.scene else { return Err("not a linkage scene".into()) };
    let length_scale = s.mechanism.length_scale;
    let mut solver = Solver::new(s.mechanism)?;
    solver.assemble(0.0)?;
    let dt = 1.0 / 360.0;
    let turns = 300;
    let mut max_residual: f64 = 0.0;
    let mut k = 0u64;
    // Warm-up turn, then the timed turns.
    for _ in 0..360 {
        k += 1;
        solver.step(k as f64 * dt)?;
    }
    let start = Instant::now();
    for _ in 0..turns * 360 {
        k += 1;
        solver.step(k as f64 * dt)?;
    }
    let elapsed = start.elapsed().as_nanos() as f64;
    // Residuals and Newton iterations over one more turn (not timed).
    let mut iterations = 0;
    for _ in 0..360 {
        k += 1;
        iterations += solver.step(k as f64 * dt)?;
        max_residual = max_residual.max(solver.state().residual);
    }
    println!(
        "{{\"ns_per_step\": {:.1}, \"max_residual\": {:e}, \"newton_iterations_mean\": {:.3}, \"length_scale\": {}, \"steps\": {}}}",
        elapsed / (turns * 360) as f64,
        max_residual,
        iterations as f64 / 360.0,
        length_scale,
        turns * 360
    );
    Ok(())
}
