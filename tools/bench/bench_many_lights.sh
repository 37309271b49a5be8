#!/usr/bin/env bash
# Many lights: the frame time of the many-lights scene (tools/bench/make_many_lights.py N:
# the sphere grid over a floor, N small coloured point lights with range = "auto")
# at 1280x720, for each light count and thread count, with light culling three ways,
# measured side by side (the variants alternate within each round, so all see the
# same machine noise):
#   clustered  this build: ranges cut per pixel, lights culled per tile and per cluster
#   none       this build with --no-light-culling: every light at every pixel
#   baseline   BASELINE=path/to/tessera, any other build (e.g. commit 0ba3df5, per-tile
#              culling, or an older shading kernel); left out when BASELINE is not set
#   RANGE="3 5" adds scenes of local lights: the same lights, each with that explicit
#   range (make_many_lights.py --range); "auto", the default, is the committed scene's
#   (13-20 units). With an explicit range "none" still shades every light everywhere.
#   [BASELINE=old/tessera] [ROUNDS=5] [FRAMES=3] [LIGHTS="256 1024"] [THREADS="1 2"] [RANGE="auto 3"] \
#     tools/bench/bench_many_lights.sh
# Prints each round, then per configuration the median over rounds of each variant's
# median frame time, the median per-round ratios, the clustered variant's stage split
# (medians) and fragment-lights shaded per fragment, and the load average before and after.
set -euo pipefail
source "$(dirname "$0")/bench_args.sh"
parse_bench_args bench_many_lights spheres  # sets root and build; the scenes are generated
rounds="${ROUNDS:-5}"
frames="${FRAMES:-3}"
light_counts="${LIGHTS:-256 1024}"
thread_counts="${THREADS:-1 2}"
light_ranges="${RANGE:-auto}"
baseline="${BASELINE:-}"
build_targets tessera
[ -z "$baseline" ] || [ -x "$baseline" ] || { echo "bench_many_lights: BASELINE $baseline is not an executable" >&2; exit 1; }

scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT

# One bench run as JSON: run BINARY SCENE THREADS [extra flags]
run() {
  local binary="$1" scene="$2" threads="$3"
  shift 3
  "$binary" bench "$scene" --threads "$threads" --frames "$frames" --warmup 1 --json "$@"
}

echo "bench_many_lights: 1280x720, lights: $light_counts, ranges: $light_ranges, threads: $thread_counts, $frames frames, $rounds rounds"
echo "load before: $(uptime)"
for light_range in $light_ranges; do
for lights in $light_counts; do
  scene="$scratch/many_lights_${lights}_$light_range.toml"
  if [ "$light_range" = auto ]; then
    python3 "$root/tools/bench/make_many_lights.py" "$lights" >"$scene"
  else
    python3 "$root/tools/bench/make_many_lights.py" "$lights" --range "$light_range" >"$scene"
  fi
  for threads in $thread_counts; do
    results="$scratch/results_${lights}_${light_range}_$threads.jsonl"
    : >"$results"
    for round in $(seq 1 "$rounds"); do
      for variant in clustered none baseline; do
        case "$variant" in
          clustered) json="$(run "$build/tessera" "$scene" "$threads")" ;;
          none) json="$(run "$build/tessera" "$scene" "$threads" --no-light-culling)" ;;
          baseline) [ -n "$baseline" ] || continue; json="$(run "$baseline" "$scene" "$threads")" ;;
        esac
        printf '{"variant": "%s", "round": %d, "run": %s}\n' "$variant" "$round" "$json" >>"$results"
      done
      python3 - "$results" "$round" "$lights" "$threads" "$light_range" <<'PY'
import json, sys
rows = [json.loads(line) for line in open(sys.argv[1])]
now = {r["variant"]: r["run"]["frame_ms_median"] for r in rows if r["round"] == int(sys.argv[2])}
print(f"  {sys.argv[3]} lights (range {sys.argv[5]}), {sys.argv[4]} thread(s), round {sys.argv[2]}: " +
      "   ".join(f"{v} {ms:8.2f} ms" for v, ms in now.items()))
PY
    done
    python3 - "$results" "$lights" "$threads" "$light_range" <<'PY'
import json, statistics, sys
rows = [json.loads(line) for line in open(sys.argv[1])]
by = {}
for r in rows:
    by.setdefault(r["variant"], {})[r["round"]] = r["run"]
med = {v: statistics.median(run["frame_ms_median"] for run in runs.values()) for v, runs in by.items()}
print(f"{sys.argv[2]} lights (range {sys.argv[4]}), {sys.argv[3]} thread(s): " + "   ".join(f"{v} {ms:.2f} ms" for v, ms in med.items()))
for other in ("none", "baseline"):
    if other in by:
        ratio = statistics.median(by[other][k]["frame_ms_median"] / by["clustered"][k]["frame_ms_median"]
                                  for k in by["clustered"])
        print(f"  {other} / clustered: {ratio:.2f}x (median of per-round ratios)")
clustered = list(by["clustered"].values())
stages = clustered[0]["stages_ms"].keys()
print("  clustered stages (ms): " + ", ".join(
    f"{s} {statistics.median(r['stages_ms'][s] for r in clustered):.1f}" for s in stages))
for v, runs in by.items():
    run = next(iter(runs.values()))
    if "fragment_lights" in run:
        print(f"  {v}: {run['fragment_lights'] / run['fragments_shaded']:.1f} lights per fragment shaded, "
              f"{run['ns_per_fragment_light']:.2f} ns per fragment-light (shading step, one thread)")
PY
  done
done
done
echo "load after: $(uptime)"
