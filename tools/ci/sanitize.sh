#!/usr/bin/env bash
# Builds everything in Debug with AddressSanitizer + UndefinedBehaviorSanitizer
# in build-asan/ and runs the whole test suite there:
#   tools/ci/sanitize.sh [SANITIZERS]     # default address,undefined; "thread" builds build-tsan/
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
sanitizers="${1:-address,undefined}"
case "$sanitizers" in
  *thread*) build="$root/build-tsan" ;;
  *) build="$root/build-asan" ;;
esac

bash "$root/tools/install_dependencies.sh"
source "$root/tools/compiler_cache.sh"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Debug -DTESSERA_SANITIZE="$sanitizers" \
  -DTESSERA_BUILD_GL_REFERENCE=OFF -DTESSERA_BUILD_MICROBENCH=OFF "${compiler_cache[@]}" >/dev/null
cmake --build "$build" -j"$(nproc)"
# Any ASan report (leaks included) or UBSan report fails the test that caused it,
# except the third-party leaks listed in tools/ci/lsan.supp.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}"
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$root/tools/ci/lsan.supp:print_suppressions=0}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
ctest --test-dir "$build" --output-on-failure -j"$(nproc)"
