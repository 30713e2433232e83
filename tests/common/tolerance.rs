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
