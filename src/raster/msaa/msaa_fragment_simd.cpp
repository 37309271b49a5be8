// λ1, λ2 of 4× MSAA fragments at their pixel centres (msaa_fragment_kernels.hpp),
// compiled once per ISA: a vector of fragments at a time, their triangles'
// corners gathered lane by lane, the edge functions in double.
#include <cstddef>
#include <cstdint>

#include "simd/kernel_prelude.hpp"
#include "simd/lane_helpers.hpp"
#include "simd/transpose.hpp"

#include "raster/msaa/msaa_fragment_kernels.hpp"
#include "raster/msaa/msaa_list_kernel.hpp"
#include "raster/raster_limits.hpp"

namespace tessera::raster {
namespace {

using Arch = TESSERA_SIMD_ARCH;
using Int = xsimd::batch<std::int32_t, Arch>;
using Float = xsimd::batch<float, Arch>;
using Double = xsimd::batch<double, Arch>;
static_assert(Double::size * 2 == Float::size);
constexpr std::size_t kLanes = Float::size;

using simd::round_to_float;

// The lanes of an int32 vector as two vectors of doubles (exact).
[[gnu::always_inline]] inline void widen(const Int& v, Double& lo, Double& hi) {
#if XSIMD_WITH_AVX512F
    lo = _mm512_cvtepi32_pd(_mm512_castsi512_si256(v));
    hi = _mm512_cvtepi32_pd(_mm512_extracti64x4_epi64(v, 1));
#elif XSIMD_WITH_AVX
    lo = _mm256_cvtepi32_pd(_mm256_castsi256_si128(v));
    hi = _mm256_cvtepi32_pd(_mm256_extractf128_si256(v, 1));
#else
    lo = _mm_cvtepi32_pd(v);
    hi = _mm_cvtepi32_pd(_mm_unpackhi_epi64(v, v));
#endif
}

// A vector's worth of uint16 as int32 lanes.
[[gnu::always_inline]] inline Int widen_u16(const std::uint16_t* v) {
#if XSIMD_WITH_AVX512F
    return _mm512_cvtepu16_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(v)));
#elif XSIMD_WITH_AVX2
    return _mm256_cvtepu16_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(v)));
#else
    return _mm_cvtepu16_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(v)));
#endif
}

// (a_x · b_y − a_y · b_x) rounded once to float: the products and their
// difference are exact integers in double.
[[gnu::always_inline]] inline Float cross_to_float(const Int& ax, const Int& ay, const Int& bx, const Int& by) {
    Double ax_lo, ax_hi, ay_lo, ay_hi, bx_lo, bx_hi, by_lo, by_hi;
    widen(ax, ax_lo, ax_hi), widen(ay, ay_lo, ay_hi), widen(bx, bx_lo, bx_hi), widen(by, by_lo, by_hi);
    return round_to_float(ax_lo * by_lo - ay_lo * bx_lo, ax_hi * by_hi - ay_hi * bx_hi);
}

// One vector of fragments' triangles: corners and 1/area, lane i from
// triangle[i]. A record's first 8 words are x0 x1 x2 y0 y1 y2 and the
// pixel box: a load each and a transpose, as the triangle setup kernel reads
// its corners (a hardware gather costs more on the AMD VMs).
struct Corners {
    Int x0, y0, x1, y1, x2, y2;
    Float inv_area;
};
static_assert(offsetof(RasterTriangle, x) == 0 && offsetof(RasterTriangle, y) == 12);

#if XSIMD_WITH_AVX2
// Words x0 x1 x2 y0 y1 y2 of eight records, a vector each (an 8×8 transpose
// of their first 32 bytes, of which the box's two words are not kept).
[[gnu::always_inline]] inline void load_corners8(const RasterTriangle* const* triangle, __m256i (&c)[6]) {
    __m256i r[8], t[8], u[8];
    for (int i = 0; i < 8; ++i) r[i] = _mm256_load_si256(reinterpret_cast<const __m256i*>(triangle[i]));
    for (int i = 0; i < 8; i += 2)
        t[i] = _mm256_unpacklo_epi32(r[i], r[i + 1]), t[i + 1] = _mm256_unpackhi_epi32(r[i], r[i + 1]);
    for (int i = 0; i < 8; i += 4) {
        u[i] = _mm256_unpacklo_epi64(t[i], t[i + 2]), u[i + 1] = _mm256_unpackhi_epi64(t[i], t[i + 2]);
        u[i + 2] = _mm256_unpacklo_epi64(t[i + 1], t[i + 3]), u[i + 3] = _mm256_unpackhi_epi64(t[i + 1], t[i + 3]);
    }
    // u[j] (j < 4): word j of records 0-3 in its low half, word j + 4 of them
    // in its high half; u[j + 4] the same of records 4-7.
    c[0] = _mm256_permute2x128_si256(u[0], u[4], 0x20), c[4] = _mm256_permute2x128_si256(u[0], u[4], 0x31);
    c[1] = _mm256_permute2x128_si256(u[1], u[5], 0x20), c[5] = _mm256_permute2x128_si256(u[1], u[5], 0x31);
    c[2] = _mm256_permute2x128_si256(u[2], u[6], 0x20), c[3] = _mm256_permute2x128_si256(u[3], u[7], 0x20);
}
#endif

[[gnu::always_inline]] inline Corners load_corners(const RasterTriangle* const* triangle) {
    Corners c;
#if XSIMD_WITH_AVX512F
    // Two sets of eight, one per 256-bit half.
    __m256i low[6], high[6];
    load_corners8(triangle, low);
    load_corners8(triangle + 8, high);
    Int w[6];
    for (int k = 0; k < 6; ++k) w[k] = simd::join_halves(low[k], high[k]);
    c.x0 = w[0], c.x1 = w[1], c.x2 = w[2], c.y0 = w[3], c.y1 = w[4], c.y2 = w[5];
#elif XSIMD_WITH_AVX2
    __m256i w[6];
    load_corners8(triangle, w);
    c.x0 = w[0], c.x1 = w[1], c.x2 = w[2], c.y0 = w[3], c.y1 = w[4], c.y2 = w[5];
#else
    __m128 r[4];
    for (int i = 0; i < 4; ++i) r[i] = _mm_load_ps(reinterpret_cast<const float*>(triangle[i]));
    _MM_TRANSPOSE4_PS(r[0], r[1], r[2], r[3]);  // x0 x1 x2 y0
    c.x0 = _mm_castps_si128(r[0]), c.x1 = _mm_castps_si128(r[1]), c.x2 = _mm_castps_si128(r[2]), c.y0 = _mm_castps_si128(r[3]);
    for (int i = 0; i < 4; ++i) r[i] = _mm_load_ps(reinterpret_cast<const float*>(triangle[i]) + 4);
    _MM_TRANSPOSE4_PS(r[0], r[1], r[2], r[3]);  // y1 y2, the box
    c.y1 = _mm_castps_si128(r[0]), c.y2 = _mm_castps_si128(r[1]);
#endif
    alignas(64) float inv_area[kLanes];
    for (std::size_t i = 0; i < kLanes; ++i) inv_area[i] = triangle[i]->inv_area;
    c.inv_area = Float::load_aligned(inv_area);
    return c;
}

}  // namespace

void TESSERA_SIMD_ENTRY(fragment_barycentrics)(const FragmentCentres& f) {
    const Int centre_x(f.origin_x * kSubpixelScale + kSubpixelScale / 2);
    const Int centre_y(f.origin_y * kSubpixelScale + kSubpixelScale / 2);
    std::size_t k = 0;
    for (; k + kLanes <= f.count; k += kLanes) {
        const Corners c = load_corners(f.triangle + k);
        const Int px = centre_x + (widen_u16(f.x + k) << kSubpixelBits);
        const Int py = centre_y + (widen_u16(f.y + k) << kSubpixelBits);
        // As screen_barycentrics(): λ1 = E(2→0)/area, λ2 = E(0→1)/area, with
        // E(a→b) at p = (b − a) × (p − a).
        const Float lambda1 = cross_to_float(c.x0 - c.x2, c.y0 - c.y2, px - c.x2, py - c.y2) * c.inv_area;
        const Float lambda2 = cross_to_float(c.x1 - c.x0, c.y1 - c.y0, px - c.x0, py - c.y0) * c.inv_area;
        lambda1.store_unaligned(f.lambda1 + k), lambda2.store_unaligned(f.lambda2 + k);
    }
    for (; k < f.count; ++k) {  // the last few, as screen_barycentrics()
        const RasterTriangle& t = *f.triangle[k];
        const std::int64_t px = std::int64_t(f.origin_x + f.x[k]) * kSubpixelScale + kSubpixelScale / 2;
        const std::int64_t py = std::int64_t(f.origin_y + f.y[k]) * kSubpixelScale + kSubpixelScale / 2;
        f.lambda1[k] = float(edge_function(t.x[2], t.y[2], t.x[0], t.y[0], px, py)) * t.inv_area;
        f.lambda2[k] = float(edge_function(t.x[0], t.y[0], t.x[1], t.y[1], px, py)) * t.inv_area;
    }
}

std::size_t TESSERA_SIMD_ENTRY(list_fragments)(const SampleListing& samples) { return list_sample_fragments(samples); }

}  // namespace tessera::raster
