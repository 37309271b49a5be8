#include "raster/tile_rasterizer.hpp"

#include <algorithm>

#include "raster/raster_limits.hpp"

namespace tessera::raster {

void TileBuffers::reset(int tile_side) {
    const std::size_t n = std::size_t(tile_side) * std::size_t(tile_side);
    side = tile_side;
    depth.assign(n, 1.0f);
    triangle.resize(n);
    lambda1.resize(n);
    lambda2.resize(n);
}

namespace {

// One edge a→b stepped over pixel centres. The top-left rule is a bias:
// a centre exactly on an edge belongs to the triangle only when the edge is a
// top edge (horizontal, interior below) or a left edge (interior to its right),
// so edges of neither kind test E - 1 >= 0 instead of E >= 0.
struct EdgeStepper {
    std::int64_t row;     // biased E at the current row's first pixel centre
    std::int64_t step_x;  // change of E for one pixel right
    std::int64_t step_y;  // change of E for one pixel down
    std::int64_t bias;    // 0 or -1

    EdgeStepper(std::int32_t ax, std::int32_t ay, std::int32_t bx, std::int32_t by, std::int64_t px, std::int64_t py) {
        const std::int64_t dx = std::int64_t(bx) - ax;
        const std::int64_t dy = std::int64_t(by) - ay;
        const bool top_left = dy < 0 || (dy == 0 && dx > 0);
        bias = top_left ? 0 : -1;
        row = edge_function(ax, ay, bx, by, px, py) + bias;
        step_x = -dy * kSubpixelScale;
        step_y = dx * kSubpixelScale;
    }
};

}  // namespace

void rasterize_triangle(const RasterTriangle& t, std::uint32_t triangle_id, const TileRect& tile, TileBuffers& buffers,
                        RasterCounters& counters) {
    const int x_begin = std::max(t.px_min, tile.x0), x_end = std::min(t.px_max + 1, tile.x1);
    const int y_begin = std::max(t.py_min, tile.y0), y_end = std::min(t.py_max + 1, tile.y1);
    if (x_begin >= x_end || y_begin >= y_end) return;

    const std::int64_t px = std::int64_t(x_begin) * kSubpixelScale + kSubpixelScale / 2;
    const std::int64_t py = std::int64_t(y_begin) * kSubpixelScale + kSubpixelScale / 2;
    // Edge k is opposite corner k, so its value is corner k's barycentric weight × area.
    EdgeStepper e0(t.x[1], t.y[1], t.x[2], t.y[2], px, py);
    EdgeStepper e1(t.x[2], t.y[2], t.x[0], t.y[0], px, py);
    EdgeStepper e2(t.x[0], t.y[0], t.x[1], t.y[1], px, py);

    const float inv_area = 1.0f / float(t.double_area);
    const float d0 = t.depth[0], d10 = t.depth[1] - t.depth[0], d20 = t.depth[2] - t.depth[0];
    for (int y = y_begin; y < y_end; ++y) {
        std::int64_t w0 = e0.row, w1 = e1.row, w2 = e2.row;
        std::size_t index = std::size_t(y - tile.y0) * buffers.side + (x_begin - tile.x0);
        for (int x = x_begin; x < x_end; ++x, ++index) {
            if ((w0 | w1 | w2) >= 0) {
                ++counters.fragments;
                const float lambda1 = float(w1 - e1.bias) * inv_area;
                const float lambda2 = float(w2 - e2.bias) * inv_area;
                const float z = d0 + lambda1 * d10 + lambda2 * d20;  // depth is linear in screen space
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

}  // namespace tessera::raster
