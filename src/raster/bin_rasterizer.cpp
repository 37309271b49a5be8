#include "raster/bin_rasterizer.hpp"

namespace tessera::raster {

void rasterize_bin(simd::Isa isa, const RasterTriangle* records, std::span<const std::uint32_t> bin,
                   std::uint32_t id_base, const TileRect& tile, TileBuffers& buffers, RasterCounters& counters,
                   DrawnCallback drawn, CornerPrefetch prefetch) {
    const TileView view{buffers.depth.data(), buffers.triangle.data(), buffers.lambda1.data(), buffers.lambda2.data(),
                        buffers.side};
    switch (isa) {
        case simd::Isa::sse4:
            return rasterize_bin_sse4(records, bin.data(), bin.size(), id_base, tile, buffers, view, counters, drawn,
                                      prefetch);
        case simd::Isa::avx2:
            return rasterize_bin_avx2(records, bin.data(), bin.size(), id_base, tile, buffers, view, counters, drawn,
                                      prefetch);
        case simd::Isa::avx512:
            return rasterize_bin_avx512(records, bin.data(), bin.size(), id_base, tile, buffers, view, counters,
                                        drawn, prefetch);
        case simd::Isa::scalar: break;
    }
    for (const std::uint32_t entry : bin) {
        const std::uint64_t passed = counters.depth_passed;
        rasterize_triangle(records[entry], id_base | entry, tile, buffers, counters);
        if (counters.depth_passed != passed) {
            if (prefetch.vertices) prefetch_corners(records[entry], prefetch);
            if (drawn.call) drawn.call(drawn.context, entry);
        }
    }
}

}  // namespace tessera::raster
