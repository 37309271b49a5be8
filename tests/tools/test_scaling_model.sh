#!/usr/bin/env bash
# tools/bench/scaling_model.py on a real trace: a 1-thread `tessera bench --trace` of the demo scene at
# a small size. The model's 1-core frame must be the sum of the passes' work, more cores must
# never make a pass slower than its longest task allows, and it must name a pass.
#   test_scaling_model.sh SOURCE_DIR TESSERA_BINARY
set -euo pipefail
src="$1"
tessera="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
"$tessera" bench "$src/scenes/spheres.toml" --width 320 --height 180 --threads 1 --frames 3 --warmup 0 \
  --tile-size 32 --trace "$work/t.json" >/dev/null
python3 "$src/tools/bench/scaling_model.py" "$work/t.json" --cores 1,2,64 >"$work/model.txt"
cat "$work/model.txt"
python3 - "$work/model.txt" <<'PY'
import re, sys
lines = open(sys.argv[1]).read().splitlines()
rows = {l.split()[0]: l.split()[1:] for l in lines if re.match(r"^(vertex|triangles|tiles) +[0-9.]+ +[0-9]+ +[0-9.]+$", l)}
assert set(rows) == {"vertex", "triangles", "tiles"}, rows
work = {n: float(v[0]) for n, v in rows.items()}
longest = {n: float(v[2]) for n, v in rows.items()}
assert int(rows["tiles"][1]) == 10 * 6, rows["tiles"]  # 320x180 in 32-pixel tiles
frame = next(l for l in lines if l.startswith("frame ms")).split()[2:]
lo1 = float(frame[0].split("-")[0])
assert abs(lo1 - sum(work.values())) < 0.02, (lo1, work)  # one core: all the work, in sequence
lo64 = float(frame[2].split("-")[0])
assert lo64 >= max(longest.values()) - 1e-6 and lo64 < lo1, (lo64, lo1)
assert re.search(r"^first to serialise: (vertex|triangles|tiles) ", lines[-1]), lines[-1]
print("scaling_model: ok")
PY
