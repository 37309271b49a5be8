// Transposes of 32-bit lanes for AVX2 kernels that move records (structs of
// 32-bit words) in and out of one-vector-per-word form: xsimd 8.1 has no
// transpose, hence the intrinsics. For kernel sources compiled with AVX2 or AVX-512.
#pragma once

#if defined(__AVX2__)
#include <immintrin.h>

namespace tessera::simd {

// 4×4 within each 128-bit half: word w of lane j (j < 4) and of lane j + 4
// trade places with word j of lanes w and w + 4. Its own inverse: it turns
// four records per half (one per register) into four word vectors and back.
inline void transpose4x4_halves(__m256 (&r)[4]) {
    const __m256 t0 = _mm256_unpacklo_ps(r[0], r[1]), t1 = _mm256_unpacklo_ps(r[2], r[3]);
    const __m256 t2 = _mm256_unpackhi_ps(r[0], r[1]), t3 = _mm256_unpackhi_ps(r[2], r[3]);
    r[0] = _mm256_shuffle_ps(t0, t1, 0x44), r[1] = _mm256_shuffle_ps(t0, t1, 0xEE);
    r[2] = _mm256_shuffle_ps(t2, t3, 0x44), r[3] = _mm256_shuffle_ps(t2, t3, 0xEE);
}

// 8×8: lane j of r[i] becomes lane i of r[j].
inline void transpose8x8(__m256 (&r)[8]) {
    __m256 t[8], u[8];
    for (int i = 0; i < 8; i += 2) t[i] = _mm256_unpacklo_ps(r[i], r[i + 1]), t[i + 1] = _mm256_unpackhi_ps(r[i], r[i + 1]);
    for (int i = 0; i < 8; i += 4) {
        u[i] = _mm256_shuffle_ps(t[i], t[i + 2], 0x44), u[i + 1] = _mm256_shuffle_ps(t[i], t[i + 2], 0xEE);
        u[i + 2] = _mm256_shuffle_ps(t[i + 1], t[i + 3], 0x44), u[i + 3] = _mm256_shuffle_ps(t[i + 1], t[i + 3], 0xEE);
    }
    for (int i = 0; i < 4; ++i) {
        r[i] = _mm256_permute2f128_ps(u[i], u[i + 4], 0x20);
        r[i + 4] = _mm256_permute2f128_ps(u[i], u[i + 4], 0x31);
    }
}

#if defined(__AVX512F__)
// Lanes 8h .. 8h + 8 of a 512-bit vector (h = 0 or 1), and two 256-bit halves
// as one vector: for running the 8-lane transposes above on each half.
inline __m256 half_of(__m512 x, int h) { return h == 0 ? _mm512_castps512_ps256(x) : _mm512_extractf32x8_ps(x, 1); }
inline __m512 join_halves(__m256 low, __m256 high) {
    return _mm512_insertf32x8(_mm512_castps256_ps512(low), high, 1);
}
inline __m512i join_halves(__m256i low, __m256i high) {
    return _mm512_inserti64x4(_mm512_castsi256_si512(low), high, 1);
}

// transpose4x4_halves for 512 bits: 4×4 within each 128-bit quarter.
inline void transpose4x4_quarters(__m512 (&r)[4]) {
    const __m512 t0 = _mm512_unpacklo_ps(r[0], r[1]), t1 = _mm512_unpacklo_ps(r[2], r[3]);
    const __m512 t2 = _mm512_unpackhi_ps(r[0], r[1]), t3 = _mm512_unpackhi_ps(r[2], r[3]);
    r[0] = _mm512_shuffle_ps(t0, t1, 0x44), r[1] = _mm512_shuffle_ps(t0, t1, 0xEE);
    r[2] = _mm512_shuffle_ps(t2, t3, 0x44), r[3] = _mm512_shuffle_ps(t2, t3, 0xEE);
}
#endif

}  // namespace tessera::simd
#endif
