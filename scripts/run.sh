#!/usr/bin/env bash
# Sets up raylab and opens its window on a scene (default: the lecture's
# assets/scenes/seed.xml). Without a display (no $DISPLAY or
# $WAYLAND_DISPLAY, e.g. over ssh) it renders the scene to out/NAME.png (or
# out/NAME-2.png, … when taken) instead and says where the picture went.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
scene=${1:-assets/scenes/seed.xml}
if [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ]; then
  exec cargo run --release --quiet -p raylab -- "$scene"
fi
echo "raylab: no display here; rendering $scene to a PNG instead of opening the window"
mkdir -p out
# A free name: out/NAME.png, else out/NAME-2.png, … (an earlier picture stays).
name=$(basename "${scene%.*}")
out="out/$name.png"
n=2
while [ -e "$out" ]; do
  out="out/$name-$n.png"
  n=$((n + 1))
done
cargo run --release --quiet -p raylab -- render "$scene" -o "$out" --spp 16
echo "The image is at $(pwd)/$out"
