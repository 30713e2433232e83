//! Times the general linkage solver on the shaper (templates/shaper.toml) for the SolveSpace
//! comparison (benches/slvs_compare.py): one crank turn of 360 positions repeated, each
//! step solving positions (Newton–Raphson from the extrapolated previous step),
//! velocities and accelerations. Prints one JSON line:
//! `{"ns_per_step": …, "max_residual": …, "length_scale": …, "steps": …}`.
//!
//! Run with `cargo run --release --example linkage_shaper_timing`.

use std::time::Instant;

/// CPU time of this process (user + system), seconds, from /proc/self/stat (Linux; clock
/// ticks of 10 ms), or None elsewhere. On a shared machine it is the fairer figure.
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    let after = stat.rsplit_once(')')?.1;
    let fields: Vec<&str> = after.split_whitespace().collect();
    let utime: f64 = fields.get(11)?.parse().ok()?;
    let stime: f64 = fields.get(12)?.parse().ok()?;
    Some((utime + stime) / 100.0)
}

use mechdraw::scene::{self, Scene};
use mechdraw::solve::linkage::Solver;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("templates/shaper.toml");
    let Scene::Linkage(s) = scene::load(&path, &[])?.scene else { return Err("not a linkage scene".into()) };
    let length_scale = s.mechanism.length_scale;
    let mut solver = Solver::new(s.mechanism)?;
    solver.assemble(0.0)?;
    let dt = 1.0 / 360.0;
    let turns = 1000;
    let mut max_residual: f64 = 0.0;
    let mut k = 0u64;
    // Warm-up turn, then the timed turns.
    for _ in 0..360 {
        k += 1;
        solver.step(k as f64 * dt)?;
    }
    let cpu0 = cpu_seconds();
    let start = Instant::now();
    for _ in 0..turns * 360 {
        k += 1;
        solver.step(k as f64 * dt)?;
    }
    let elapsed = start.elapsed().as_nanos() as f64;
    let cpu_ns = match (cpu0, cpu_seconds()) {
        (Some(a), Some(b)) => format!("{:.1}", (b - a) * 1e9 / (turns * 360) as f64),
        _ => "null".to_string(),
    };
    // Residuals and Newton iterations over one more turn (not timed).
    let mut iterations = 0;
    for _ in 0..360 {
        k += 1;
        iterations += solver.step(k as f64 * dt)?;
        max_residual = max_residual.max(solver.state().residual);
    }
    println!(
        "{{\"ns_per_step\": {:.1}, \"cpu_ns_per_step\": {}, \"max_residual\": {:e}, \"newton_iterations_mean\": {:.3}, \"length_scale\": {}, \"steps\": {}}}",
        elapsed / (turns * 360) as f64,
        cpu_ns,
        max_residual,
        iterations as f64 / 360.0,
        length_scale,
        turns * 360
    );
    Ok(())
}
