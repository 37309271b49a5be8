#!/usr/bin/env bash
# Thread scaling: median frame time of one scene on 1 thread and on N threads,
# measured side by side (the two alternate for several rounds, so both see the same
# machine noise), and the speed-up 1-thread / N-thread.
#   tools/bench_scaling.sh [SCENE] [WIDTH HEIGHT] [THREADS] [FRAMES]
# Defaults: scenes/spheres.toml 1280 720, 2 threads, 30 frames; ROUNDS (default 5)
# sets the rounds, BUILD_DIR the build folder (default build/, Release). The result is
# the median over rounds of each side's median frame time, and the median of the
# per-round speed-ups.
set -euo pipefail
source "$(dirname "$0")/bench_args.sh"
parse_bench_args bench_scaling "$@"
rounds="${ROUNDS:-5}"
build_targets tessera

median_ms() {  # median_ms THREADS: one bench run's median frame time
  "$build/tessera" bench "$scene" --width "$width" --height "$height" --threads "$1" \
    --frames "$frames" --warmup 3 --json |
    python3 -c 'import json, sys; print(json.load(sys.stdin)["frame_ms_median"])'
}

echo "scaling: $(basename "$scene") ${width}x${height}, 1 vs $threads threads, $frames frames, $rounds rounds"
one=()
many=()
for round in $(seq 1 "$rounds"); do
  a="$(median_ms 1)"
  b="$(median_ms "$threads")"
  one+=("$a")
  many+=("$b")
  printf '  round %d: 1 thread %8.2f ms   %d threads %8.2f ms   speed-up %5.2f\n' "$round" "$a" "$threads" "$b" \
    "$(python3 -c 'import sys; print(float(sys.argv[1]) / float(sys.argv[2]))' "$a" "$b")"
done

python3 - "$threads" "${one[*]}" "${many[*]}" <<'PY'
import statistics, sys
n = sys.argv[1]
one = [float(v) for v in sys.argv[2].split()]
many = [float(v) for v in sys.argv[3].split()]
print(f"1 thread  median {statistics.median(one):8.2f} ms")
print(f"{n} threads median {statistics.median(many):8.2f} ms")
print(f"speed-up {statistics.median(a / b for a, b in zip(one, many)):.2f}x (median of the per-round ratios)")
PY
