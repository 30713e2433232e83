//! The same bytes on every platform (issue 30): the WebAssembly module (the live page's, built
//! from these sources by `bash web/build.sh`) and the native build write the same files, byte
//! for byte, for every template: every file `run::bytes::to_files` makes in the module — the
//! DXF, the SVG picture and sheets, every frame, the diagrams, the CSV and the JSON. (The
//! module has no PNG or PDF writer: features `png` and `pdf`, the command line's only.) The
//! module runs in Node's V8 (`tests/wasm_files.js`); the native side is `web::scene_files`,
//! which `tests/web_bytes.rs` holds to the `mechdraw` binary's files.
//!
//! wasm32 computes with Rust's libm port and the native build with whatever the crate calls:
//! any call of the platform's math library (glibc here) shows up as a last-digit difference
//! in a CSV, a JSON or a drawing (clippy.toml forbids them; docs/ci.md).
//!
//! Needs `node` and the module in `$CARGO_TARGET_DIR/web` (or `target/web`): `bash .ci/test`
//! builds it. Without the `system-tools` feature the test is reported as ignored.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use mechdraw::web::{self, WebOptions};

/// Where web/build.sh puts the module.
fn module_dir() -> PathBuf {
    let dir =
        std::env::var_os("CARGO_TARGET_DIR").map_or_else(|| common::root().join("target"), PathBuf::from).join("web");
    assert!(
        dir.join("mechdraw_bg.wasm").is_file() && dir.join("mechdraw.js").is_file(),
        "no WebAssembly module in {}: build it with `bash web/build.sh` (needs `rustup target add \
         wasm32-unknown-unknown` and wasm-bindgen-cli at Cargo.lock's version; `bash .ci/test` does all of it)",
        dir.display()
    );
    dir
}

/// One run of a scene, as both builds make it.
struct Job {
    file: String,
    text: String,
    opts: WebOptions,
}

fn job_json(job: &Job, out: &Path) -> serde_json::Value {
    serde_json::json!({
        "file": job.file,
        "text": job.text,
        "out": out,
        "frames": job.opts.frames,
    })
}

/// Runs `jobs` through the module in Node; job k's files land in `out/k/`.
fn run_module(jobs: &[Job], out: &Path) {
    let list: Vec<serde_json::Value> =
        jobs.iter().enumerate().map(|(k, j)| job_json(j, &out.join(k.to_string()))).collect();
    let list_file = out.join("jobs.json");
    std::fs::write(&list_file, serde_json::to_vec(&list).unwrap()).unwrap();
    let run = Command::new("node")
        .arg(common::root().join("tests/wasm_files.js"))
        .arg(module_dir())
        .arg(&list_file)
        .output()
        .expect("run node (Debian's nodejs)");
    assert!(run.status.success(), "the module failed:\n{}", String::from_utf8_lossy(&run.stderr));
}

/// The first byte where `a` and `b` differ, with a little of each around it.
fn first_difference(a: &[u8], b: &[u8]) -> String {
    let i = a.iter().zip(b).position(|(x, y)| x != y).unwrap_or(a.len().min(b.len()));
    let around = |s: &[u8]| String::from_utf8_lossy(&s[i.saturating_sub(20)..(i + 20).min(s.len())]).into_owned();
    format!("byte {i} of {}/{}: wasm {:?} vs native {:?}", a.len(), b.len(), around(a), around(b))
}

/// Every job's files from the module equal the native build's, name for name (in the same
/// order) and byte for byte; returns how many files were compared.
fn compare(jobs: &[Job]) -> usize {
    let tmp = tempfile::tempdir().unwrap();
    run_module(jobs, tmp.path());
    let mut compared = 0;
    let mut differ = Vec::new();
    for (k, job) in jobs.iter().enumerate() {
        let dir = tmp.path().join(k.to_string());
        let native = web::scene_files(&job.text, &job.file, job.opts).unwrap_or_else(|e| panic!("{}: {e}", job.file));
        let names: Vec<String> = serde_json::from_slice(&std::fs::read(dir.join(".names.json")).unwrap()).unwrap();
        let native_names: Vec<&str> = native.files.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, native_names, "{} ({:?}): the files and their order", job.file, job.opts);
        for (name, bytes) in &native.files {
            let wasm = std::fs::read(dir.join(name)).unwrap();
            if wasm != *bytes {
                differ.push(format!("{} ({:?}) {name}: {}", job.file, job.opts, first_difference(&wasm, bytes)));
            }
            compared += 1;
        }
    }
    assert!(
        differ.is_empty(),
        "{} of {compared} files differ between wasm32 and native:\n{}",
        differ.len(),
        differ.join("\n")
    );
    compared
}

fn scene_text(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap()
}

fn file_name(path: &Path) -> String {
    path.file_name().unwrap().to_string_lossy().into_owned()
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs node and the wasm module (bash web/build.sh): bash .ci/test, or cargo test --features system-tools"
)]
fn every_templates_files_are_the_same_bytes_from_wasm32_and_native() {
    let jobs: Vec<Job> = common::template_paths()
        .iter()
        .map(|p| Job {
            file: file_name(p),
            text: scene_text(p),
            opts: WebOptions { frames: true, ..WebOptions::default() },
        })
        .collect();
    let n = compare(&jobs);
    // Every template's whole run: frames, diagrams, sheets, tables (2055 files when written).
    assert!(n > 2000, "only {n} files compared");
}
