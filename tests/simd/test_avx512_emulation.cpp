#include <doctest/doctest.h>

#include <string>

#include "simd/isa.hpp"

namespace tessera::test {
int avx512_emulation_mismatches(std::string& first);  // avx512_emulation_check.cpp, built for x86-64-v3
}

// Only in the -DTESSERA_EMULATE_AVX512=ON build (tests/simd/CMakeLists.txt). The name
// mentions avx512 so that tools/ci/check_avx512_emulated.sh runs it with the every-ISA tests.
TEST_CASE("emulated avx512: the SIMDe shims compute what AVX2's instructions compute, lane by lane") {
    REQUIRE(tessera::simd::isa_supported(tessera::simd::Isa::avx2));
    std::string first;
    const int mismatches = tessera::test::avx512_emulation_mismatches(first);
    CAPTURE(first);
    CHECK(mismatches == 0);
    CHECK(tessera::simd::isa_supported(tessera::simd::Isa::avx512));  // the emulation is active
}
