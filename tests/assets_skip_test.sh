#!/usr/bin/env bash
# The tests that need the sample models (TESSERA_ASSETS_DIR) report Skipped, never Passed, where
# there are none: each doctest test case that starts with `if (test::skip_without_assets()) return;`
# runs through ctest with TESSERA_ASSETS_DIR in the environment pointing to an empty folder, and
# ctest must list every one of them as Skipped.
#   assets_skip_test.sh SOURCE_DIR BUILD_DIR WORK_DIR
set -euo pipefail
source="$1" build="$2" work="$3"
fail() { echo "FAIL: $*" >&2; exit 1; }
rm -rf "$work" && mkdir -p "$work/empty"

# The test cases: the TEST_CASE("...") { line right above each skip_without_assets() call.
marker='if \((tessera::)?test::skip_without_assets\(\)\) return;'
calls=$(grep -rhE --include='*.cpp' "$marker" "$source/tests" | wc -l)
grep -rhE --include='*.cpp' -B1 "$marker" "$source/tests" | sed -n 's/^TEST_CASE("\(.*\)") {$/\1/p' >"$work/names"
names=$(wc -l <"$work/names")
[ "$names" -ge 7 ] || fail "found $names test cases calling skip_without_assets() in tests/, expected at least 7"
[ "$names" -eq "$calls" ] ||
  fail "$calls skip_without_assets() calls, but only $names come right after a TEST_CASE(\"...\") { line: put each first in its test case"
# Their ctest numbers (doctest_discover_tests names a ctest test by its test case).
numbers=$(ctest --test-dir "$build" -N | awk -v list="$work/names" '
  BEGIN { while ((getline name < list) > 0) wanted[name] = 1 }
  match($0, /^ *Test +#[0-9]+: /) {
    name = substr($0, RLENGTH + 1); n = $0; sub(/^ *Test +#/, "", n); sub(/:.*/, "", n)
    if (name in wanted) { printf "%s%s", sep, n; sep = "," }
  }')
found=$(echo "$numbers" | tr ',' '\n' | grep -c . || true)
[ "$found" -eq "$names" ] || fail "ctest lists $found of the $names test cases ($(tr '\n' '|' <"$work/names"))"

set +e
TESSERA_ASSETS_DIR="$work/empty" ctest --test-dir "$build" -I "0,0,0,$numbers" >"$work/ctest.log" 2>&1
set -e
if grep -E 'Test +#[0-9]+: .* (Passed|\*\*\*Failed|\*\*\*Exception|\*\*\*Timeout)' "$work/ctest.log"; then
  fail "without the sample models these did not report Skipped (log: $work/ctest.log)"
fi
skipped=$(grep -c '\*\*\*Skipped' "$work/ctest.log" || true)
[ "$skipped" -eq "$names" ] || { cat "$work/ctest.log"; fail "$skipped of the $names test cases were Skipped"; }
echo "ok: without the sample models ctest reports all $names tests that need them as Skipped"
