#!/usr/bin/env bash
# Sets up raylab and runs every check and test: formatting, clippy, no import
# cycles between modules, and the workspace's tests (unit, property,
# golden-image and end-to-end).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
# A clean build gains nothing from incremental caches; they cost ~2 GB of disk.
if [ "${CI:-}" = "true" ]; then export CARGO_INCREMENTAL=0; fi
cargo fmt --all -- --check
cargo clippy --workspace --all-targets --quiet -- -D warnings
python3 scripts/module_cycles.py --self-test
python3 scripts/module_cycles.py
cargo test --workspace
