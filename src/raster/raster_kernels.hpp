// The rasterizer's SIMD inner loop, compiled once per ISA
// (tile_rasterizer_simd.cpp) and called by rasterize_triangle() when a
// triangle's edge functions over its pixel block fit in 32-bit integers: then
// a vector of int32 lanes tests that many pixel centres at once, exactly as the
// scalar int64 loop would.
#pragma once

#include <cstdint>

#include "raster/tile_rasterizer.hpp"

namespace tessera::raster {

// Lanes in the widest vector any kernel uses; tile buffers are padded by this
// much so a vector load at the end of a row never leaves the allocation.
inline constexpr int kMaxRasterLanes = 16;

// One triangle over a block of one tile, all in int32 (plain data: the
// per-ISA code must not touch std::vector).
struct EdgeBlock32 {
    std::int32_t row[3];     // biased edge values at the block's first pixel centre
    std::int32_t step_x[3];  // per pixel to the right
    std::int32_t step_y[3];  // per pixel down
    std::int32_t bias[3];    // 0 or -1 (top-left rule), removed again for barycentrics
    int x_begin, x_end;      // tile-relative pixel columns [x_begin, x_end)
    int y_begin, y_end;      // tile-relative pixel rows
    float inv_area;          // 1 / double_area
    float d0, d10, d20;      // depth at corner 0, and corners 1, 2 minus corner 0
    std::uint32_t triangle_id;
};

struct TileView {
    float* depth;
    std::uint32_t* triangle;
    float* lambda1;
    float* lambda2;
    int side;
};

#define TESSERA_DECLARE_RASTER_KERNEL(suffix) \
    void rasterize_block_##suffix(const EdgeBlock32& block, const TileView& tile, RasterCounters& counters);
TESSERA_DECLARE_RASTER_KERNEL(sse4)
TESSERA_DECLARE_RASTER_KERNEL(avx2)
TESSERA_DECLARE_RASTER_KERNEL(avx512)
#undef TESSERA_DECLARE_RASTER_KERNEL

}  // namespace tessera::raster
