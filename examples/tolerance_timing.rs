//! Times the four-bar's Monte Carlo over the whole motion (issue 34's speed figure):
//! templates/fourbar-tolerances.toml (6 toleranced dimensions, M and the rocker watched:
//! 5 components at each of 360 positions), 1e4, 1e5 and 1e6 samples, as `mechdraw bench`
//! times its 1e5 row (`mechdraw::bench::tolerance`). Prints one JSON line per sample count:
//! wall and CPU seconds, ns per sample-position, threads.
//!
//! Run with `cargo run --release --example tolerance_timing [-- 10000 100000 1000000]`, on an
//! idle machine.

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
    let counts: Vec<u64> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    let counts = if counts.is_empty() { vec![10_000, 100_000, 1_000_000] } else { counts };
    for n in counts {
        let c0 = cpu_seconds();
        let t = mechdraw::bench::tolerance::fourbar_monte_carlo(n)?;
        let cpu = cpu_seconds().zip(c0).map(|(a, b)| a - b);
        println!(
            "{{\"samples\": {n}, \"positions\": {}, \"dimensions\": {}, \"components\": {}, \"wall_s\": {:.3}, \"cpu_s\": {}, \"ns_per_sample_position_wall\": {:.1}, \"threads\": {}, \"failed\": {}}}",
            t.positions,
            t.dimensions,
            t.components,
            t.wall_s,
            cpu.map_or("null".into(), |c| format!("{c:.2}")),
            t.ns_per_sample_position,
            t.threads,
            t.failed
        );
    }
    Ok(())
}
