#!/usr/bin/env bash
# The live pages (issue 17, docs/web.md): one self-contained HTML file per scene with the
# core's WebAssembly module inside (base64), opening from file:// with no server, and an
# index of them (the gallery a course can publish as static files).
#   bash web/build.sh [SCENE.toml ...]   ->  $CARGO_TARGET_DIR (or target)/web/<scene>.html, index.html
# Without arguments: every bundled template. Each page opens its scene in a web::Session:
# scrub and play the positions (the CLI's frames), drag a joint, a number field and a slider
# for every number of the scene (a --set path), its TOML in a text area; each change solves
# the scene again in the page and redraws it, with the CLI's message on an error, a triad's
# assembly modes, and the CLI's files to download.
# Needs the wasm32-unknown-unknown target and wasm-bindgen-cli at the version of the
# wasm-bindgen crate in Cargo.lock (cargo install wasm-bindgen-cli --version 0.2.130).
set -euo pipefail
cd "$(dirname "$0")/.."
target="${CARGO_TARGET_DIR:-target}"
if [ $# -eq 0 ]; then set -- templates/*.toml; fi
mkdir -p "$target/web" && rm -f "$target/web/"*.html
# The same bytes from any checkout: no absolute path of the checkout, the target directory or
# the cargo home in the module (panic locations, build scripts' generated sources).
abs_target="$(cd "$target" && pwd)"
export CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_RUSTFLAGS="--remap-path-prefix=$abs_target=/target --remap-path-prefix=$PWD=/mechdraw --remap-path-prefix=${CARGO_HOME:-$HOME/.cargo}=/cargo"
cargo rustc --lib --profile wasm --target wasm32-unknown-unknown --no-default-features --crate-type cdylib
wasm-bindgen --target no-modules --no-typescript --remove-name-section --remove-producers-section --out-dir "$target/web" \
  "$target/wasm32-unknown-unknown/wasm/mechdraw.wasm"
python3 - "$target/web" "$@" <<'PY'
import base64, html, json, pathlib, sys
out = pathlib.Path(sys.argv[1])
template = pathlib.Path("web/page.html").read_text()
glue = (out / "mechdraw.js").read_text()
wasm = base64.b64encode((out / "mechdraw_bg.wasm").read_bytes()).decode()
# The module's base64 once, for src/run/page.rs (through web/dist/): no run encodes it again.
(out / "mechdraw_bg.wasm.b64").write_text(wasm)
links = []
for scene in map(pathlib.Path, sys.argv[2:]):
    text = scene.read_text()
    page = template
    for key, value in [
        ("__WASM_BINDGEN_JS__", glue),
        ("__WASM_BASE64__", wasm),
        # Inside <script type="text/plain">: only "</" could end it early.
        ("__SCENE_TOML__", text.replace("</", "<\\/")),
        ("__SCENE_SETS__", "[]"),
        ("__SCENE_FILE__", json.dumps(scene.name)),
    ]:
        page = page.replace(key, value, 1)
    target = out / (scene.stem + ".html")
    target.write_text(page)
    title = next((l.split("=", 1)[1].strip().strip('"') for l in text.splitlines() if l.startswith("name")), scene.stem)
    kind = next((l.split("=", 1)[1].strip().strip('"') for l in text.splitlines() if l.startswith("kind")), "")
    links.append(f'<li><a href="{html.escape(target.name)}">{html.escape(title)}</a> ({html.escape(kind)})</li>')
    print(f"{target}: {len(page.encode())} bytes")
index = ("<!DOCTYPE html>\n<html lang=\"en\">\n<head><meta charset=\"utf-8\"><title>mechdraw live: the templates</title></head>\n"
         "<body>\n<h1>mechdraw live</h1>\n<p>Each page solves and draws its scene in the browser (no server): drag a joint, "
         "change any number, edit the TOML, download the files.</p>\n<ul>\n" + "\n".join(links) + "\n</ul>\n</body>\n</html>\n")
(out / "index.html").write_text(index)
print(f"{out / 'index.html'}: {len(links)} pages")
PY
