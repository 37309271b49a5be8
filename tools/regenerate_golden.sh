#!/usr/bin/env bash
# Re-renders every scene in scenes/ into golden/<scene>.png with the current build.
# Look at every changed image before committing it, and say in the commit why it changed.
#   usage: tools/regenerate_golden.sh [build-dir]   (default: build)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
cmake --build "$build" --target tessera -j"$(nproc)"
for scene in "$root"/scenes/*.toml; do
  name="$(basename "$scene" .toml)"
  "$build/tessera" render "$scene" -o "$root/golden/$name.png"
  echo "golden/$name.png"
done
