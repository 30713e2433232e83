//! `mechdraw web`: the live page of every bundled template (or of the scenes given) and an
//! index linking them, written atomically; a bad scene is reported by its file and nothing
//! is written.

mod common;

#[test]
fn the_gallery_has_a_live_page_per_template_and_an_index() {
    let tmp = tempfile::tempdir().unwrap();
    let out = common::mechdraw().args(["web", "--out"]).arg(tmp.path()).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let index = std::fs::read_to_string(tmp.path().join("index.html")).unwrap();
    let templates = common::template_paths();
    for path in &templates {
        let stem = path.file_stem().unwrap().to_string_lossy().into_owned();
        assert!(index.contains(&format!("href=\"{stem}.html\"")), "the index links {stem}");
        let mut files = vec![(format!("{stem}.html"), std::fs::read(tmp.path().join(format!("{stem}.html"))).unwrap())];
        let page = common::take_live_page(&mut files, &stem);
        // The scene's own text, with its comments, as the file has it.
        let text = std::fs::read_to_string(path).unwrap().replace("</", "<\\/");
        assert!(page.contains(text.trim()), "{stem}: the page carries the template's text");
    }
    assert_eq!(std::fs::read_dir(tmp.path()).unwrap().count(), templates.len() + 1);
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
