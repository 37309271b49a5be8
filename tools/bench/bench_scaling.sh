#!/usr/bin/env bash
# Thread scaling: median frame time of one scene on 1 thread and on N threads,
# measured side by side (the two alternate for several rounds, so both see the same
# machine noise), and the speed-up 1-thread / N-thread.
#   tools/bench/bench_scaling.sh [SCENE] [WIDTH HEIGHT] [THREADS] [FRAMES]
# Defaults: scenes/spheres.toml 1280 720, 2 threads, 30 frames; ROUNDS (default 5)
# sets the rounds, BUILD_DIR the build folder (default build/, Release). The result is
# the median over rounds of each side's median frame time, and the median of the
# per-round speed-ups; then each pass's (wall) and step's (busy time / threads) medians and
# speed-ups. EXTRA_ARGS (bench options split at spaces, e.g. "--msaa 4 --cull-back-faces") go to both sides.
set -euo pipefail
source "$(dirname "$0")/bench_args.sh"
parse_bench_args bench_scaling "$@"
rounds="${ROUNDS:-5}"
build_targets tessera
read -r -a EXTRA_ARGS <<<"${EXTRA_ARGS:-}"

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

bench_json() {  # bench_json THREADS FILE: one bench run's JSON
  "$build/tessera" bench "$scene" --width "$width" --height "$height" --threads "$1" \
    --frames "$frames" --warmup 3 --json "${EXTRA_ARGS[@]}" >"$2"
}

echo "scaling: $(basename "$scene") ${width}x${height}, 1 vs $threads threads, $frames frames, $rounds rounds"
for round in $(seq 1 "$rounds"); do
  bench_json 1 "$work/one.$round.json"
  bench_json "$threads" "$work/many.$round.json"
  python3 - "$round" "$threads" "$work/one.$round.json" "$work/many.$round.json" <<'PY'
import json, sys
a, b = (json.load(open(f))["frame_ms_median"] for f in sys.argv[3:5])
print(f"  round {sys.argv[1]}: 1 thread {a:8.2f} ms   {sys.argv[2]} threads {b:8.2f} ms   speed-up {a / b:5.2f}")
PY
done

python3 - "$threads" "$rounds" "$work" <<'PY'
import json, statistics, sys
n, rounds, work = sys.argv[1], int(sys.argv[2]), sys.argv[3]
one = [json.load(open(f"{work}/one.{r}.json")) for r in range(1, rounds + 1)]
many = [json.load(open(f"{work}/many.{r}.json")) for r in range(1, rounds + 1)]
frame1 = [j["frame_ms_median"] for j in one]
frame_n = [j["frame_ms_median"] for j in many]
print(f"1 thread  median {statistics.median(frame1):8.2f} ms")
print(f"{n} threads median {statistics.median(frame_n):8.2f} ms")
print(f"speed-up {statistics.median(a / b for a, b in zip(frame1, frame_n)):.2f}x (median of the per-round ratios)")
# Passes are wall time (idle workers included); steps are busy time over all workers / threads,
# so a step whose speed-up falls short of the threads is slowed by sharing the machine
# (memory, caches), and a pass that scales worse than its steps waits on load imbalance.
print(f"{'':<12}{'1 thread ms':>12}{n + ' threads ms':>14}{'speed-up':>10}")
for kind, names in (("pass", ("vertex", "triangles", "tiles")),
                    ("step", ("clip_setup", "binning", "rasterize", "shade", "resolve"))):
    for name in names:
        a = statistics.median(j["stages_ms"][name] for j in one)
        b = statistics.median(j["stages_ms"][name] for j in many)
        ratio = statistics.median(x["stages_ms"][name] / y["stages_ms"][name] for x, y in zip(one, many)
                                  if y["stages_ms"][name] > 0) if b > 0 else float("nan")
        print(f"{kind} {name:<10}{a:10.2f}{b:14.2f}{ratio:10.2f}x")
PY
