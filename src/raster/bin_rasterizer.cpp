#include "raster/bin_rasterizer.hpp"

namespace tessera::raster {

void rasterize_bin(simd::Isa isa, const RasterTriangle* records, std::span<const std::uint32_t> bin,
                   std::uint32_t id_base, const TileRect& tile, TileBuffers& buffers, RasterCounters& counters,
                   DrawnCallback drawn, CornerPrefetch prefetch) {
    const TileView view{buffers.depth.data(), buffers.triangle.data(), buffers.lambda1.data(), buffers.lambda2.data(),
                        buffers.side};
    // The bin's ids join the tile's list; the kernels store ids[i] as they meet the triangles.
    std::uint32_t* const ids = buffers.triangles.room_for(bin.size());
    const std::uint32_t first_id = buffers.triangles.count;
    buffers.triangles.count += std::uint32_t(bin.size());
    switch (isa) {
        case simd::Isa::sse4:
            return rasterize_bin_sse4(records, bin.data(), bin.size(), id_base, ids, first_id, tile, buffers, view,
                                      counters, drawn, prefetch);
        case simd::Isa::avx2:
            return rasterize_bin_avx2(records, bin.data(), bin.size(), id_base, ids, first_id, tile, buffers, view,
                                      counters, drawn, prefetch);
        case simd::Isa::avx512:
            return rasterize_bin_avx512(records, bin.data(), bin.size(), id_base, ids, first_id, tile, buffers, view,
                                        counters, drawn, prefetch);
        case simd::Isa::scalar: break;
    }
    for (std::size_t i = 0; i < bin.size(); ++i) {
        const std::uint32_t entry = bin[i];
        ids[i] = id_base | entry;
        const std::uint64_t passed = counters.depth_passed;
        rasterize_triangle(records[entry], first_id + std::uint32_t(i), tile, buffers, counters);
        if (counters.depth_passed != passed) {
            if (prefetch.vertices) prefetch_corners(records[entry], prefetch);
            if (drawn.call) drawn.call(drawn.context, entry);
        }
    }
}

}  // namespace tessera::raster
