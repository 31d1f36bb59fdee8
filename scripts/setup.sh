#!/usr/bin/env bash
# Installs what raylab needs on a fresh Debian 12 machine that has Rust (rustup):
# a C and C++ toolchain (linking; FLIP's C++ in `raylab chart`); Mesa's software Vulkan (lavapipe) and the X client
# libraries the window loads at run time (no GPU needed); Xvfb,
# ImageMagick and xdotool (screenshots, resizing, keys) for the end-to-end tests of the real window; Python 3
# for the import-cycle check (scripts/module_cycles.py); GNU parallel for the farm script and its test; and the rustfmt/clippy components the checks use.
# Safe to run again: it installs only what is missing.
set -euo pipefail

packages=(
  gcc g++ libc6-dev ca-certificates
  mesa-vulkan-drivers libvulkan1
  libx11-6 libx11-xcb1 libxcursor1 libxi6 libxrandr2 libxkbcommon0 libxkbcommon-x11-0
  xvfb xauth imagemagick xdotool
  python3
  parallel
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "raylab setup: installing ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -q
  "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

if ! command -v cargo >/dev/null 2>&1; then
  echo "raylab setup: cargo not found; install Rust first (https://rustup.rs)" >&2
  exit 1
fi
if command -v rustup >/dev/null 2>&1; then
  for c in rustfmt clippy; do
    rustup component list --installed 2>/dev/null | grep -q "^$c" || rustup component add "$c"
  done
fi
