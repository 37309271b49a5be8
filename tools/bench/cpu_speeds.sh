#!/usr/bin/env bash
# How fast each CPU is right now, for the same 1-thread frame: Tessera (and llvmpipe, where
# tools/gl_reference was built) pinned to one CPU at a time, alternating over the CPUs for
# several rounds. On a shared VM one vCPU can run a frame 1.3x slower than the other for
# minutes (a neighbour on its physical core), and a 1-thread race row then depends on
# which CPU the scheduler gave each renderer. tools/bench/race_table.sh prints this before and
# after its table.
#   tools/bench/cpu_speeds.sh [SCENE] [WIDTH HEIGHT] [FRAMES]
# Defaults: scenes/spheres.toml 1280 720, 10 frames; ROUNDS (default 3); BUILD_DIR as in
# bench_args.sh. Prints, per renderer, each CPU's median frame (ms) and slowest/fastest.
set -euo pipefail
source "$(dirname "$0")/bench_args.sh"
parse_bench_args cpu_speeds "${1:-}" "${2:-}" "${3:-}" 1 "${4:-10}"
rounds="${ROUNDS:-3}"
[[ "$rounds" =~ ^[1-9][0-9]*$ ]] || { echo "cpu_speeds: ROUNDS must be a positive integer, not $rounds" >&2; exit 1; }
[[ "$frames" =~ ^[1-9][0-9]*$ ]] || { echo "cpu_speeds: FRAMES must be a positive integer, not $frames" >&2; exit 1; }
build_targets tessera
# llvmpipe's side where OpenGL/EGL were found (the target exists only then).
(build_targets tessera_gl_reference_cli) 2>/dev/null || true
command -v taskset >/dev/null || { echo "cpu_speeds: taskset (util-linux) is missing" >&2; exit 1; }

# The CPUs this process may run on, from the kernel's list (e.g. "0-1,4").
cpus=()
IFS=, read -ra ranges <<<"$(awk '/^Cpus_allowed_list/ {print $2}' /proc/self/status)"
for range in "${ranges[@]}"; do
  first="${range%-*}" last="${range#*-}"
  for ((c = first; c <= last; ++c)); do cpus+=("$c"); done
done

renderers=(tessera)
[ -x "$build/tessera_gl_reference" ] && renderers+=(llvmpipe)

frame_ms() {  # frame_ms RENDERER CPU: the median frame of one pinned run
  local json
  case "$1" in
    tessera)
      json="$(taskset -c "$2" "$build/tessera" bench "$scene" --width "$width" --height "$height" --threads 1 \
        --frames "$frames" --json)" ;;
    llvmpipe)
      json="$(env $(llvmpipe_env 1) taskset -c "$2" \
        "$build/tessera_gl_reference" "$scene" --width "$width" --height "$height" --frames "$frames" --json)" ;;
  esac
  json_field "$json" frame_ms_median
}

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
for round in $(seq 1 "$rounds"); do
  for renderer in "${renderers[@]}"; do
    for cpu in "${cpus[@]}"; do frame_ms "$renderer" "$cpu" >>"$work/$renderer.$cpu"; done
  done
done

echo "cpu speeds: $(basename "$scene") ${width}x${height}, 1 thread pinned to each CPU, $frames frames, $rounds rounds"
for renderer in "${renderers[@]}"; do
  python3 - "$renderer" "$work" "${cpus[@]}" <<'PY'
import statistics, sys
renderer, work, cpus = sys.argv[1], sys.argv[2], sys.argv[3:]
medians = {c: statistics.median(float(v) for v in open(f"{work}/{renderer}.{c}")) for c in cpus}
cells = "  ".join(f"cpu{c} {m:8.2f} ms" for c, m in medians.items())
spread = max(medians.values()) / min(medians.values())
note = "  (CPUs differ: 1-thread rows depend on placement)" if spread > 1.1 else ""
print(f"  {renderer:<9} {cells}  slowest/fastest {spread:.2f}{note}")
PY
done
