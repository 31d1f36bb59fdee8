#!/usr/bin/env bash
# Prints a SHA-256 of the pixels of every image raylab renders from the scenes in assets/ (and the glTF
# samples in ../shared/gltf when present): both integrators × both intersection methods, Sobol and adaptive
# sampling, and every AOV, as linear EXR (the film itself) and as PNG (the display conversion). A change
# that must not alter any image — a refactor, a faster traversal — keeps every line the same:
#
#   scripts/film-hashes.sh > before.txt        # on the old commit
#   scripts/film-hashes.sh --check before.txt  # on the new one: lists what differs, exits 1 if anything does
#
# Small images (160×120, 8 spp) keep it to about half a minute in release. The digests are of the pixels
# (scripts/image_digest.py), not the file bytes: an EXR's chunks are stored in whatever order the writer's
# threads finish them, and both formats record the scene's absolute path.
set -euo pipefail
cd "$(dirname "$0")/.."

check=""
if [[ "${1:-}" == "--check" ]]; then
    check="${2:?--check needs the file of an earlier run}"
fi

cargo build --release -p raylab --quiet
raylab=target/release/raylab
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

scenes=(assets/scenes/*.xml assets/reference/*.xml)
if [[ -d ../shared/gltf ]]; then
    scenes+=(../shared/gltf/*.gltf)
fi

size=(--width 160 --height 120)
hashes="$out/hashes.txt"
: >"$hashes"

render() { # NAME SCENE ARGS… : renders SCENE to $out/NAME.* and records its hash
    local name=$1 scene=$2
    shift 2
    "$raylab" render "$scene" "${size[@]}" "$@" -o "$out/$name" >/dev/null 2>&1
    printf '%s  %s %s\n' "$(python3 scripts/image_digest.py "$out/$name")" "$scene" "$*" >>"$hashes"
}

for scene in "${scenes[@]}"; do
    for integrator in whitted path; do
        for method in lecture robust; do
            render c.exr "$scene" --spp 8 --integrator "$integrator" --method "$method"
        done
        render c.png "$scene" --spp 8 --integrator "$integrator"
        render s.exr "$scene" --spp 8 --integrator "$integrator" --sampler sobol
        render a.exr "$scene" --integrator "$integrator" --adaptive 0.2 --spp 20
    done
    for aov in depth normal albedo object variance cost spp; do
        render "$aov.exr" "$scene" --spp 8 --aov "$aov"
        render "$aov.png" "$scene" --spp 8 --aov "$aov"
    done
done

if [[ -n "$check" ]]; then
    if diff <(sort -k2 "$check") <(sort -k2 "$hashes"); then
        echo "all $(wc -l <"$hashes") images identical" >&2
    else
        echo "images differ (< $check, > now)" >&2
        exit 1
    fi
else
    cat "$hashes"
fi
