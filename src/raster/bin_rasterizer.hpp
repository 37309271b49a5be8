// A tile's bin of one chunk, all its triangles in one call: the loop over the
// bin runs inside the ISA's kernel, so a tiny triangle (most of a finely
// tessellated mesh, a pixel or two each) costs its setup and stamps and no
// more: no call per triangle through the ISA dispatch, no entry and exit of
// the kernel (saved registers, stack realignment, reloaded constants).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "raster/raster_kernels.hpp"
#include "raster/tile_rasterizer.hpp"

namespace tessera::raster {

// Called for each triangle of a bin that passed the depth test somewhere,
// with its bin entry, right after it is drawn: the renderer prefetches what
// shading the triangle will need.
struct DrawnCallback {
    void (*call)(void* context, std::uint32_t entry) = nullptr;
    void* context = nullptr;
};

// Rasterizes the triangles records[bin[i]] (ids id_base | bin[i]) into the
// tile in bin order, exactly as rasterize_triangle(isa, ...) of each in turn
// (bit-identical buffers and counters for every ISA, scalar included).
// `counters` are brought up to date when the call returns (the kernels count
// in registers), not at each `drawn` call.
void rasterize_bin(simd::Isa isa, const RasterTriangle* records, std::span<const std::uint32_t> bin,
                   std::uint32_t id_base, const TileRect& tile, TileBuffers& buffers, RasterCounters& counters,
                   DrawnCallback drawn = {});

#define TESSERA_DECLARE_BIN_KERNEL(suffix) \
    void rasterize_bin_##suffix(const RasterTriangle* records, const std::uint32_t* bin, std::size_t count, \
                                std::uint32_t id_base, const TileRect& tile, TileBuffers& buffers, \
                                const TileView& view, RasterCounters& counters, DrawnCallback drawn);
TESSERA_DECLARE_BIN_KERNEL(sse4)
TESSERA_DECLARE_BIN_KERNEL(avx2)
TESSERA_DECLARE_BIN_KERNEL(avx512)
#undef TESSERA_DECLARE_BIN_KERNEL

}  // namespace tessera::raster
