#!/usr/bin/env bash
# Runs the AVX-512 kernel copies on a CPU without AVX-512, through SIMDe's portable
# AVX-512 intrinsics (cmake option TESSERA_EMULATE_AVX512, src/simd/avx512_emulation.hpp):
# builds the test binary in build-avx512emu/ (Release, ccache when installed) and runs,
# through ctest, the test cases that compare every ISA with the scalar path (those of the
# test files that name avx512 or the ISA helpers). In that build isa_supported(avx512)
# is true, so they run the avx512 copies instead of skipping them.
#   tools/ci/check_avx512_emulated.sh         the every-ISA tests
#   tools/ci/check_avx512_emulated.sh --all   the build's whole suite (avx512 is also `--isa auto` there)
# It proves the avx512 kernels' logic, not g++'s real AVX-512 code generation.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
build="$root/build-avx512emu"
jobs="$(nproc)"

bash "$root/tools/install_dependencies.sh"
source "$root/tools/compiler_cache.sh"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DTESSERA_BUILD_TESTS=ON \
  -DTESSERA_BUILD_GL_REFERENCE=OFF -DTESSERA_BUILD_MICROBENCH=OFF -DTESSERA_EMULATE_AVX512=ON \
  "${compiler_cache[@]}" >/dev/null

if [ "${1:-}" = --all ]; then
  cmake --build "$build" -j"$jobs"
  exec ctest --test-dir "$build" --output-on-failure -j"$jobs"
fi

cmake --build "$build" -j"$jobs" --target tessera_tests
tests="$build/tests/tessera_tests"
# The test files that compare ISAs, as a doctest source-file filter.
files=$(cd "$root" && grep -rlE 'avx512|isa_supported|isa_agreement' tests --include='*.cpp' | sort | sed 's|^|*|' | paste -sd, -)
[ -n "$files" ] || { echo "no every-ISA test files found under tests/" >&2; exit 1; }
"$tests" --version >/dev/null
"$tests" --reporters=console --source-file="$files" --list-test-cases --no-version |
  sed -e '/^\[doctest\]/d' -e '/^=\{5,\}$/d' -e '/^$/d' >"$build/avx512_tests.txt"
# The ctest numbers of those test cases (doctest_discover_tests names a ctest test by its test case).
numbers=$(ctest --test-dir "$build" -N | awk -v list="$build/avx512_tests.txt" '
  BEGIN { while ((getline name < list) > 0) if (!(name in wanted)) { wanted[name] = 1; total++ } }
  match($0, /^ *Test +#[0-9]+: /) {
    name = substr($0, RLENGTH + 1); n = $0; sub(/^ *Test +#/, "", n); sub(/:.*/, "", n)
    if (name in wanted) { printf "%s%s", sep, n; sep = ","; found++ }
  }
  END { if (found != total) { print "\nctest lists " found " of " total " test cases" > "/dev/stderr"; exit 1 } }')
echo "AVX-512 (emulated): $(wc -l <"$build/avx512_tests.txt") every-ISA test cases from $(echo "$files" | tr ',' '\n' | wc -l) files"
# The avx512 copy must really be in play: the build reports it supported.
"$tests" --test-case='ISA names and support' --success 2>&1 | grep -q 'ISA avx512 supported' ||
  { echo "build-avx512emu does not report avx512 as supported: the emulation is not active" >&2; exit 1; }
ctest --test-dir "$build" --output-on-failure -j"$jobs" -I "0,0,0,$numbers"
