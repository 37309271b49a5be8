#!/usr/bin/env bash
# Batch throughput: a 720p turntable (scenes/turntable.toml, 240 frames) rendered
# to PNG in one process, and where each frame's time goes beyond the renderer's
# own frame time (what `tessera bench` measures): moving the scene to the frame,
# PNG encoding and the atomic write. Runs alternate, side by side, the default
# (the next frame renders while the previous one is encoded) and --serial-writes
# (each frame written before the next renders); the median run of each is quoted,
# with per-frame medians from the --log records of the serial runs.
#   tools/bench/bench_batch.sh [FRAMES] [RUNS]     defaults 0-239, 3 runs of each mode
# BUILD_DIR overrides the build folder. Compare with 4 Slurm array tasks on a one-node
# cluster: FRAMES=0-239 TASKS=4 tools/slurm/check_cluster.sh
set -euo pipefail
source "$(dirname "$0")/bench_args.sh"
parse_bench_args bench_batch turntable
frames="${1:-0-239}"
runs="${2:-3}"
build_targets tessera
out="$(mktemp -d /tmp/tessera_bench_batch.XXXXXX)"
trap 'rm -rf "$out"' EXIT

for run in $(seq "$runs"); do
  for mode in behind serial; do
    rm -f "$out"/*.png
    extra=()
    [ "$mode" = serial ] && extra=(--serial-writes)
    start=$(date +%s.%N)
    "$build/tessera" render "$scene" --width 1280 --height 720 --frames "$frames" "${extra[@]}" \
      -o "$out/frame_{frame:04}.png" --log "$out/$mode$run.jsonl" >/dev/null
    awk -v start="$start" -v now="$(date +%s.%N)" 'BEGIN { printf "%.3f\n", now - start }' >"$out/$mode$run.seconds"
  done
done
bench_json="$("$build/tessera" bench "$scene" --width 1280 --height 720 --frames 30 --warmup 3 --json)"

python3 - "$out" "$runs" "$bench_json" <<'PY'
import json, statistics, sys
out, runs, bench = sys.argv[1], int(sys.argv[2]), json.loads(sys.argv[3])
def median_run(mode):
    results = []
    for run in range(1, runs + 1):
        records = [json.loads(line) for line in open(f"{out}/{mode}{run}.jsonl")]
        seconds = float(open(f"{out}/{mode}{run}.seconds").read())
        results.append((seconds, records))
        print(f"{mode} run {run}: {len(records)} frames in {seconds:.1f} s = {len(records) / seconds:.2f} frames/s")
    return sorted(results, key=lambda r: r[0])[len(results) // 2]
behind_seconds, _ = median_run("behind")
seconds, records = median_run("serial")
n = len(records)
med = lambda key: statistics.median(r[key] for r in records)
print(f"median runs: write-behind {n / behind_seconds:.2f} frames/s, serial writes {n / seconds:.2f} frames/s "
      f"(x{seconds / behind_seconds:.2f}); wall-clock per frame {1000 * behind_seconds / n:.1f} vs {1000 * seconds / n:.1f} ms "
      f"(process start and scene load included)")
print(f"serial per-frame medians: whole {med('ms'):.1f} ms = setup {med('setup_ms'):.2f} + render {med('render_ms'):.1f} "
      f"+ encode and write {med('write_ms'):.1f}")
print(f"serial CPU time medians: render {med('render_cpu_ms'):.1f} ms (all threads), encode and write "
      f"{med('write_cpu_ms'):.1f} ms (one thread): wall above CPU is waiting for a busy machine")
print(f"tessera bench, frame 0 only: {bench['frame_ms_median']:.1f} ms median ({bench['threads']} threads)")
overhead = med('ms') - med('render_ms')
print(f"serial overhead beyond the render: {overhead:.1f} ms per frame ({100 * overhead / med('ms'):.0f}% of the frame)")
PY
