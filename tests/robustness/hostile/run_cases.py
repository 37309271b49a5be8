#!/usr/bin/env python3
"""Runs make_cases.py's hostile inputs through tessera under prlimit caps (issue 35).

    run_cases.py TESSERA OUT_DIR [NAME_FILTER]

Each case runs in its own folder with its address space and CPU time capped
(prlimit) and a wall-clock timeout. It must end with the exit status wanted
and, on failure, print exactly one line "tessera: error: ..." holding the
expected text (nothing from libraries); its peak memory must stay under the
cap; a refused render leaves no output (nor temporary files) behind; and
nothing outside the case's folder changes.
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import threading
import time

tessera, out = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
only = sys.argv[3] if len(sys.argv) > 3 else ""
here = os.path.dirname(os.path.abspath(__file__))
AS_CAP = 2 << 30        # bytes of address space
CPU_CAP = 30            # seconds of CPU time
WALL_CAP = 60           # seconds
PEAK_CAP_KB = 768 << 10 # resident memory any case may reach
# Under AddressSanitizer (tools/ci/sanitize.sh) the binary reserves terabytes of shadow address space
# at start, so no address-space cap can hold; the resident-memory cap still does, with room for
# ASan's own allocator and quarantine.
SANITIZED = os.environ.get("TESSERA_HOSTILE_SANITIZED") == "1"
if SANITIZED:
    PEAK_CAP_KB = 2048 << 10

if os.path.isdir(out):
    shutil.rmtree(out)
subprocess.run([sys.executable, os.path.join(here, "make_cases.py"), out], check=True)
cases = json.load(open(os.path.join(out, "cases.json")))


def snapshot(root):
    """path -> (size, mtime_ns) of everything under root, links not followed."""
    seen = {}
    for folder, dirs, files in os.walk(root):
        for name in dirs + files:
            path = os.path.join(folder, name)
            st = os.lstat(path)
            seen[path] = (st.st_size, st.st_mtime_ns) if not os.path.isdir(path) else None
    return seen


def run(args, cwd, env=None):
    """(status, stdout, stderr, peak RSS in KB, seconds) of tessera under the caps; status None: timed out."""
    caps = [f"--cpu={CPU_CAP}"] if SANITIZED else [f"--as={AS_CAP}", f"--cpu={CPU_CAP}"]
    cmd = ["prlimit", *caps, "--", tessera, *args]
    start = time.monotonic()
    with tempfile.TemporaryFile() as out_file, tempfile.TemporaryFile() as err_file:
        proc = subprocess.Popen(cmd, cwd=cwd, stdout=out_file, stderr=err_file, stdin=subprocess.DEVNULL, env=env)
        timed_out = []
        timer = threading.Timer(WALL_CAP, lambda: (timed_out.append(1), proc.kill()))
        timer.start()
        _, wait_status, usage = os.wait4(proc.pid, 0)  # prlimit execs tessera: this is tessera's usage
        timer.cancel()
        proc.returncode = os.waitstatus_to_exitcode(wait_status)
        out_file.seek(0)
        err_file.seek(0)
        stdout = out_file.read().decode(errors="replace")
        stderr = err_file.read().decode(errors="replace")
    status = None if timed_out else proc.returncode
    return status, stdout, stderr, usage.ru_maxrss, time.monotonic() - start


def make_shard(case, folder):
    """A real one-scene shard report in <folder>/<shard>, then its summary edited as the case says."""
    shard = case["args"][2]
    os.makedirs(os.path.join(folder, "suite", "scenes"), exist_ok=True)
    with open(os.path.join(folder, "suite", "scenes", "s.toml"), "w") as f:
        f.write('[output]\nwidth = 16\nheight = 12\n[camera]\nposition = [0, 0, 5]\ntarget = [0, 0, 0]\n'
                '[[lights]]\ntype = "point"\nposition = [0, 0, 4]\ncolor = [10, 10, 10]\n'
                '[[objects]]\nmesh = "sphere"\n')
    with open(os.path.join(folder, "suite", "check.toml"), "w") as f:
        f.write('scenes = ["scenes/*.toml"]\ngolden = "golden"\n')
    status, o, e, _, _ = run(["check", "suite/check.toml", "--shard", "1/1", "-r", shard, "-q"], folder)
    summary_path = os.path.join(folder, shard, "summary.json")
    assert os.path.exists(summary_path), f"setting up the shard failed ({status}): {o}{e}"
    summary = json.load(open(summary_path))
    images = summary["scenes"][0]["images"]
    actual = images["actual"]
    assert actual, f"the shard's summary links no image: {images}"
    kind = case["summary"]
    if kind == "deep":
        text = open(summary_path).read().rstrip()
        text = text[:-1] + ', "x": ' + "[" * 100000 + "]" * 100000 + "}\n"
        open(summary_path, "w").write(text)
        return
    if kind == "escape":
        # Inside the shard's folder as written, outside the merged folder when joined to it.
        victim_rel = "../" + os.path.basename(shard) + "/victim.png"
        shutil.copy(os.path.join(folder, shard, actual), os.path.join(folder, shard, "victim.png"))
        images["actual"] = victim_rel
        os.makedirs(os.path.join(folder, os.path.basename(shard)), exist_ok=True)
        shutil.move(os.path.join(folder, "victim.png"), os.path.join(folder, os.path.basename(shard), "victim.png"))
        case["untouched"] = [os.path.join(os.path.basename(shard), "victim.png")]
    elif kind == "symlink":
        target = os.path.join(folder, shard, actual)
        os.remove(target)
        os.symlink(os.path.relpath(os.path.join(folder, "outside.png"), os.path.dirname(target)), target)
    elif kind == "billion":
        summary["suite_scenes"] = 1000000000
    json.dump(summary, open(summary_path, "w"), indent=1)


failures = []
ran = 0
peak_of_all = 0
for case in cases:
    name = case["name"]
    if only and only not in name:
        continue
    ran += 1
    folder = os.path.join(out, name)
    if case.get("setup") == "shard":
        if case["summary"] == "escape":
            case["args"] = ["check", "--merge", "s/shard", "-r", "merged"]
        make_shard(case, folder)
    untouched = {p: open(os.path.join(folder, p), "rb").read() for p in case.get("untouched", [])}
    before = snapshot(out)
    status, stdout, stderr, peak, seconds = run(case["args"], folder)
    after = snapshot(out)
    peak_of_all = max(peak_of_all, peak)
    problems = []
    want = case["status"]
    if status is None:
        problems.append(f"did not finish in {WALL_CAP} s")
    elif status < 0:
        problems.append(f"killed by signal {-status}")
    elif want == "nonzero" and status == 0:
        problems.append("exit status 0, expected a refusal")
    elif isinstance(want, int) and status != want:
        problems.append(f"exit status {status}, expected {want}")
    lines = [line for line in stderr.splitlines() if line]
    # check's report lines ("[1/1] fail s ...") are its own; elsewhere only tessera's lines may appear.
    foreign = [line for line in lines if not line.startswith("tessera: ")]
    if foreign and not case.get("in_report") and want != "any":
        problems.append(f"stderr holds lines that are not tessera's: {foreign[:3]}")
    if case.get("in_report"):
        if case["expect"] not in stdout + stderr:
            problems.append(f"'{case['expect']}' is not in the output")
    elif status not in (0, None) and want != "any":
        errors = [line for line in lines if line.startswith("tessera: error: ")]
        if len(errors) != 1 or len(lines) != 1:
            problems.append(f"expected one error line, got {len(lines)} lines: {lines[:4]}")
        elif case["expect"] not in errors[0]:
            problems.append(f"'{case['expect']}' is not in: {errors[0]}")
    if peak > PEAK_CAP_KB:
        problems.append(f"peak memory {peak >> 10} MB, over the {PEAK_CAP_KB >> 10} MB cap")
    # Nothing changes outside the case's folder.
    outside = [p for p in set(before) | set(after)
               if before.get(p) != after.get(p) and not p.startswith(folder + os.sep)]
    if outside:
        problems.append(f"changed outside its folder: {sorted(outside)[:3]}")
    changed = [p for p in set(before) | set(after) if before.get(p) != after.get(p)]
    produced = [os.path.relpath(p, folder) for p in changed if p not in before]
    if case["args"][0] == "render" and status != 0:
        if produced:
            problems.append(f"a refused render left files behind: {produced[:3]}")
    if case.get("output") and status == 0 and not os.path.exists(os.path.join(folder, case["output"])):
        problems.append(f"{case['output']} was not written")
    for path, content in untouched.items():
        if open(os.path.join(folder, path), "rb").read() != content:
            problems.append(f"{path} was overwritten")
    verdict = "ok" if not problems else "FAILED"
    print(f"{verdict:6} {name:32} status {status}, {peak >> 10} MB, {seconds:.2f} s")
    if problems:
        failures.append(name)
        for p in problems:
            print(f"         {p}")
        if stderr.strip():
            print("         stderr: " + stderr.strip().replace("\n", "\n                 ")[:600])

print(f"{ran - len(failures)} of {ran} hostile cases passed; peak memory of any {peak_of_all >> 10} MB")
sys.exit(1 if failures or ran == 0 else 0)
