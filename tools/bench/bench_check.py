#!/usr/bin/env python3
"""One `tessera check` call over N scenes against N separate `tessera render` + `idiff`
calls (what a user scripts by hand without it), side by side.

usage: tools/bench/bench_check.py [--build DIR] [--scenes 200] [--runs 3] [--width 1280 --height 720]

Makes N distinct 1280x720 scenes (built-in meshes, three lights, the camera and
materials varied per scene) and their golden PNGs in a temporary folder, then
alternates, --runs times:
  check      tessera check SCENES --golden G            (every scene passes)
  check-fail tessera check SCENES --golden G --msaa 4   (every scene fails: the report
                                                          writes expected, actual and diff PNGs)
  render+idiff  for each scene: tessera render S -o S.png; idiff S.png G/S.png
and prints the median wall time of each, the ratio, the per-scene overhead of
check beyond loading and rendering (wall time minus the render_ms summed from its
summary.json, per scene), and the report's size.
"""
import argparse
import json
import math
import os
import shutil
import statistics
import subprocess
import tempfile
import time

SCENE = """[output]
width = {width}
height = {height}
clear_color = [0.05, 0.06, 0.08]

[camera]
position = [{cx:.4f}, {cy:.4f}, {cz:.4f}]
target = [0.0, -0.6, 0.0]
fov_y = 45.0

[[lights]]
position = [4.0, 6.0, 6.0]
color = [150.0, 150.0, 150.0]

[[lights]]
position = [-5.0, 3.0, 5.0]
color = [40.0, 45.0, 60.0]

[[lights]]
position = [0.0, 5.0, -5.0]
color = [60.0, 60.0, 60.0]

[[objects]]
mesh = "plane"
material = {{ albedo = [0.6, 0.6, 0.6], roughness = 0.8 }}
translate = [0.0, -1.0, 0.0]
scale = 6.0

[[objects]]
mesh = "cube"
material = {{ albedo = [0.95, 0.64, 0.54], metallic = 1.0, roughness = {rough:.3f} }}
translate = [-1.6, -0.3, 0.0]
rotate = [0.0, {turn:.2f}, 0.0]
scale = 0.7

[[objects]]
mesh = "sphere"
material = {{ albedo = [{r:.3f}, 0.2, 0.8], roughness = 0.3 }}
translate = [0.3, -0.2, 0.4]
scale = 0.8

[[objects]]
mesh = "sphere"
material = {{ albedo = [1.0, 0.78, 0.34], metallic = 1.0, roughness = 0.25 }}
translate = [1.8, -0.5, -0.3]
scale = [0.6, 0.45, 0.6]
"""


def timed(cmd, expect=None):
    start = time.perf_counter()
    result = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    if expect is not None and result.returncode != expect:
        raise SystemExit(f"{' '.join(cmd[:3])}...: exit status {result.returncode}, expected {expect}")
    return time.perf_counter() - start


def folder_bytes(path):
    return sum(os.path.getsize(os.path.join(d, f)) for d, _, files in os.walk(path) for f in files)


def main():
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(root, "build"))
    parser.add_argument("--scenes", type=int, default=200)
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--width", type=int, default=1280)
    parser.add_argument("--height", type=int, default=720)
    args = parser.parse_args()
    tessera = os.path.join(args.build, "tessera")
    idiff = shutil.which("idiff")
    if not idiff:
        raise SystemExit("no idiff (openimageio-tools)")

    work = tempfile.mkdtemp(prefix="tessera-bench-check-")
    try:
        scenes_dir, golden, out = (os.path.join(work, d) for d in ("scenes", "golden", "out"))
        os.makedirs(scenes_dir)
        os.makedirs(out)
        scenes = []
        for i in range(args.scenes):
            angle = 2 * math.pi * i / args.scenes
            path = os.path.join(scenes_dir, f"scene_{i:03d}.toml")
            with open(path, "w") as f:
                f.write(SCENE.format(width=args.width, height=args.height, cx=6.5 * math.sin(angle),
                                     cy=2.0 + 1.5 * ((i * 7) % 10) / 10, cz=6.5 * math.cos(angle),
                                     rough=0.2 + 0.6 * ((i * 3) % 10) / 10, turn=(i * 37) % 360,
                                     r=0.1 + 0.8 * ((i * 13) % 10) / 10))
            scenes.append(path)
        subprocess.run([tessera, "check", *scenes, "--golden", golden, "--report", os.path.join(work, "made"),
                        "--update=missing", "-q"], check=True, stdout=subprocess.DEVNULL)

        check_cmd = [tessera, "check", *scenes, "--golden", golden, "-q"]
        times = {"check": [], "check-fail": [], "render+idiff": []}
        overhead, render_means, compare_means = [], [], []
        for run in range(args.runs):  # alternating, so that load on the shared machine hits all alike
            report = os.path.join(work, f"report_pass_{run}")
            times["check"].append(timed(check_cmd + ["--report", report], expect=0))
            with open(os.path.join(report, "summary.json")) as f:
                summary = json.load(f)
            render_ms = [s["render_ms"] for s in summary["scenes"]]
            overhead.append((times["check"][-1] * 1000 - sum(render_ms)) / args.scenes)
            render_means.append(statistics.mean(render_ms))
            compare_means.append(statistics.mean(s["compare_ms"] for s in summary["scenes"]))
            fail_report = os.path.join(work, "report_fail")
            shutil.rmtree(fail_report, ignore_errors=True)
            times["check-fail"].append(timed(check_cmd + ["--report", fail_report, "--msaa", "4"], expect=1))
            start = time.perf_counter()
            for scene in scenes:
                png = os.path.join(out, os.path.basename(scene)[:-5] + ".png")
                subprocess.run([tessera, "render", scene, "-o", png], check=True, stdout=subprocess.DEVNULL)
                subprocess.run([idiff, png, os.path.join(golden, os.path.basename(png))],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            times["render+idiff"].append(time.perf_counter() - start)
            print(f"run {run + 1}: " + ", ".join(f"{k} {v[-1]:.1f} s" for k, v in times.items()) +
                  f"; check overhead beyond load+render {overhead[-1]:.1f} ms/scene", flush=True)

        med = {k: statistics.median(v) for k, v in times.items()}
        n = args.scenes
        print(f"\n{n} scenes of {args.width}x{args.height}, median of {args.runs} alternating runs:")
        print(f"  {'':30s} {'total s':>8s} {'per scene ms':>13s}")
        print(f"  {'tessera check (all pass)':30s} {med['check']:8.2f} {med['check'] / n * 1000:13.1f}")
        print(f"  {'tessera check (all fail)':30s} {med['check-fail']:8.2f} {med['check-fail'] / n * 1000:13.1f}")
        print(f"  {'tessera render + idiff each':30s} {med['render+idiff']:8.2f} {med['render+idiff'] / n * 1000:13.1f}")
        print(f"  render+idiff / check (all pass): {med['render+idiff'] / med['check']:.1f}x;"
              f" / check (all fail): {med['render+idiff'] / med['check-fail']:.1f}x")
        print(f"  inside check (all pass), per scene: load+render {statistics.median(render_means):.1f} ms,"
              f" compare+report images {statistics.median(compare_means):.1f} ms;"
              f" overhead beyond load+render {statistics.median(overhead):.1f} ms")
        last_pass = os.path.join(work, f"report_pass_{args.runs - 1}")
        print(f"  report, all pass: index.html {os.path.getsize(os.path.join(last_pass, 'index.html')) / 1024:.0f} KiB,"
              f" folder {folder_bytes(last_pass) / 1024:.0f} KiB (passing rows link the goldens)")
        print(f"  report, all fail: index.html {os.path.getsize(os.path.join(fail_report, 'index.html')) / 1024:.0f} KiB,"
              f" folder {folder_bytes(fail_report) / 1048576:.1f} MiB ({n} x expected + actual + diff PNGs)")
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
