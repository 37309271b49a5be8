// λ1, λ2 of 4× MSAA fragments at their pixel centres (msaa_fragment_kernels.hpp),
// compiled once per ISA: a vector of fragments at a time, their triangles'
// corners gathered lane by lane, the edge functions in double.
#include <algorithm>
#include <cstdint>

#include "simd/kernel_prelude.hpp"
#include "simd/lane_helpers.hpp"

#include "raster/msaa_fragment_kernels.hpp"
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

// (a_x · b_y − a_y · b_x) rounded once to float: the products and their
// difference are exact integers in double.
[[gnu::always_inline]] inline Float cross_to_float(const Int& ax, const Int& ay, const Int& bx, const Int& by) {
    Double ax_lo, ax_hi, ay_lo, ay_hi, bx_lo, bx_hi, by_lo, by_hi;
    widen(ax, ax_lo, ax_hi), widen(ay, ay_lo, ay_hi), widen(bx, bx_lo, bx_hi), widen(by, by_lo, by_hi);
    return round_to_float(ax_lo * by_lo - ay_lo * bx_lo, ax_hi * by_hi - ay_hi * bx_hi);
}

// One vector's corners, centres and 1/area, lane by lane (lanes past the
// last fragment keep earlier values; their results are not stored).
struct Lanes {
    alignas(64) std::int32_t x0[kLanes] = {}, y0[kLanes] = {}, x1[kLanes] = {}, y1[kLanes] = {}, x2[kLanes] = {},
                                        y2[kLanes] = {}, px[kLanes] = {}, py[kLanes] = {};
    alignas(64) float inv_area[kLanes] = {};
    alignas(64) float lambda1[kLanes] = {}, lambda2[kLanes] = {};
};

}  // namespace

void TESSERA_SIMD_ENTRY(fragment_barycentrics)(const FragmentCentres& f) {
    Lanes lanes;
    const std::int32_t centre_x = f.origin_x * kSubpixelScale + kSubpixelScale / 2;
    const std::int32_t centre_y = f.origin_y * kSubpixelScale + kSubpixelScale / 2;
    for (std::size_t k = 0; k < f.count; k += kLanes) {
        const std::size_t n = std::min(kLanes, f.count - k);
        for (std::size_t i = 0; i < n; ++i) {
            const RasterTriangle& t = *f.triangle[k + i];
            lanes.x0[i] = t.x[0], lanes.y0[i] = t.y[0], lanes.x1[i] = t.x[1], lanes.y1[i] = t.y[1];
            lanes.x2[i] = t.x[2], lanes.y2[i] = t.y[2], lanes.inv_area[i] = t.inv_area;
            lanes.px[i] = centre_x + std::int32_t(f.x[k + i]) * kSubpixelScale;
            lanes.py[i] = centre_y + std::int32_t(f.y[k + i]) * kSubpixelScale;
        }
        const Int x0 = Int::load_aligned(lanes.x0), y0 = Int::load_aligned(lanes.y0);
        const Int x1 = Int::load_aligned(lanes.x1), y1 = Int::load_aligned(lanes.y1);
        const Int x2 = Int::load_aligned(lanes.x2), y2 = Int::load_aligned(lanes.y2);
        const Int px = Int::load_aligned(lanes.px), py = Int::load_aligned(lanes.py);
        const Float inv_area = Float::load_aligned(lanes.inv_area);
        // As screen_barycentrics(): λ1 = E(2→0)/area, λ2 = E(0→1)/area, with
        // E(a→b) at p = (b − a) × (p − a).
        const Float lambda1 = cross_to_float(x0 - x2, y0 - y2, px - x2, py - y2) * inv_area;
        const Float lambda2 = cross_to_float(x1 - x0, y1 - y0, px - x0, py - y0) * inv_area;
        if (n == kLanes) {
            lambda1.store_unaligned(f.lambda1 + k), lambda2.store_unaligned(f.lambda2 + k);
            continue;
        }
        lambda1.store_aligned(lanes.lambda1), lambda2.store_aligned(lanes.lambda2);
        std::copy_n(lanes.lambda1, n, f.lambda1 + k), std::copy_n(lanes.lambda2, n, f.lambda2 + k);
    }
}

}  // namespace tessera::raster
