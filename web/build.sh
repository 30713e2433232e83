#!/usr/bin/env bash
# The live pages (docs/web.md): the core compiled to WebAssembly, and pages that carry it.
#   bash web/build.sh [SCENE.toml ...]   ->  $CARGO_TARGET_DIR (or target)/web/
# Without arguments: every bundled template. It writes
#   mechdraw_bg.wasm, mechdraw.js        the module and its glue (web/dist.sh copies them)
#   <scene>.html                         one self-contained page per scene, as `mechdraw run`
#                                        writes it (the module inside, base64): opens from
#                                        file:// with no server, mailed as one file
#   gallery/index.html, gallery/<scene>.html, gallery/mechdraw-module.js
#                                        the gallery as `mechdraw web` writes it: the module
#                                        once, in a script beside the pages (file:// and any
#                                        static web server)
# Needs the wasm32-unknown-unknown target, wasm-bindgen-cli at the version of the
# wasm-bindgen crate in Cargo.lock (cargo install wasm-bindgen-cli --version 0.2.130) and
# wasm-opt from npm's binaryen (WASM_OPT, default target/npm/node_modules/.bin/wasm-opt:
# npm install --prefix target/npm binaryen@132.0.0). .ci/test installs all three.
set -euo pipefail
cd "$(dirname "$0")/.."
target="${CARGO_TARGET_DIR:-target}"
wasm_opt="${WASM_OPT:-$target/npm/node_modules/.bin/wasm-opt}"
if [ $# -eq 0 ]; then set -- templates/*.toml; fi
mkdir -p "$target/web" && rm -f "$target/web/"*.html && rm -rf "$target/web/gallery"
# The same bytes from any checkout: no absolute path of the checkout, the target directory or
# the cargo home in the module (panic locations, build scripts' generated sources).
abs_target="$(cd "$target" && pwd)"
export CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_RUSTFLAGS="-C target-feature=+simd128 --remap-path-prefix=$abs_target=/target --remap-path-prefix=$PWD=/mechdraw --remap-path-prefix=${CARGO_HOME:-$HOME/.cargo}=/cargo"
cargo rustc --lib --profile wasm --target wasm32-unknown-unknown --no-default-features --crate-type cdylib
wasm-bindgen --target no-modules --no-typescript --remove-name-section --remove-producers-section --out-dir "$target/web" \
  "$target/wasm32-unknown-unknown/wasm/mechdraw.wasm"
# Size: binaryen's optimiser at -Oz, with the features rustc's wasm32 target emits.
"$wasm_opt" -Oz --enable-bulk-memory --enable-sign-ext --enable-mutable-globals --enable-nontrapping-float-to-int \
  --enable-reference-types --enable-multivalue --enable-simd --strip-debug --strip-producers --converge \
  "$target/web/mechdraw_bg.wasm" -o "$target/web/mechdraw_bg.opt.wasm"
mv "$target/web/mechdraw_bg.opt.wasm" "$target/web/mechdraw_bg.wasm"
python3 web/pages.py "$target/web" "$@"
