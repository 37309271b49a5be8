// Lane operations xsimd 8.1 lacks, for the sources compiled once per ISA
// (after simd/kernel_prelude.hpp), hand-written per instruction set.
#pragma once

#include <cstdint>

#include "simd/kernel_prelude.hpp"

namespace tessera::simd {
namespace {  // each ISA's copy its own, as kernel_prelude.hpp asks

// Which lanes of a 32-bit comparison hold, as bits (bit i for lane i): a movemask.
[[gnu::always_inline]] inline unsigned lane_bits(const xsimd::batch_bool<std::int32_t, TESSERA_SIMD_ARCH>& b) {
#if XSIMD_WITH_AVX512F
    return unsigned(b.data);
#elif XSIMD_WITH_AVX2
    return unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(b)));
#else
    return unsigned(_mm_movemask_ps(_mm_castsi128_ps(b)));
#endif
}

[[gnu::always_inline]] inline unsigned lane_bits(const xsimd::batch_bool<float, TESSERA_SIMD_ARCH>& b) {
#if XSIMD_WITH_AVX512F
    return unsigned(b.data);
#elif XSIMD_WITH_AVX2
    return unsigned(_mm256_movemask_ps(b));
#else
    return unsigned(_mm_movemask_ps(b));
#endif
}

// Two vectors of doubles (lanes 0..n/2-1, n/2..n-1) rounded to one of floats:
// a conversion between batches of different lane counts.
[[gnu::always_inline]] inline xsimd::batch<float, TESSERA_SIMD_ARCH> round_to_float(
    const xsimd::batch<double, TESSERA_SIMD_ARCH>& lo, const xsimd::batch<double, TESSERA_SIMD_ARCH>& hi) {
#if XSIMD_WITH_AVX512F
    const __m512d low = _mm512_castpd256_pd512(_mm256_castps_pd(_mm512_cvtpd_ps(lo)));
    return _mm512_castpd_ps(_mm512_insertf64x4(low, _mm256_castps_pd(_mm512_cvtpd_ps(hi)), 1));
#elif XSIMD_WITH_AVX
    return _mm256_set_m128(_mm256_cvtpd_ps(hi), _mm256_cvtpd_ps(lo));
#else
    return _mm_movelh_ps(_mm_cvtpd_ps(lo), _mm_cvtpd_ps(hi));
#endif
}

}  // namespace
}  // namespace tessera::simd
