// A tile's bin of one chunk with 4× MSAA, all its triangles in one call, as
// rasterize_bin() (bin_rasterizer.hpp) does for one sample: the loop over the
// bin runs inside the ISA's kernel, so a tiny triangle costs its setup and
// samples and no more (no call per triangle through the ISA dispatch, no
// entry and exit of the kernel, no reloaded constants).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "raster/bin_rasterizer.hpp"
#include "raster/msaa/msaa.hpp"
#include "raster/msaa/msaa_kernels.hpp"

namespace tessera::raster {

// Rasterizes the triangles records[bin[i]] (ids id_base | bin[i]) into the
// tile's samples in bin order, exactly as rasterize_triangle_msaa(isa, ...) of
// each in turn (bit-identical depth and ids, written box and counters, for
// every ISA, scalar included). `drawn` and `prefetch` as for rasterize_bin():
// called, and the corners fetched, for each triangle that passed the depth
// test at some sample. `counters` are brought up to date when the call
// returns, not at each `drawn` call. No fragment test (alpha-tested
// triangles go one by one through the scalar loop).
void rasterize_bin_msaa(simd::Isa isa, const RasterTriangle* records, std::span<const std::uint32_t> bin,
                        std::uint32_t id_base, const TileRect& tile, TileSamples& samples, RasterCounters& counters,
                        DrawnCallback drawn = {}, CornerPrefetch prefetch = {});

// TileSamples' written box as plain data for the kernels (which must not
// touch std::vector): they widen it by each triangle's box, as
// TileSamples::mark_written() would, and rasterize_bin_msaa() writes it back.
struct WrittenBox {
    int x0, y0, x1, y1;
};

// The bin loop: tiny triangles set up and rasterized inline (as
// rasterize_msaa_tiny), others handed to rasterize_general_msaa(), which is
// given `samples` (whose arrays `view` holds) for its scalar fallback.
#define TESSERA_DECLARE_MSAA_BIN_KERNEL(suffix) \
    void rasterize_bin_msaa_##suffix(const RasterTriangle* records, const std::uint32_t* bin, std::size_t count, \
                                     std::uint32_t id_base, const TileRect& tile, TileSamples& samples, \
                                     const SampleView& view, RasterCounters& counters, WrittenBox& written, \
                                     DrawnCallback drawn, const CornerPrefetch& prefetch);
TESSERA_DECLARE_MSAA_BIN_KERNEL(sse4)
TESSERA_DECLARE_MSAA_BIN_KERNEL(avx2)
TESSERA_DECLARE_MSAA_BIN_KERNEL(avx512)
#undef TESSERA_DECLARE_MSAA_BIN_KERNEL

}  // namespace tessera::raster
