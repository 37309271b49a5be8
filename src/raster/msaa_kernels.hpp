// The 4× MSAA rasterizer's SIMD inner loop, compiled once per ISA
// (msaa_simd.cpp) and called by rasterize_triangle_msaa(isa, ...) when every
// edge value it meets fits in int32. A vector of int32 lanes holds whole
// pixels' samples in their TileSamples order (lane i: pixel i / 4, sample
// i % 4; 1, 2 or 4 pixels for SSE, AVX2, AVX-512), so depth and triangle ids
// load and store as they lie, and each lane does what the scalar int64 loop
// does for its sample.
#pragma once

#include <cstdint>

#include "raster/raster_kernels.hpp"
#include "raster/tile_rasterizer.hpp"

namespace tessera::raster {

// Samples the widest kernel's last vector of a row can reach past the row's
// end (3 pixels of 4 samples); TileSamples pads depth and triangle by this.
inline constexpr int kMsaaKernelOverreach = 16;

// One triangle over a block of one tile, edges in int32 (plain data: the
// per-ISA code must not touch std::vector).
struct MsaaBlock32 {
    std::int32_t row[3];     // biased edge values at the block's first pixel centre
    std::int32_t step_x[3];  // per pixel to the right (a multiple of 256)
    std::int32_t step_y[3];  // per pixel down (a multiple of 256)
    std::int32_t bias[3];    // 0 or -1 (top-left rule), removed again for barycentrics
    int x_begin, x_end;      // tile-relative pixel columns [x_begin, x_end)
    int y_begin, y_end;      // tile-relative pixel rows
    float inv_area;          // 1 / double_area
    float d0, d10, d20;      // depth at corner 0, and corners 1, 2 minus corner 0
    std::uint32_t triangle_id;
};

// Barycentric numerators of a block where they leave int32, given to the
// kernel instead of taking them from MsaaBlock32::row[1], row[2]; row/step
// then only test coverage, edges known to be >= 0 over the block given as 0.
// double holds every edge value exactly (|E| < 2^49 < 2^53), so
// float(double(E)) rounds once, like the scalar loop's float(int64 E).
struct MsaaWideWeights {
    double row[2];     // unbiased E1, E2 at the block's first pixel centre
    double step_x[2];  // per pixel right (multiples of 256)
    double step_y[2];  // per pixel down
};

struct SampleView {
    float* depth;               // TileSamples::depth
    std::uint32_t* triangle;    // TileSamples::triangle
    int side;                   // pixels per tile row
};

// rasterize_msaa_block: one MsaaBlock32, a row of pixels at a time; weights
// null, or the barycentric numerators in double.
// rasterize_msaa_tiny: the box of a tiny triangle (corners within kTinySpan of
// each other, raster_kernels.hpp), its edges set up in int32 from the record.
#define TESSERA_DECLARE_MSAA_KERNEL(suffix) \
    void rasterize_msaa_block_##suffix(const MsaaBlock32& block, const MsaaWideWeights* weights, \
                                       const SampleView& tile, RasterCounters& counters); \
    void rasterize_msaa_tiny_##suffix(const RasterTriangle& t, std::uint32_t triangle_id, const TinyBox& box, \
                                      const SampleView& tile, RasterCounters& counters);
TESSERA_DECLARE_MSAA_KERNEL(sse4)
TESSERA_DECLARE_MSAA_KERNEL(avx2)
TESSERA_DECLARE_MSAA_KERNEL(avx512)
#undef TESSERA_DECLARE_MSAA_KERNEL

}  // namespace tessera::raster
