//! The browser's entry (`mechdraw::web`, exported to JavaScript on wasm32) gives the bytes
//! the command line writes: for every template, its files are those of `bytes::to_files`
//! over the scene loaded from disk, and those the `mechdraw` binary writes into its output
//! directory, name for name and byte for byte, in one order; a bad scene gives the message
//! the command line prints after `error: `.

mod common;

use std::path::Path;

use mechdraw::run::RunOptions;
use mechdraw::run::bytes::{self, WriteOptions};
use mechdraw::scene::{self, Override};
use mechdraw::web::{self, WebOptions};

fn names(files: &[(String, Vec<u8>)]) -> Vec<&str> {
    files.iter().map(|(n, _)| n.as_str()).collect()
}

#[test]
fn web_files_are_the_command_lines_bytes_for_every_template() {
    for (path, set) in common::reduced_templates() {
        let file = path.display().to_string();
        for frames in [true, false] {
            let web = web::scene_files(
                &common::text_with(&path, &set),
                &file,
                WebOptions { frames, ..WebOptions::default() },
            )
            .unwrap_or_else(|e| panic!("{file}: {e}"));

            // The library's own route: the scene read from disk, its products to bytes.
            let over: Vec<Override> = set.iter().map(|s| s.parse().unwrap()).collect();
            let loaded = scene::load(&path, &over).unwrap();
            let opts = RunOptions { no_frames: !frames, ..RunOptions::default() };
            let products = mechdraw::run::products(&loaded, &opts).unwrap();
            let memory =
                bytes::to_files(&products, &WriteOptions { no_frames: !frames, ..WriteOptions::default() }).unwrap();
            assert_eq!(names(&web.files), names(&memory), "{file} (frames {frames}): file names and order");
            for ((name, w), (_, m)) in web.files.iter().zip(&memory) {
                assert!(w == m, "{file}: {name} differs from bytes::to_files");
            }
            assert_eq!(web.summary, products.summary, "{file}: summary");
            assert_eq!(web.warnings, products.warnings, "{file}: warnings");

            // The command line's files on disk.
            let tmp = tempfile::tempdir().unwrap();
            let mut cmd = common::mechdraw();
            cmd.arg("run").arg(&path).arg("--out").arg(tmp.path()).arg("-q");
            for s in &set {
                cmd.arg("--set").arg(s);
            }
            if !frames {
                cmd.arg("--no-frames");
            }
            let out = cmd.output().unwrap();
            assert!(out.status.success(), "{file}: {}", String::from_utf8_lossy(&out.stderr));
            let mut disk = Vec::new();
            common::read_tree(tmp.path(), Path::new(""), &mut disk);
            if frames {
                // The live page is the command line's own (it carries the module).
                common::take_live_page(&mut disk, web.summary["name"].as_str().unwrap());
            }
            disk.sort();
            let mut sorted = web.files.clone();
            sorted.sort();
            assert_eq!(names(&sorted), names(&disk), "{file} (frames {frames}): file names");
            for ((name, w), (_, d)) in sorted.iter().zip(&disk) {
                assert!(w == d, "{file}: {name} differs from the command line's file");
            }
        }
    }
}

/// The message the `mechdraw` binary prints for `path`, without its `error: `.
fn cli_error(path: &Path) -> String {
    let tmp = tempfile::tempdir().unwrap();
    let out = common::mechdraw().arg("run").arg(path).arg("--out").arg(tmp.path()).arg("-q").output().unwrap();
    assert!(!out.status.success(), "{} should fail", path.display());
    let stderr = String::from_utf8(out.stderr).unwrap();
    stderr.trim_end().strip_prefix("error: ").unwrap_or_else(|| panic!("no `error: ` in {stderr:?}")).to_string()
}

#[test]
fn a_bad_scene_gives_the_command_lines_message() {
    let tmp = tempfile::tempdir().unwrap();
    let fourbar = std::fs::read_to_string(common::root().join("templates/fourbar-chebyshev.toml")).unwrap();
    let cases = [
        ("syntax.toml", "kind = \"fourbar\"\nname = [unclosed\n".to_string()),
        ("kind.toml", "kind = \"pentagon\"\nname = \"p\"\n".to_string()),
        // A negative crank: a field error naming the field.
        (
            "field.toml",
            common::text_with(&common::root().join("templates/fourbar-chebyshev.toml"), &["l1=-0.04".into()]),
        ),
        // A rocker far too long to meet the coupler at any crank angle: the solver's message.
        ("solve.toml", fourbar.replace("l_bc = 0.10", "l_bc = 1.0")),
    ];
    for (name, text) in cases {
        let path = tmp.path().join(name);
        std::fs::write(&path, &text).unwrap();
        let file = path.display().to_string();
        let expected = cli_error(&path);
        let got = web::scene_files(&text, &file, WebOptions::default()).map(|_| ()).unwrap_err().to_string();
        assert_eq!(got, expected, "{name}");
        assert!(got.contains(&file), "{name}: the message names the file: {got}");
    }
}
