#!/usr/bin/env python3
"""How far each stage of a frame is from this machine's limits.

Runs (or reads) `tessera bench --json` for a scene and `tessera_microbench`'s machine/ rows
(the peak rate of independent multiply-adds per ISA, and streaming memory bandwidth), both
on this machine, and sets each stage against the ceiling that bounds it:

- shade: lane operations per fragment·light (an FMA counts once) against the FP issue peak,
  half the measured FMA flops peak (two flops per FMA). --ops-per-fragment-light is counted
  by hand from shade_kernels_simd.cpp's point-light loop (its default says which version);
  the shade step also interpolates the varyings, so the gap is kernel + gather.
- resolve: the bytes it must move (each pixel's 8-bit RGB written, its depth read, each
  shaded sample's radiance read: 12 bytes; x4 samples with MSAA) against the memory write
  bandwidth. A lower bound on traffic: the tile buffers mostly stay in cache, so this says
  how far the stage is from being memory bound, not that it is.
- vertex, clip_setup, binning, rasterize: no single ceiling; the rate (triangles per second
  per thread) and the cycles per triangle at the clock the FMA peak implies (32 flops per
  cycle per core with AVX2: two 8-lane FMA pipes; 64 with AVX-512).

Stage times are `tessera bench`'s medians: busy time over all workers divided by the
threads, so per-thread rates are work / (ms x threads).

  build/tessera_microbench --benchmark_filter=machine/ --benchmark_format=json > /tmp/machine.json
  tools/bench/stage_limits.py --machine /tmp/machine.json -- scenes/spheres.toml --threads 1 --frames 20
  tools/bench/stage_limits.py --machine /tmp/machine.json --bench-json /tmp/bench.json   # a bench already run
"""
import argparse
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# Counted by hand in shade_kernels_simd.cpp's point-light path: ~47
# operations on the multiply-add pipes per fragment·light (1/|d| by rsqrt and a Newton step,
# the unnormalized half vector, the one division of the specular fraction, the Fresnel
# weight, nine colour × term accumulations), plus a division and a square root that hold
# the pipes about as long as ~9 more: 56 issue slots.
DEFAULT_OPS_PER_FRAGMENT_LIGHT = 56


def machine_limits(path):
    rows = json.load(open(path))["benchmarks"]
    limits = {}
    for row in rows:
        # With --benchmark_repetitions, the median row stands for the repetitions.
        if row.get("error_occurred") or row.get("aggregate_name", "median") != "median":
            continue
        name = row["name"].removesuffix("_median")  # machine/flops/avx2/real_time/threads:1
        parts = name.split("/")
        if parts[1] not in ("flops", "memory"):
            continue  # machine/handover/...: not a ceiling
        threads = int(parts[-1].split(":")[1])
        # A threaded run's rate is that of all its threads together (items summed over threads, per second).
        if parts[1] == "flops":
            limits[("flops", parts[2], threads)] = row["items_per_second"]
        elif parts[1] == "memory":
            limits[("memory", parts[2], threads)] = row["bytes_per_second"]
    return limits


def run_bench(bench_args):
    tessera = os.path.join(ROOT, "build", "tessera")
    out = subprocess.run([tessera, "bench", "--json", *bench_args], check=True, capture_output=True, text=True)
    return json.loads(out.stdout)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--machine", required=True, help="tessera_microbench --benchmark_filter=machine/ JSON")
    parser.add_argument("--bench-json", help="tessera bench --json output (else run tessera bench with the arguments after --)")
    parser.add_argument("--ops-per-fragment-light", type=float, default=DEFAULT_OPS_PER_FRAGMENT_LIGHT)
    parser.add_argument("bench_args", nargs="*")
    args = parser.parse_args()
    limits = machine_limits(args.machine)
    bench = json.load(open(args.bench_json)) if args.bench_json else run_bench(args.bench_args)

    threads, isa, msaa = bench["threads"], bench["isa"], bench["msaa"]
    machine_threads = 2 if threads >= 2 else 1
    flops = limits.get(("flops", isa, machine_threads))
    if flops is None:
        sys.exit(f"{args.machine}: no machine/flops/{isa} row for {machine_threads} thread(s)")
    flops_per_thread = flops / machine_threads
    lanes_flops_per_cycle = {"sse4": 16, "avx2": 32, "avx512": 64}.get(isa, 32)
    # The clock, from the widest FMA row measured on one thread.
    clock_hz = next((limits[("flops", k, 1)] / per_cycle for k, per_cycle in (("avx512", 64), ("avx2", 32), ("sse4", 16))
                     if ("flops", k, 1) in limits), flops_per_thread / lanes_flops_per_cycle)
    write_bw = limits.get(("memory", "write", machine_threads))
    stages = bench["stages_ms"]

    print(f"{bench['scene']}: {bench['width']}x{bench['height']}, msaa {msaa}, {threads} thread(s), {isa}; "
          f"frame {bench['frame_ms_median']:.2f} ms")
    print(f"machine: {flops / 1e9:.1f} GFLOP/s {isa} peak on {machine_threads} thread(s), "
          f"clock ~{clock_hz / 1e9:.2f} GHz" + (f", memory write {write_bw / 1e9:.1f} GB/s" if write_bw else ""))
    print(f"{'stage':<11} {'ms':>7}  {'work':<34} {'rate per thread':<26} limit")

    def per_thread_seconds(stage):
        return stages[stage] * threads / 1000.0

    for stage, count, unit in (("vertex", bench["triangles"], "triangles in"),
                               ("clip_setup", bench["triangles"], "triangles in"),
                               ("binning", bench["triangles_binned"], "triangles binned"),
                               ("rasterize", bench["triangles_binned"], "triangles binned")):
        seconds = per_thread_seconds(stage)
        rate = count / seconds if seconds > 0 else float("inf")
        cycles = clock_hz / rate
        print(f"{stage:<11} {stages[stage]:7.2f}  {count:>10} {unit:<23} {rate / 1e6:7.1f} Mtri/s            "
              f"{cycles:6.0f} cycles per triangle")

    fragment_lights = bench["fragment_lights"]
    seconds = per_thread_seconds("shade")
    ops_rate = fragment_lights * args.ops_per_fragment_light / seconds
    peak_ops = flops_per_thread / 2
    print(f"{'shade':<11} {stages['shade']:7.2f}  {fragment_lights:>10} fragment·lights        "
          f"{seconds * 1e9 / fragment_lights:7.2f} ns/fragment·light    "
          f"{100 * ops_rate / peak_ops:5.1f}% of FP issue peak "
          f"({args.ops_per_fragment_light:.0f} ops each; at peak {args.ops_per_fragment_light / peak_ops * 1e9:.2f} ns)")

    pixels = bench["width"] * bench["height"]
    samples = bench["fragments_shaded"] if msaa == 1 else pixels * msaa
    resolve_bytes = pixels * (3 + 4) + samples * 12
    seconds = per_thread_seconds("resolve")
    if write_bw:
        # Per-thread share of the machine's bandwidth when all threads resolve at once.
        share = write_bw / machine_threads
        print(f"{'resolve':<11} {stages['resolve']:7.2f}  {resolve_bytes / 1e6:>10.1f} MB moved (at least)    "
              f"{resolve_bytes / seconds / 1e9:7.2f} GB/s                "
              f"{100 * resolve_bytes / seconds / share:5.1f}% of write bandwidth per thread")


if __name__ == "__main__":
    main()
