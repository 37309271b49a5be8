#!/usr/bin/env bash
# Re-renders golden images with the current build. Look at every changed image
# before committing it, and say in the commit why it changed.
#   usage: tools/regenerate_golden.sh [build-dir] [scene.toml ...]   (default: build)
# Without scene files: every scenes/*.toml into golden/<scene>.png, and, when the
# sample models (../shared/assets) are there, every scenes/gltf/*.toml that already
# has a golden/gltf/<scene>.png. A new sample-model golden is made by naming its
# scene file (then remove it from golden_pending in tests/test_paths.hpp).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
shift || true
cmake --build "$build" --target tessera -j"$(nproc)"

render() {  # scene file, golden image
  "$build/tessera" render "$1" -o "$2"
  echo "${2#"$root"/}"
}

if [ $# -gt 0 ]; then
  for scene in "$@"; do
    scene="$(cd "$(dirname "$scene")" && pwd)/$(basename "$scene")"
    name="$(basename "$scene" .toml)"
    case "$scene" in
      "$root"/scenes/gltf/*) mkdir -p "$root/golden/gltf"; render "$scene" "$root/golden/gltf/$name.png" ;;
      *) render "$scene" "$root/golden/$name.png" ;;
    esac
  done
  exit 0
fi

for scene in "$root"/scenes/*.toml; do
  render "$scene" "$root/golden/$(basename "$scene" .toml).png"
done
if [ -d "$root/../shared/assets" ]; then
  for scene in "$root"/scenes/gltf/*.toml; do
    golden="$root/golden/gltf/$(basename "$scene" .toml).png"
    if [ -f "$golden" ]; then render "$scene" "$golden"; else echo "no golden yet for ${scene#"$root"/} (name it to make one)"; fi
  done
else
  echo "skipped scenes/gltf: no sample models at $root/../shared/assets"
fi
