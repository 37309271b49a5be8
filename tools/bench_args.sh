# Sourced by the side-by-side bench scripts (bench_scaling.sh, race_llvmpipe.sh),
# which take the same arguments: [SCENE] [WIDTH HEIGHT] [THREADS] [FRAMES], with
# defaults scenes/spheres.toml 1280 720, 2 threads, 30 frames; SCENE is a path or a
# name in scenes/. BUILD_DIR overrides the build folder (default build/, Release).
#   parse_bench_args NAME "$@"   sets root, scene, width, height, threads, frames, build
#   build_targets TARGET...      configures the build folder once, then builds TARGETs

parse_bench_args() {
  local name="$1"
  shift
  root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
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
