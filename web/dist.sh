#!/usr/bin/env bash
# The module `mechdraw run` puts into its live pages (src/run/page.rs includes web/dist/):
#   bash web/dist.sh           builds the pages (web/build.sh) and copies the module to web/dist/
#   bash web/dist.sh --check   builds them and fails when web/dist/ is not what the sources build
# Run it after any change to the library's core and commit web/dist/ with the change.
# web/dist/mechdraw_bg.wasm.b64 is the module deflated, in base64 (what the page carries), made here once
# so that no run of mechdraw encodes 7.5 MB again.
set -euo pipefail
cd "$(dirname "$0")/.."
target="${CARGO_TARGET_DIR:-target}"
bash web/build.sh
stale=()
for f in mechdraw_bg.wasm mechdraw_bg.wasm.b64 mechdraw.js; do
  cmp -s "$target/web/$f" "web/dist/$f" || stale+=("$f")
done
if [ "${1:-}" = "--check" ]; then
  if [ ${#stale[@]} -gt 0 ]; then
    echo "web/dist/ is stale (${stale[*]} differ from what the sources build): run bash web/dist.sh and commit web/dist/" >&2
    exit 1
  fi
  echo "web/dist/ is what the sources build"
else
  cp "$target/web/mechdraw_bg.wasm" "$target/web/mechdraw_bg.wasm.b64" "$target/web/mechdraw.js" web/dist/
  echo "web/dist/: ${stale[*]:-nothing} updated"
fi
