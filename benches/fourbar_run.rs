//! Whole `mechdraw run` of the four-bar template (360 positions: solve, 360 SVG frames,
//! the DXF with a layer per position, CSV, JSON, 13 diagrams, the HTML viewer), as the
//! library runs it for the CLI; and its parts: the frames' drawings and SVG, the DXF.
//! Target (issue 3): the whole run ≤ 300 ms wall in release on the 2-core machine.
//!
//! The runs write into a temporary directory (`TMPDIR`). On a journal-less ext4 many
//! back-to-back runs slow file creation down (docs/fourbar-output.md, "Speed"); run with
//! `TMPDIR=/dev/shm cargo bench --bench fourbar_run` to time the program rather than that.

use std::path::PathBuf;

use criterion::{Criterion, criterion_group, criterion_main};
use mechdraw::run::{RunOptions, run};
use mechdraw::scene::load;

fn template() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("templates/fourbar-chebyshev.toml")
}

fn whole_run(c: &mut Criterion) {
    let loaded = load(&template(), &[]).expect("template loads");
    let dir = tempfile::tempdir().expect("temp dir");
    let mut g = c.benchmark_group("fourbar_run");
    g.sample_size(10);
    for (name, no_frames) in
        [("whole run (360 frames, DXF, viewer, diagrams, CSV, JSON)", false), ("without frames and viewer", true)]
    {
        let opts = RunOptions { out_dir: Some(dir.path().to_path_buf()), no_frames, ..RunOptions::default() };
        g.bench_function(name, |b| b.iter(|| run(&loaded, &opts).expect("run")));
    }
    let opts = RunOptions::default();
    g.bench_function("solve and summarise only (no files)", |b| b.iter(|| run(&loaded, &opts).expect("run")));
    g.finish();
}

criterion_group!(benches, whole_run);
criterion_main!(benches);
