#!/usr/bin/env bash
# SolveSpace (PyPI `slvs`) against mechdraw's linkage solver on the shaper's positions.
# Creates target/slvs-venv with slvs, builds the timing example in release mode, prints a
# Markdown table (time per position, residual). The machine may be shared: run it twice.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -x target/slvs-venv/bin/python ] || ! target/slvs-venv/bin/python -c "import slvs" 2>/dev/null; then
  python3 -m venv target/slvs-venv
  target/slvs-venv/bin/pip install --quiet --disable-pip-version-check slvs
fi
ours=$(cargo run --quiet --release --example linkage_shaper_timing)
target/slvs-venv/bin/python benches/slvs_compare.py "$ours"
