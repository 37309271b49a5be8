#!/usr/bin/env bash
# The bash completion file and the man page made at build time (into
# BUILD/share/) from the command-line definition: they exist, they are what
# the binary prints now, bash and man read them, and they hold the commands
# and options of both binaries (tessera's render, tessera-tools' bench, check,
# contact-sheet) with completions that work.
#   completion_and_man_test.sh BUILD/tessera BUILD
set -euo pipefail
tessera="$1"
build="$2"
completion="$build/share/bash-completion/completions/tessera"
man_page="$build/share/man/man1/tessera.1"
fail() { echo "FAIL: $*" >&2; exit 1; }

[ -s "$completion" ] || fail "no bash completion at $completion"
[ -s "$man_page" ] || fail "no man page at $man_page"
diff -q <("$tessera" --print-completion bash) "$completion" >/dev/null || fail "$completion is stale"
diff -q <("$tessera" --print-man) "$man_page" >/dev/null || fail "$man_page is stale"
bash -n "$completion" || fail "bash cannot parse $completion"

# Completions as bash computes them for a partial command line.
complete_words() {  # WORDS... : COMPREPLY for the last word
  # shellcheck disable=SC1090
  source "$completion"
  COMP_WORDS=("$@")
  COMP_CWORD=$(($# - 1))
  COMPREPLY=()
  _tessera
  printf '%s\n' "${COMPREPLY[@]}"
}
grep -qx render <(complete_words tessera ren) || fail "'tessera ren<TAB>' does not offer render"
grep -qx contact-sheet <(complete_words tessera con) || fail "'tessera con<TAB>' does not offer contact-sheet"
grep -qx -- --width <(complete_words tessera render --wi) || fail "'tessera render --wi<TAB>' does not offer --width"
grep -qx -- --trace <(complete_words tessera bench --tr) || fail "'tessera bench --tr<TAB>' does not offer --trace"
grep -qx -- --quiet <(complete_words tessera check --qu) || fail "'tessera check --qu<TAB>' does not offer --quiet"
[ "$(complete_words tessera bench --heatmap-metric '' | sort | tr '\n' ' ')" = "time work " ] ||
  fail "'tessera bench --heatmap-metric <TAB>' does not offer time and work"
[ "$(complete_words tessera render x.toml --msaa '' | sort | tr '\n' ' ')" = "1 4 " ] ||
  fail "'tessera render --msaa <TAB>' does not offer 1 and 4"
if grep -qx -- --trace <(complete_words tessera render --tr); then fail "render offers bench's --trace"; fi

grep -q '^\.TH TESSERA 1' "$man_page" || fail "the man page has no .TH TESSERA 1 header"
for sub in render bench 'contact\\-sheet' check; do
  grep -q "^\.SS \"tessera $sub" "$man_page" || fail "the man page has no section for $sub"
done
for option in '\\-\\-width' '\\-\\-trace' '\\-\\-golden' '\\-\\-columns' '\\-\\-frames'; do
  grep -q -- "$option" "$man_page" || fail "the man page does not mention $option"
done
grep -q 'default: 30' "$man_page" || fail "the man page does not give bench --frames' default 30"
if command -v man >/dev/null; then
  MANWIDTH=100 man -l "$man_page" 2>/dev/null | grep -q "EXIT STATUS" || fail "man cannot format $man_page"
fi
echo "ok: completion and man page made from the CLI definition, $(wc -l <"$completion") and $(wc -l <"$man_page") lines"
