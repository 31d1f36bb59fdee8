#!/usr/bin/env bash
# Sets up raylab and runs it on the default scene. For now raylab renders
# assets/scenes/seed.xml (the lecture's scene) to out/seed.png; the window comes next.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
scene=${1:-assets/scenes/seed.xml}
mkdir -p out
out="out/$(basename "${scene%.*}").png"
cargo run --release --quiet -p raylab -- render "$scene" -o "$out" --spp 16
echo "The image is at $(pwd)/$out"
