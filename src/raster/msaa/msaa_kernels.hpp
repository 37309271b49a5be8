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

struct SampleView {
    float* depth;               // TileSamples::depth
    std::uint32_t* triangle;    // TileSamples::triangle
    int side;                   // pixels per tile row
};

// rasterize_msaa_block: one block in the one-sample kernels' form
// (raster_kernels.hpp; steps multiples of 256, fully_covered unused: every
// sample is tested), a row of pixels at a time; weights null, or the
// barycentric numerators in double (edges >= 0 over the block given as 0).
// rasterize_msaa_tiny: the box of a tiny triangle (corners within kTinySpan of
// each other, raster_kernels.hpp), its edges set up in int32 from the record.
#define TESSERA_DECLARE_MSAA_KERNEL(suffix) \
    void rasterize_msaa_block_##suffix(const EdgeBlock32& block, const WideWeights* weights, \
                                       const SampleView& tile, RasterCounters& counters); \
    void rasterize_msaa_tiny_##suffix(const RasterTriangle& t, std::uint32_t triangle_id, const TinyBox& box, \
                                      const SampleView& tile, RasterCounters& counters);
TESSERA_DECLARE_MSAA_KERNEL(sse4)
TESSERA_DECLARE_MSAA_KERNEL(avx2)
TESSERA_DECLARE_MSAA_KERNEL(avx512)
#undef TESSERA_DECLARE_MSAA_KERNEL

struct TileSamples;

// Every triangle but tiny ones (msaa.cpp), over its box [x_begin, x_end) ×
// [y_begin, y_end) in image pixels, already clipped to the tile and marked
// written: the ISA's block kernel, or the scalar loop where edge values leave
// int32. `view` is `samples`' arrays. rasterize_triangle_msaa(isa, ...) and
// the bin kernels (msaa_bin.hpp) hand such triangles over to it.
void rasterize_general_msaa(simd::Isa isa, const RasterTriangle& t, std::uint32_t triangle_id, const TileRect& tile,
                            int x_begin, int x_end, int y_begin, int y_end, const SampleView& view,
                            TileSamples& samples, RasterCounters& counters);

}  // namespace tessera::raster
