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
static_assert(Int::size <= kMaxRasterLanes);

alignas(64) constexpr std::int32_t kLaneIndex[16] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};

void rasterize_block(const EdgeBlock32& b, const TileView& tile, RasterCounters& counters) {
    constexpr int kLanes = int(Int::size);
    const Int lane = Int::load_aligned(kLaneIndex);
    const Int lane_step0 = lane * Int(b.step_x[0]), lane_step1 = lane * Int(b.step_x[1]),
              lane_step2 = lane * Int(b.step_x[2]);
    const Int x_end(b.x_end);
    const Float inv_area(b.inv_area), d0(b.d0), d10(b.d10), d20(b.d20), zero(0.0f);
    const Int id(std::int32_t(b.triangle_id)), one(1), none(0);
    Int covered_lanes(0), passed_lanes(0);

    std::int32_t row0 = b.row[0], row1 = b.row[1], row2 = b.row[2];
    for (int y = b.y_begin; y < b.y_end; ++y) {
        for (int x = b.x_begin; x < b.x_end; x += kLanes) {
            const std::int32_t dx = x - b.x_begin;
            const Int w0 = Int(row0 + dx * b.step_x[0]) + lane_step0;
            const Int w1 = Int(row1 + dx * b.step_x[1]) + lane_step1;
            const Int w2 = Int(row2 + dx * b.step_x[2]) + lane_step2;
            const auto inside = ((w0 | w1 | w2) >= none) & ((Int(x) + lane) < x_end);
            if (xsimd::none(inside)) continue;
            // As the scalar loop: barycentrics, then depth linear in screen space, kept >= 0.
            const Float lambda1 = xsimd::to_float(w1 - Int(b.bias[1])) * inv_area;
            const Float lambda2 = xsimd::to_float(w2 - Int(b.bias[2])) * inv_area;
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
    }
    counters.fragments += std::uint64_t(xsimd::hadd(covered_lanes));
    counters.depth_passed += std::uint64_t(xsimd::hadd(passed_lanes));
}

}  // namespace

void TESSERA_SIMD_ENTRY(rasterize_block)(const EdgeBlock32& block, const TileView& tile,
                                                              RasterCounters& counters) {
    rasterize_block(block, tile, counters);
}

}  // namespace tessera::raster
