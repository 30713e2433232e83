//! What the tolerance suites (four-bar, linkage, triad) share: bands scaled, one component per
//! channel, and a study run whole and in shards merged.

use std::path::{Path, PathBuf};

use mechdraw::solve::tolerance::{Component, Dimension, Distribution, Projection};

/// The study's dimensions with every band scaled by `f` and spread by `dist`.
pub fn scaled(dims: &[Dimension], f: f64, dist: Distribution) -> Vec<Dimension> {
    dims.iter().map(|d| Dimension { upper: d.upper * f, lower: d.lower * f, distribution: dist, ..d.clone() }).collect()
}

/// One component per output channel of a model with `channels` channels: the channel's value,
/// absolute, named `ch<c>`.
pub fn channel_components(channels: usize) -> Vec<Component> {
    (0..channels)
        .map(|c| Component {
            name: format!("ch{c}"),
            output: format!("ch{c}"),
            part: "value",
            absolute: true,
            projection: Projection::Channel(c),
        })
        .collect()
}

/// A study run whole and in shards merged (run_sharded).
pub struct Sharded {
    /// The single run's output directory.
    pub single: PathBuf,
    /// The shard runs' output directory (only the shard files in it).
    pub shards: PathBuf,
    /// The merge's output directory.
    pub merged: PathBuf,
    /// The shard files, 1 to n.
    pub files: Vec<PathBuf>,
}

/// Runs `scene` (named `name`) whole into `dir/single` (with `single_args` besides `args`), in
/// `n` shards into `dir/shards` (last shard first when `reverse`, to show the order does not
/// matter) and merges the shards (given in the same order) into `dir/merged`; every run must
/// succeed.
pub fn run_sharded(
    dir: &Path,
    scene: &str,
    name: &str,
    n: usize,
    args: &[&str],
    single_args: &[&str],
    reverse: bool,
) -> Sharded {
    let (single, shards, merged) = (dir.join("single"), dir.join("shards"), dir.join("merged"));
    let ok = |o: std::process::Output| assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    ok(super::mechdraw()
        .args(["run", scene, "--out", single.to_str().unwrap()])
        .args(args)
        .args(single_args)
        .output()
        .unwrap());
    let mut order: Vec<usize> = (1..=n).collect();
    if reverse {
        order.reverse();
    }
    for &k in &order {
        let spec = format!("{k}/{n}");
        ok(super::mechdraw()
            .args(["run", scene, "--shard", &spec, "--out", shards.to_str().unwrap()])
            .args(args)
            .output()
            .unwrap());
    }
    let files: Vec<PathBuf> = (1..=n).map(|k| shards.join(format!("{name}-shard-{k}-of-{n}.json"))).collect();
    let mut merge = super::mechdraw();
    merge.args(["merge", "-q", "--out", merged.to_str().unwrap()]);
    merge.args(order.iter().map(|&k| &files[k - 1]));
    ok(merge.output().unwrap());
    Sharded { single, shards, merged, files }
}

/// Asserts that each of `files` has the same bytes in the single run's directory as in the
/// merge's.
pub fn assert_merged_equals_single(s: &Sharded, files: &[&str]) {
    for f in files {
        let (a, b) = (std::fs::read(s.single.join(f)).unwrap(), std::fs::read(s.merged.join(f)).unwrap());
        assert!(a == b, "{f} of the merged shards differs from the single run's");
    }
}

/// The Monte Carlo of `model` (`n` samples, seed 7, 400 bins, one component per channel)
/// against its linear stack-up under `dims`, at every position and channel: no sample
/// fails, σ within 5 sampling errors (σ/√(2N)) of the linear σ, the 99.865 % point within
/// 3 % of the RSS (the histogram's resolution and the sampling error); a channel whose
/// linear σ is at most `floor` is not compared.
pub fn assert_monte_carlo_sigma_is_linear<M: mechdraw::solve::tolerance::Sensitive>(
    model: &M,
    dims: &[Dimension],
    n: u64,
    floor: f64,
) {
    use mechdraw::solve::tolerance::monte_carlo::{self, chunk_count};
    use mechdraw::solve::tolerance::{linear_all, ranges};
    let comps = channel_components(model.channels());
    let linear = linear_all(model, dims, &comps);
    let mc = monte_carlo::run(model, dims, &comps, &ranges(&linear, comps.len()), 400, n, 7, 0..chunk_count(n));
    assert_eq!(mc.failed_samples, 0);
    let se = 1.0 / (2.0 * n as f64).sqrt();
    for (k, lin) in linear.iter().enumerate() {
        for c in 0..comps.len() {
            let l = &lin.as_ref().unwrap()[c];
            let t = mc.tallies[k * comps.len() + c].summary().unwrap();
            if l.sigma <= floor {
                continue;
            }
            assert!(
                (t.sigma / l.sigma - 1.0).abs() < 5.0 * se,
                "position {k}, channel {c}: MC σ {} vs linear σ {}",
                t.sigma,
                l.sigma
            );
            assert!((t.p_high - l.rss).abs() < 0.03 * l.rss, "p99.865 {} vs RSS {}", t.p_high, l.rss);
        }
    }
}

/// Central differences of a model's own samples (`Model::evaluate` with one dimension at
/// ±h, the others nominal): per position, channel-major (`channels · dims`), as
/// `Sensitive::sensitivities` lays them out. Every evaluation must assemble everywhere.
pub fn central_differences<M: mechdraw::solve::tolerance::monte_carlo::Model>(
    m: &M,
    np: usize,
    h: f64,
) -> Vec<Vec<f64>> {
    let (nc, n) = (m.channels(), m.positions());
    let mut work = m.work();
    let (mut plus, mut minus) = (vec![0.0; n * nc], vec![0.0; n * nc]);
    let mut failed = vec![false; n];
    let mut fd = vec![vec![0.0; nc * np]; n];
    for j in 0..np {
        let mut dev = vec![0.0; np];
        dev[j] = h;
        assert!(!m.evaluate(&mut work, &dev, &mut plus, &mut failed));
        dev[j] = -h;
        assert!(!m.evaluate(&mut work, &dev, &mut minus, &mut failed));
        for k in 0..n {
            for c in 0..nc {
                fd[k][c * np + j] = (plus[k * nc + c] - minus[k * nc + c]) / (2.0 * h);
            }
        }
    }
    fd
}
