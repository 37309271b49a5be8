#!/usr/bin/env bash
# `tessera check --shard` and `--merge` from the command line: the printed
# part, the same split from --shard and from a Slurm array's environment, an
# empty shard, each shard's own default report folder, a merge that says what
# one run says (exit status, counts, statuses, images), and merges refused (2).
#   usage: cli_shard_test.sh TESSERA WORK_DIR
set -euo pipefail
tessera="$1"
work="$2"
scenes="$(cd "$(dirname "$0")/scenes" && pwd)"
rm -rf "$work"
mkdir -p "$work"
cd "$work"
work="$(pwd -P)"  # as the command names files: absolute, symbolic links resolved
# The runs below must not take a part from the environment this test itself runs in.
unset SLURM_ARRAY_TASK_ID SLURM_ARRAY_TASK_MIN SLURM_ARRAY_TASK_MAX SLURM_ARRAY_TASK_COUNT SLURM_ARRAY_TASK_STEP \
  JOB_COMPLETION_INDEX

failures=0
fail() { echo "FAILED: $*"; failures=$((failures + 1)); }
expect_status() {  # expected-status description command...
  local expected="$1" what="$2"
  shift 2
  local status=0
  "$@" >out.txt 2>err.txt || status=$?
  if [ "$status" -ne "$expected" ]; then
    fail "$what: exit status $status, expected $expected"; cat out.txt err.txt
  fi
}
expect_text() {  # file text description
  grep -qF -- "$2" "$1" || { fail "$3: '$2' not in $1:"; cat "$1"; }
}
# The scene names of a summary.json, one a line, in its order.
names() { python3 -c 'import json,sys; print("\n".join(s["name"] for s in json.load(open(sys.argv[1]))["scenes"]))' "$1"; }
# What a run says, without its times: exit status, counts, and each scene's name, status and reason.
outcome() {
  python3 -c 'import json,sys; d=json.load(open(sys.argv[1]))
print(d["exit_status"], json.dumps(d["counts"], sort_keys=True))
for s in d["scenes"]: print(s["name"], s["status"], s["reason"])' "$1"
}

# A suite with every status: ball fails (another scene's golden), broken is an error, cube
# passes (identical: its golden is linked from the report), more/glint has no golden.
printf 'scenes = ["%s/*.toml", "%s/more/*.toml"]\ngolden = "golden"\n' "$scenes" "$scenes" > check.toml
expect_status 1 "making the goldens" "$tessera" check check.toml --update=missing -r setup
cp golden/cube.png golden/ball.png
rm golden/more/glint.png
expect_status 1 "the whole suite in one run" "$tessera" check check.toml -r whole
outcome whole/summary.json > whole.txt
names whole/summary.json > all_names.txt
[ "$(wc -l < all_names.txt)" -eq 4 ] || fail "expected 4 scenes in the suite"

for count in 1 2 3; do
  rm -f taken.txt
  for index in $(seq 1 "$count"); do
    status=0
    "$tessera" check check.toml --shard "$index/$count" -r "of_$count/shard_$index" -q >out.txt 2>err.txt || status=$?
    [ "$status" -le 1 ] || { fail "--shard $index/$count: exit status $status"; cat out.txt err.txt; }
    expect_text out.txt "shard $index/$count (from --shard $index/$count): " "the run says which part it took"
    names "of_$count/shard_$index/summary.json" >> taken.txt
  done
  sort taken.txt | diff - <(sort all_names.txt) >/dev/null || fail "$count shards did not take every scene once: $(cat taken.txt)"
  expect_status 1 "merging $count shards" "$tessera" check --merge $(ls -d of_$count/shard_* | sort -r) -r "of_$count/merged"
  expect_text out.txt "merged $count shard reports" "the merge says what it merged"
  outcome "of_$count/merged/summary.json" > merged.txt
  diff whole.txt merged.txt || fail "the merge of $count shards says something else than one run"
  for f in index.html junit.xml summary.json; do [ -s "of_$count/merged/$f" ] || fail "of_$count/merged/$f was not written"; done
  # Every image the merged page shows is there.
  for src in $(grep -o '<img src="[^"]*"' "of_$count/merged/index.html" | sed 's/<img src="//; s/"$//' | sort -u); do
    [ -f "of_$count/merged/$src" ] || fail "of_$count/merged/index.html shows $src, which is not there"
  done
done

# A Slurm array task (--array=4-6, task 5) takes the part --shard 2/3 takes, and says so.
expect_status 1 "a Slurm array task (broken: an error)" env SLURM_ARRAY_TASK_ID=5 SLURM_ARRAY_TASK_MIN=4 SLURM_ARRAY_TASK_MAX=6 \
  SLURM_ARRAY_TASK_COUNT=3 "$tessera" check check.toml -r slurm_5 -q
expect_text out.txt "shard 2/3 (from SLURM_ARRAY_TASK_ID=5" "the part taken from Slurm"
[ "$(names slurm_5/summary.json)" = "$(names of_3/shard_2/summary.json)" ] || fail "Slurm task 5 of 4-6 is not --shard 2/3"
# A Kubernetes Indexed Job's pod: JOB_COMPLETION_INDEX with --shard-count.
expect_status 1 "a Kubernetes indexed pod" env JOB_COMPLETION_INDEX=0 "$tessera" check check.toml --shard-count 3 -r k8s_0 -q
[ "$(names k8s_0/summary.json)" = "$(names of_3/shard_1/summary.json)" ] || fail "JOB_COMPLETION_INDEX=0 of 3 is not --shard 1/3"

# Without --report, each shard writes a folder of its own under the default one.
expect_status 0 "a shard without --report" "$tessera" check check.toml --shard 3/3 -q
[ -s check-report/shard_3/summary.json ] || fail "--shard 3/3 without --report did not write check-report/shard_3"
# More parts than scenes: an empty shard is a run of nothing, exit 0.
expect_status 0 "an empty shard" "$tessera" check check.toml --shard 5/5 -r empty -q
expect_text out.txt "shard 5/5 (from --shard 5/5): 0 of 4 scenes" "an empty shard says so"
expect_text out.txt "of 0 scenes" "an empty shard checks nothing"

# Refused merges: 2, naming the file.
expect_status 2 "a shard given twice" "$tessera" check --merge of_2/shard_1 of_2/shard_1 of_2/shard_2 -r bad
expect_text err.txt "tessera: error: $work/of_2/shard_1/summary.json: shard 1/2 is also $work/of_2/shard_1/summary.json" "which shard is twice"
expect_status 2 "a shard missing" "$tessera" check --merge of_3/shard_1 of_3/shard_3 -r bad
expect_text err.txt "shard 2/3 is missing" "which shard is missing"
cp -r of_2/shard_2 doubled
python3 -c 'import json,sys
one=json.load(open("of_2/shard_1/summary.json")); d=json.load(open("doubled/summary.json"))
d["scenes"][0]["name"]=one["scenes"][0]["name"]; json.dump(d, open("doubled/summary.json","w"))'
expect_status 2 "a scene in two shards" "$tessera" check --merge of_2/shard_1 doubled -r bad
expect_text err.txt "$work/doubled/summary.json: scene \"$(names of_2/shard_1/summary.json | head -1)\" is also in $work/of_2/shard_1/summary.json" "which scene is twice"
expect_status 2 "a folder without summary.json" "$tessera" check --merge of_2/shard_1 golden -r bad
expect_text err.txt "$work/golden/summary.json: no such file" "the missing summary is named"
sed -i 's|tessera-check-summary/1|tessera-check-summary/9|' doubled/summary.json
expect_status 2 "a summary of another format" "$tessera" check --merge of_2/shard_1 doubled -r bad
expect_text err.txt "$work/doubled/summary.json: not a tessera check summary: format" "the other format is named"
expect_status 2 "--merge with --shard" "$tessera" check --merge of_2/shard_1 of_2/shard_2 --shard 1/2
expect_status 2 "--merge with thresholds" "$tessera" check --merge of_2/shard_1 of_2/shard_2 --fail 0.1 -r bad
expect_status 2 "a bad --shard" "$tessera" check check.toml --shard 4/3

if find . -name '*.tmp.*' | grep -q .; then fail "temporary files left behind"; fi
if [ "$failures" -ne 0 ]; then echo "$failures checks failed"; exit 1; fi
echo "all tessera check --shard / --merge command-line checks passed"
