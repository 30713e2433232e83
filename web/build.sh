#!/usr/bin/env bash
# The first live page (issue 17, docs/web.md): one self-contained HTML file with the core's
# WebAssembly module inside (base64), opening from file:// with no server. It opens a scene
# (default: the Chebyshev four-bar) in a web::Session: scrub and play its positions (the CLI's
# frames), a number field and a slider for every number of the scene (a --set path), its TOML
# in a text area; each change solves the scene again in the page and redraws it, with the
# CLI's message on an error, a triad's assembly modes, and the CLI's files to download.
#   bash web/build.sh [SCENE.toml]    ->  $CARGO_TARGET_DIR (or target)/web/mechdraw.html
# Needs the wasm32-unknown-unknown target and wasm-bindgen-cli at the version of the
# wasm-bindgen crate in Cargo.lock (cargo install wasm-bindgen-cli --version 0.2.130).
set -euo pipefail
cd "$(dirname "$0")/.."
target="${CARGO_TARGET_DIR:-target}"
scene="${1:-templates/fourbar-chebyshev.toml}"
cargo rustc --lib --profile wasm --target wasm32-unknown-unknown --no-default-features --crate-type cdylib
wasm-bindgen --target no-modules --no-typescript --remove-name-section --remove-producers-section --out-dir "$target/web" \
  "$target/wasm32-unknown-unknown/wasm/mechdraw.wasm"
python3 - "$target/web" "$scene" <<'PY'
import base64, pathlib, sys
out, scene = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
page = pathlib.Path("web/page.html").read_text()
wasm = (out / "mechdraw_bg.wasm").read_bytes()
for key, value in [
    ("__WASM_BINDGEN_JS__", (out / "mechdraw.js").read_text()),
    ("__WASM_BASE64__", base64.b64encode(wasm).decode()),
    ("__SCENE_TOML__", scene.read_text()),
    ("__SCENE_FILE__", scene.name),
]:
    page = page.replace(key, value, 1)
(out / "mechdraw.html").write_text(page)
print(f"{out / 'mechdraw.html'}: {len(page.encode())} bytes (module {len(wasm)} bytes)")
PY
