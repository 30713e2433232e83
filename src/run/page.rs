//! The live page `mechdraw run` writes as `<name>.html` (issue 17, docs/web.md): one
//! self-contained HTML file with the core compiled to WebAssembly inside it (base64), the
//! scene's text and its `--set` changes; it opens from `file://` with no server and solves
//! and draws the scene in the browser — scrub and play, drag a joint, change any number,
//! edit the TOML, download the files — with the same code as the command line.
//!
//! The module is `web/dist/` (built by `bash web/dist.sh`, which `.ci/test` runs with
//! `--check`: CI fails when the committed module is not the one the sources build); the page
//! is `web/page.html`, the template `web/build.sh` fills for the gallery too.

use base64::Engine;

/// The page's template.
const TEMPLATE: &str = include_str!("../../web/page.html");
/// wasm-bindgen's glue for the module (`--target no-modules`).
const GLUE: &str = include_str!("../../web/dist/mechdraw.js");
/// The core, compiled for wasm32-unknown-unknown (profile `wasm`) and through wasm-bindgen.
const MODULE: &[u8] = include_bytes!("../../web/dist/mechdraw_bg.wasm");

/// The live page of the scene `text` (the scene file's text, named `file` in messages) with
/// `sets` (`KEY=VALUE`, as `--set` took them) applied when it opens.
pub fn live_page(text: &str, file: &str, sets: &[String]) -> String {
    let module = base64::engine::general_purpose::STANDARD.encode(MODULE);
    // JSON inside <script type="application/json">: "</" must not end it early.
    let sets = serde_json::to_string(sets).unwrap_or_else(|_| "[]".into()).replace("</", "<\\/");
    let mut page = String::with_capacity(TEMPLATE.len() + GLUE.len() + module.len() + text.len() + 256);
    let mut rest = TEMPLATE;
    for (key, value) in [
        ("__SCENE_TOML__", text.replace("</", "<\\/").as_str()),
        ("__SCENE_SETS__", sets.as_str()),
        ("__WASM_BINDGEN_JS__", GLUE),
        ("__WASM_BASE64__", module.as_str()),
        ("__SCENE_FILE__", &serde_json::to_string(file).unwrap_or_else(|_| "\"scene.toml\"".into())),
    ] {
        if let Some(i) = rest.find(key) {
            page.push_str(&rest[..i]);
            page.push_str(value);
            rest = &rest[i + key.len()..];
        }
    }
    page.push_str(rest);
    page
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_placeholder_is_filled_once_in_order() {
        let page = live_page("kind = \"triad\"\n# </script>\n", "t.toml", &["l12=55".into()]);
        assert!(!page.contains("__SCENE_") && !page.contains("__WASM_"));
        assert!(page.contains("# <\\/script>"), "a scene cannot end its script block");
        assert!(page.contains(r#"["l12=55"]"#));
        assert!(page.contains(r#"const FILE = "t.toml";"#));
        let b64 = base64::engine::general_purpose::STANDARD.encode(MODULE);
        assert!(page.contains(&b64));
    }
}
