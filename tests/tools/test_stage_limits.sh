#!/usr/bin/env bash
# tools/bench/stage_limits.py on a real bench of the demo scene and a machine file with known peaks:
# the shade row's share of the FP issue peak and the resolve row's bytes must be what the
# bench's own counts give by the script's stated model, and every stage must have its row.
#   test_stage_limits.sh SOURCE_DIR TESSERA_BINARY
set -euo pipefail
src="$1"
tessera="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
"$tessera" bench "$src/scenes/spheres.toml" --width 320 --height 180 --threads 1 --frames 3 --warmup 0 --json \
  >"$work/bench.json"
# Google Benchmark's JSON rows, as tessera_microbench --benchmark_filter=machine/ writes them
# (a threaded row's rate is its threads' together): 32 flops per cycle at 2 GHz with AVX2 on one core,
# half of that with SSE4, twice with AVX-512.
python3 - "$work/machine.json" <<'PY'
import json, sys
rows = []
for isa, gflops in (("sse4", 32), ("avx2", 64), ("avx512", 128)):
    for threads in (1, 2):
        rows.append({"name": f"machine/flops/{isa}/real_time/threads:{threads}", "run_type": "iteration",
                     "items_per_second": gflops * threads * 1e9})
# A repetitions' aggregate that is not the median is skipped.
rows.append({"name": "machine/flops/avx2/real_time/threads:1_mean", "run_type": "aggregate",
             "aggregate_name": "mean", "items_per_second": 1e9})
for kind in ("read", "write", "copy"):
    for threads in (1, 2):
        rows.append({"name": f"machine/memory/{kind}/real_time/threads:{threads}", "run_type": "iteration",
                     "bytes_per_second": 10e9})
# Rows that are no ceiling (machine/handover) are skipped.
rows.append({"name": "machine/handover/other_core/manual_time", "run_type": "iteration", "bytes_per_second": 1e9})
json.dump({"benchmarks": rows}, open(sys.argv[1], "w"))
PY
python3 "$src/tools/bench/stage_limits.py" --machine "$work/machine.json" --bench-json "$work/bench.json" \
  --ops-per-fragment-light 50 >"$work/limits.txt"
cat "$work/limits.txt"
python3 - "$work/bench.json" "$work/limits.txt" <<'PY'
import json, re, sys
bench = json.load(open(sys.argv[1]))
text = open(sys.argv[2]).read()
for stage in ("vertex", "clip_setup", "binning", "rasterize", "shade", "resolve"):
    assert re.search(rf"^{stage} ", text, re.M), stage
assert "clock ~2.00 GHz" in text, text  # 64 GFLOP/s of AVX2 on one core / 32 flops per cycle
peak_ops = {"sse4": 32e9, "avx2": 64e9, "avx512": 128e9}[bench["isa"]] / 2
seconds = bench["stages_ms"]["shade"] / 1000
share = 100 * bench["fragment_lights"] * 50 / seconds / peak_ops
shown = float(re.search(r"^shade .* ([0-9.]+)% of FP issue peak", text, re.M).group(1))
assert abs(shown - share) < 0.06, (shown, share)
mb = (320 * 180 * 7 + bench["fragments_shaded"] * 12) / 1e6
assert abs(float(re.search(r"^resolve +[0-9.]+ +([0-9.]+) MB", text, re.M).group(1)) - mb) < 0.06, mb
print("stage_limits: ok")
PY
