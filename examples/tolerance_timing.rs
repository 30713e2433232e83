//! Times the four-bar's Monte Carlo over the whole motion (issue 34's speed figure):
//! templates/fourbar-tolerances.toml (6 toleranced dimensions, M and the rocker watched:
//! 5 components at each of 360 positions), 1e4, 1e5 and 1e6 samples. Prints one JSON line per
//! sample count: wall and CPU seconds, ns per sample-position, threads.
//!
//! Run with `cargo run --release --example tolerance_timing [-- 10000 100000 1000000]`.

use std::time::Instant;

use mechdraw::scene::{self, Scene};
use mechdraw::solve::fourbar::solve_motion;
use mechdraw::solve::tolerance::fourbar::{FourbarModel, FourbarOutput, FourbarPoint};
use mechdraw::solve::tolerance::monte_carlo::{self, Model, chunk_count};
use mechdraw::solve::tolerance::{Component, Projection, linear_all, ranges};

/// CPU time of this process (user + system), seconds, from /proc/self/stat (Linux; clock
/// ticks of 10 ms), or None elsewhere.
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    let after = stat.rsplit_once(')')?.1;
    let fields: Vec<&str> = after.split_whitespace().collect();
    let utime: f64 = fields.get(11)?.parse().ok()?;
    let stime: f64 = fields.get(12)?.parse().ok()?;
    Some((utime + stime) / 100.0)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("templates/fourbar-tolerances.toml");
    let Scene::Fourbar(s) = scene::load(&path, &[])?.scene else { return Err("not a four-bar scene".into()) };
    let tol = s.tolerances.as_ref().ok_or("no [tolerances]")?;
    let motion = solve_motion(&s.spec)?;
    let outputs = vec![FourbarOutput::Point(FourbarPoint::M), FourbarOutput::Phi3];
    let model = FourbarModel::new(s.spec.geometry, &motion.positions, tol.study.params.clone(), outputs);
    let tangents = model.tangents(FourbarPoint::M);
    let normals = tangents.iter().map(|t| mechdraw::geom::perp(*t)).collect();
    let comp = |name: &str, projection| Component {
        name: name.into(),
        output: name.into(),
        part: "value",
        absolute: false,
        projection,
    };
    let comps = vec![
        comp("M.x", Projection::Channel(0)),
        comp("M.y", Projection::Channel(1)),
        comp("M.normal", Projection::Along { x: 0, y: 1, dirs: normals }),
        comp("M.along", Projection::Along { x: 0, y: 1, dirs: tangents }),
        comp("phi3", Projection::Channel(2)),
    ];
    let dims = &tol.study.dims;
    let linear = linear_all(&model, dims, &comps);
    let rs = ranges(&linear, comps.len());
    let counts: Vec<u64> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    let counts = if counts.is_empty() { vec![10_000, 100_000, 1_000_000] } else { counts };
    for n in counts {
        let (t0, c0) = (Instant::now(), cpu_seconds());
        let mc = monte_carlo::run(&model, dims, &comps, &rs, 400, n, 1, 0..chunk_count(n));
        let wall = t0.elapsed().as_secs_f64();
        let cpu = cpu_seconds().zip(c0).map(|(a, b)| a - b);
        let evals = n as f64 * model.positions() as f64;
        println!(
            "{{\"samples\": {n}, \"positions\": {}, \"dimensions\": {}, \"components\": {}, \"wall_s\": {wall:.3}, \"cpu_s\": {}, \"ns_per_sample_position_wall\": {:.1}, \"threads\": {}, \"failed\": {}}}",
            model.positions(),
            dims.len(),
            comps.len(),
            cpu.map_or("null".into(), |c| format!("{c:.2}")),
            1e9 * wall / evals,
            rayon::current_num_threads(),
            mc.failed_samples
        );
    }
    Ok(())
}
