// The 4× MSAA rasterizer's inner loop over vectors of samples
// (msaa_kernels.hpp), compiled once per ISA. Same arithmetic as the scalar
// loop in msaa.cpp, lane by lane, so both give bit-identical sample buffers.
#include <bit>
#include <cstdint>

#include "simd/kernel_prelude.hpp"

#include "raster/msaa_kernels.hpp"
#include "raster/msaa_pattern.hpp"

namespace tessera::raster {
namespace {

using Arch = TESSERA_SIMD_ARCH;
using Int = xsimd::batch<std::int32_t, Arch>;
using Float = xsimd::batch<float, Arch>;
using IntMask = xsimd::batch_bool<std::int32_t, Arch>;

constexpr int kPixels = int(Int::size) / kMsaaSamples;  // pixels per vector
static_assert(kPixels * kMsaaSamples == int(Int::size));
static_assert(kMsaaKernelOverreach >= (kPixels - 1) * kMsaaSamples);

// Per lane i (pixel i / 4, sample i % 4): the sample's offset from the first
// pixel's centre in 1/256 pixel, x (pixel · 256 + sample offset) and y.
struct LaneOffsets {
    alignas(64) std::int32_t x[16], y[16], pixel[16];
    constexpr LaneOffsets() : x{}, y{}, pixel{} {
        for (int i = 0; i < 16; ++i) {
            x[i] = 256 * (i / kMsaaSamples) + kSampleOffsetX[i % kMsaaSamples];
            y[i] = kSampleOffsetY[i % kMsaaSamples];
            pixel[i] = i / kMsaaSamples;
        }
    }
};
constexpr LaneOffsets kLane;

// Which lanes of a comparison hold: bit i for lane i. Hand-written: xsimd 8.1
// has no movemask.
[[gnu::always_inline]] inline unsigned lane_bits(const IntMask& b) {
#if XSIMD_WITH_AVX512F
    return unsigned(b.data);
#elif XSIMD_WITH_AVX2
    return unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(b)));
#else
    return unsigned(_mm_movemask_ps(_mm_castsi128_ps(b)));
#endif
}

}  // namespace

void TESSERA_SIMD_ENTRY(rasterize_msaa_block)(const MsaaBlock32& b, const SampleView& tile, RasterCounters& counters) {
    // E is affine: E at a lane's sample = E at the block's first pixel centre
    // + (step_x / 256) · offset x + (step_y / 256) · offset y, exact in int32
    // (the steps are multiples of 256), as the scalar loop's offset[k][s]
    // plus its whole-pixel steps.
    const Int offset_x = Int::load_aligned(kLane.x), offset_y = Int::load_aligned(kLane.y);
    const Int lane_pixel = Int::load_aligned(kLane.pixel);
    Int lane_edge[3], vector_step[3];
    for (int k = 0; k < 3; ++k) {
        lane_edge[k] = offset_x * Int(b.step_x[k] / 256) + offset_y * Int(b.step_y[k] / 256);
        vector_step[k] = Int(kPixels * b.step_x[k]);
    }
    const Int bias1(b.bias[1]), bias2(b.bias[2]), none(0), id(std::int32_t(b.triangle_id));
    const Float inv_area(b.inv_area), d0(b.d0), d10(b.d10), d20(b.d20), zero(0.0f);
    unsigned fragments = 0, passed = 0;
    std::int32_t row0 = b.row[0], row1 = b.row[1], row2 = b.row[2];
    for (int y = b.y_begin; y < b.y_end; ++y) {
        Int e0 = Int(row0) + lane_edge[0], e1 = Int(row1) + lane_edge[1], e2 = Int(row2) + lane_edge[2];
        const std::size_t first = std::size_t(kMsaaSamples) * (std::size_t(y) * tile.side + b.x_begin);
        std::int32_t* depth = reinterpret_cast<std::int32_t*>(tile.depth) + first;
        std::int32_t* triangle = reinterpret_cast<std::int32_t*>(tile.triangle) + first;
        for (int x = b.x_begin; x < b.x_end;
             x += kPixels, depth += Int::size, triangle += Int::size) {
            const IntMask inside = ((e0 | e1 | e2) >= none) & (lane_pixel < Int(b.x_end - x));
            const Int w1 = e1, w2 = e2;
            e0 += vector_step[0], e1 += vector_step[1], e2 += vector_step[2];
            const unsigned inside_bits = lane_bits(inside);
            if (inside_bits == 0) continue;
            fragments += unsigned(std::popcount(inside_bits));
            // As the scalar loop: barycentrics, then depth linear in screen space, kept >= 0
            // (max(z, 0) gives 0 for -0 too, as the scalar z0 > 0 ? z0 : 0 does).
            const Float lambda1 = xsimd::to_float(w1 - bias1) * inv_area;
            const Float lambda2 = xsimd::to_float(w2 - bias2) * inv_area;
            const Int new_depth = xsimd::bitwise_cast<Int>(xsimd::max(d0 + lambda1 * d10 + lambda2 * d20, zero));
            // Depths in [0, 1] order like their bit patterns: LESS as an integer compare.
            const Int old_depth = Int::load_unaligned(depth);
            const IntMask pass = inside & (new_depth < old_depth);
            const unsigned pass_bits = lane_bits(pass);
            if (pass_bits == 0) continue;
            passed += unsigned(std::popcount(pass_bits));
            xsimd::select(pass, new_depth, old_depth).store_unaligned(depth);
            xsimd::select(pass, id, Int::load_unaligned(triangle)).store_unaligned(triangle);
        }
        row0 += b.step_y[0], row1 += b.step_y[1], row2 += b.step_y[2];
    }
    counters.fragments += fragments;
    counters.depth_passed += passed;
}

}  // namespace tessera::raster
