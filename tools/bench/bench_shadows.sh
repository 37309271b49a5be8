#!/usr/bin/env bash
# Shadows: the frame time of a scene with every light casting shadows (the scene with
# `[shadows] enabled = true` added) against the scene as it is, side by side (the two
# alternate within each round, so both see the same machine noise), per thread count.
# Default: spheres at 1280x720, its 4 point lights with 1024² cube maps.
#   [ROUNDS=5] [FRAMES=8] [THREADS="1 2"] tools/bench/bench_shadows.sh [SCENE] [WIDTH HEIGHT]
# Prints each round (both medians, their ratio, the shadow passes' median), then per thread
# count the median over rounds of each, the median per-round ratio, and the load average.
set -euo pipefail
source "$(dirname "$0")/bench_args.sh"
parse_bench_args bench_shadows "$@"
rounds="${ROUNDS:-5}"
frames="${FRAMES:-8}"
thread_counts="${THREADS:-1 2}"
build_targets tessera
shadowed="$(mktemp --suffix=.toml)"
trap 'rm -f "$shadowed"' EXIT
# The scene with [shadows] before its [camera]; relative paths in it are the scene's own.
sed '/^\[camera\]/i [shadows]\nenabled = true\n' "$scene" >"$shadowed"
scene_dir="$(dirname "$scene")"
bench() {  # scene, threads -> "frame_ms shadows_ms"
  (cd "$scene_dir" && "$build/tessera" bench "$1" --width "$width" --height "$height" --threads "$2" \
    --frames "$frames" --warmup 2) | awk '/^frame/{f=$3} /^  shadows/{s=$2} END{print f, s}'
}
median() { sort -g | awk '{v[NR]=$1} END{print (NR%2 ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2)}'; }
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
for t in $thread_counts; do
  plain_all=() shadow_all=() ratio_all=() pass_all=()
  for r in $(seq "$rounds"); do
    read -r plain _ < <(bench "$scene" "$t")
    read -r with pass < <(bench "$shadowed" "$t")
    ratio="$(awk -v a="$plain" -v b="$with" 'BEGIN{printf "%.2f", b/a}')"
    echo "threads $t round $r: without $plain ms, with shadows $with ms (shadow passes $pass ms), ${ratio}x"
    plain_all+=("$plain") shadow_all+=("$with") ratio_all+=("$ratio") pass_all+=("$pass")
  done
  echo "threads $t medians: without $(printf '%s\n' "${plain_all[@]}" | median) ms," \
    "with shadows $(printf '%s\n' "${shadow_all[@]}" | median) ms" \
    "(shadow passes $(printf '%s\n' "${pass_all[@]}" | median) ms), per-round ratio $(printf '%s\n' "${ratio_all[@]}" | median)x"
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
