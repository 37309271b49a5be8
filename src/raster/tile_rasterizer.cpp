#include "raster/tile_rasterizer.hpp"

#include <algorithm>
#include <cstdlib>
#include <optional>

#include "raster/raster_kernels.hpp"
#include "raster/raster_limits.hpp"

namespace tessera::raster {

void TileBuffers::reset(int tile_side) {
    // Padded so that a vector of pixels starting in the last row stays inside.
    const std::size_t n = std::size_t(tile_side) * std::size_t(tile_side) + kMaxRasterLanes;
    side = tile_side;
    depth.assign(n, 1.0f);
    triangle.resize(n);
    lambda1.resize(n);
    lambda2.resize(n);
}

namespace {

// The pixel block of the tile a triangle can cover, and its edges stepped from
// the block's first pixel centre.
struct TriangleInTile {
    int x_begin, x_end, y_begin, y_end;  // image pixel coordinates
    EdgeStepper e0, e1, e2;              // edge k is opposite corner k: its value is corner k's weight × area
};

[[gnu::always_inline]] inline std::optional<TriangleInTile> place_in_tile(const RasterTriangle& t, const TileRect& tile) {
    const int x_begin = std::max<int>(t.px_min, tile.x0), x_end = std::min<int>(t.px_max + 1, tile.x1);
    const int y_begin = std::max<int>(t.py_min, tile.y0), y_end = std::min<int>(t.py_max + 1, tile.y1);
    if (x_begin >= x_end || y_begin >= y_end) return std::nullopt;
    const std::int64_t px = std::int64_t(x_begin) * kSubpixelScale + kSubpixelScale / 2;
    const std::int64_t py = std::int64_t(y_begin) * kSubpixelScale + kSubpixelScale / 2;
    return TriangleInTile{x_begin, x_end, y_begin, y_end, EdgeStepper(t.x[1], t.y[1], t.x[2], t.y[2], px, py),
                          EdgeStepper(t.x[2], t.y[2], t.x[0], t.y[0], px, py),
                          EdgeStepper(t.x[0], t.y[0], t.x[1], t.y[1], px, py)};
}

// Depth is linear in screen space; kept >= 0 (and -0 made +0) so that depths
// also order like their bit patterns, which the SIMD kernels rely on.
inline float window_depth(const RasterTriangle& t, float lambda1, float lambda2) {
    const float z = t.depth[0] + lambda1 * (t.depth[1] - t.depth[0]) + lambda2 * (t.depth[2] - t.depth[0]);
    return z > 0.0f ? z : 0.0f;
}

// Whether every edge value the SIMD kernel can meet — over the block, plus a
// vector's worth of lanes past its right end — fits in int32.
bool fits_int32(const TriangleInTile& p) {
    const std::int64_t width = p.x_end - p.x_begin + kMaxRasterLanes, height = p.y_end - p.y_begin;
    for (const EdgeStepper* e : {&p.e0, &p.e1, &p.e2}) {
        const std::int64_t reach = std::llabs(e->row) + std::llabs(e->step_x) * width + std::llabs(e->step_y) * height;
        if (reach >= (std::int64_t(1) << 31) - 1) return false;
    }
    return true;
}

}  // namespace

namespace {

// The scalar loop: one pixel centre at a time, edge values in int64.
[[gnu::always_inline]] inline void rasterize_scalar(const RasterTriangle& t, const TriangleInTile& placed, std::uint32_t triangle_id,
                      const TileRect& tile, TileBuffers& buffers, RasterCounters& counters) {
    EdgeStepper e0 = placed.e0, e1 = placed.e1, e2 = placed.e2;
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
                if (z < buffers.depth[index]) {
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

void rasterize_triangle(simd::Isa isa, const RasterTriangle& t, std::uint32_t triangle_id, const TileRect& tile,
                        TileBuffers& buffers, RasterCounters& counters) {
    const auto placed = place_in_tile(t, tile);
    if (!placed) return;
    // Blocks narrower than this are quicker one pixel at a time (most
    // triangles of a finely tessellated mesh); large triangles, whose edge
    // values leave int32, take the int64 loop too.
    constexpr int kMinSimdWidth = 4;
    if (isa == simd::Isa::scalar || placed->x_end - placed->x_begin < kMinSimdWidth || !fits_int32(*placed))
        return rasterize_scalar(t, *placed, triangle_id, tile, buffers, counters);
    const EdgeStepper* e[3] = {&placed->e0, &placed->e1, &placed->e2};
    EdgeBlock32 block;
    for (int k = 0; k < 3; ++k) {
        block.row[k] = std::int32_t(e[k]->row);
        block.step_x[k] = std::int32_t(e[k]->step_x);
        block.step_y[k] = std::int32_t(e[k]->step_y);
        block.bias[k] = std::int32_t(e[k]->bias);
    }
    block.x_begin = placed->x_begin - tile.x0, block.x_end = placed->x_end - tile.x0;
    block.y_begin = placed->y_begin - tile.y0, block.y_end = placed->y_end - tile.y0;
    block.inv_area = t.inv_area;
    block.d0 = t.depth[0], block.d10 = t.depth[1] - t.depth[0], block.d20 = t.depth[2] - t.depth[0];
    block.triangle_id = triangle_id;
    const TileView view{buffers.depth.data(), buffers.triangle.data(), buffers.lambda1.data(), buffers.lambda2.data(),
                        buffers.side};
    switch (isa) {
        case simd::Isa::sse4: return rasterize_block_sse4(block, view, counters);
        case simd::Isa::avx2: return rasterize_block_avx2(block, view, counters);
        case simd::Isa::avx512: return rasterize_block_avx512(block, view, counters);
        case simd::Isa::scalar: break;
    }
}

}  // namespace tessera::raster
