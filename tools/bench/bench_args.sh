# Sourced by the side-by-side bench scripts (bench_scaling.sh, race_llvmpipe.sh, cpu_speeds.sh),
# which take the same arguments: [SCENE] [WIDTH HEIGHT] [THREADS] [FRAMES], with
# defaults scenes/spheres.toml 1280 720, 2 threads, 30 frames; SCENE is a path or a
# name in scenes/. BUILD_DIR overrides the build folder (default build/, Release).
# cpu_speeds.sh passes THREADS = 1 itself.
#   parse_bench_args NAME "$@"   sets root, scene, width, height, threads, frames, build
#   build_targets TARGET...      configures the build folder once, then builds TARGETs
#   json_field JSON NAME         one top-level value of a JSON object
#   llvmpipe_env THREADS         the environment llvmpipe races with, for `env`

parse_bench_args() {
  local name="$1"
  shift
  root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
  scene="${1:-spheres}"
  width="${2:-1280}"
  height="${3:-720}"
  threads="${4:-2}"
  frames="${5:-30}"
  build="${BUILD_DIR:-$root/build}"
  [ -f "$scene" ] || scene="$root/scenes/${scene%.toml}.toml"
  [ -f "$scene" ] || { echo "$name: no scene file $scene" >&2; exit 1; }
}

build_targets() {
  if [ ! -f "$build/CMakeCache.txt" ]; then
    cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
  fi
  cmake --build "$build" -j"$(nproc)" --target "$@" >/dev/null
}

json_field() {
  python3 -c 'import json, sys; print(json.loads(sys.argv[1])[sys.argv[2]])' "$1" "$2"
}

# LP_NUM_THREADS=THREADS, and a high trim threshold: it stops glibc returning llvmpipe's
# large per-frame scene allocations to the kernel each frame (which would time page
# faults, not rendering). One word per line, for `env $(llvmpipe_env N) ...`.
llvmpipe_env() {
  printf '%s\n' "LP_NUM_THREADS=$1" GLIBC_TUNABLES=glibc.malloc.trim_threshold=1073741824
}
