#!/usr/bin/env bash
# Environment lighting's frame-time cost: spheres.toml against spheres_environment.toml
# (the same scene lit by the shipped studio environment and showing it as the
# background), alternated within each round so both see the same machine noise.
# Prints, per binary, size and thread count, the median frames and the median of
# the per-round ratios environment / without (issue 32's target: <= 1.35).
#   [ROUNDS=3] [FRAMES=5] [SIZES="1280x720 3840x2160"] [THREADS="1 2"] tools/bench/bench_environment.sh [TESSERA...]
# e.g. tools/bench/bench_environment.sh old/tessera build/tessera
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
rounds="${ROUNDS:-3}"
frames="${FRAMES:-5}"
sizes="${SIZES:-1280x720 3840x2160}"
threads_list="${THREADS:-1 2}"
[ $# -gt 0 ] || set -- "$root/build/tessera"
for binary in "$@"; do [ -x "$binary" ] || { echo "bench_environment: $binary is not an executable" >&2; exit 1; }; done
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
echo "rounds $rounds, $frames frames (1 warm-up); load before: $(cut -d' ' -f1-3 /proc/loadavg)"
# Each binary gets its own environment disk cache (builds may store other
# formats), filled first, so no timed run pre-computes.
b=0
for binary in "$@"; do
  b=$((b + 1))
  TESSERA_CACHE_DIR="$work/cache.$b" "$binary" render "$root/scenes/spheres_environment.toml" --width 64 --height 36 \
    -o "$work/warm.png" >/dev/null
done
for round in $(seq 1 "$rounds"); do
  for size in $sizes; do
    for threads in $threads_list; do
      b=0
      for binary in "$@"; do
        b=$((b + 1))
        for scene in spheres spheres_environment; do
          TESSERA_CACHE_DIR="$work/cache.$b" "$binary" bench "$root/scenes/$scene.toml" --width "${size%x*}" --height "${size#*x}" --threads "$threads" \
            --frames "$frames" --warmup 1 --json >"$work/$b.$size.$threads.$scene.$round.json"
        done
      done
    done
  done
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
python3 - "$work" "$rounds" "$sizes" "$threads_list" "$@" <<'PY'
import json, statistics, sys
work, rounds, sizes, threads = sys.argv[1], int(sys.argv[2]), sys.argv[3].split(), sys.argv[4].split()
binaries = sys.argv[5:]
def ms(b, size, t, scene, r):
    return json.load(open(f"{work}/{b}.{size}.{t}.{scene}.{r}.json"))["frame_ms_median"]
print(f"{'binary':<40}{'size':>11}{'threads':>8}{'spheres':>10}{'with env':>10}{'ratio':>7}")
for b, binary in enumerate(binaries, 1):
    for size in sizes:
        for t in threads:
            plain = [ms(b, size, t, "spheres", r) for r in range(1, rounds + 1)]
            env = [ms(b, size, t, "spheres_environment", r) for r in range(1, rounds + 1)]
            ratio = statistics.median(e / p for e, p in zip(env, plain))
            print(f"{binary[-40:]:<40}{size:>11}{t:>8}{statistics.median(plain):10.1f}{statistics.median(env):10.1f}{ratio:7.2f}")
PY
