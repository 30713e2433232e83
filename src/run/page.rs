//! The live page `mechdraw run` writes as `<name>.html` (issue 17, docs/web.md): one
//! self-contained HTML file with the core compiled to WebAssembly inside it (base64), the
//! scene's text and its `--set` changes; it opens from `file://` with no server and solves
//! and draws the scene in the browser — scrub and play, drag a joint, change any number,
//! edit the TOML, download the files — with the same code as the command line.
//!
//! The module is `web/dist/` (built by `bash web/dist.sh`, which `.ci/test` runs with
//! `--check`: CI fails when the committed module is not the one the sources build); the page
//! is `web/page.html`, the template `web/build.sh` fills for the gallery too. The module is
//! included as its base64 text (`web/dist/mechdraw_bg.wasm.b64`, written by the same script):
//! a run copies the 10 MB into the page instead of encoding 7.5 MB each time.

/// The page's template.
const TEMPLATE: &str = include_str!("../../web/page.html");
/// wasm-bindgen's glue for the module (`--target no-modules`).
const GLUE: &str = include_str!("../../web/dist/mechdraw.js");
/// The core, compiled for wasm32-unknown-unknown (profile `wasm`) and through wasm-bindgen,
/// in standard base64 with padding and no line breaks (`web/dist/mechdraw_bg.wasm` encoded
/// by `web/build.sh`; a test checks that the two agree).
static MODULE_BASE64: &str = include_str!("../../web/dist/mechdraw_bg.wasm.b64");

/// The live page of the scene `text` (the scene file's text, named `file` in messages) with
/// `sets` (`KEY=VALUE`, as `--set` took them) applied when it opens.
pub fn live_page(text: &str, file: &str, sets: &[String]) -> String {
    LivePage::new(text, file, sets).strs().concat()
}

/// The live page of one scene, held as what is its own (the scene's text, its `--set`
/// changes, its file name, each made safe for its place in the page); [`LivePage::pieces`]
/// gives the page as pieces to write one after the other, the template's and the module's
/// borrowed from the program (no 10 MB page is built in memory).
#[derive(Debug, Clone)]
pub struct LivePage {
    scene: String,
    sets: String,
    file: String,
}

impl LivePage {
    /// The page of the scene `text` (named `file` in messages) with `sets` applied when it
    /// opens.
    pub fn new(text: &str, file: &str, sets: &[String]) -> LivePage {
        // JSON inside <script type="application/json">: "</" must not end it early.
        let sets = serde_json::to_string(sets).unwrap_or_else(|_| "[]".into()).replace("</", "<\\/");
        LivePage {
            scene: text.replace("</", "<\\/"),
            sets,
            file: serde_json::to_string(file).unwrap_or_else(|_| "\"scene.toml\"".into()),
        }
    }

    /// The page's bytes in pieces, in order: the template with each placeholder replaced
    /// once.
    pub fn pieces(&self) -> Vec<&[u8]> {
        self.strs().into_iter().map(str::as_bytes).collect()
    }

    fn strs(&self) -> Vec<&str> {
        let mut out = Vec::with_capacity(11);
        let mut rest = TEMPLATE;
        for (key, value) in [
            ("__SCENE_TOML__", self.scene.as_str()),
            ("__SCENE_SETS__", self.sets.as_str()),
            ("__WASM_BINDGEN_JS__", GLUE),
            ("__WASM_BASE64__", MODULE_BASE64),
            ("__SCENE_FILE__", self.file.as_str()),
        ] {
            if let Some(i) = rest.find(key) {
                out.push(&rest[..i]);
                out.push(value);
                rest = &rest[i + key.len()..];
            }
        }
        out.push(rest);
        out
    }
}

/// The bundled templates (`templates/*.toml`), for `mechdraw web` without scenes.
pub const TEMPLATES: &[(&str, &str)] = &[
    ("chain-humienny-2.toml", include_str!("../../templates/chain-humienny-2.toml")),
    ("chain-humienny-3.toml", include_str!("../../templates/chain-humienny-3.toml")),
    ("fourbar-chebyshev.toml", include_str!("../../templates/fourbar-chebyshev.toml")),
    ("fourbar-linkage.toml", include_str!("../../templates/fourbar-linkage.toml")),
    ("fourbar-tolerances.toml", include_str!("../../templates/fourbar-tolerances.toml")),
    ("shaper-forces.toml", include_str!("../../templates/shaper-forces.toml")),
    ("shaper.toml", include_str!("../../templates/shaper.toml")),
    ("slider-crank.toml", include_str!("../../templates/slider-crank.toml")),
    ("triad-driven.toml", include_str!("../../templates/triad-driven.toml")),
    ("triad-popa.toml", include_str!("../../templates/triad-popa.toml")),
];

/// Writes the live page of every scene (`(file name, text)`) into `dir` and an `index.html`
/// linking them — the gallery a course can publish as static files. Every scene is checked
/// first: a bad one is reported (by its file name) and nothing is written.
pub fn gallery(scenes: &[(String, String)], dir: &std::path::Path) -> Result<Vec<std::path::PathBuf>, crate::Error> {
    let mut items = Vec::with_capacity(scenes.len());
    for (file, text) in scenes {
        let scene = crate::scene::parse(text, file, &[])?;
        let stem =
            std::path::Path::new(file).file_stem().map_or_else(|| file.clone(), |s| s.to_string_lossy().into_owned());
        items.push((stem, file.clone(), text.clone(), scene.name().to_string(), scene.kind()));
    }
    let mut out = super::output::Output::new(dir)?;
    let mut index = String::from(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head><meta charset=\"utf-8\"><title>mechdraw live</title></head>\n<body>\n\
         <h1>mechdraw live</h1>\n<p>Each page solves and draws its scene in the browser, with no server: drag a joint, \
         change any number, edit the TOML, download the files the command line writes.</p>\n<ul>\n",
    );
    for (stem, file, text, name, kind) in &items {
        out.write_pieces(format!("{stem}.html"), &LivePage::new(text, file, &[]).pieces())?;
        index.push_str(&format!(
            "<li><a href=\"{}.html\">{}</a> ({kind}, {})</li>\n",
            escape(stem),
            escape(name),
            escape(file)
        ));
    }
    index.push_str("</ul>\n</body>\n</html>\n");
    out.write("index.html", index)?;
    out.commit()
}

/// `s` for HTML text and attribute values.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;
    use base64::Engine;

    #[test]
    fn every_placeholder_is_filled_once_in_order() {
        let page = live_page("kind = \"triad\"\n# </script>\n", "t.toml", &["l12=55".into()]);
        assert!(!page.contains("__SCENE_") && !page.contains("__WASM_"));
        assert!(page.contains("# <\\/script>"), "a scene cannot end its script block");
        assert!(page.contains(r#"["l12=55"]"#));
        assert!(page.contains(r#"const FILE = "t.toml";"#));
        let wasm =
            std::fs::read(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("web/dist/mechdraw_bg.wasm")).unwrap();
        assert!(page.contains(&base64::engine::general_purpose::STANDARD.encode(wasm)));
    }

    #[test]
    fn the_pieces_are_the_page() {
        let page = LivePage::new("name = \"x\"\n", "x.toml", &["a=1".into()]);
        let joined: Vec<u8> = page.pieces().concat();
        assert!(joined == live_page("name = \"x\"\n", "x.toml", &["a=1".into()]).into_bytes());
        assert!(page.pieces().iter().any(|p| p.as_ptr() == MODULE_BASE64.as_ptr()), "the module is not copied");
    }

    #[test]
    fn the_included_base64_is_the_module_in_web_dist() {
        let wasm =
            std::fs::read(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("web/dist/mechdraw_bg.wasm")).unwrap();
        assert!(MODULE_BASE64 == base64::engine::general_purpose::STANDARD.encode(&wasm), "run bash web/dist.sh");
        let back = base64::engine::general_purpose::STANDARD.decode(MODULE_BASE64).unwrap();
        assert!(back == wasm, "web/dist/mechdraw_bg.wasm.b64 decodes to web/dist/mechdraw_bg.wasm");
    }

    #[test]
    fn the_bundled_templates_are_templates_dir() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("templates");
        let mut on_disk: Vec<(String, String)> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|e| e == "toml"))
            .map(|p| (p.file_name().unwrap().to_string_lossy().into_owned(), std::fs::read_to_string(&p).unwrap()))
            .collect();
        on_disk.sort();
        let bundled: Vec<(String, String)> = TEMPLATES.iter().map(|(n, t)| (n.to_string(), t.to_string())).collect();
        assert_eq!(bundled, on_disk, "run::page::TEMPLATES must list templates/*.toml");
    }
}
