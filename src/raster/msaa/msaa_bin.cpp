#include "raster/msaa/msaa_bin.hpp"

namespace tessera::raster {

void rasterize_bin_msaa(simd::Isa isa, const RasterTriangle* records, std::span<const std::uint32_t> bin,
                        std::uint32_t id_base, const TileRect& tile, TileSamples& samples, RasterCounters& counters,
                        DrawnCallback drawn, CornerPrefetch prefetch) {
    if (isa == simd::Isa::scalar) {
        for (const std::uint32_t entry : bin) {
            const std::uint64_t passed = counters.depth_passed;
            rasterize_triangle_msaa(records[entry], id_base | entry, tile, samples, counters);
            if (counters.depth_passed != passed) {
                if (prefetch.vertices) prefetch_corners(records[entry], prefetch);
                if (drawn.call) drawn.call(drawn.context, entry);
            }
        }
        return;
    }
    const SampleView view{samples.depth.data(), samples.triangle.data(), samples.side};
    WrittenBox written{samples.written_x0, samples.written_y0, samples.written_x1, samples.written_y1};
    switch (isa) {
        case simd::Isa::sse4:
            rasterize_bin_msaa_sse4(records, bin.data(), bin.size(), id_base, tile, samples, view, counters, written,
                                    drawn, prefetch);
            break;
        case simd::Isa::avx2:
            rasterize_bin_msaa_avx2(records, bin.data(), bin.size(), id_base, tile, samples, view, counters, written,
                                    drawn, prefetch);
            break;
        case simd::Isa::avx512:
            rasterize_bin_msaa_avx512(records, bin.data(), bin.size(), id_base, tile, samples, view, counters,
                                      written, drawn, prefetch);
            break;
        case simd::Isa::scalar: break;
    }
    // A union of boxes: the scalar fallback's own marks inside the kernel change nothing here.
    samples.mark_written(written.x0, written.y0, written.x1, written.y1);
}

}  // namespace tessera::raster
