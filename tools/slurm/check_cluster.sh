#!/usr/bin/env bash
# Starts a real one-node Slurm cluster (Debian 12's slurmctld, slurmd and
# munge) in a temporary folder, submits tools/slurm/render_array.sbatch as a
# 4-task job array rendering a 24-frame turntable, waits, and checks that every
# frame is present once (files and the tasks' JSON Lines records) and
# bit-identical to a single-process render of the same range.
#
#   tools/slurm/check_cluster.sh [build-dir]      (default: build; exit 0 = pass)
#
# Made for a sandbox: no systemd (each daemon runs in its foreground mode as a
# background process of this script, stopped by its PID on every exit path),
# no cgroups (ProctrackType=proctrack/linuxproc, TaskPlugin=task/none), munged
# with a key generated here and its own socket, ports picked free on loopback.
# KEEP=1 leaves the temporary folder (configs, daemon logs, frames) for a look.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
build="${1:-$root/build}"
frames="${FRAMES:-0-23}"
tasks="${TASKS:-4}"
start_time=$(date +%s)

for tool in munged slurmctld slurmd sbatch squeue scancel sinfo pgrep python3; do
  command -v "$tool" >/dev/null || { echo "check_cluster: '$tool' is missing: bash tools/install_dependencies.sh" >&2; exit 2; }
done
[ "${SKIP_BUILD:-0}" = 1 ] || cmake --build "$build" --target tessera -j2 >/dev/null
tessera="$build/tessera"

work="$(mktemp -d /tmp/tessera_slurm.XXXXXX)"
chmod 755 "$work"  # munged refuses a socket folder others may write to
pids=()  # the daemons we start, in order
job=""   # the array's job id once submitted
descendants() {  # every process below PID $1, by walking parent PIDs
  local child
  for child in $(pgrep -P "$1" || true); do
    echo "$child"
    descendants "$child"
  done
}
cleanup() {
  local status=$?
  trap - INT TERM  # a second signal does not cut the cleanup short
  # The job first, while the daemons still run: cancelled tasks end through slurmd.
  if [ -n "$job" ]; then
    scancel "$job" 2>/dev/null || true
    for _ in $(seq 50); do [ -z "$(squeue -h -j "$job" 2>/dev/null)" ] && break; sleep 0.1; done
  fi
  # What the daemons started (slurmstepd and the tasks) would outlive them: collect it by PID first.
  local below=()
  for pid in "${pids[@]}"; do below+=($(descendants "$pid")); done
  # Newest first: slurmd, slurmctld, then munged, which they authenticate through.
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do
    kill "${pids[i]}" 2>/dev/null || true
  done
  [ ${#below[@]} -eq 0 ] || kill "${below[@]}" 2>/dev/null || true
  for pid in "${pids[@]}" "${below[@]}"; do
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
  done
  if [ "${KEEP:-0}" = 1 ] || [ $status -ne 0 ]; then
    echo "check_cluster: files left in $work" >&2
  else
    rm -rf "$work"
  fi
  exit $status
}
trap cleanup EXIT
trap 'exit 130' INT TERM

seconds_since() {  # wall seconds since a `date +%s.%N` time
  awk -v start="$1" -v now="$(date +%s.%N)" 'BEGIN { printf "%.3f", now - start }'
}

free_port() {  # a TCP port on loopback nobody listens on
  python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}

# munge: a fresh key, its own socket, log and state in the folder.
mkdir -p "$work/munge"
chmod 755 "$work/munge"
dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$work/munge/munge.key"
socket="$work/munge/munge.socket"
munged --foreground --force --key-file="$work/munge/munge.key" --socket="$socket" \
  --pid-file="$work/munge/munged.pid" --log-file="$work/munge/munged.log" --seed-file="$work/munge/munged.seed" \
  >"$work/munge/munged.stdout" 2>&1 &
pids+=($!)
for _ in $(seq 50); do [ -S "$socket" ] && break; sleep 0.1; done
[ -S "$socket" ] || { echo "check_cluster: munged did not start (see $work/munge/munged.log)" >&2; exit 1; }
munge --socket="$socket" -n | unmunge --socket="$socket" >/dev/null

node="$(hostname -s)"
user="$(id -un)"
cpus="$(nproc)"
mkdir -p "$work/state" "$work/spool" "$work/out" "$work/reference"
cat >"$work/slurm.conf" <<CONF
ClusterName=tessera
SlurmctldHost=$node(127.0.0.1)
SlurmUser=$user
SlurmdUser=$user
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
AuthType=auth/munge
AuthInfo=socket=$socket
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SwitchType=switch/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MaxArraySize=100000
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=local Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$work/slurm.conf"
slurmctld -D -i -f "$SLURM_CONF" >"$work/slurmctld.stdout" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" -N "$node" >"$work/slurmd.stdout" 2>&1 &
pids+=($!)
for _ in $(seq 100); do
  state="$(sinfo -h -n "$node" -o %t 2>/dev/null || true)"
  case "$state" in idle*|mix*|alloc*) break ;; esac
  sleep 0.2
done
case "${state:-}" in idle*|mix*|alloc*) ;; *)
  echo "check_cluster: the node did not come up (state '${state:-none}'); logs in $work" >&2
  tail -5 "$work/slurmctld.log" "$work/slurmd.log" >&2 || true
  exit 1 ;;
esac
echo "check_cluster: cluster up on $node ($cpus CPUs) after $(( $(date +%s) - start_time )) s"

# The array: 4 tasks share the frames; each task's log and output in the folder.
scene="$root/scenes/turntable.toml"
submit_time=$(date +%s.%N)
job=$(cd "$work" && TESSERA="$tessera" LOG="$work/out/frames.jsonl" sbatch --parsable --array="0-$((tasks - 1))" \
  --output="$work/task-%a.out" "$root/tools/slurm/render_array.sbatch" "$scene" "$frames" "$work/out/frame_{frame:04}.png")
job="${job%%;*}"
echo "check_cluster: submitted job array $job ($tasks tasks, frames $frames)"
for _ in $(seq 3000); do
  [ -z "$(squeue -h -j "$job" 2>/dev/null)" ] && break
  sleep 0.2
done
[ -z "$(squeue -h -j "$job" 2>/dev/null)" ] || { echo "check_cluster: job $job did not finish in 10 minutes" >&2; exit 1; }
array_seconds=$(seconds_since "$submit_time")
for ((t = 0; t < tasks; t++)); do
  grep -q "^shard $((t + 1))/$tasks (from SLURM_ARRAY_TASK_ID=$t " "$work/task-$t.out" \
    || { echo "check_cluster: task $t did not take shard $((t + 1))/$tasks:" >&2; cat "$work/task-$t.out" >&2; exit 1; }
done

# The same range in one process, and the comparison.
reference_start=$(date +%s.%N)
"$tessera" render "$scene" --frames "$frames" -o "$work/reference/frame_{frame:04}.png" >/dev/null
reference_seconds=$(seconds_since "$reference_start")
expected=$(ls "$work/reference" | wc -l)
got=$(ls "$work/out" | grep -c '\.png$' || true)
[ "$got" -eq "$expected" ] || { echo "check_cluster: $got frames from the array, $expected expected" >&2; exit 1; }
for file in "$work/reference"/*.png; do
  cmp -s "$file" "$work/out/$(basename "$file")" \
    || { echo "check_cluster: $(basename "$file") differs from the single-process render" >&2; exit 1; }
done
records=$(wc -l <"$work/out/frames.jsonl")
distinct=$(grep -o '"frame": [0-9]*' "$work/out/frames.jsonl" | sort -u | wc -l)
[ "$records" -eq "$expected" ] && [ "$distinct" -eq "$expected" ] \
  || { echo "check_cluster: $records records of $distinct frames in frames.jsonl, $expected expected once each" >&2; exit 1; }
echo "check_cluster: pass: $expected frames from $tasks array tasks, each once, bit-identical to one process"
# Submission to the last task's end (scheduling included) against one process of the same range.
awk -v n="$expected" -v tasks="$tasks" -v array="$array_seconds" -v one="$reference_seconds" -v whole=$(( $(date +%s) - start_time )) \
  'BEGIN { printf "check_cluster: %d frames: array of %d tasks %.1f s (%.2f frames/s), one process %.1f s (%.2f frames/s); whole check %d s\n", n, tasks, array, n / array, one, n / one, whole }'
