#!/usr/bin/env bash
# raylab against Embree on the same triangles and the same rays, side by side
# in one run (optional; not part of CI; needs Python 3 with venv and PyPI access).
#
#   scripts/bench-vs-embree.sh [SCENE] [--width W] [--height H] [--rounds R] [--out FILE] [--no-robust]
#
# SCENE is what `raylab bench` takes (default: knot, the 1,000,000-triangle
# torus knot on its floor, 1920×1080 rays). The script installs embreex and
# numpy into a throw-away venv, builds raylab in release, exports the scene and
# rays with `raylab bench SCENE --export`, then runs R rounds (default 5) of
#   raylab bench → Embree on 1 thread → Embree on all threads
# so that a busy neighbour slows both alike, and prints the medians over the
# rounds (each round's figure is itself a median of 5 casts): BVH build seconds,
# primary and incoherent closest-hit Mrays/s on 1 thread and on all threads,
# both hit fractions (they must agree) and the ratios raylab/Embree, plus
# raylab's batches of the same rays (World::intersect_batch: primary rays in
# packets of sixteen, a 4×4 tile each, incoherent rays interleaved) against Embree's
# one-at-a-time casts. The JSON goes to FILE (default:
# out/bench-vs-embree.json). See scripts/embree_cast.py
# for how Embree's thread count is controlled. Embree runs with
# RTC_SCENE_FLAG_ROBUST (embreex's default; raylab never loses a hit either)
# unless --no-robust.
set -euo pipefail
here=$PWD
cd "$(dirname "$0")/.."

scene=knot
rounds=5
out=out/bench-vs-embree.json
size=()
embree=()
while [ $# -gt 0 ]; do
  case "$1" in
    --width | --height) size+=("$1" "$2"); shift 2 ;;
    --rounds) rounds=$2; shift 2 ;;
    --out) out=$2; [[ $out = /* ]] || out=$here/$out; shift 2 ;;
    --no-robust) embree+=(--no-robust); shift ;;
    -h | --help) sed -n '2,22p' "$0"; exit 0 ;;
    -*) echo "bench-vs-embree: unknown option $1" >&2; exit 2 ;;
    *) scene=$1; shift ;;
  esac
done

tmp=$(mktemp -d "${TMPDIR:-/tmp}/raylab-vs-embree.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

echo "== venv with embreex and numpy in $tmp"
python3 -m venv "$tmp/venv"
"$tmp/venv/bin/pip" install --quiet --disable-pip-version-check embreex numpy
py="$tmp/venv/bin/python"

echo "== cargo build --release -p raylab"
cargo build --release --quiet -p raylab
raylab="${CARGO_TARGET_DIR:-target}/release/raylab"

mkdir -p "$tmp/rounds"
run() { # run LOG CMD...: CMD's stdout to LOG; its stderr shown only if it fails
  local log=$1; shift
  if ! "$@" >"$log" 2>"$tmp/stderr"; then
    cat "$tmp/stderr" >&2
    echo "bench-vs-embree: failed: $*" >&2
    exit 1
  fi
}
for r in $(seq 1 "$rounds"); do
  echo "== round $r of $rounds"
  if [ "$r" -eq 1 ]; then
    # Round 1's raylab run also exports the scene and rays it measures.
    run "$tmp/rounds/raylab-$r.json" "$raylab" bench "$scene" ${size[@]+"${size[@]}"} --json --export "$tmp/export"
    threads=$("$py" -c 'import json,sys; print(json.load(open(sys.argv[1]))["threads"])' "$tmp/rounds/raylab-1.json")
  else
    run "$tmp/rounds/raylab-$r.json" "$raylab" bench "$scene" ${size[@]+"${size[@]}"} --json
  fi
  run "$tmp/rounds/embree-1-$r.json" "$py" scripts/embree_cast.py cast "$tmp/export" --threads 1 ${embree[@]+"${embree[@]}"}
  run "$tmp/rounds/embree-all-$r.json" "$py" scripts/embree_cast.py cast "$tmp/export" --threads "$threads" ${embree[@]+"${embree[@]}"}
done

echo
"$py" scripts/embree_cast.py report "$tmp/rounds" --out "$out"
