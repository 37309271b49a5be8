#!/usr/bin/env bash
# Model load end to end: `tessera render MODEL -o x.png --threads N` for the
# Khronos sample models in ../shared/assets (skipped, saying so, when absent),
# with its wall time, CPU time (user + system) and peak RSS (GNU time), and the split `render --stats`
# prints: glTF file read, parse, convert, images (wall), and the images' decode,
# upload (to the sampler's RGBA8 layout) and mip thread time, render, encode.
# Also `tessera --version`: the process start (dynamic loading) every run pays.
# Each figure is the median over RUNS runs (default 5).
#   tools/bench/bench_model_load.sh [MODEL.glb|.gltf ...]
# Environment: RUNS, THREADS (default 2), BUILD_DIR (default build/, Release),
# BASELINE=/path/to/another/tessera to measure it too, alternating run by run
# with this build (both see the same machine noise; compare the ratio). On a
# shared machine CPU time and peak RSS move less with the load than wall time.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
build="${BUILD_DIR:-$root/build}"
runs="${RUNS:-5}"
threads="${THREADS:-2}"
assets="$root/../shared/assets/gltf"

if [ ! -f "$build/CMakeCache.txt" ]; then cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null; fi
cmake --build "$build" -j"$(nproc)" --target tessera >/dev/null

models=("$@")
if [ ${#models[@]} -eq 0 ]; then
  if [ ! -d "$assets" ]; then
    echo "bench_model_load: skipped: no sample models in $assets"
    exit 0
  fi
  for m in DamagedHelmet/DamagedHelmet.glb BoomBox/BoomBox.gltf MetalRoughSpheresNoTextures/MetalRoughSpheresNoTextures.glb; do
    if [ -f "$assets/$m" ]; then models+=("$assets/$m"); else echo "bench_model_load: skipped $m (not in $assets)"; fi
  done
fi

binaries=("$build/tessera")
[ -n "${BASELINE:-}" ] && binaries+=("$BASELINE")
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT

# One run: "wall_s peak_kb" from GNU time, then the --stats lines (only our build prints the split).
run_once() {  # BINARY ARGS...
  local bin="$1"
  shift
  /usr/bin/time -f "time %e %M %U %S" -o "$out/time" "$bin" "$@" >"$out/stdout" 2>"$out/stderr" || {
    echo "bench_model_load: failed: $bin $*" >&2
    cat "$out/stderr" >&2
    exit 1
  }
  cat "$out/time" "$out/stdout"
}

echo "machine load at start: $(cut -d' ' -f1-3 /proc/loadavg)"
for model in version "${models[@]}"; do
  for bin in "${binaries[@]}"; do : >"$out/$(echo "$bin" | md5sum | cut -c1-8).log"; done
  for run in $(seq 1 "$runs"); do
    for bin in "${binaries[@]}"; do
      log="$out/$(echo "$bin" | md5sum | cut -c1-8).log"
      if [ "$model" = version ]; then
        run_once "$bin" --version >>"$log"
      else
        run_once "$bin" render "$model" -o "$out/x.png" --threads "$threads" --stats >>"$log"
      fi
      echo "---" >>"$log"
    done
  done
  for bin in "${binaries[@]}"; do
    label="$([ "$bin" = "$build/tessera" ] && echo this || echo baseline)"
    python3 - "$model" "$label" "$out/$(echo "$bin" | md5sum | cut -c1-8).log" <<'PY'
import re, statistics, sys, os
model, label, path = sys.argv[1], sys.argv[2], sys.argv[3]
runs = [r for r in open(path).read().split("---\n") if r.strip()]
fields = {}
def add(name, value):
    fields.setdefault(name, []).append(float(value))
for r in runs:
    m = re.search(r"time ([\d.]+) (\d+) ([\d.]+) ([\d.]+)", r)
    add("wall s", m.group(1)); add("peak RSS MB", int(m.group(2)) / 1024)
    add("cpu s", float(m.group(3)) + float(m.group(4)))
    m = re.search(r"load ([\d.]+) ms \(glTF file read ([\d.]+), parse ([\d.]+), convert ([\d.]+), images ([\d.]+)\)", r)
    if m:
        for name, value in zip(["load", "file read", "parse", "convert", "images"], m.groups()):
            add(name + " ms", value)
    m = re.search(r"kernels: ([\d.]+) ms", r)
    if m: add("render ms", m.group(1))
    m = re.search(r"encode ([\d.]+) ms", r)
    if m: add("encode ms", m.group(1))
    m = re.search(r"images: (\d+) textures, ([\d.]+) MB; thread time: decode ([\d.]+) ms, upload ([\d.]+) ms, "
                  r"mips ([\d.]+) ms", r)
    if m:
        for name, value in zip(["textures", "texture MB", "decode cpu", "upload cpu", "mips cpu"], m.groups()):
            add(name + ("" if name in ("textures", "texture MB") else " ms"), value)
name = "tessera --version" if model == "version" else os.path.basename(model)
med = {k: statistics.median(v) for k, v in fields.items()}
line = (f"{name} [{label}, median of {len(runs)}]: wall {med['wall s']:.3f} s, CPU {med['cpu s']:.2f} s, "
        f"peak RSS {med['peak RSS MB']:.1f} MB")
print(line)
if "load ms" in med:
    print("    load {load ms:.1f} ms = file read {file read ms:.1f} + parse {parse ms:.1f} + convert {convert ms:.1f} "
          "+ images {images ms:.1f} (wall); render {render ms:.1f} ms; encode {encode ms:.1f} ms".format(**med))
if "decode cpu ms" in med:
    print("    images: {textures:.0f} textures, {texture MB:.1f} MB; thread time decode {decode cpu ms:.1f} ms, "
          "upload {upload cpu ms:.1f} ms, mips {mips cpu ms:.1f} ms".format(**med))
PY
  done
done
echo "(wall includes process start; the split's times are inside the process; machine load: $(cut -d' ' -f1-3 /proc/loadavg))"
