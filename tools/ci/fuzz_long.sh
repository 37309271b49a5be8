#!/usr/bin/env bash
# Fuzzing at length: runs each libFuzzer target for SECONDS (default 3600) with
# its corpus kept between runs, then minimises that corpus:
#   tools/ci/fuzz_long.sh [SECONDS] [TARGET...]
#   tools/ci/fuzz_long.sh 3600                  every target an hour
#   tools/ci/fuzz_long.sh 300 gltf_loader       one target five minutes
# The corpus lives in build-fuzz/corpus/<target>/ (grown by tools/ci/fuzz.sh as
# well) and is kept: the next run goes on from it. Afterwards it is merged
# (-merge=1: the fewest inputs with the same coverage) into
# build-fuzz/minimized/<target>/; copy the small ones to tests/fuzz/corpus/<target>/
# to commit them (FUZZ_COMMIT_MINIMIZED=1 copies those up to 4 KB, at most 40
# a target). Crashes go to build-fuzz/findings/<target>/ and fail the script:
# copy them to tests/fuzz/regressions/<target>/ so the suite replays them.
# Prints, per target: executions, executions per second, corpus size, crashes.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
seconds="${1:-3600}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(scene_parser gltf_loader rasterizer)
build="$root/build-fuzz"
jobs="${FUZZ_BUILD_JOBS:-$(nproc)}"

if [ ! -x "$build/fuzz/fuzz_${targets[0]}" ] || [ "${FUZZ_REBUILD:-1}" = 1 ]; then
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
    -DTESSERA_BUILD_FUZZERS=ON -DTESSERA_BUILD_TESTS=OFF -DTESSERA_BUILD_GL_REFERENCE=OFF \
    -DTESSERA_BUILD_MICROBENCH=OFF >/dev/null
  cmake --build "$build" -j"$jobs" --target "${targets[@]/#/fuzz_}"
fi

export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=0}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1}"
status=0
printf '%-14s %12s %10s %8s %8s\n' target executions exec/s corpus crashes
for target in "${targets[@]}"; do
  corpus="$build/corpus/$target"
  findings="$build/findings/$target"
  minimized="$build/minimized/$target"
  mkdir -p "$corpus" "$findings"
  log="$build/fuzz_long_$target.log"
  dict=()
  [ -f "$root/tests/fuzz/$target.dict" ] && dict=(-dict="$root/tests/fuzz/$target.dict")
  before=$(ls "$findings" | wc -l)
  # -fork keeps fuzzing after a crash (each crash is kept) instead of stopping at the first.
  "$build/fuzz/fuzz_$target" -max_total_time="$seconds" -max_len=4096 -timeout=20 -rss_limit_mb=4096 \
    -fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 \
    -artifact_prefix="$findings/" -print_final_stats=1 "${dict[@]}" \
    "$corpus" "$root/tests/fuzz/corpus/$target" >"$log" 2>&1 || true
  crashes=$(( $(ls "$findings" | wc -l) - before ))
  # Executions: the fork mode's last status line ("#N ... exec/s: R").
  execs=$(grep -oE '^#[0-9]+' "$log" | tail -n 1 | tr -d '#')
  rate=$(grep -oE 'exec/s:? [0-9]+' "$log" | tail -n 1 | grep -oE '[0-9]+' || echo 0)
  rm -rf "$minimized" && mkdir -p "$minimized"
  "$build/fuzz/fuzz_$target" -merge=1 -max_len=4096 "$minimized" "$corpus" "$root/tests/fuzz/corpus/$target" \
    >"$build/fuzz_merge_$target.log" 2>&1 || true
  printf '%-14s %12s %10s %8s %8s\n' "$target" "${execs:-0}" "${rate:-0}" "$(ls "$minimized" | wc -l)" "$crashes"
  if [ "$crashes" -gt 0 ]; then
    status=1
    echo "  fuzz_$target FOUND $crashes PROBLEM(S): $findings/ (log: $log)"
  fi
  if [ "${FUZZ_COMMIT_MINIMIZED:-0}" = 1 ]; then
    find "$minimized" -type f -size -4097c | sort | head -n 40 | while read -r f; do
      cp "$f" "$root/tests/fuzz/corpus/$target/min_$(basename "$f" | cut -c1-12)"
    done
  fi
done
exit "$status"
