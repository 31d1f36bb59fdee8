#!/usr/bin/env bash
# Sets up raylab and opens its window on a scene (default: the lecture's
# assets/scenes/seed.xml). Without a display (no $DISPLAY or
# $WAYLAND_DISPLAY, e.g. over ssh) it renders the scene to out/NAME.png instead
# and says where the picture went.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
scene=${1:-assets/scenes/seed.xml}
if [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ]; then
  exec cargo run --release --quiet -p raylab -- "$scene"
fi
echo "raylab: no display here; rendering $scene to a PNG instead of opening the window"
mkdir -p out
out="out/$(basename "${scene%.*}").png"
cargo run --release --quiet -p raylab -- render "$scene" -o "$out" --spp 16
echo "The image is at $(pwd)/$out"
