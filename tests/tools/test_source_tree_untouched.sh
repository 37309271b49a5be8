#!/usr/bin/env bash
# A build writes nothing into the source tree (issue 34): generated files go to
# the build folder. Run after a build, this lists what git ignores in the source
# tree, where generated files used to hide (scenes/textures/ once did), and
# fails on anything but the build folders and what a person's own commands write
# there (.gitignore: spheres.png of the quick start, check-report/, .ci/artifacts/).
# tools/ci/fresh_machine_check.sh checks a fresh clone's whole `git status` after
# building.
#   test_source_tree_untouched.sh SOURCE_DIR BUILD_DIR     (exit 77: not a git checkout)
set -euo pipefail
src="$1"
build="$2"
command -v git >/dev/null || { echo "SKIP: git is not installed"; exit 77; }
git -C "$src" rev-parse --is-inside-work-tree >/dev/null 2>&1 || { echo "SKIP: $src is not a git checkout"; exit 77; }
top="$(git -C "$src" rev-parse --show-toplevel)"
# The build folder, relative to the source tree when it lies inside it.
build_rel="$(realpath -m --relative-to="$top" "$build")"
unexpected=()
while IFS= read -r line; do
  path="${line#!! }"
  case "$path" in
    build*/* | build*/ | spheres.png | check-report/* | check-report/ | .ci/artifacts/*) continue ;;
  esac
  case "$build_rel" in ../*) ;; *) [[ "$path" == "$build_rel"/* || "$path" == "$build_rel/" ]] && continue ;; esac
  unexpected+=("$path")
done < <(git -C "$top" status --porcelain --ignored=matching --untracked-files=all | grep '^!! ' || true)
if [ ${#unexpected[@]} -gt 0 ]; then
  echo "FAIL: files git ignores in the source tree $top, not written by a person's commands:" >&2
  printf '  %s\n' "${unexpected[@]}" >&2
  exit 1
fi
echo "ok: the source tree holds no ignored file but the build folders and the documented outputs"
