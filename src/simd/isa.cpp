#include "simd/isa.hpp"

#include <stdexcept>
#include <string>

#include <xsimd/xsimd.hpp>

namespace tessera::simd {

namespace {

struct IsaSupport {
    bool sse4 = false, avx2 = false, avx512 = false;
};

// Each kernel copy is built with -march=x86-64-v2/v3/v4, so the compiler may use
// anything in that level (POPCNT, BMI2, AVX512VL, ...), and the OS must save
// the wider registers. xsimd 8.1 checks neither, so the levels' features are
// asked of the compiler's runtime too, which checks both. (Spelled out: clang
// before 16 does not know the level names "x86-64-v2".)
IsaSupport detect_isa_support() {
    const auto arch = xsimd::available_architectures();
    __builtin_cpu_init();
    const bool v2 = __builtin_cpu_supports("sse4.2") && __builtin_cpu_supports("ssse3") &&
                    __builtin_cpu_supports("popcnt");
    const bool v3 = v2 && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
                    __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2");
    const bool v4 = v3 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                    __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512dq") &&
                    __builtin_cpu_supports("avx512vl");
    IsaSupport s;
    s.sse4 = arch.sse4_2 && v2;
    s.avx2 = arch.fma3_avx2 && v3;
    s.avx512 = arch.avx512bw && v4;
#if defined(TESSERA_EMULATE_AVX512)
    // This build's avx512 copies are x86-64-v3 code calling SIMDe's emulated
    // AVX-512 intrinsics (cmake/SimdTargets.cmake): they run wherever avx2 does.
    s.avx512 = s.avx2;
#endif
    return s;
}

const IsaSupport& isa_support() {
    static const IsaSupport support = detect_isa_support();
    return support;
}

}  // namespace

std::string_view isa_name(Isa isa) {
    switch (isa) {
        case Isa::scalar: return "scalar";
        case Isa::sse4: return "sse4";
        case Isa::avx2: return "avx2";
        case Isa::avx512: return "avx512";
    }
    return "unknown";
}

bool isa_supported(Isa isa) {
    switch (isa) {
        case Isa::scalar: return true;
        case Isa::sse4: return isa_support().sse4;
        case Isa::avx2: return isa_support().avx2;
        case Isa::avx512: return isa_support().avx512;
    }
    return false;
}

Isa best_supported_isa() {
    for (Isa isa : {Isa::avx512, Isa::avx2, Isa::sse4})
        if (isa_supported(isa)) return isa;
    return Isa::scalar;
}

void require_supported(Isa isa) {
    if (!isa_supported(isa))
        throw std::invalid_argument("instruction set '" + std::string(isa_name(isa)) +
                                    "' is not supported by this CPU (best available: '" +
                                    std::string(isa_name(best_supported_isa())) + "')");
}

}  // namespace tessera::simd
