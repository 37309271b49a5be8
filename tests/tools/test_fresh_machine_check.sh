#!/usr/bin/env bash
# tools/ci/fresh_machine_check.sh refuses clearly, with exit status 2, where it cannot run:
# without root, and without a network to the package registry. (Its real run, both
# quick-start commands on new Debian 12 roots, is a step of .ci/run: minutes, not a unit test.)
# Exit 77 (ctest's skip) when this machine cannot set up a case.
set -uo pipefail
script="$1/tools/ci/fresh_machine_check.sh"
checked=0

expect_refusal() {  # NAME EXPECTED_TEXT COMMAND...
  local name="$1" expected="$2"; shift 2
  local output status
  output="$("$@" 2>&1)"; status=$?
  if [ "$status" -ne 2 ] || ! grep -q "cannot run: .*$expected" <<<"$output"; then
    echo "FAIL $name: exit $status, output:"; echo "$output"; exit 1
  fi
  echo "ok   $name: $output"
  checked=$((checked + 1))
}

if [ "$(id -u)" -eq 0 ] && command -v setpriv >/dev/null; then
  expect_refusal "not root" "needs root" setpriv --reuid=65534 --regid=65534 --clear-groups bash "$script"
  # A network namespace of its own has no route anywhere: the registry is out of reach.
  if unshare -n true 2>/dev/null && command -v mmdebstrap >/dev/null; then
    expect_refusal "no network" "no network to the Debian package registry" unshare -n bash "$script"
  else
    echo "skip no network: needs unshare -n and mmdebstrap"
  fi
elif [ "$(id -u)" -ne 0 ]; then
  expect_refusal "not root" "needs root" bash "$script"
fi
[ "$checked" -gt 0 ] || { echo "skipped: no case could be set up here"; exit 77; }
