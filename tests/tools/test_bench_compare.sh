#!/usr/bin/env bash
# tools/bench/bench_compare.sh with the built tessera as both A and B at a small size: every row is
# printed with both medians and a ratio, and bad arguments are refused with a message.
#   test_bench_compare.sh SOURCE_DIR TESSERA_BINARY
set -euo pipefail
src="$1"
tessera="$2"
out="$(bash "$src/tools/bench/bench_compare.sh" "$tessera" "$tessera" 2 -- "$src/scenes/spheres.toml" \
  --width 160 --height 90 --threads 1 --frames 2 --warmup 0)"
echo "$out"
for row in frame vertex triangles tiles clip_setup binning rasterize shade resolve; do
  grep -Eq "^$row +[0-9.]+ +[0-9.]+ +([0-9.]+|-)$" <<<"$out" || { echo "no row for $row"; exit 1; }
done
if bash "$src/tools/bench/bench_compare.sh" "$tessera" /nonexistent -- x 2>/dev/null; then
  echo "a missing binary was accepted"; exit 1
fi
if bash "$src/tools/bench/bench_compare.sh" "$tessera" "$tessera" 2 x 2>/dev/null; then
  echo "arguments without -- were accepted"; exit 1
fi
echo "bench_compare: ok"
