#!/usr/bin/env bash
# Every row of the llvmpipe race in one run, on one machine: 1280x720 and 3840x2160, 1 and 2
# threads, without and with 4x MSAA, back faces drawn (the scene's two-sided materials) and
# culled in both (CULL=1). Each row is tools/bench/race_llvmpipe.sh (alternating rounds, medians);
# the table prints Tessera's and llvmpipe's medians and llvmpipe/Tessera.
#   tools/bench/race_table.sh [SCENE] [FRAMES]        defaults: spheres, 20 frames; ROUNDS (default 3)
# ROWS="720p:1:1:0 4k:2:4:1 ..." picks rows (size:threads:msaa:cull) instead of all sixteen.
# Before and after the table, tools/bench/cpu_speeds.sh times each CPU alone (CPU_SPEEDS=0 skips it):
# where they differ, the 1-thread rows depend on where the scheduler put each renderer.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
scene="${1:-spheres}"
frames="${2:-20}"
rows="${ROWS:-}"
if [ -z "$rows" ]; then
  for size in 720p 4k; do for threads in 1 2; do for msaa in 1 4; do for cull in 0 1; do
    rows+="$size:$threads:$msaa:$cull "
  done; done; done; done
fi
cpu_speeds() { [ "${CPU_SPEEDS:-1}" = 0 ] || ROUNDS=3 bash "$root/tools/bench/cpu_speeds.sh" "$scene"; }
cpu_speeds
printf '%-10s %7s %4s %5s %12s %12s %9s\n' size threads msaa cull tessera_ms llvmpipe_ms ratio
for row in $rows; do
  IFS=: read -r size threads msaa cull <<<"$row"
  case "$size" in 720p) w=1280 h=720 ;; 4k) w=3840 h=2160 ;; *) echo "race_table: size must be 720p or 4k, not $size" >&2; exit 1 ;; esac
  out="$(MSAA="$msaa" CULL="$cull" bash "$root/tools/bench/race_llvmpipe.sh" "$scene" "$w" "$h" "$threads" "$frames")"
  t="$(awk '/^tessera  median/ {print $3}' <<<"$out")"
  g="$(awk '/^llvmpipe median/ {print $3}' <<<"$out")"
  r="$(awk '/^llvmpipe\/tessera/ {print $2}' <<<"$out")"
  printf '%-10s %7s %4s %5s %12s %12s %9s\n' "${w}x${h}" "$threads" "$msaa" "$cull" "$t" "$g" "$r"
done
echo "(load average: $(cut -d' ' -f1-3 /proc/loadavg); $(nproc) CPUs)"
cpu_speeds
