#!/usr/bin/env bash
# Quick start, command 1: install what is missing, build in Release, and render
# the demo scene to spheres.png in the repository's top folder.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bash "$root/tools/install_dependencies.sh" render
source "$root/tools/compiler_cache.sh"  # when installed
# Only the renderer: tests and tools are tools/test.sh's (which turns them back on).
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release -DTESSERA_BUILD_TESTS=OFF \
  -DTESSERA_BUILD_GL_REFERENCE=OFF -DTESSERA_BUILD_MICROBENCH=OFF "${compiler_cache[@]}"
cmake --build "$root/build" --target tessera -j"$(nproc)"
"$root/build/tessera" render "$root/scenes/spheres.toml" -o "$root/spheres.png" --stats
echo "wrote $root/spheres.png"
