#!/usr/bin/env bash
# raylab's path tracer against Mitsuba 3 on the reference scenes, side by side
# in one run: time to reach an error, and samples per second (optional; not
# part of CI; needs Python 3 with venv, PyPI access, and Debian's libllvm19,
# installed with apt-get when missing).
#
#   scripts/bench-vs-mitsuba.sh [--rounds R] [--scenes a,b] [--max-seconds S]
#                               [--method M] [--out FILE] [--dir DIR [--references SPP]]
#
# The scenes are every assets/reference/NAME.xml with a NAME.exr beside it
# (--scenes picks some by NAME), or every DIR/NAME.xml: scenes not in the
# repository, such as those scripts/unseen_scenes.py writes. With
# --references SPP, a DIR/NAME.xml without its NAME.exr first gets one,
# rendered by Mitsuba at SPP samples per pixel (scripts/mitsuba_reference.py). The script installs mitsuba and numpy into a
# throw-away venv, builds raylab in release, then runs R rounds (default 3); in
# each, per scene, Mitsuba and raylab one after the other, the order swapped
# every other round, so that a busy neighbour slows both alike:
#   - Mitsuba (llvm_ad_rgb, scripts/mitsuba_time_to_error.py render): the
#     scene translated by scripts/mitsuba_reference.py as the reference was
#     rendered (path, max_depth 8, rr_depth 5, independent sampler, box
#     filter). A warm-up render at 1 spp compiles the kernel first; it and the
#     scene load are reported apart and not counted. Then renders of 1, 1, 2,
#     4, … more spp are averaged into images of 1, 2, 4, 8, … spp; a point's
#     time is the sum of the render times so far (progressive, like raylab's).
#     Stops once below 1e-3 or at S seconds.
#   - raylab: `raylab chart SCENE --reference NAME.exr --methods M --max-depth 8
#     --seconds S` (M default path-sobol; the path integrator counts max_depth
#     and starts Russian roulette as Mitsuba does). Its times are the passes'
#     render time, without scene load, BVH build or error measurement.
# Both run on every core (Dr.Jit's thread count, RAYON_NUM_THREADS). S is the
# render time each renderer gets per scene and round (default 35): a default
# run takes about 13 minutes on 2 cores. From each curve: the time to relMSE
# 1e-2 and 1e-3 (assets/reference/README.md's measure; the first point at or
# below, interpolated log-log with the point before; "not reached" if never
# within S) and spp per second (last point's spp over its time); medians over
# the rounds, a markdown table per scene with the ratios raylab/Mitsuba. The
# JSON, with every curve, goes to FILE (default: out/bench-vs-mitsuba.json).
set -euo pipefail
here=$PWD
cd "$(dirname "$0")/.."

rounds=3
max_seconds=35
method=path-sobol
out=out/bench-vs-mitsuba.json
picked=
dir=assets/reference
references=
while [ $# -gt 0 ]; do
  case "$1" in
    --rounds) rounds=$2; shift 2 ;;
    --scenes) picked=$2; shift 2 ;;
    --max-seconds) max_seconds=$2; shift 2 ;;
    --method) method=$2; shift 2 ;;
    --out) out=$2; [[ $out = /* ]] || out=$here/$out; shift 2 ;;
    --dir) dir=$2; [[ $dir = /* ]] || dir=$here/$dir; shift 2 ;;
    --references) references=$2; shift 2 ;;
    -h | --help) sed -n '2,38p' "$0"; exit 0 ;;
    *) echo "bench-vs-mitsuba: unknown option $1" >&2; exit 2 ;;
  esac
done

scenes=()
for xml in "$dir"/*.xml; do
  name=$(basename "$xml" .xml)
  [ -f "$dir/$name.exr" ] || [ -n "$references" ] || continue
  if [ -z "$picked" ] || [[ ",$picked," == *",$name,"* ]]; then scenes+=("$name"); fi
done
if [ ${#scenes[@]} -eq 0 ]; then
  echo "bench-vs-mitsuba: no reference scene (NAME.xml with NAME.exr) in $dir matches '${picked:-*}'" >&2
  exit 2
fi
for name in ${picked//,/ }; do
  [ -f "$dir/$name.exr" ] || [ -n "$references" ] || { echo "bench-vs-mitsuba: no $dir/$name.xml + .exr" >&2; exit 2; }
done

# Mitsuba's llvm variant JITs through the LLVM shared library it finds at
# DRJIT_LIBLLVM_PATH: Debian's libllvm19 (the .so.19.1 file; libLLVM-19.so links to it).
if [ -z "${DRJIT_LIBLLVM_PATH:-}" ]; then
  if ! dpkg -s libllvm19 >/dev/null 2>&1; then
    echo "== apt-get install libllvm19"
    sudo=()
    [ "$(id -u)" -eq 0 ] || sudo=(sudo)
    "${sudo[@]}" apt-get update -qq
    DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq libllvm19 >/dev/null
  fi
  DRJIT_LIBLLVM_PATH=$(readlink -f "$(dpkg -L libllvm19 | grep -m1 -E '/libLLVM[^/]*\.so[.0-9]*$')")
  export DRJIT_LIBLLVM_PATH
fi

tmp=$(mktemp -d "${TMPDIR:-/tmp}/raylab-vs-mitsuba.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

echo "== venv with mitsuba and numpy in $tmp"
python3 -m venv "$tmp/venv"
"$tmp/venv/bin/pip" install --quiet --disable-pip-version-check mitsuba numpy
py="$tmp/venv/bin/python"

for scene in "${scenes[@]}"; do
  if [ ! -f "$dir/$scene.exr" ]; then
    echo "== reference for $scene: Mitsuba at $references spp"
    "$py" scripts/mitsuba_reference.py "$dir/$scene.xml" "$references"
  fi
done

echo "== cargo build --release -p raylab"
cargo build --release --quiet -p raylab
raylab="${CARGO_TARGET_DIR:-target}/release/raylab"

threads=$(nproc)
mkdir -p "$tmp/rounds"
run() { # run LOG CMD...: CMD's stdout to LOG; its stderr shown only if it fails
  local log=$1; shift
  if ! "$@" >"$log" 2>"$tmp/stderr"; then
    cat "$tmp/stderr" >&2
    echo "bench-vs-mitsuba: failed: $*" >&2
    exit 1
  fi
}
run_mitsuba() {
  run "$tmp/rounds/mitsuba-$1-$2.json" "$py" scripts/mitsuba_time_to_error.py render \
    "$dir/$1.xml" --reference "$dir/$1.exr" \
    --max-seconds "$max_seconds" --threads "$threads" --seed "$2"
}
run_raylab() {
  run "$tmp/rounds/raylab-$1-$2.log" env RAYON_NUM_THREADS="$threads" "$raylab" chart \
    "$dir/$1.xml" --reference "$dir/$1.exr" --methods "$method" \
    --max-depth 8 --seconds "$max_seconds" --seed "$2" --output "$tmp/rounds/raylab-$1-$2"
}
for r in $(seq 1 "$rounds"); do
  for scene in "${scenes[@]}"; do
    echo "== round $r of $rounds: $scene"
    if [ $((r % 2)) -eq 1 ]; then
      run_mitsuba "$scene" "$r"; run_raylab "$scene" "$r"
    else
      run_raylab "$scene" "$r"; run_mitsuba "$scene" "$r"
    fi
  done
done

echo
"$py" scripts/mitsuba_time_to_error.py report "$tmp/rounds" --method "$method" --out "$out"
