// Only in a build configured with -DTESSERA_EMULATE_AVX512=ON (a test build, never
// a release): the avx512 kernel copies are compiled for x86-64-v3 and every
// 512-bit intrinsic they or xsimd's avx512 backend call comes from SIMDe's
// portable implementations, so the AVX-512 kernels' logic runs (and is tested
// against the scalar path) on a machine without AVX-512. It proves the
// kernels' logic, not g++'s real AVX-512 code generation.
//
// Included by kernel_prelude.hpp before xsimd. Order matters:
//  1. g++'s <immintrin.h> first, with its own target pragmas, so its __m512
//     types exist and SIMDe reuses them (its __m512 typedefs then repeat g++'s);
//  2. SIMDe with native aliases: _mm512_foo becomes a macro for simde_mm512_foo;
//  3. then the __AVX512*__ macros the real -march=x86-64-v4 would define, which
//     make xsimd 8.1 build its avx512 backend and our #if __AVX512F__ paths.
// An intrinsic SIMDe 0.7.4 lacks falls through to g++'s own, which fails to
// compile here ("inlining failed ... target specific option mismatch"), never
// silently; the shims below fill the ones our kernels and xsimd need.
#pragma once

#if !defined(TESSERA_EMULATE_AVX512)
#error "avx512_emulation.hpp is only for the -DTESSERA_EMULATE_AVX512=ON build"
#endif
#if defined(__AVX512F__)
#error "TESSERA_EMULATE_AVX512 builds the avx512 copies for x86-64-v3; do not add -mavx512f"
#endif

#include <immintrin.h>

#define SIMDE_ENABLE_NATIVE_ALIASES
// Emulate every AVX-512 subset, whatever the compiler is told.
#define SIMDE_X86_AVX512F_NO_NATIVE
#define SIMDE_X86_AVX512BW_NO_NATIVE
#define SIMDE_X86_AVX512CD_NO_NATIVE
#define SIMDE_X86_AVX512DQ_NO_NATIVE
#define SIMDE_X86_AVX512VL_NO_NATIVE
#include <simde/x86/avx512.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

// Lane by lane, as Intel's manual defines each instruction (default MXCSR:
// round to nearest even, exceptions masked).
namespace tessera::simd::emulated {

// Each lane of `a` (of type In) converted by static_cast to Out: VCVTDQ2PS,
// VCVTDQ2PD, VPMOVZXWD and VCVTPD2PS, whose lanes C++'s conversions round as
// the instructions do (to nearest even; int32 → double and uint16 → int32 exact).
template <class In, class Out, class OutVector, class InVector>
OutVector convert_lanes(InVector a) {
    constexpr std::size_t kLanes = sizeof(OutVector) / sizeof(Out);
    static_assert(sizeof(InVector) >= kLanes * sizeof(In));
    In in[kLanes];
    Out out[kLanes];
    std::memcpy(in, &a, sizeof in);
    for (std::size_t i = 0; i < kLanes; ++i) out[i] = static_cast<Out>(in[i]);
    OutVector result;
    std::memcpy(&result, out, sizeof result);
    return result;
}

// VCVTPS2DQ: out of range and NaN give the "integer indefinite" 0x80000000.
inline simde__m512i cvtps_epi32(simde__m512 a) {
    const simde__m512_private in = simde__m512_to_private(a);
    simde__m512i_private out;
    for (int i = 0; i < 16; ++i) {
        const float rounded = std::nearbyint(in.f32[i]);
        out.i32[i] = rounded >= -2147483648.0f && rounded < 2147483648.0f ? static_cast<std::int32_t>(rounded)
                                                                           : INT32_MIN;
    }
    return simde__m512i_from_private(out);
}

// VCVTTPS2DQ: truncates; out of range and NaN as above.
inline simde__m512i cvttps_epi32(simde__m512 a) {
    const simde__m512_private in = simde__m512_to_private(a);
    simde__m512i_private out;
    for (int i = 0; i < 16; ++i) {
        const float truncated = std::trunc(in.f32[i]);
        out.i32[i] = truncated >= -2147483648.0f && truncated < 2147483648.0f
                         ? static_cast<std::int32_t>(truncated)
                         : INT32_MIN;
    }
    return simde__m512i_from_private(out);
}

// VPSRAD: a count above 31 fills with the sign bit.
inline simde__m512i srai_epi32(simde__m512i a, unsigned count) {
    simde__m512i_private v = simde__m512i_to_private(a);
    const unsigned shift = count > 31 ? 31 : count;
    for (int i = 0; i < 16; ++i) v.i32[i] = v.i32[i] >> shift;
    return simde__m512i_from_private(v);
}

// VPCMPD with an _MM_CMPINT_* predicate.
inline simde__mmask16 cmp_epi32_mask(simde__m512i a, simde__m512i b, int predicate) {
    const simde__m512i_private x = simde__m512i_to_private(a), y = simde__m512i_to_private(b);
    simde__mmask16 mask = 0;
    for (int i = 0; i < 16; ++i) {
        bool bit = false;
        switch (predicate & 7) {
            case 0: bit = x.i32[i] == y.i32[i]; break;
            case 1: bit = x.i32[i] < y.i32[i]; break;
            case 2: bit = x.i32[i] <= y.i32[i]; break;
            case 3: bit = false; break;
            case 4: bit = x.i32[i] != y.i32[i]; break;
            case 5: bit = x.i32[i] >= y.i32[i]; break;
            case 6: bit = x.i32[i] > y.i32[i]; break;
            case 7: bit = true; break;
        }
        mask = static_cast<simde__mmask16>(mask | (bit ? 1u << i : 0u));
    }
    return mask;
}

// VPGATHERDD / VGATHERDPS: base + sign-extended index · scale, per lane.
template <class Lane, class Vector>
Vector gather_32(simde__m512i index, const void* base, int scale) {
    const simde__m512i_private offsets = simde__m512i_to_private(index);
    Lane lanes[16];
    for (int i = 0; i < 16; ++i)
        std::memcpy(&lanes[i], static_cast<const char*>(base) + std::int64_t{offsets.i32[i]} * scale, sizeof(Lane));
    Vector out;
    std::memcpy(&out, lanes, sizeof(out));
    return out;
}

// VRSQRT14PS's result is an estimate (relative error < 2^-14) whose exact bits
// the hardware defines; this gives the correctly rounded 1/sqrt instead, so
// code that uses it is tested within that bound, not bit for bit.
inline simde__m512 rsqrt14_ps(simde__m512 a) {
    simde__m512_private v = simde__m512_to_private(a);
    for (int i = 0; i < 16; ++i) v.f32[i] = 1.0f / std::sqrt(v.f32[i]);
    return simde__m512_from_private(v);
}

// VMOVDQU32 m{k}, v (512, 256 and 128 bits): lane i of `a` stored to
// base + 4i where bit i of `mask` is set; the other lanes' memory untouched.
template <class Vector>
void mask_storeu_epi32(void* base, unsigned mask, Vector a) {
    constexpr int kLanes = int(sizeof(Vector) / 4);
    std::int32_t lanes[kLanes];
    std::memcpy(lanes, &a, sizeof lanes);
    for (int i = 0; i < kLanes; ++i)
        if ((mask >> i) & 1u) std::memcpy(static_cast<char*>(base) + 4 * i, &lanes[i], 4);
}

// VMOVDQU32 zmm{k}{z}, m: lane i from base + 4i where bit i of `mask` is set
// (no other lane's memory is read), 0 elsewhere.
inline simde__m512i maskz_loadu_epi32(unsigned mask, const void* base) {
    std::int32_t lanes[16] = {};
    for (int i = 0; i < 16; ++i)
        if ((mask >> i) & 1u) std::memcpy(&lanes[i], static_cast<const char*>(base) + 4 * i, 4);
    simde__m512i out;
    std::memcpy(&out, lanes, sizeof out);
    return out;
}

// VPEXPANDD zmm{k}, zmm with merging: the set lanes of `mask` take a's lanes
// 0, 1, 2, ... in order; the others keep src's.
inline simde__m512i mask_expand_epi32(simde__m512i src, unsigned mask, simde__m512i a) {
    std::int32_t out[16], in[16];
    std::memcpy(out, &src, sizeof out);
    std::memcpy(in, &a, sizeof in);
    for (int i = 0, next = 0; i < 16; ++i)
        if ((mask >> i) & 1u) out[i] = in[next++];
    simde__m512i result;
    std::memcpy(&result, out, sizeof result);
    return result;
}

}  // namespace tessera::simd::emulated

// Missing from SIMDe 0.7.4.
#define _mm512_extractf32x8_ps(a, imm) \
    simde_mm256_castpd_ps(simde_mm512_extractf64x4_pd(simde_mm512_castps_pd(a), (imm)))
#define _mm512_cvtepi32_ps(a) (::tessera::simd::emulated::convert_lanes<std::int32_t, float, simde__m512>(a))
#define _mm512_cvtps_epi32(a) ::tessera::simd::emulated::cvtps_epi32(a)
#define _mm512_cvttps_epi32(a) ::tessera::simd::emulated::cvttps_epi32(a)
#define _mm512_cvtpd_ps(a) (::tessera::simd::emulated::convert_lanes<double, float, simde__m256>(a))
#define _mm512_cvtepi32_pd(a) (::tessera::simd::emulated::convert_lanes<std::int32_t, double, simde__m512d>(a))
#define _mm512_cvtepu16_epi32(a) (::tessera::simd::emulated::convert_lanes<std::uint16_t, std::int32_t, simde__m512i>(a))
#define _mm512_srai_epi32(a, count) ::tessera::simd::emulated::srai_epi32((a), (count))
#define _mm512_cmp_epi32_mask(a, b, predicate) ::tessera::simd::emulated::cmp_epi32_mask((a), (b), (predicate))
#define _mm512_i32gather_epi32(index, base, scale) \
    (::tessera::simd::emulated::gather_32<std::int32_t, simde__m512i>((index), (base), (scale)))
#define _mm512_i32gather_ps(index, base, scale) \
    (::tessera::simd::emulated::gather_32<float, simde__m512>((index), (base), (scale)))
#define _mm512_rsqrt14_ps(a) ::tessera::simd::emulated::rsqrt14_ps(a)
#define _mm512_mask_storeu_epi32(base, mask, a) ::tessera::simd::emulated::mask_storeu_epi32((base), unsigned(mask), (a))
#define _mm256_mask_storeu_epi32(base, mask, a) ::tessera::simd::emulated::mask_storeu_epi32((base), unsigned(mask), (a))
#define _mm512_maskz_loadu_epi32(mask, base) ::tessera::simd::emulated::maskz_loadu_epi32(unsigned(mask), (base))
#define _mm512_mask_expand_epi32(src, mask, a) ::tessera::simd::emulated::mask_expand_epi32((src), unsigned(mask), (a))
#define _mm_mask_storeu_epi32(base, mask, a) ::tessera::simd::emulated::mask_storeu_epi32((base), unsigned(mask), (a))

#define __AVX512F__ 1
#define __AVX512CD__ 1
#define __AVX512DQ__ 1
#define __AVX512BW__ 1
#define __AVX512VL__ 1
