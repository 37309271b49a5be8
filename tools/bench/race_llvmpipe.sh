#!/usr/bin/env bash
# Races Tessera against Mesa's llvmpipe (the OpenGL peer renderer running the same
# reference GLSL) on one scene, with the same thread count for both.
#   tools/bench/race_llvmpipe.sh [SCENE] [WIDTH HEIGHT] [THREADS] [FRAMES]
# Defaults: scenes/spheres.toml 1280 720, 2 threads, 30 frames. SCENE may be a path or a
# name in scenes/. BUILD_DIR overrides the build folder (default build/, Release).
# MSAA=1|4 overrides the scene's output.msaa in both (--msaa); unset, both use the
# scene's own. With 4x, llvmpipe's frame includes its resolve blit, as Tessera's does.
# CULL=1 draws every material single-sided in both (--cull-back-faces: Tessera culls back
# faces in triangle setup, llvmpipe with GL_CULL_FACE); unset or 0, both use the scene's own
# double_sided (all two-sided in the demo scenes, llvmpipe without GL_CULL_FACE).
# The two alternate for several rounds (ROUNDS, default 3) so both see the same machine
# noise; the result is the median over rounds of each one's median frame time, and
# llvmpipe/tessera (above 1: Tessera is faster). Frame times exclude readback and file output.
set -euo pipefail
source "$(dirname "$0")/bench_args.sh"
parse_bench_args race_llvmpipe "$@"
rounds="${ROUNDS:-3}"
msaa_args=()
if [ -n "${MSAA:-}" ]; then
  case "$MSAA" in 1|4) msaa_args=(--msaa "$MSAA") ;; *) echo "race_llvmpipe: MSAA must be 1 or 4, not $MSAA" >&2; exit 1 ;; esac
fi
cull_args=()
case "${CULL:-0}" in 0) ;; 1) cull_args=(--cull-back-faces) ;; *) echo "race_llvmpipe: CULL must be 0 or 1, not $CULL" >&2; exit 1 ;; esac

# Builds if needed: configure once, then an incremental build of the two binaries.
build_targets tessera tessera_gl_reference_cli
[ -x "$build/tessera_gl_reference" ] || {
  echo "race_llvmpipe: $build/tessera_gl_reference was not built (OpenGL/EGL missing? see tools/install_dependencies.sh)" >&2
  exit 1
}

echo "race: $(basename "$scene") ${width}x${height}, msaa ${MSAA:-as the scene}, back faces ${cull_args[*]:-as the scene}, $threads threads, $frames frames, $rounds rounds"
tessera_medians=()
llvmpipe_medians=()
for round in $(seq 1 "$rounds"); do
  t_json="$("$build/tessera" bench "$scene" --width "$width" --height "$height" --threads "$threads" \
    --frames "$frames" "${msaa_args[@]}" "${cull_args[@]}" --json)"
  g_json="$(env $(llvmpipe_env "$threads") \
    "$build/tessera_gl_reference" "$scene" --width "$width" --height "$height" --frames "$frames" "${msaa_args[@]}" \
    "${cull_args[@]}" --json)"
  t_ms="$(json_field "$t_json" frame_ms_median)"
  g_ms="$(json_field "$g_json" frame_ms_median)"
  tessera_medians+=("$t_ms")
  llvmpipe_medians+=("$g_ms")
  printf '  round %d: tessera %9.2f ms   llvmpipe %9.2f ms   ratio %5.2f\n' "$round" "$t_ms" "$g_ms" \
    "$(python3 -c 'import sys; print(float(sys.argv[2]) / float(sys.argv[1]))' "$t_ms" "$g_ms")"
done
echo "  (tessera: $(json_field "$t_json" isa) kernels, $(json_field "$t_json" threads) threads, msaa $(json_field "$t_json" msaa);" \
  "$(json_field "$g_json" renderer), LP_NUM_THREADS=$threads, msaa $(json_field "$g_json" msaa))"

python3 - "${tessera_medians[*]}" "${llvmpipe_medians[*]}" <<'PY'
import statistics, sys
t = statistics.median(float(v) for v in sys.argv[1].split())
g = statistics.median(float(v) for v in sys.argv[2].split())
print(f"tessera  median {t:9.2f} ms")
print(f"llvmpipe median {g:9.2f} ms")
r = statistics.median(float(b) / float(a) for a, b in zip(sys.argv[1].split(), sys.argv[2].split()))
print(f"llvmpipe/tessera {g / t:.2f}x (ratio of the medians; median of the per-round ratios {r:.2f}x)")
PY
