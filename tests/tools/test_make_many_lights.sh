#!/usr/bin/env bash
# tools/bench/make_many_lights.py: the committed scene is what it writes; --range R gives
# every light that explicit range, and the scene renders; bad arguments are refused
# with a message naming them and a non-zero exit.
#   test_make_many_lights.sh SOURCE_DIR TESSERA_BINARY
set -euo pipefail
src="$1"
tessera="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
script="$src/tools/bench/make_many_lights.py"

python3 "$script" 256 | cmp - "$src/scenes/many_lights.toml"  # edit the script, not the scene

python3 "$script" 24 --range 2.5 >"$work/local.toml"
[ "$(grep -c '^\[\[lights\]\]' "$work/local.toml")" = 24 ]
[ "$(grep -c '^range = 2.5$' "$work/local.toml")" = 24 ]
! grep -q 'range = "auto"' "$work/local.toml"
"$tessera" bench "$work/local.toml" --width 160 --height 90 --threads 1 --frames 1 --warmup 0 >/dev/null

refused() {  # refused EXPECTED_TEXT ARGS...: a non-zero exit whose message holds EXPECTED_TEXT
  local expected="$1"
  shift
  if python3 "$script" "$@" >"$work/out.toml" 2>"$work/err.txt"; then
    echo "make_many_lights.py $* was accepted" >&2
    exit 1
  fi
  grep -q -- "$expected" "$work/err.txt" || { echo "no '$expected' in:" >&2; cat "$work/err.txt" >&2; exit 1; }
}
refused "N must be at least 1" 0
refused "--range must be" 8 --range -1
refused "--range must be" 8 --range nan
refused "--range must be" 8 --range 0
refused "invalid float value" 8 --range far
echo "make_many_lights: ok"
