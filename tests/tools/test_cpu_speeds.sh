#!/usr/bin/env bash
# tools/bench/cpu_speeds.sh on the built tessera at a small size: a median per allowed CPU and
# the slowest/fastest ratio, one cell when the process may use only one CPU, and bad
# arguments refused with a message.
#   test_cpu_speeds.sh SOURCE_DIR TESSERA_BINARY
set -euo pipefail
src="$1"
export BUILD_DIR="$(dirname "$2")"
run() { ROUNDS=1 bash "$src/tools/bench/cpu_speeds.sh" "$src/scenes/spheres.toml" 160 90 2; }
cpus="$(nproc)"
out="$(run)"
echo "$out"
row="$(grep -E '^  tessera ' <<<"$out")" || { echo "no tessera row"; exit 1; }
[ "$(grep -oE 'cpu[0-9]+ +[0-9.]+ ms' <<<"$row" | wc -l)" = "$cpus" ] || { echo "not one cell per CPU ($cpus)"; exit 1; }
grep -Eq 'slowest/fastest [0-9]+\.[0-9]{2}' <<<"$row" || { echo "no ratio"; exit 1; }
first="$(awk '/^Cpus_allowed_list/ {print $2}' /proc/self/status | grep -oE '^[0-9]+')"
one="$(taskset -c "$first" bash -c "$(declare -f run); src='$src' run")"
echo "$one"
grep -Eq "^  tessera +cpu$first +[0-9.]+ ms +slowest/fastest 1\.00\$" <<<"$one" || { echo "pinned to CPU $first: not one cell"; exit 1; }
if ROUNDS=0 bash "$src/tools/bench/cpu_speeds.sh" 2>/dev/null; then echo "ROUNDS=0 was accepted"; exit 1; fi
if bash "$src/tools/bench/cpu_speeds.sh" "$src/scenes/spheres.toml" 160 90 x 2>/dev/null; then
  echo "FRAMES=x was accepted"; exit 1
fi
echo "cpu_speeds: ok"
