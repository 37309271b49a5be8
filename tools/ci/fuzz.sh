#!/usr/bin/env bash
# Builds the libFuzzer targets with clang in build-fuzz/ and runs each for a
# bounded time (default 60 seconds each):
#   tools/ci/fuzz.sh [SECONDS]
# Each fuzzer starts from its seed corpus in tests/fuzz/corpus/<target>/, with
# tests/fuzz/<target>.dict as its dictionary (keys, nesting tokens, sizes), and
# keeps what it learns in build-fuzz/corpus/<target>/ (not committed). A crash
# is written to build-fuzz/findings/<target>/ and fails the script: copy the
# file to tests/fuzz/regressions/<target>/ so the test suite replays it.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
seconds="${1:-60}"
build="$root/build-fuzz"
targets=(scene_parser gltf_loader rasterizer)

bash "$root/tools/install_dependencies.sh"
source "$root/tools/compiler_cache.sh"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DTESSERA_BUILD_FUZZERS=ON -DTESSERA_BUILD_TESTS=OFF -DTESSERA_BUILD_GL_REFERENCE=OFF \
  -DTESSERA_BUILD_MICROBENCH=OFF "${compiler_cache[@]}" >/dev/null
cmake --build "$build" -j"$(nproc)" --target "${targets[@]/#/fuzz_}"

# Leaks in uninstrumented libraries (oneTBB's worker threads) are not findings.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=0}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1}"
status=0
for target in "${targets[@]}"; do
  corpus="$build/corpus/$target"
  findings="$build/findings/$target"
  mkdir -p "$corpus" "$findings"
  echo "== fuzz_$target for ${seconds}s"
  log="$build/fuzz_$target.log"
  dict=()
  [ -f "$root/tests/fuzz/$target.dict" ] && dict=(-dict="$root/tests/fuzz/$target.dict")
  if ! "$build/fuzz/fuzz_$target" -max_total_time="$seconds" -max_len=4096 -timeout=20 -rss_limit_mb=4096 \
      -artifact_prefix="$findings/" -print_final_stats=1 "${dict[@]}" \
      "$corpus" "$root/tests/fuzz/corpus/$target" >"$log" 2>&1; then
    status=1
    echo "fuzz_$target FOUND A PROBLEM (inputs in $findings/); the end of $log:"
    tail -n 40 "$log"
  fi
  grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "$log" | sed "s/^/  /" || true
done
exit "$status"
