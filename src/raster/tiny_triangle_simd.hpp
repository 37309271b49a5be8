// The tiny-triangle test of the kernels that set tiny triangles up themselves
// (tile_rasterizer_simd.cpp, msaa_simd.cpp), in vector registers. Included by
// kernel sources only, after simd/kernel_prelude.hpp: each ISA's copy lives in
// its object's anonymous namespace.
#pragma once

#include <cstddef>

#include "raster/raster_kernels.hpp"
#include "raster/triangle_setup.hpp"

namespace tessera::raster {
namespace {

// Whether every corner lies within kTinySpan of the others in x and in y:
// |a - b| < kTinySpan for the three pairs of x and of y, six lanes of one
// vector (|a - b| < 2^24: no overflow). Hand-written: xsimd 8.1 has no lane
// permutation, and the scalar tests kept x and y in registers the edge setup
// then lacked (spilled to the stack).
[[gnu::always_inline]] inline bool tiny(const RasterTriangle& t) {
    static_assert(offsetof(RasterTriangle, x) == 0 && offsetof(RasterTriangle, y) == 12);
#if XSIMD_WITH_AVX2
    // x0 x1 x2 y0 y1 y2 and two lanes of the pixel box, against x1 x2 x0 y1 y2 y0 (box lanes against themselves).
    const __m256i corners = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(&t));
    const __m256i next = _mm256_permutevar8x32_epi32(corners, _mm256_setr_epi32(1, 2, 0, 4, 5, 3, 6, 7));
    const __m256i span = _mm256_abs_epi32(_mm256_sub_epi32(corners, next));
    return _mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpgt_epi32(_mm256_set1_epi32(kTinySpan), span))) == 0xff;
#else
    // x0 x1 x2 y0 against x1 x2 x0 y0, and y0 y1 y2 (box) against y1 y2 y0 (box).
    const __m128i xs = _mm_loadu_si128(reinterpret_cast<const __m128i*>(&t.x[0]));
    const __m128i ys = _mm_loadu_si128(reinterpret_cast<const __m128i*>(&t.y[0]));
    const __m128i span_x = _mm_abs_epi32(_mm_sub_epi32(xs, _mm_shuffle_epi32(xs, _MM_SHUFFLE(3, 0, 2, 1))));
    const __m128i span_y = _mm_abs_epi32(_mm_sub_epi32(ys, _mm_shuffle_epi32(ys, _MM_SHUFFLE(3, 0, 2, 1))));
    const __m128i limit = _mm_set1_epi32(kTinySpan);
    const __m128i near = _mm_and_si128(_mm_cmpgt_epi32(limit, span_x), _mm_cmpgt_epi32(limit, span_y));
    return _mm_movemask_ps(_mm_castsi128_ps(near)) == 0xf;
#endif
}

}  // namespace
}  // namespace tessera::raster
