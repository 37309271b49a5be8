// A tile's bin of one chunk, all its triangles in one call: the loop over the
// bin runs inside the ISA's kernel, so a tiny triangle (most of a finely
// tessellated mesh, a pixel or two each) costs its setup and stamps and no
// more: no call per triangle through the ISA dispatch, no entry and exit of
// the kernel (saved registers, stack realignment, reloaded constants).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "geometry/shaded_vertex.hpp"
#include "raster/raster_kernels.hpp"
#include "raster/tile_rasterizer.hpp"

namespace tessera::raster {

// Called for each triangle of a bin that passed the depth test somewhere,
// with its bin entry, right after it is drawn (and its corners prefetched):
// the tests see through it which triangles the kernels count as drawn. The
// renderer passes none; the corner prefetch below is the kernels' own.
struct DrawnCallback {
    void (*call)(void* context, std::uint32_t entry) = nullptr;
    void* context = nullptr;
};

// What the renderer's callback did, done by the kernel itself (no call per
// drawn triangle): for each drawn triangle, a prefetch of its three corners'
// vertices, each `stride` bytes at vertices + ref · stride, or at
// clipped_vertices + (ref without geometry::kClippedVertexBit) · stride where
// the reference has that bit. Both ends of each vertex are fetched, as a
// vertex may straddle two cache lines. A hint only: the buffers do not change.
struct CornerPrefetch {
    const std::byte* vertices = nullptr;  // null: no prefetch
    const std::byte* clipped_vertices = nullptr;
    std::size_t stride = 0;
};

// Rasterizes the triangles records[bin[i]] (ids id_base | bin[i]) into the
// tile in bin order: appends their ids to buffers.triangles and draws each
// as its position there, exactly as rasterize_triangle(isa, ...) of each in
// turn with that position as its id (bit-identical buffers and counters for
// every ISA, scalar included).
// `counters` are brought up to date when the call returns (the kernels count
// in registers), not at each `drawn` call.
void rasterize_bin(simd::Isa isa, const RasterTriangle* records, std::span<const std::uint32_t> bin,
                   std::uint32_t id_base, const TileRect& tile, TileBuffers& buffers, RasterCounters& counters,
                   DrawnCallback drawn = {}, CornerPrefetch prefetch = {});

// Where CornerPrefetch finds the vertex of a corner reference.
[[gnu::always_inline]] inline const std::byte* corner_vertex(const CornerPrefetch& prefetch, std::uint32_t ref) {
    const std::byte* base = (ref & geometry::kClippedVertexBit) ? prefetch.clipped_vertices : prefetch.vertices;
    return base + std::size_t(ref & ~geometry::kClippedVertexBit) * prefetch.stride;
}

// CornerPrefetch's prefetches of one triangle.
[[gnu::always_inline]] inline void prefetch_corners(const RasterTriangle& t, const CornerPrefetch& prefetch) {
    for (int k = 0; k < 3; ++k) {
        const std::byte* v = corner_vertex(prefetch, t.vertex[k]);
        __builtin_prefetch(v);
        __builtin_prefetch(v + prefetch.stride - 1);
    }
}

// The kernels: ids[i] = id_base | bin[i], and triangle i drawn as first_id + i.
#define TESSERA_DECLARE_BIN_KERNEL(suffix) \
    void rasterize_bin_##suffix(const RasterTriangle* records, const std::uint32_t* bin, std::size_t count, \
                                std::uint32_t id_base, std::uint32_t* ids, std::uint32_t first_id, \
                                const TileRect& tile, TileBuffers& buffers, \
                                const TileView& view, RasterCounters& counters, DrawnCallback drawn, \
                                const CornerPrefetch& prefetch);
TESSERA_DECLARE_BIN_KERNEL(sse4)
TESSERA_DECLARE_BIN_KERNEL(avx2)
TESSERA_DECLARE_BIN_KERNEL(avx512)
#undef TESSERA_DECLARE_BIN_KERNEL

}  // namespace tessera::raster
