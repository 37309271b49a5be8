#!/usr/bin/env python3
"""A model of how a frame would scale past this machine's cores, from one profile.

Reads a Chrome trace written by `tessera bench --trace FILE.json` (best with --threads 1,
where task times carry no contention) and, per pass of the frame, takes the work done
(the pass's time at one thread: the sum of its tasks, or the pass span where it records no
tasks) and its tasks (chunks of triangles, tiles). On P cores a pass takes at least
max(work / P, longest task) and, scheduled greedily, at most work / P + longest task; the
frame is the sum of its passes (they are separated by barriers). The pass whose longest task
overtakes work / P first is the one that serialises first. Not modelled: memory bandwidth
(vertex and clip+setup stream ~10 MB per 720p frame and share it), the cost of the
barriers and of task scheduling, and cache effects; so the model is an upper bound on speed-up.

  build/tessera bench scenes/spheres.toml --threads 1 --frames 10 --trace /tmp/t1.json
  tools/bench/scaling_model.py /tmp/t1.json [--cores 1,2,4,8,16,32,64]
"""
import argparse
import json
import statistics
import sys
from collections import defaultdict


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("trace")
    parser.add_argument("--cores", default="1,2,4,8,16,32,64")
    args = parser.parse_args()
    cores = [int(c) for c in args.cores.split(",")]
    events = [e for e in json.load(open(args.trace))["traceEvents"] if e.get("ph") == "X"]

    frames = sorted((e for e in events if e["cat"] == "frame"), key=lambda e: e["ts"])
    if not frames:
        sys.exit(f"{args.trace}: no frame spans (write it with tessera bench --trace)")
    threads = int(frames[0].get("args", {}).get("threads", 1))
    # Per pass: its span in each frame, and each task's time in each frame. A task's cost is
    # its shortest time over the frames: on a shared machine a task is now and then pre-empted
    # for a whole scheduler slice (~4 ms), and would then pass for the longest.
    spans = defaultdict(list)
    task_times = defaultdict(lambda: defaultdict(list))
    names = []
    for frame in frames:
        for p in (e for e in events if e["cat"] == "pass" and frame["ts"] <= e["ts"] < frame["ts"] + frame["dur"]):
            if p["name"] not in names:
                names.append(p["name"])
            spans[p["name"]].append(p["dur"] / 1000)
            for e in events:
                if e["cat"] in ("chunk", "tile") and p["ts"] <= e["ts"] < p["ts"] + p["dur"]:
                    task_times[p["name"]][e["name"]].append(e["dur"] / 1000)
    model = {}  # pass -> (work ms, tasks, longest task ms)
    for name in names:
        costs = [min(times) for times in task_times[name].values()]
        if costs:
            model[name] = (sum(costs), len(costs), max(costs))
        else:  # no task spans (the vertex pass): its span times the threads that ran it, finely divisible
            model[name] = (min(spans[name]) * threads, 0, 0.0)

    frame = frames[0]["args"]
    print(f"{args.trace}: {frame.get('width')}x{frame.get('height')}, tile {frame.get('tile_size')}, "
          f"traced with {threads} thread(s), {len(frames)} frame(s); task costs: minimum over frames")
    print(f"{'pass':10} {'work ms':>9} {'tasks':>6} {'longest ms':>11}   (work: the pass's busy time summed over workers)")
    for name, (work, count, longest) in model.items():
        print(f"{name:10} {work:9.2f} {count:6d} {longest:11.3f}")
    print()
    header = "".join(f"{p:>14}" for p in cores)
    print(f"{'cores':10}{header}")
    print("(each cell: the pass's time in ms on that many cores, lower-upper bound)")
    for name, (work, count, longest) in model.items():
        row = "".join(f"{max(work / p, longest):7.2f}-{work / p + longest:<6.2f}" for p in cores)
        print(f"{name:10}{row}")
    lower = [sum(max(w / p, l) for w, _, l in model.values()) for p in cores]
    upper = [sum(w / p + l for w, _, l in model.values()) for p in cores]
    print(f"{'frame ms':10}" + "".join(f"{lo:7.2f}-{hi:<6.2f}" for lo, hi in zip(lower, upper)))
    print(f"{'speed-up':10}" + "".join(f"{lower[0] / hi:6.1f}x-{lower[0] / lo:<5.1f}x" for lo, hi in zip(lower, upper)))
    first = min(((w / l if l else float("inf")), n) for n, (w, _, l) in model.items())
    print(f"\nfirst to serialise: {first[1]} (its longest task equals work / P at P = {first[0]:.0f} cores)")


if __name__ == "__main__":
    main()
