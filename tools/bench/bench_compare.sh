#!/usr/bin/env bash
# Two builds of Tessera side by side on one bench: the two alternate for several rounds
# (so both see the same machine noise) and the script prints, for the frame and each pass
# and step, each build's median over rounds and the median of the per-round ratios A/B
# (above 1: B is faster).
#   tools/bench/bench_compare.sh A_TESSERA B_TESSERA [ROUNDS] -- BENCH ARGUMENTS...
# e.g. tools/bench/bench_compare.sh old/tessera build/tessera 5 -- scenes/spheres.toml --threads 1 --frames 20
set -euo pipefail
[ $# -ge 3 ] || { echo "usage: bench_compare.sh A_TESSERA B_TESSERA [ROUNDS] -- BENCH ARGUMENTS..." >&2; exit 1; }
a="$1"
b="$2"
shift 2
rounds=5
if [ "$1" != "--" ]; then rounds="$1"; shift; fi
[ "${1:-}" = "--" ] || { echo "bench_compare: expected -- before the bench arguments" >&2; exit 1; }
shift
for binary in "$a" "$b"; do [ -x "$binary" ] || { echo "bench_compare: $binary is not an executable" >&2; exit 1; }; done
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
echo "A: $a"
echo "B: $b"
echo "bench $*, $rounds rounds; load before: $(cut -d' ' -f1-3 /proc/loadavg)"
for round in $(seq 1 "$rounds"); do
  "$a" bench "$@" --json >"$work/a.$round.json"
  "$b" bench "$@" --json >"$work/b.$round.json"
done
python3 - "$rounds" "$work" <<'PY'
import json, statistics, sys
rounds, work = int(sys.argv[1]), sys.argv[2]
A = [json.load(open(f"{work}/a.{r}.json")) for r in range(1, rounds + 1)]
B = [json.load(open(f"{work}/b.{r}.json")) for r in range(1, rounds + 1)]
print(f"{'':<12}{'A ms':>10}{'B ms':>10}{'A/B':>8}")
def row(name, get):
    a, b = [get(j) for j in A], [get(j) for j in B]
    ratios = [x / y for x, y in zip(a, b) if y > 0]
    ratio = f"{statistics.median(ratios):8.2f}" if ratios else f"{'-':>8}"
    print(f"{name:<12}{statistics.median(a):10.2f}{statistics.median(b):10.2f}{ratio}")
row("frame", lambda j: j["frame_ms_median"])
for stage in ("vertex", "triangles", "tiles", "clip_setup", "binning", "rasterize", "shade", "resolve"):
    row(stage, lambda j, stage=stage: j["stages_ms"][stage])
PY
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
