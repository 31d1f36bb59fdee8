#!/usr/bin/env bash
# A render split into bands of rows, rendered by GNU parallel (on this machine, or on others over
# ssh with its --sshlogin), then joined by `raylab merge`. Each sample is seeded by (seed, pixel,
# sample index), so the merged image is bit for bit the one `raylab render` makes in one go.
#
#   scripts/farm/parallel.sh SCENE WIDTH HEIGHT OUT.exr [--bands N] [--jobs J] [-- RENDER-ARGS…]
#
# e.g. scripts/farm/parallel.sh assets/scenes/seed.xml 1280 720 out/seed.exr --bands 8 --jobs 2 -- \
#        --integrator path --spp 256
#
# Over ssh: add `--sshlogin host1,host2 --workdir …` to the parallel line below (raylab and the scene
# must be at the same paths there; see `man parallel_tutorial`). Installs GNU parallel with apt-get
# when missing. Prints the merged image's path.
set -euo pipefail
cd "$(dirname "$0")/../.."

if [ $# -lt 4 ]; then
  sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
scene=$1 width=$2 height=$3 out=$4
shift 4
bands=4 jobs=$(nproc)
while [ $# -gt 0 ]; do
  case "$1" in
    --bands) bands=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --) shift; break ;;
    *) echo "unknown option $1" >&2; exit 2 ;;
  esac
done

if ! command -v parallel >/dev/null; then
  echo "== apt-get install parallel" >&2
  sudo=()
  [ "$(id -u)" -eq 0 ] || sudo=(sudo)
  "${sudo[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq parallel >/dev/null
fi
# RAYLAB: a raylab binary to use instead of building one (the test of this script passes its own).
if [ -n "${RAYLAB:-}" ]; then
  raylab=$RAYLAB
else
  cargo build --release -p raylab --quiet
  raylab=$PWD/target/release/raylab
fi
parts=$(mktemp -d)
trap 'rm -rf "$parts"' EXIT

# Band k: rows from k·H/N to (k+1)·H/N.
seq 0 $((bands - 1)) | parallel --will-cite --halt now,fail=1 -j "$jobs" \
  "$raylab" render "$scene" --width "$width" --height "$height" "$@" \
  --crop 0 '$(( {} * '"$height"' / '"$bands"' ))' "$width" '$(( ({} + 1) * '"$height"' / '"$bands"' ))' \
  -o "$parts/band-{}.exr" ">/dev/null"
"$raylab" merge "$out" "$parts"/band-*.exr
