#!/usr/bin/env bash
# Quick start, command 2: install what is missing, build everything in Release,
# and run the whole test suite through ctest.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bash "$root/tools/install_dependencies.sh"
source "$root/tools/compiler_cache.sh"
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release -DTESSERA_BUILD_TESTS=ON \
  -DTESSERA_BUILD_GL_REFERENCE=ON -DTESSERA_BUILD_MICROBENCH=ON "${compiler_cache[@]}"
cmake --build "$root/build" -j"$(nproc)"
ctest --test-dir "$root/build" --output-on-failure -j"$(nproc)"
