#include "raster/tile_rasterizer.hpp"

#include <algorithm>
#include <cstdlib>
#include <optional>

#include "raster/raster_kernels.hpp"
#include "raster/raster_limits.hpp"
#include "raster/triangle_in_tile.hpp"

namespace tessera::raster {

void TileBuffers::reset(int tile_side) {
    // Padded so that a vector of pixels starting in the last row stays inside.
    const std::size_t n = std::size_t(tile_side) * std::size_t(tile_side) + kMaxRasterLanes;
    side = tile_side;
    depth.assign(n, 1.0f);
    triangle.resize(n);
    lambda1.resize(n);
    lambda2.resize(n);
    triangles.count = 0;
}

namespace {

// Whether every value of edge e the SIMD kernel can meet over a width×height
// block starting at e.row — plus a vector's worth of lanes past its right end —
// fits in int32.
[[gnu::always_inline]] inline bool edge_fits_int32(const EdgeStepper& e, int width, int height) {
    const std::int64_t reach = std::llabs(e.row) + std::llabs(e.step_x) * (width + kMaxRasterLanes) +
                               std::llabs(e.step_y) * height;
    return reach < (std::int64_t(1) << 31) - 1;
}

[[gnu::always_inline]] inline bool fits_int32(const TriangleInTile& p) {
    const int width = p.x_end - p.x_begin, height = p.y_end - p.y_begin;
    return edge_fits_int32(p.e[0], width, height) && edge_fits_int32(p.e[1], width, height) &&
           edge_fits_int32(p.e[2], width, height);
}

// Whether the stamp kernel's edge values fit in int32: its lanes reach
// kStampWidth - 1 pixels right of the box's first column and, after the last
// stamp, up to kMaxRasterLanes / kStampWidth rows below the box.
[[gnu::always_inline]] inline bool stamp_fits_int32(const TriangleInTile& p) {
    const int reach_down = p.y_end - p.y_begin + kMaxRasterLanes / kStampWidth;
    for (const EdgeStepper* e : {&p.e[0], &p.e[1], &p.e[2]}) {
        const std::int64_t reach = std::llabs(e->row) + std::llabs(e->step_x) * (kStampWidth - 1) +
                                   std::llabs(e->step_y) * reach_down;
        if (reach >= (std::int64_t(1) << 31) - 1) return false;
    }
    return true;
}

// The part [x_begin, x_end) × [y_begin, y_end) of a placed triangle's block,
// its edges stepped to that part's first pixel centre.
TriangleInTile sub_block(const TriangleInTile& p, int x_begin, int x_end, int y_begin, int y_end) {
    TriangleInTile sub = p;
    sub.x_begin = x_begin, sub.x_end = x_end, sub.y_begin = y_begin, sub.y_end = y_end;
    for (EdgeStepper* e : {&sub.e[0], &sub.e[1], &sub.e[2]})
        e->row += std::int64_t(x_begin - p.x_begin) * e->step_x + std::int64_t(y_begin - p.y_begin) * e->step_y;
    return sub;
}

// An edge function is linear, so over a block its extremes are at corners,
// chosen by the signs of its steps.
struct EdgeRange {
    std::int64_t min, max;  // biased, over the block's pixel centres
};
EdgeRange edge_range(const EdgeStepper& e, int width, int height) {
    const std::int64_t across = e.step_x * (width - 1), down = e.step_y * (height - 1);
    return {e.row + std::min<std::int64_t>(across, 0) + std::min<std::int64_t>(down, 0),
            e.row + std::max<std::int64_t>(across, 0) + std::max<std::int64_t>(down, 0)};
}

enum class BlockCoverage { none, partial, full };

BlockCoverage block_coverage(const TriangleInTile& b) {
    const int width = b.x_end - b.x_begin, height = b.y_end - b.y_begin;
    bool full = true;
    for (const EdgeStepper* e : {&b.e[0], &b.e[1], &b.e[2]}) {
        const EdgeRange range = edge_range(*e, width, height);
        if (range.max < 0) return BlockCoverage::none;  // every centre outside this edge
        full = full && range.min >= 0;
    }
    return full ? BlockCoverage::full : BlockCoverage::partial;
}

// The scalar loop: one pixel centre at a time, edge values in int64. With
// kTested, `test` runs on each fragment that passes the depth test.
template <bool kTested = false>
[[gnu::always_inline]] inline
void rasterize_scalar(const RasterTriangle& t, const TriangleInTile& placed, std::uint32_t triangle_id,
                      const TileRect& tile, TileBuffers& buffers, RasterCounters& counters,
                      const FragmentTest* test = nullptr) {
    EdgeStepper e0 = placed.e[0], e1 = placed.e[1], e2 = placed.e[2];
    const float inv_area = t.inv_area;
    for (int y = placed.y_begin; y < placed.y_end; ++y) {
        std::int64_t w0 = e0.row, w1 = e1.row, w2 = e2.row;
        std::size_t index = std::size_t(y - tile.y0) * buffers.side + (placed.x_begin - tile.x0);
        for (int x = placed.x_begin; x < placed.x_end; ++x, ++index) {
            if ((w0 | w1 | w2) >= 0) {
                ++counters.fragments;
                const float lambda1 = float(w1 - e1.bias) * inv_area;
                const float lambda2 = float(w2 - e2.bias) * inv_area;
                const float z = window_depth(t, lambda1, lambda2);
                if (z < buffers.depth[index] && (!kTested || test->keep(test->context, x, y, lambda1, lambda2))) {
                    ++counters.depth_passed;
                    buffers.depth[index] = z;
                    buffers.triangle[index] = triangle_id;
                    buffers.lambda1[index] = lambda1;
                    buffers.lambda2[index] = lambda2;
                }
            }
            w0 += e0.step_x, w1 += e1.step_x, w2 += e2.step_x;
        }
        e0.row += e0.step_y, e1.row += e1.step_y, e2.row += e2.step_y;
    }
}

}  // namespace

void rasterize_triangle(const RasterTriangle& t, std::uint32_t triangle_id, const TileRect& tile, TileBuffers& buffers,
                        RasterCounters& counters) {
    if (const auto placed = place_in_tile(t, tile)) rasterize_scalar(t, *placed, triangle_id, tile, buffers, counters);
}

void rasterize_triangle(const RasterTriangle& t, std::uint32_t triangle_id, const TileRect& tile, TileBuffers& buffers,
                        RasterCounters& counters, const FragmentTest& test) {
    if (const auto placed = place_in_tile(t, tile))
        rasterize_scalar<true>(t, *placed, triangle_id, tile, buffers, counters, &test);
}

namespace {

// What the kernels need besides the edges, for block p of triangle t.
[[gnu::always_inline]] inline
EdgeBlock32 kernel_block(const RasterTriangle& t, const TriangleInTile& p, std::uint32_t triangle_id,
                         const TileRect& tile) {
    EdgeBlock32 block;
    block.x_begin = p.x_begin - tile.x0, block.x_end = p.x_end - tile.x0;
    block.y_begin = p.y_begin - tile.y0, block.y_end = p.y_end - tile.y0;
    block.inv_area = t.inv_area;
    block.d0 = t.depth[0], block.d10 = t.depth[1] - t.depth[0], block.d20 = t.depth[2] - t.depth[0];
    block.triangle_id = triangle_id;
    const EdgeStepper* e[3] = {&p.e[0], &p.e[1], &p.e[2]};
    for (int k = 0; k < 3; ++k) block.bias[k] = std::int32_t(e[k]->bias);
    return block;
}

[[gnu::always_inline]] inline
void run_kernel(simd::Isa isa, const EdgeBlock32& block, const WideWeights* wide, TileBuffers& buffers,
                RasterCounters& counters) {
    const TileView view{buffers.depth.data(), buffers.triangle.data(), buffers.lambda1.data(), buffers.lambda2.data(),
                        buffers.side};
    switch (isa) {
        case simd::Isa::sse4: return rasterize_block_sse4(block, wide, view, counters);
        case simd::Isa::avx2: return rasterize_block_avx2(block, wide, view, counters);
        case simd::Isa::avx512: return rasterize_block_avx512(block, wide, view, counters);
        case simd::Isa::scalar: break;
    }
}

// The kernels' record of block p with its edge values narrowed to int32 (they fit: fits_int32 or
// stamp_fits_int32).
[[gnu::always_inline]] inline
EdgeBlock32 int32_block(const RasterTriangle& t, const TriangleInTile& p, std::uint32_t triangle_id,
                        const TileRect& tile) {
    EdgeBlock32 block = kernel_block(t, p, triangle_id, tile);
    const EdgeStepper* e[3] = {&p.e[0], &p.e[1], &p.e[2]};
    for (int k = 0; k < 3; ++k) {
        block.row[k] = std::int32_t(e[k]->row);
        block.step_x[k] = std::int32_t(e[k]->step_x);
        block.step_y[k] = std::int32_t(e[k]->step_y);
    }
    return block;
}

// A box at most kStampWidth wide whose edge values fit in int32 (stamp_fits_int32).
[[gnu::always_inline]] inline
void rasterize_stamp(simd::Isa isa, const RasterTriangle& t, const TriangleInTile& p, std::uint32_t triangle_id,
                     const TileRect& tile, TileBuffers& buffers, RasterCounters& counters) {
    EdgeBlock32 block = int32_block(t, p, triangle_id, tile);
    const TileView view{buffers.depth.data(), buffers.triangle.data(), buffers.lambda1.data(), buffers.lambda2.data(),
                        buffers.side};
    switch (isa) {
        case simd::Isa::sse4: return rasterize_stamp_sse4(block, view, counters);
        case simd::Isa::avx2: return rasterize_stamp_avx2(block, view, counters);
        case simd::Isa::avx512: return rasterize_stamp_avx512(block, view, counters);
        case simd::Isa::scalar: break;
    }
}

// Block p with every edge value in int32 (fits_int32(p)). Inlined: the
// whole-box path of medium triangles pays for every call (raster/*/medium).
[[gnu::always_inline]] inline
void rasterize_int32(simd::Isa isa, const RasterTriangle& t, const TriangleInTile& p, bool fully_covered,
                     std::uint32_t triangle_id, const TileRect& tile, TileBuffers& buffers, RasterCounters& counters) {
    EdgeBlock32 block = int32_block(t, p, triangle_id, tile);
    block.fully_covered = fully_covered;
    run_kernel(isa, block, nullptr, buffers, counters);
}

// Block p whose barycentric numerators leave int32: weights in double, and
// coverage tested in int32 only for the edges that cross the block. False,
// doing nothing, when even those leave int32 (edges thousands of pixels long).
bool rasterize_wide(simd::Isa isa, const RasterTriangle& t, const TriangleInTile& p, bool fully_covered,
                    std::uint32_t triangle_id, const TileRect& tile, TileBuffers& buffers, RasterCounters& counters) {
    const int width = p.x_end - p.x_begin, height = p.y_end - p.y_begin;
    EdgeBlock32 block = kernel_block(t, p, triangle_id, tile);
    const EdgeStepper* e[3] = {&p.e[0], &p.e[1], &p.e[2]};
    for (int k = 0; k < 3; ++k) {
        // An edge >= 0 over the whole block passes everywhere: tested as 0.
        const bool passes = fully_covered || edge_range(*e[k], width, height).min >= 0;
        if (!passes && !edge_fits_int32(*e[k], width, height)) return false;
        block.row[k] = passes ? 0 : std::int32_t(e[k]->row);
        block.step_x[k] = passes ? 0 : std::int32_t(e[k]->step_x);
        block.step_y[k] = passes ? 0 : std::int32_t(e[k]->step_y);
    }
    block.fully_covered = fully_covered;
    WideWeights wide;
    for (int k = 0; k < 2; ++k) {
        const EdgeStepper& weight = k == 0 ? p.e[1] : p.e[2];
        wide.row[k] = double(weight.row - weight.bias);
        wide.step_x[k] = double(weight.step_x);
        wide.step_y[k] = double(weight.step_y);
    }
    run_kernel(isa, block, &wide, buffers, counters);
    return true;
}

// Hierarchical rasterization (as llvmpipe's lp_rast, one level): the box is
// cut into kBlockSide² blocks, each found outside an edge (skipped), inside
// all three (no edge test), or crossed by one. Blocks of one kind next to each
// other in a row of blocks go to the kernel together, fewer and wider calls.
// 16 measured best (raster/*/large and huge, against 8 and 32, and 8- or
// 32-row strips): smaller blocks mean more, shorter kernel calls.
constexpr int kBlockSide = 16;

// A run of blocks of one kind, one row of blocks tall.
void rasterize_run(simd::Isa isa, const RasterTriangle& t, const TriangleInTile& run, BlockCoverage coverage,
                   std::uint32_t triangle_id, const TileRect& tile, TileBuffers& buffers, RasterCounters& counters) {
    const bool full = coverage == BlockCoverage::full;
    if (fits_int32(run)) return rasterize_int32(isa, t, run, full, triangle_id, tile, buffers, counters);
    if (rasterize_wide(isa, t, run, full, triangle_id, tile, buffers, counters)) return;
    // Long edges crossing a wide run: block by block, the int64 loop as last resort.
    for (int x = run.x_begin; x < run.x_end; x += kBlockSide) {
        const TriangleInTile block = sub_block(run, x, std::min(x + kBlockSide, run.x_end), run.y_begin, run.y_end);
        if (!rasterize_wide(isa, t, block, full, triangle_id, tile, buffers, counters))
            rasterize_scalar(t, block, triangle_id, tile, buffers, counters);
    }
}

// Out of line, so that the dispatcher's path for tiny triangles (most of a
// finely tessellated mesh) stays short.
[[gnu::noinline]] void rasterize_hierarchical(simd::Isa isa, const RasterTriangle& t, const TriangleInTile& placed,
                            std::uint32_t triangle_id, const TileRect& tile, TileBuffers& buffers,
                            RasterCounters& counters) {
    for (int y = placed.y_begin; y < placed.y_end; y += kBlockSide) {
        const int y_end = std::min(y + kBlockSide, placed.y_end);
        int run_begin = placed.x_begin;
        BlockCoverage run_coverage = BlockCoverage::none;
        auto finish_run = [&](int run_end) {
            if (run_coverage != BlockCoverage::none)
                rasterize_run(isa, t, sub_block(placed, run_begin, run_end, y, y_end), run_coverage, triangle_id, tile,
                              buffers, counters);
        };
        for (int x = placed.x_begin; x < placed.x_end; x += kBlockSide) {
            const BlockCoverage coverage =
                block_coverage(sub_block(placed, x, std::min(x + kBlockSide, placed.x_end), y, y_end));
            if (coverage == run_coverage) continue;
            finish_run(x);
            run_begin = x, run_coverage = coverage;
        }
        finish_run(placed.x_end);
    }
}

}  // namespace

// Everything but tiny triangles: out of line, so that the tiny path, most
// calls for a finely tessellated mesh, pays for no more than it uses.
[[gnu::noinline]] void rasterize_general(simd::Isa isa, const RasterTriangle& t, std::uint32_t triangle_id,
                                         const TileRect& tile, TileBuffers& buffers, RasterCounters& counters) {
    const auto placed = place_in_tile(t, tile);
    if (!placed) return;
    if (isa == simd::Isa::scalar) return rasterize_scalar(t, *placed, triangle_id, tile, buffers, counters);
    const int width = placed->x_end - placed->x_begin, height = placed->y_end - placed->y_begin;
    // Other narrow boxes as stamps too, or one pixel at a time when their edge values leave int32.
    if (width <= kStampWidth) {
        if (stamp_fits_int32(*placed)) return rasterize_stamp(isa, t, *placed, triangle_id, tile, buffers, counters);
        return rasterize_scalar(t, *placed, triangle_id, tile, buffers, counters);
    }
    // Boxes whose edge values leave int32 as a whole take the hierarchy: per
    // block they mostly fit, or need only their weights in double. Others take
    // it when over four vectors wide: below that (with AVX-512, up to 64 px,
    // where the box is one or two blocks across) the kernel skips empty vectors
    // more cheaply than blocks are classified and called (raster/*/large).
    const int lanes = isa == simd::Isa::avx512 ? 16 : isa == simd::Isa::avx2 ? 8 : 4;
    const bool big_box = width > 4 * lanes && height >= kBlockSide;
    if (!big_box && fits_int32(*placed))
        return rasterize_int32(isa, t, *placed, false, triangle_id, tile, buffers, counters);
    rasterize_hierarchical(isa, t, *placed, triangle_id, tile, buffers, counters);
}

void rasterize_triangle(simd::Isa isa, const RasterTriangle& t, std::uint32_t triangle_id, const TileRect& tile,
                        TileBuffers& buffers, RasterCounters& counters) {
    // Straight to the ISA's kernel, which sets tiny triangles (most of a
    // finely tessellated mesh) up in int32 itself and hands the others back.
    const TileView view{buffers.depth.data(), buffers.triangle.data(), buffers.lambda1.data(), buffers.lambda2.data(),
                        buffers.side};
    switch (isa) {
        case simd::Isa::sse4: return rasterize_triangle_sse4(t, triangle_id, tile, buffers, view, counters);
        case simd::Isa::avx2: return rasterize_triangle_avx2(t, triangle_id, tile, buffers, view, counters);
        case simd::Isa::avx512: return rasterize_triangle_avx512(t, triangle_id, tile, buffers, view, counters);
        case simd::Isa::scalar: break;
    }
    rasterize_general(isa, t, triangle_id, tile, buffers, counters);
}

}  // namespace tessera::raster
