//! `mechdraw web`: the live page of every bundled template (or of the scenes given), the
//! module once beside them and an index linking them, written atomically; a bad scene is
//! reported by its file and nothing is written. And the sizes the pages must keep (issue
//! 32): a run's page ≤ 2 MB, the gallery ≤ 3 MB, the module no larger than reached (2.28 MB,
//! 960 KB gzipped; the 1.5 MB, 600 KB gzipped, is not met).
//! Sizes are deterministic (the module is `web/dist/`, built reproducibly); times are left
//! to the benchmark (`web/page_timing.py`).

mod common;

/// The module, as the pages carry it (inflated). Issue 32's target is 1.5 MB, not met yet:
/// the module was 1.92 MB when the page was rebuilt, 2.57 MB once issues 28, 29, 31 and the
/// page's report (33), tolerances (34) and synthesis (35) landed, 2.19 MB after the fourth
/// session's rounds (no rayon, no `dxf` crate, the linkage sweep one step at a time in the
/// module), 2.23 MB once that session's subscripts (31) and tolerance rates and zones (34)
/// were merged, 2.26 MB after the fifth session's drawings (31: the detail view, the names
/// near the pole, subscripts in tables and dimensions, the forces page's orders and
/// stretching; +26 KB): docs/web.md, "Size", says what is in it and what would take it
/// below 1.5 MB. This bound is what was reached (2 259 905 bytes), so that the module does
/// not grow unnoticed.
const MODULE_MAX_BYTES: usize = 2_280_000;
/// ... and gzipped (what a web server sends): the target is 600 KB, reached 947 151.
const MODULE_MAX_GZIP_BYTES: usize = 960_000;
/// A run's page: one self-contained file (module inside) that a student can mail.
const PAGE_MAX_BYTES: u64 = 2_000_000;
/// The whole gallery: every template's page and the module once.
const GALLERY_MAX_BYTES: u64 = 3_000_000;

#[test]
fn the_gallery_has_a_live_page_per_template_the_module_once_and_an_index() {
    let tmp = tempfile::tempdir().unwrap();
    let out = common::mechdraw().args(["web", "--out"]).arg(tmp.path()).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let index = std::fs::read_to_string(tmp.path().join("index.html")).unwrap();
    let module = std::fs::read_to_string(tmp.path().join("mechdraw-module.js")).unwrap();
    let b64 = std::fs::read_to_string(common::root().join("web/dist/mechdraw_bg.wasm.b64")).unwrap();
    assert!(module.contains(&format!("window.MECHDRAW_WASM = \"{b64}\";")), "the module is in mechdraw-module.js");
    let templates = common::template_paths();
    for path in &templates {
        let stem = path.file_stem().unwrap().to_string_lossy().into_owned();
        assert!(index.contains(&format!("href=\"{stem}.html\"")), "the index links {stem}");
        let page = std::fs::read_to_string(tmp.path().join(format!("{stem}.html"))).unwrap();
        assert!(page.contains("<script src=\"mechdraw-module.js\"></script>"), "{stem}: loads the module beside it");
        assert!(!page.contains(&b64[..1000]), "{stem}: the module is not copied into the page");
        // The scene's own text, with its comments, as the file has it.
        let text = std::fs::read_to_string(path).unwrap().replace("</", "<\\/");
        assert!(page.contains(text.trim()), "{stem}: the page carries the template's text");
    }
    assert_eq!(std::fs::read_dir(tmp.path()).unwrap().count(), templates.len() + 2);
    let total: u64 = std::fs::read_dir(tmp.path()).unwrap().map(|e| e.unwrap().metadata().unwrap().len()).sum();
    assert!(total <= GALLERY_MAX_BYTES, "the gallery is {total} bytes (at most {GALLERY_MAX_BYTES})");
}

#[test]
fn the_module_and_a_runs_page_are_small() {
    let wasm = std::fs::read(common::root().join("web/dist/mechdraw_bg.wasm")).unwrap();
    assert!(wasm.len() <= MODULE_MAX_BYTES, "the module is {} bytes (at most {MODULE_MAX_BYTES})", wasm.len());
    let gz = miniz_oxide::deflate::compress_to_vec(&wasm, 9).len() + 18;
    assert!(gz <= MODULE_MAX_GZIP_BYTES, "the module is {gz} bytes gzipped (at most {MODULE_MAX_GZIP_BYTES})");
    // The page `mechdraw run` writes, for the largest template scene: one file, module inside.
    let tmp = tempfile::tempdir().unwrap();
    let out = common::mechdraw()
        .arg("run")
        .arg(common::root().join("templates/fourbar-chebyshev.toml"))
        .args(["--set", "phi1_deg.step=30", "-q", "--out"])
        .arg(tmp.path())
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let page = tmp.path().join("fourbar-chebyshev.html");
    let len = std::fs::metadata(&page).unwrap().len();
    assert!(len <= PAGE_MAX_BYTES, "the run's page is {len} bytes (at most {PAGE_MAX_BYTES})");
    let text = std::fs::read_to_string(page).unwrap();
    assert!(!text.contains("<script src="), "the run's page is self-contained");
}

#[test]
fn a_bad_scene_is_named_and_nothing_is_written() {
    let tmp = tempfile::tempdir().unwrap();
    let bad = tmp.path().join("bad.toml");
    std::fs::write(&bad, "kind = \"fourbar\"\nname = \"x\"\n").unwrap();
    let good = common::root().join("templates/triad-popa.toml");
    let dir = tmp.path().join("site");
    let out = common::mechdraw().arg("web").arg(&good).arg(&bad).arg("--out").arg(&dir).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains(&bad.display().to_string()) && err.contains("units"), "{err}");
    assert!(!dir.exists(), "nothing written");
}
