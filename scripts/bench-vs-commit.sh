#!/usr/bin/env bash
# Render time of this checkout against another commit's, side by side on this machine: builds both in
# release (the other in a git worktree under target/bench-vs-commit/), then renders a few scenes with each, alternating,
# for several rounds, and prints the medians and the ratio new/old. A change that must not cost speed
# (a refactor, a new abstraction on the render path) keeps every ratio near 1.
#
#   scripts/bench-vs-commit.sh 43619cd                # 9 rounds, 400×300 at 16 spp
#   scripts/bench-vs-commit.sh HEAD~3 --rounds 15 --spp 32
#
# The machine is shared and noisy: only ratios from one run mean anything. Two identical binaries gave
# ratios of 0.96–1.03 in one 9-round run here, so a ratio within ±3% says nothing by itself.
set -euo pipefail
cd "$(dirname "$0")/.."

base=${1:?usage: scripts/bench-vs-commit.sh COMMIT [--rounds N] [--spp N]}
shift
rounds=9
spp=16
while [[ $# -gt 0 ]]; do
    case $1 in
        --rounds) rounds=$2; shift 2 ;;
        --spp) spp=$2; shift 2 ;;
        *) echo "unknown option $1" >&2; exit 2 ;;
    esac
done

commit=$(git rev-parse --short "$base")
tree=target/bench-vs-commit/$commit
bin=target/bench-vs-commit/bin
mkdir -p "$bin"
if [[ ! -d $tree ]]; then
    git worktree add --detach "$tree" "$commit" >/dev/null
fi
# The other commit builds in its own target folder (the first run builds its dependencies too): sharing
# this checkout's would leave one binary at target/release/raylab that cargo then thinks is up to date.
(cd "$tree" && cargo build --release -p raylab --quiet)
cp "$tree/target/release/raylab" "$bin/raylab-$commit"
cargo build --release -p raylab --quiet
cp target/release/raylab "$bin/raylab-new"

cases=("seed whitted" "cornell path" "glass whitted" "primitives path")
out=$(mktemp)
trap 'rm -f "$out"' EXIT
for round in $(seq 1 "$rounds"); do
    for case in "${cases[@]}"; do
        read -r scene integrator <<<"$case"
        # ABBA: the order alternates between rounds, so that going first or second favours neither.
        order=("$commit" new)
        if ((round % 2 == 0)); then order=(new "$commit"); fi
        for version in "${order[@]}"; do
            seconds=$("$bin/raylab-$version" render "assets/scenes/$scene.xml" --integrator "$integrator" \
                --spp "$spp" --width 400 --height 300 -o "$bin/out-$version.exr" |
                sed -n 's/.* in \([0-9.]*\) s.*/\1/p')
            echo "$scene $integrator $version $seconds" >>"$out"
        done
    done
done

python3 - "$out" "$commit" "$rounds" "$spp" <<'PY'
import statistics, sys
rows = [line.split() for line in open(sys.argv[1])]
commit, rounds, spp = sys.argv[2:]
print(f'render time, 400×300 at {spp} spp, median of {rounds} alternated rounds')
print(f'{"scene":<12}{"integrator":<12}{commit:>10}{"this":>10}{"this/" + commit:>16}')
for scene, integrator in dict.fromkeys((r[0], r[1]) for r in rows):
    median = lambda v: statistics.median(float(r[3]) for r in rows if r[:3] == [scene, integrator, v])
    old, new = median(commit), median('new')
    print(f'{scene:<12}{integrator:<12}{old:>9.3f}s{new:>9.3f}s{new / old:>16.3f}')
PY
