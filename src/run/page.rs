//! The live page `mechdraw run` writes as `<name>.html` (docs/web.md): one self-contained
//! HTML file with the core compiled to WebAssembly inside it (base64), the scene's text and
//! its `--set` changes; it opens from `file://` with no server and solves and draws the
//! scene in the browser — scrub and play, drag a joint or reshape the mechanism, build one
//! by clicking, change any number, edit the TOML, undo, share, download the files — with
//! the same code as the command line. And the gallery `mechdraw web` writes: the same page
//! per scene, the module once in `mechdraw-module.js` beside them.
//!
//! The module is `web/dist/` (built by `bash web/dist.sh`, which `.ci/test` runs with
//! `--check`: CI fails when the committed module is not the one the sources build); the page
//! is `web/page.html`, the template `web/pages.py` fills the same way for the tests. The
//! module is included deflated, as base64 text (`web/dist/mechdraw_bg.wasm.b64`, written by
//! the same script; the page inflates it with the browser's `DecompressionStream`): a run
//! copies it into the page instead of encoding it each time.

/// The page's template.
const TEMPLATE: &str = include_str!("../../web/page.html");
/// wasm-bindgen's glue for the module (`--target no-modules`).
const GLUE: &str = include_str!("../../web/dist/mechdraw.js");
/// The core, compiled for wasm32-unknown-unknown (profile `wasm`, wasm-bindgen, wasm-opt),
/// raw-deflated and in standard base64 with padding and no line breaks
/// (`web/dist/mechdraw_bg.wasm` packed by `web/pages.py`; a test checks that the two agree).
static MODULE_BASE64: &str = include_str!("../../web/dist/mechdraw_bg.wasm.b64");

/// The gallery's script with the module, beside its pages.
pub const MODULE_SCRIPT: &str = "mechdraw-module.js";

/// Where the page's module comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Module {
    /// Inside the page (a page on its own: `mechdraw run`).
    Inline,
    /// From [`MODULE_SCRIPT`] beside the page (the gallery).
    Beside,
}

/// The live page of the scene `text` (the scene file's text, named `file` in messages) with
/// `sets` (`KEY=VALUE`, as `--set` took them) applied when it opens, the module inside.
pub fn live_page(text: &str, file: &str, sets: &[String]) -> String {
    LivePage::new(text, file, sets).strs(Module::Inline).concat()
}

/// The gallery's module script: the glue, then the module's base64 as
/// `window.MECHDRAW_WASM`, in pieces.
pub fn module_script() -> [&'static str; 4] {
    [GLUE, "\nwindow.MECHDRAW_WASM = \"", MODULE_BASE64, "\";\n"]
}

/// The live page of one scene, held as what is its own (the scene's text, its `--set`
/// changes, its file name, each made safe for its place in the page); [`LivePage::pieces`]
/// gives the page as pieces to write one after the other, the template's and the module's
/// borrowed from the program (no page is built in memory).
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
    /// once, the module as `module` says.
    pub fn pieces(&self, module: Module) -> Vec<&[u8]> {
        self.strs(module).into_iter().map(str::as_bytes).collect()
    }

    fn strs(&self, module: Module) -> Vec<&str> {
        let script: Vec<&str> = match module {
            Module::Inline => {
                vec![
                    "<script>\n",
                    GLUE,
                    "\n</script>\n<script>window.MECHDRAW_WASM = \"",
                    MODULE_BASE64,
                    "\";</script>",
                ]
            }
            Module::Beside => vec!["<script src=\"", MODULE_SCRIPT, "\"></script>"],
        };
        let mut out = Vec::with_capacity(16);
        let mut rest = TEMPLATE;
        for (key, value) in [
            ("__SCENE_TOML__", vec![self.scene.as_str()]),
            ("__SCENE_SETS__", vec![self.sets.as_str()]),
            ("<!--__MODULE__-->", script),
            ("__SCENE_FILE__", vec![self.file.as_str()]),
        ] {
            if let Some(i) = rest.find(key) {
                out.push(&rest[..i]);
                out.extend(value);
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
    ("slider-crank-tolerances.toml", include_str!("../../templates/slider-crank-tolerances.toml")),
    ("slider-crank.toml", include_str!("../../templates/slider-crank.toml")),
    ("synthesis-crank-rocker.toml", include_str!("../../templates/synthesis-crank-rocker.toml")),
    ("synthesis-function.toml", include_str!("../../templates/synthesis-function.toml")),
    ("synthesis-motion.toml", include_str!("../../templates/synthesis-motion.toml")),
    ("synthesis-shaper.toml", include_str!("../../templates/synthesis-shaper.toml")),
    ("synthesis-slider-crank.toml", include_str!("../../templates/synthesis-slider-crank.toml")),
    ("triad-driven.toml", include_str!("../../templates/triad-driven.toml")),
    ("triad-popa.toml", include_str!("../../templates/triad-popa.toml")),
    ("triad-tolerances.toml", include_str!("../../templates/triad-tolerances.toml")),
];

/// Writes the live page of every scene (`(file name, text)`) into `dir`, the module once in
/// [`MODULE_SCRIPT`] beside them, and an `index.html` linking them — the gallery a course can
/// publish as static files or open from `file://`. Every scene is checked first: a bad one
/// is reported (by its file name) and nothing is written.
pub fn gallery(scenes: &[(String, String)], dir: &std::path::Path) -> Result<Vec<std::path::PathBuf>, crate::Error> {
    let mut items = Vec::with_capacity(scenes.len());
    for (file, text) in scenes {
        let scene = crate::scene::parse(text, file, &[])?;
        let stem =
            std::path::Path::new(file).file_stem().map_or_else(|| file.clone(), |s| s.to_string_lossy().into_owned());
        items.push((stem, file.clone(), text.clone(), scene.name().to_string(), scene.kind()));
    }
    let mut out = super::output::Output::new(dir)?;
    let script = module_script();
    let pieces: Vec<&[u8]> = script.iter().map(|s| s.as_bytes()).collect();
    out.write_pieces(MODULE_SCRIPT, &pieces)?;
    let mut index = String::from(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head><meta charset=\"utf-8\"><meta name=\"viewport\" content=\"width=device-width, \
         initial-scale=1\"><link rel=\"icon\" href=\"data:,\"><title>mechdraw live</title></head>\n<body>\n<h1>mechdraw live</h1>\n<p>Each page solves and draws \
         its scene in the browser, with no server: drag a joint, change any number, edit the TOML, download the files the \
         command line writes.</p>\n<ul>\n",
    );
    for (stem, file, text, name, kind) in &items {
        let page = super::paths::RelPath::join(&[&format!("{stem}.html")])?;
        out.write_pieces(page.as_str(), &LivePage::new(text, file, &[]).pieces(Module::Beside))?;
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
        assert!(!page.contains("__SCENE_") && !page.contains("__MODULE__"));
        assert!(page.contains("# <\\/script>"), "a scene cannot end its script block");
        assert!(page.contains(r#"["l12=55"]"#));
        assert!(page.contains(r#"const FILE = "t.toml";"#));
        assert!(page.contains("window.MECHDRAW_WASM = \"") && page.contains(GLUE), "the module inside");
        assert!(page.contains(MODULE_BASE64));
    }

    #[test]
    fn the_pieces_are_the_page() {
        let page = LivePage::new("name = \"x\"\n", "x.toml", &["a=1".into()]);
        let joined: Vec<u8> = page.pieces(Module::Inline).concat();
        assert!(joined == live_page("name = \"x\"\n", "x.toml", &["a=1".into()]).into_bytes());
        assert!(
            page.pieces(Module::Inline).iter().any(|p| p.as_ptr() == MODULE_BASE64.as_ptr()),
            "the module is not copied"
        );
        // In the gallery the page loads the module from the script beside it.
        let beside = String::from_utf8(page.pieces(Module::Beside).concat()).unwrap();
        assert!(beside.contains("<script src=\"mechdraw-module.js\"></script>") && !beside.contains(MODULE_BASE64));
    }

    #[test]
    fn the_included_base64_is_the_module_in_web_dist() {
        let wasm =
            std::fs::read(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("web/dist/mechdraw_bg.wasm")).unwrap();
        let packed = base64::engine::general_purpose::STANDARD.decode(MODULE_BASE64).expect("base64");
        let back = miniz_oxide::inflate::decompress_to_vec(&packed).expect("raw deflate");
        assert!(
            back == wasm,
            "web/dist/mechdraw_bg.wasm.b64 inflates to web/dist/mechdraw_bg.wasm: run bash web/dist.sh"
        );
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
