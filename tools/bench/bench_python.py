#!/usr/bin/env python3
"""Rendering through Python against the command line (docs/performance.md).

1. The 720p spheres through tessera.Renderer and through `tessera bench`, 1 and
   2 threads: the median frame time of each, side by side. The Python time is
   the whole render() call (GIL release, locks, handing the images to NumPy).
2. A dataset-style loop: one glTF model (DamagedHelmet, ../shared/assets), 100
   camera poses on an orbit, RGB + depth + object_id at 640x480 on 2 threads,
   in frames per second: in memory from Python, then with each frame saved as
   EXR from Python, then the same 100 frames from `tessera render --frames`
   (which writes EXR files), to show where the time goes.

    PYTHONPATH=build/python python3 tools/bench/bench_python.py [--build build] [--rounds 3]

Each number is a median of several; the machine is shared and noisy, so read
the ratios within one run.
"""
import argparse
import json
import math
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=str(ROOT / "build"), help="the CMake build folder (tessera, python/)")
    parser.add_argument("--rounds", type=int, default=3, help="alternating rounds per comparison")
    parser.add_argument("--frames", type=int, default=15, help="timed frames per round of the spheres")
    parser.add_argument("--poses", type=int, default=100, help="camera poses of the dataset loop")
    args = parser.parse_args()
    build = pathlib.Path(args.build).resolve()
    sys.path.insert(0, str(build / "python"))
    import numpy as np
    import tessera

    cli = str(build / "tessera")

    # 1. The spheres, Python's render() against tessera bench, rounds alternating.
    spheres = ROOT / "scenes" / "spheres.toml"
    scene = tessera.load(spheres)
    print(f"spheres {scene.width}x{scene.height}: median frame ms ({args.rounds} rounds of {args.frames} frames)")
    # The last two columns compare each render() call with the frame it ran
    # (Frame.stats total_ms, the renderer's own clock, what tessera bench
    # reports): the binding's cost per call, free of the noise between processes.
    print(f"{'threads':>7}  {'tessera bench':>13}  {'Python render()':>15}  {'Python / bench':>14}"
          f"  {'call - frame ms':>15}  {'call / frame':>12}")
    for threads in (1, 2):
        bench_ms, python_ms, extra_ms, call_ratio = [], [], [], []
        renderer = tessera.Renderer(threads=threads)
        for _ in range(args.rounds):
            done = subprocess.run([cli, "bench", str(spheres), "--threads", str(threads), "--frames", str(args.frames),
                                   "--warmup", "3", "--json"], check=True, capture_output=True, text=True)
            bench_ms.append(json.loads(done.stdout)["frame_ms_median"])
            for _ in range(3):
                renderer.render(scene)
            samples = []
            for _ in range(args.frames):
                start = time.perf_counter()
                frame = renderer.render(scene)
                call = 1000 * (time.perf_counter() - start)
                samples.append(call)
                inside = frame.stats["total_ms"]
                extra_ms.append(call - inside)
                call_ratio.append(call / inside)
                del frame
            python_ms.append(statistics.median(samples))
        b, p = statistics.median(bench_ms), statistics.median(python_ms)
        print(f"{threads:>7}  {b:>13.2f}  {p:>15.2f}  {p / b:>14.3f}"
              f"  {statistics.median(extra_ms):>15.3f}  {statistics.median(call_ratio):>12.3f}")

    # 2. The dataset loop.
    helmet = ROOT / "scenes" / "gltf" / "damaged_helmet.toml"
    if not (ROOT / ".." / "shared" / "assets" / "gltf" / "DamagedHelmet").is_dir():
        print("dataset loop: skipped, no ../shared/assets/gltf/DamagedHelmet")
        return
    scene = tessera.load(helmet)
    start_camera = scene.camera
    target = np.array(start_camera.target)
    offset = np.array(start_camera.position) - target
    radius, height = math.hypot(offset[0], offset[2]), offset[1]
    start_angle = math.degrees(math.atan2(offset[0], offset[2]))

    def pose(f):  # the orbit of scenes' [animation.orbit], one turn over the poses
        angle = math.radians(start_angle + 360.0 * f / args.poses)
        position = target + (radius * math.sin(angle), height, radius * math.cos(angle))
        return tessera.Camera(position=position, target=target, near=start_camera.near, far=start_camera.far,
                              fov_y=start_camera.fov_y)

    cameras = [pose(f) for f in range(args.poses)]
    renderer = tessera.Renderer(640, 480, threads=2, aovs=("depth", "object_id"))
    renderer_exr = tessera.Renderer(640, 480, threads=2, aovs=("depth", "object_id"), radiance=True)
    # What a data pipeline keeps: the arrays copied into its own batch (one copy each).
    rgb = np.empty((args.poses, 480, 640, 3), np.uint8)
    depth = np.empty((args.poses, 480, 640), np.float32)
    ids = np.empty((args.poses, 480, 640), np.uint32)

    def python_loop():
        start = time.perf_counter()
        for f, camera in enumerate(cameras):
            scene.camera = camera
            frame = renderer.render(scene)
            rgb[f], depth[f], ids[f] = frame.color, frame.depth, frame.object_id
        return args.poses / (time.perf_counter() - start)

    def python_exr_loop(folder):
        start = time.perf_counter()
        for f, camera in enumerate(cameras):
            scene.camera = camera
            renderer_exr.render(scene).save(folder / f"f{f}.exr")
        return args.poses / (time.perf_counter() - start)

    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        animated = tmp / "helmet_orbit.toml"
        animated.write_text(helmet.read_text().replace("../../../shared", str((ROOT / ".." / "shared").resolve())) +
                            f"\n[animation]\nframes = {args.poses}\nfps = 24\n[animation.orbit]\nturns = 1\n")

        def cli_loop(output):
            start = time.perf_counter()
            subprocess.run([cli, "render", str(animated), "--frames", f"0-{args.poses - 1}", "--threads", "2",
                            "-o", str(tmp / output), *(["--aov", "depth,object_id"] if output.endswith(".exr") else [])],
                           check=True, capture_output=True)
            return args.poses / (time.perf_counter() - start)

        python_loop()  # warm up: the model's textures, the renderer's memory
        rows = {"Python, arrays in memory": [], "Python, frame.save(EXR) each": [],
                "CLI render --frames, EXR + AOVs": [], "CLI render --frames, PNG only": []}
        for _ in range(args.rounds):
            rows["Python, arrays in memory"].append(python_loop())
            rows["Python, frame.save(EXR) each"].append(python_exr_loop(tmp))
            rows["CLI render --frames, EXR + AOVs"].append(cli_loop("c{frame}.exr"))
            rows["CLI render --frames, PNG only"].append(cli_loop("c{frame}.png"))
    print(f"\ndataset loop: DamagedHelmet, {args.poses} poses, 640x480, RGB + depth + object_id, 2 threads "
          f"(median of {args.rounds})")
    for name, fps in rows.items():
        print(f"  {name:<34} {statistics.median(fps):7.1f} fps")


if __name__ == "__main__":
    main()
