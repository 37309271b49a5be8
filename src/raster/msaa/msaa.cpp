#include "raster/msaa/msaa.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdlib>

#include "raster/msaa/msaa_fragment_kernels.hpp"
#include "raster/msaa/msaa_kernels.hpp"
#include "raster/msaa/msaa_list_kernel.hpp"
#include "raster/raster_limits.hpp"
#include "raster/triangle_in_tile.hpp"

namespace tessera::raster {

void TileSamples::reset(int tile_side) {
    const std::size_t n = std::size_t(kMsaaSamples) * tile_side * tile_side;
    if (tile_side == side && depth.size() == n + kMsaaKernelOverreach) {
        // Outside the written box depth is still 1.
        const int x0 = std::max(written_x0, 0), x1 = std::min(written_x1, side);
        for (int y = std::max(written_y0, 0); y < std::min(written_y1, side) && x0 < x1; ++y)
            std::fill_n(&depth[std::size_t(kMsaaSamples) * (std::size_t(y) * side + x0)],
                        std::size_t(kMsaaSamples) * (x1 - x0), 1.0f);
    } else {
        side = tile_side;
        depth.assign(n + kMsaaKernelOverreach, 1.0f);
        triangle.resize(n + kMsaaKernelOverreach);
        fragment.resize(n);
    }
    written_x0 = written_y0 = kEmptyBoxLow, written_x1 = written_y1 = kEmptyBoxHigh;
}

void TileFragments::reserve(int tile_side) {
    const std::size_t n = std::size_t(kMsaaSamples) * tile_side * tile_side;  // at most one per sample
    // x, y and triangle padded: list_fragments() writes a pixel's 4 possible fragments unconditionally.
    x.resize(n + kMsaaSamples), y.resize(n + kMsaaSamples), triangle.resize(n + kMsaaSamples);
    lambda1.resize(n), lambda2.resize(n), source.resize(n);
    count = 0;
}

// The plain data list_fragments' kernels (msaa_list_kernel.hpp) work on.
SampleListing sample_listing(const TileRect& rect, TileSamples& samples, TileFragments& out) {
    // Depth is 1 outside the written box: there every sample is background.
    return {samples.depth.data(), samples.triangle.data(), samples.fragment.data(), samples.side,
            rect.width(), rect.height(),
            std::max(samples.written_x0, 0), std::min(samples.written_x1, rect.width()),
            std::max(samples.written_y0, 0), std::min(samples.written_y1, rect.height()),
            out.x.data(), out.y.data(), out.triangle.data()};
}

void list_fragments(const TileRect& rect, TileSamples& samples, TileFragments& out) {
    out.count = list_sample_fragments(sample_listing(rect, samples, out));
}

void list_fragments(simd::Isa isa, const TileRect& rect, TileSamples& samples, TileFragments& out) {
    const SampleListing listing = sample_listing(rect, samples, out);
    switch (isa) {
        case simd::Isa::sse4: out.count = list_fragments_sse4(listing); return;
        case simd::Isa::avx2: out.count = list_fragments_avx2(listing); return;
        case simd::Isa::avx512: out.count = list_fragments_avx512(listing); return;
        case simd::Isa::scalar: break;
    }
    out.count = list_sample_fragments(listing);
}

void fragment_barycentrics(simd::Isa isa, const TileRect& rect, TileFragments& out) {
    const FragmentCentres centres{out.source.data(), out.x.data(), out.y.data(), rect.x0, rect.y0, out.count,
                                  out.lambda1.data(), out.lambda2.data()};
    switch (isa) {
        case simd::Isa::sse4: return fragment_barycentrics_sse4(centres);
        case simd::Isa::avx2: return fragment_barycentrics_avx2(centres);
        case simd::Isa::avx512: return fragment_barycentrics_avx512(centres);
        case simd::Isa::scalar: break;
    }
    for (std::size_t k = 0; k < out.count; ++k) {
        const auto [l1, l2] = screen_barycentrics(*out.source[k], std::int64_t(rect.x0 + out.x[k]) * kSubpixelScale + kSubpixelScale / 2,
                                                  std::int64_t(rect.y0 + out.y[k]) * kSubpixelScale + kSubpixelScale / 2);
        out.lambda1[k] = l1, out.lambda2[k] = l2;
    }
}

bool covers_point(const RasterTriangle& t, std::int64_t px, std::int64_t py) {
    const EdgeStepper e0(t.x[1], t.y[1], t.x[2], t.y[2], px, py), e1(t.x[2], t.y[2], t.x[0], t.y[0], px, py),
        e2(t.x[0], t.y[0], t.x[1], t.y[1], px, py);
    return (e0.row | e1.row | e2.row) >= 0;
}

void rasterize_triangle_msaa(const RasterTriangle& t, std::uint32_t triangle_id, const TileRect& tile,
                             TileSamples& samples, RasterCounters& counters, const FragmentTest* test) {
    const std::optional<TriangleInTile> placed = place_in_tile(t, tile);
    if (!placed) return;
    const int x_begin = placed->x_begin, x_end = placed->x_end, y_begin = placed->y_begin, y_end = placed->y_end;
    samples.mark_written(x_begin - tile.x0, y_begin - tile.y0, x_end - tile.x0, y_end - tile.y0);
    TriangleInTile p = *placed;
    EdgeStepper* e = p.e;
    const SampleEdgeOffsets offset = sample_edge_offsets(p.e);
    const float inv_area = t.inv_area;
    for (int y = y_begin; y < y_end; ++y) {
        std::int64_t w0 = e[0].row, w1 = e[1].row, w2 = e[2].row;
        std::size_t index = std::size_t(kMsaaSamples) * (std::size_t(y - tile.y0) * samples.side + (x_begin - tile.x0));
        for (int x = x_begin; x < x_end; ++x, index += kMsaaSamples) {
            enum { untested, kept, discarded } verdict = test ? untested : kept;
            for (int s = 0; s < kMsaaSamples && verdict != discarded; ++s) {
                const std::int64_t s0 = w0 + offset[0][s], s1 = w1 + offset[1][s], s2 = w2 + offset[2][s];
                if ((s0 | s1 | s2) < 0) continue;
                ++counters.fragments;
                const float lambda1 = float(s1 - e[1].bias) * inv_area;
                const float lambda2 = float(s2 - e[2].bias) * inv_area;
                const float z = window_depth(t, lambda1, lambda2);
                if (z < samples.depth[index + s]) {
                    if (verdict == untested) {
                        // At the pixel centre: the unbiased edge values there, as screen_barycentrics().
                        const float centre1 = float(w1 - e[1].bias) * inv_area, centre2 = float(w2 - e[2].bias) * inv_area;
                        verdict = test->keep(test->context, x, y, centre1, centre2) ? kept : discarded;
                        if (verdict == discarded) break;
                    }
                    ++counters.depth_passed;
                    samples.depth[index + s] = z;
                    samples.triangle[index + s] = triangle_id;
                }
            }
            w0 += e[0].step_x, w1 += e[1].step_x, w2 += e[2].step_x;
        }
        for (int k = 0; k < 3; ++k) e[k].row += e[k].step_y;
    }
}

namespace {

// Whether every value of edge e the kernel meets over a width × height block
// fits in int32: the block's samples (within 0.375 px of the centres), lanes
// of the last vector of a row up to 3 pixels past its end, the steps taken
// after the last vector and the last row, with margin.
bool msaa_edge_fits_int32(const EdgeStepper& e, int width, int height) {
    const std::int64_t reach = std::llabs(e.row) + std::llabs(e.step_x) * (width + 8) + std::llabs(e.step_y) * (height + 1);
    return reach < (std::int64_t(1) << 31) - 1;
}

// Whether every corner lies within kTinySpan of the others in x and in y
// (as tile_rasterizer.cpp's test, branch-free): then every edge value the
// kernel meets over the triangle's box is below 2^26.
[[gnu::always_inline]] inline bool tiny(const RasterTriangle& t) {
    const auto near = [](std::int32_t a, std::int32_t b) -> unsigned {
        return std::uint32_t(a - b + (kTinySpan - 1)) < std::uint32_t(2 * kTinySpan - 1);
    };
    return (near(t.x[0], t.x[1]) & near(t.x[1], t.x[2]) & near(t.x[2], t.x[0]) & near(t.y[0], t.y[1]) &
            near(t.y[1], t.y[2]) & near(t.y[2], t.y[0])) != 0;
}

// The extremes of a biased edge over the samples of a width × height block:
// it is affine, so they lie at the block's corner pixels, at their extreme
// sample offsets.
struct EdgeRange {
    std::int64_t min, max;
};
EdgeRange sample_range(const EdgeStepper& e, int width, int height) {
    const std::int64_t across = e.step_x * (width - 1), down = e.step_y * (height - 1);
    std::int64_t offset_min = INT64_MAX, offset_max = INT64_MIN;
    for (int s = 0; s < kMsaaSamples; ++s) {
        const std::int64_t offset = (e.step_x / kSubpixelScale) * kSampleOffsetX[s] + (e.step_y / kSubpixelScale) * kSampleOffsetY[s];
        offset_min = std::min(offset_min, offset), offset_max = std::max(offset_max, offset);
    }
    return {e.row + std::min<std::int64_t>(across, 0) + std::min<std::int64_t>(down, 0) + offset_min,
            e.row + std::max<std::int64_t>(across, 0) + std::max<std::int64_t>(down, 0) + offset_max};
}

}  // namespace

// Other triangles: edges set up in int64, narrowed to int32 where they fit;
// where not, barycentric numerators in double and coverage in int32 for the
// edges that cross the box; the scalar loop when even those leave int32.
[[gnu::noinline]] void rasterize_general_msaa(simd::Isa isa, const RasterTriangle& t, std::uint32_t triangle_id,
                                              const TileRect& tile, int x_begin, int x_end, int y_begin, int y_end,
                                              const SampleView& view, TileSamples& samples, RasterCounters& counters) {
    const std::int64_t px = std::int64_t(x_begin) * kSubpixelScale + kSubpixelScale / 2;
    const std::int64_t py = std::int64_t(y_begin) * kSubpixelScale + kSubpixelScale / 2;
    const EdgeStepper e[3] = {EdgeStepper(t.x[1], t.y[1], t.x[2], t.y[2], px, py),
                              EdgeStepper(t.x[2], t.y[2], t.x[0], t.y[0], px, py),
                              EdgeStepper(t.x[0], t.y[0], t.x[1], t.y[1], px, py)};
    const int width = x_end - x_begin, height = y_end - y_begin;
    EdgeBlock32 block;
    bool fits = true;
    for (int k = 0; k < 3; ++k) fits = fits && msaa_edge_fits_int32(e[k], width, height);
    WideWeights weights;
    for (int k = 0; k < 3; ++k) {
        block.bias[k] = std::int32_t(e[k].bias);
        if (fits) {
            block.row[k] = std::int32_t(e[k].row);
            block.step_x[k] = std::int32_t(e[k].step_x);
            block.step_y[k] = std::int32_t(e[k].step_y);
            continue;
        }
        // Edge values past int32 (large triangles): an edge >= 0 at every
        // sample of the box passes everywhere, tested as 0; the others must fit.
        const EdgeRange range = sample_range(e[k], width, height);
        if (range.max < 0) return;  // no sample of the box is inside
        const bool passes = range.min >= 0;
        if (!passes && !msaa_edge_fits_int32(e[k], width, height))
            return rasterize_triangle_msaa(t, triangle_id, tile, samples, counters);
        block.row[k] = passes ? 0 : std::int32_t(e[k].row);
        block.step_x[k] = passes ? 0 : std::int32_t(e[k].step_x);
        block.step_y[k] = passes ? 0 : std::int32_t(e[k].step_y);
    }
    if (!fits)
        for (int k = 0; k < 2; ++k) {
            const EdgeStepper& weight = e[k + 1];
            weights.row[k] = double(weight.row - weight.bias);
            weights.step_x[k] = double(weight.step_x);
            weights.step_y[k] = double(weight.step_y);
        }
    block.x_begin = x_begin - tile.x0, block.x_end = x_end - tile.x0;
    block.y_begin = y_begin - tile.y0, block.y_end = y_end - tile.y0;
    block.inv_area = t.inv_area;
    block.d0 = t.depth[0], block.d10 = t.depth[1] - t.depth[0], block.d20 = t.depth[2] - t.depth[0];
    block.triangle_id = triangle_id;
    switch (isa) {
        case simd::Isa::sse4: return rasterize_msaa_block_sse4(block, fits ? nullptr : &weights, view, counters);
        case simd::Isa::avx2: return rasterize_msaa_block_avx2(block, fits ? nullptr : &weights, view, counters);
        case simd::Isa::avx512: return rasterize_msaa_block_avx512(block, fits ? nullptr : &weights, view, counters);
        case simd::Isa::scalar: break;
    }
}

void rasterize_triangle_msaa(simd::Isa isa, const RasterTriangle& t, std::uint32_t triangle_id, const TileRect& tile,
                             TileSamples& samples, RasterCounters& counters) {
    if (isa == simd::Isa::scalar) return rasterize_triangle_msaa(t, triangle_id, tile, samples, counters);
    const int x_begin = std::max<int>(t.px_min, tile.x0), x_end = std::min<int>(t.px_max + 1, tile.x1);
    const int y_begin = std::max<int>(t.py_min, tile.y0), y_end = std::min<int>(t.py_max + 1, tile.y1);
    if (x_begin >= x_end || y_begin >= y_end) return;
    samples.mark_written(x_begin - tile.x0, y_begin - tile.y0, x_end - tile.x0, y_end - tile.y0);
    const SampleView view{samples.depth.data(), samples.triangle.data(), samples.side};
    // Tiny triangles (most of a finely tessellated mesh) set up in the kernel, in int32.
    if (tiny(t)) {
        const TinyBox box{x_begin, x_end, y_begin, y_end, tile.x0, tile.y0};
        switch (isa) {
            case simd::Isa::sse4: return rasterize_msaa_tiny_sse4(t, triangle_id, box, view, counters);
            case simd::Isa::avx2: return rasterize_msaa_tiny_avx2(t, triangle_id, box, view, counters);
            case simd::Isa::avx512: return rasterize_msaa_tiny_avx512(t, triangle_id, box, view, counters);
            case simd::Isa::scalar: break;
        }
    }
    rasterize_general_msaa(isa, t, triangle_id, tile, x_begin, x_end, y_begin, y_end, view, samples, counters);
}

}  // namespace tessera::raster
