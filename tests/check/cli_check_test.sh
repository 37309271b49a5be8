#!/usr/bin/env bash
# `tessera check` from the command line: exit statuses 0 / 1 / 2, manifest
# errors at file:line:column, --update and --update=missing, plain progress
# lines when stderr is not a terminal, and the report files.
#   usage: cli_check_test.sh TESSERA WORK_DIR
set -euo pipefail
tessera="$1"
work="$2"
scenes="$(cd "$(dirname "$0")/scenes" && pwd)"
rm -rf "$work"
mkdir -p "$work"
cd "$work"

failures=0
expect_status() {  # expected-status description command...
  local expected="$1" what="$2"
  shift 2
  local status=0
  "$@" >out.txt 2>err.txt || status=$?
  if [ "$status" -ne "$expected" ]; then
    echo "FAILED: $what: exit status $status, expected $expected"; cat out.txt err.txt
    failures=$((failures + 1))
  fi
}
expect_text() {  # file text description
  if ! grep -qF -- "$2" "$1"; then
    echo "FAILED: $3: '$2' not in $1:"; cat "$1"
    failures=$((failures + 1))
  fi
}

# Missing goldens: exit 1; --update=missing adds them and lists them; then all pass: exit 0.
expect_status 1 "missing goldens" "$tessera" check "$scenes/ball.toml" "$scenes/more/glint.toml" --golden golden
expect_text err.txt "missing ball: no golden image: $work/golden/ball.png" "missing is reported"
expect_text err.txt "[1/2] missing ball (" "plain progress lines when not a terminal"
expect_status 0 "--update=missing" "$tessera" check "$scenes/ball.toml" "$scenes/more/glint.toml" --golden golden --update=missing
expect_text err.txt "added $work/golden/more/glint.png" "--update lists what it added"
expect_text out.txt "2 golden images written" "--update counts what it wrote"
expect_status 0 "all pass" "$tessera" check "$scenes/ball.toml" "$scenes/more/glint.toml" --golden golden
expect_text out.txt "check: 2 passed, 0 warned, 0 failed, 0 missing, 0 errors of 2 scenes" "summary line"
for f in check-report/index.html check-report/junit.xml check-report/summary.json; do
  [ -s "$f" ] || { echo "FAILED: $f was not written"; failures=$((failures + 1)); }
done

# A changed golden fails (1); --update=missing leaves it; --update rewrites it and says by how much.
cp golden/more/glint.png golden/ball.png
expect_status 1 "a changed golden fails" "$tessera" check "$scenes/ball.toml" --golden golden
expect_text err.txt "fail ball: 6144 pixels differ by more than 1.5/255 (0 allowed)" "what differs"
expect_status 1 "--update=missing does not touch failures" "$tessera" check "$scenes/ball.toml" --golden golden --update=missing
expect_status 0 "--update rewrites failures" "$tessera" check "$scenes/ball.toml" --golden golden --update
expect_text err.txt "updated $work/golden/ball.png (it differed: " "--update says what it changed"
expect_status 0 "then it passes" "$tessera" check "$scenes/ball.toml" --golden golden

# Thresholds on the command line: a one-pixel change passes with --fail-pixels, fails without.
oiiotool --pattern constant:color=1,1,1 1x1 3 golden/ball.png --paste +0+0 -o golden/ball.png
expect_status 1 "one pixel off fails by default" "$tessera" check "$scenes/ball.toml" --golden golden
expect_status 0 "--fail-pixels 1 lets it through" "$tessera" check "$scenes/ball.toml" --golden golden --fail-pixels 1
expect_text out.txt "1 warned" "...as a warning"

# Ignore regions from a manifest: the one changed pixel (at 0, 0) ignored, the scene passes.
printf 'scenes = ["%s/ball.toml"]\ngolden = "golden"\n[[override]]\nscenes = "ball"\nignore = [[0, 0, 2, 2]]\n' \
  "$scenes" > ignore.toml
expect_status 0 "an ignored region" "$tessera" check ignore.toml --report ignore-report
expect_text out.txt "1 passed" "...passes"
expect_text ignore-report/index.html "ignored pixels</th><td>4 (not compared" "the report counts the ignored pixels"

# --filter runs a subset of the suite; a glob that matches nothing is bad usage.
both=("$scenes/ball.toml" "$scenes/more/glint.toml")
expect_status 1 "--filter ball keeps the failing scene" "$tessera" check "${both[@]}" --golden golden --filter ball
expect_text out.txt "0 errors of 1 scenes" "--filter ran one scene"
expect_status 0 "--filter 'more/*' runs the passing one" "$tessera" check "${both[@]}" --golden golden --filter 'more/*'
expect_text out.txt "1 passed, 0 warned, 0 failed, 0 missing, 0 errors of 1 scenes" "...alone"
expect_status 2 "--filter matching nothing" "$tessera" check "${both[@]}" --golden golden --filter 'gltf/*'
expect_text err.txt "tessera: error: --filter 'gltf/*' matches no scene name of the suite" "...says which"

# --update NAME...: only the named scene is written; scene files after --update stay inputs.
cp golden/more/glint.png golden/ball.png
cp golden/more/glint.png golden/more/glint_before.png
expect_status 2 "--update with an unknown name" "$tessera" check "${both[@]}" --golden golden --update nope
expect_text err.txt "tessera: error: --update 'nope' matches no scene name of the suite" "...names it"
expect_status 0 "--update ball, before the scene files" "$tessera" check --golden golden --update ball "${both[@]}"
expect_text err.txt "updated $work/golden/ball.png (it differed: " "the named scene is updated"
expect_text out.txt "of 2 scenes" "the scene files after --update were inputs"
cmp -s golden/more/glint.png golden/more/glint_before.png || { echo "FAILED: an unnamed scene's golden changed"; failures=$((failures + 1)); }
rm golden/more/glint_before.png
expect_status 0 "then it passes" "$tessera" check "${both[@]}" --golden golden
cp golden/more/glint.png golden/ball.png
expect_status 0 "a bare --update before a scene file" "$tessera" check --golden golden --update "$scenes/ball.toml"
expect_text err.txt "updated $work/golden/ball.png" "...updates the failing scene"
expect_status 2 "--update missing and names at once" "$tessera" check "${both[@]}" --golden golden --update missing,ball

# A scene that does not load is an error (1), and the others still run.
expect_status 1 "an error" "$tessera" check "$scenes/broken.toml" "$scenes/more/glint.toml" --golden golden
expect_text err.txt "error broken: $scenes/broken.toml:2:1: missing required key 'camera.target'" "the scene's error"
expect_text err.txt "[2/2] pass more/glint" "the others go on"

# Bad usage and bad manifests: 2, with file:line:column.
expect_status 2 "no input" "$tessera" check
expect_status 2 "bad threshold value" "$tessera" check "$scenes/ball.toml" --golden golden --fail -1
expect_status 2 "bad --update value" "$tessera" check "$scenes/ball.toml" --golden golden --update=all
expect_status 2 "scenes without --golden" "$tessera" check "$scenes/ball.toml" "$scenes/cube.toml"
printf 'scenes = ["%s/*.toml"]\ngolden = "golden"\n[thresholds]\nfial = 0.1\n' "$scenes" > bad.toml
expect_status 2 "unknown manifest key" "$tessera" check bad.toml
expect_text err.txt "tessera: error: bad.toml:4:1: unknown key 'thresholds.fial'" "manifest error position"
printf 'scenes = ["%s/ball.toml", "%s/more/*.toml"]\ngolden = "golden"\nreport = "manifest-report"\n[thresholds]\nfail_pixels = 1\n' \
  "$scenes" "$scenes" > check.toml
expect_status 0 "a manifest" "$tessera" check check.toml
[ -s manifest-report/index.html ] || { echo "FAILED: the manifest's report folder was not used"; failures=$((failures + 1)); }

if find . -name '*.tmp.*' | grep -q .; then echo "FAILED: temporary files left behind"; failures=$((failures + 1)); fi
if [ "$failures" -ne 0 ]; then echo "$failures checks failed"; exit 1; fi
echo "all tessera check command-line checks passed"
