// The rasterizer's inner loop over vectors of pixel centres (raster_kernels.hpp),
// compiled once per ISA. Same arithmetic as the scalar loop in
// tile_rasterizer.cpp, lane by lane, so both give bit-identical buffers.
#include <cstdint>

#include "simd/kernel_prelude.hpp"

#include "raster/raster_kernels.hpp"

namespace tessera::raster {
namespace {

using Arch = TESSERA_SIMD_ARCH;
using Int = xsimd::batch<std::int32_t, Arch>;
using Float = xsimd::batch<float, Arch>;

using Double = xsimd::batch<double, Arch>;
static_assert(Int::size <= kMaxRasterLanes && Double::size * 2 == Float::size);

alignas(64) constexpr std::int32_t kLaneIndex[16] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
alignas(64) constexpr double kLaneIndexDouble[16] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};

// Two vectors of doubles (lanes 0..n/2-1, n/2..n-1) rounded to one of floats.
// Hand-written: xsimd 8.1 has no conversion between batches of different lane
// counts.
Float round_to_float(const Double& lo, const Double& hi) {
#if XSIMD_WITH_AVX512F
    static_assert(Float::size == 16);
    const __m512d low = _mm512_castpd256_pd512(_mm256_castps_pd(_mm512_cvtpd_ps(lo)));
    return _mm512_castpd_ps(_mm512_insertf64x4(low, _mm256_castps_pd(_mm512_cvtpd_ps(hi)), 1));
#elif XSIMD_WITH_AVX
    static_assert(Float::size == 8);
    return _mm256_set_m128(_mm256_cvtpd_ps(hi), _mm256_cvtpd_ps(lo));
#else
    static_assert(Float::size == 4);
    return _mm_movelh_ps(_mm_cvtpd_ps(lo), _mm_cvtpd_ps(hi));
#endif
}

// kCovered: every pixel of the block is inside, only the depth test remains.
// kWideWeights: barycentric numerators in double (see EdgeBlock32).
template <bool kCovered, bool kWideWeights>
void rasterize_block(const EdgeBlock32& b, const WideWeights* wide, const TileView& tile, RasterCounters& counters) {
    constexpr int kLanes = int(Int::size);
    const Int lane = Int::load_aligned(kLaneIndex);
    const Int lane_step0 = lane * Int(b.step_x[0]), lane_step1 = lane * Int(b.step_x[1]),
              lane_step2 = lane * Int(b.step_x[2]);
    const Int x_end(b.x_end);
    const Float inv_area(b.inv_area), d0(b.d0), d10(b.d10), d20(b.d20), zero(0.0f);
    const Int id(std::int32_t(b.triangle_id)), one(1), none(0);
    Int covered_lanes(0), passed_lanes(0);
    // Wide weights: lane offsets of the numerators, exact integers in double.
    const WideWeights ww = kWideWeights ? *wide : WideWeights{};
    const Double lane_lo = Double::load_aligned(kLaneIndexDouble),
                 lane_hi = Double::load_aligned(kLaneIndexDouble + Double::size);
    const Double lane_lo1 = lane_lo * Double(ww.step_x[0]), lane_hi1 = lane_hi * Double(ww.step_x[0]),
                 lane_lo2 = lane_lo * Double(ww.step_x[1]), lane_hi2 = lane_hi * Double(ww.step_x[1]);
    double weight_row1 = ww.row[0], weight_row2 = ww.row[1];

    std::int32_t row0 = b.row[0], row1 = b.row[1], row2 = b.row[2];
    for (int y = b.y_begin; y < b.y_end; ++y) {
        for (int x = b.x_begin; x < b.x_end; x += kLanes) {
            const std::int32_t dx = x - b.x_begin;
            const auto in_block = (Int(x) + lane) < x_end;
            auto inside = in_block;
            Int w1 = Int(row1 + dx * b.step_x[1]) + lane_step1;
            Int w2 = Int(row2 + dx * b.step_x[2]) + lane_step2;
            if constexpr (!kCovered) {
                const Int w0 = Int(row0 + dx * b.step_x[0]) + lane_step0;
                inside = ((w0 | w1 | w2) >= none) & in_block;
                if (xsimd::none(inside)) continue;
            }
            // As the scalar loop: barycentrics, then depth linear in screen space, kept >= 0.
            Float lambda1, lambda2;
            if constexpr (kWideWeights) {
                const Double w1(weight_row1 + double(dx) * ww.step_x[0]);
                const Double w2(weight_row2 + double(dx) * ww.step_x[1]);
                lambda1 = round_to_float(w1 + lane_lo1, w1 + lane_hi1) * inv_area;
                lambda2 = round_to_float(w2 + lane_lo2, w2 + lane_hi2) * inv_area;
            } else {
                lambda1 = xsimd::to_float(w1 - Int(b.bias[1])) * inv_area;
                lambda2 = xsimd::to_float(w2 - Int(b.bias[2])) * inv_area;
            }
            const Float z_raw = d0 + lambda1 * d10 + lambda2 * d20;
            const Float z = xsimd::select(z_raw > zero, z_raw, zero);
            // Depths in [0, 1] order like their bit patterns, so LESS is an integer compare
            // and the whole update stays in one mask type.
            const std::size_t index = std::size_t(y) * tile.side + x;
            std::int32_t* depth_bits = reinterpret_cast<std::int32_t*>(tile.depth + index);
            const Int old_depth = Int::load_unaligned(depth_bits);
            const Int new_depth = xsimd::bitwise_cast<Int>(z);
            const auto pass = inside & (new_depth < old_depth);
            covered_lanes += xsimd::select(inside, one, none);
            if (xsimd::none(pass)) continue;
            passed_lanes += xsimd::select(pass, one, none);
            xsimd::select(pass, new_depth, old_depth).store_unaligned(depth_bits);
            std::int32_t* ids = reinterpret_cast<std::int32_t*>(tile.triangle + index);
            xsimd::select(pass, id, Int::load_unaligned(ids)).store_unaligned(ids);
            std::int32_t* l1 = reinterpret_cast<std::int32_t*>(tile.lambda1 + index);
            xsimd::select(pass, xsimd::bitwise_cast<Int>(lambda1), Int::load_unaligned(l1)).store_unaligned(l1);
            std::int32_t* l2 = reinterpret_cast<std::int32_t*>(tile.lambda2 + index);
            xsimd::select(pass, xsimd::bitwise_cast<Int>(lambda2), Int::load_unaligned(l2)).store_unaligned(l2);
        }
        row0 += b.step_y[0], row1 += b.step_y[1], row2 += b.step_y[2];
        weight_row1 += ww.step_y[0], weight_row2 += ww.step_y[1];
    }
    counters.fragments += std::uint64_t(xsimd::hadd(covered_lanes));
    counters.depth_passed += std::uint64_t(xsimd::hadd(passed_lanes));
}

}  // namespace

void TESSERA_SIMD_ENTRY(rasterize_block)(const EdgeBlock32& block, const WideWeights* wide, const TileView& tile,
                                         RasterCounters& counters) {
    if (wide)
        return block.fully_covered ? rasterize_block<true, true>(block, wide, tile, counters)
                                   : rasterize_block<false, true>(block, wide, tile, counters);
    return block.fully_covered ? rasterize_block<true, false>(block, wide, tile, counters)
                               : rasterize_block<false, false>(block, wide, tile, counters);
}

}  // namespace tessera::raster
