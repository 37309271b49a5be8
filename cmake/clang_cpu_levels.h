// Forced into src/simd/isa.cpp (only) by cmake/Fuzzing.cmake when the compiler
// is a clang that does not know the x86-64 level names in
// __builtin_cpu_supports (clang 14: "invalid cpu feature string for builtin";
// g++ 12 and newer clangs know them). The levels are spelled out as the
// features that define them, checked by the same builtin (which also checks
// that the OS saves the AVX/AVX-512 registers).
#pragma once

#include <cstring>

namespace tessera_compat {

inline bool cpu_supports(const char* feature) {
    const bool v2 = __builtin_cpu_supports("sse4.2") && __builtin_cpu_supports("ssse3") &&
                    __builtin_cpu_supports("popcnt");
    const bool v3 = v2 && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
                    __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2");
    const bool v4 = v3 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                    __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512dq") &&
                    __builtin_cpu_supports("avx512vl");
    if (std::strcmp(feature, "x86-64-v2") == 0) return v2;
    if (std::strcmp(feature, "x86-64-v3") == 0) return v3;
    if (std::strcmp(feature, "x86-64-v4") == 0) return v4;
    return false;  // isa.cpp asks for nothing else
}

}  // namespace tessera_compat

#define __builtin_cpu_supports(feature) ::tessera_compat::cpu_supports(feature)
