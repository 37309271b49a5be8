#include "raster/blend_raster.hpp"

#include <algorithm>
#include <optional>

#include "raster/raster_limits.hpp"
#include "raster/triangle_in_tile.hpp"

namespace tessera::raster {

namespace {

void append(BlendFragments& out, int x, int y, const TileRect& tile, std::uint32_t id, float lambda1, float lambda2,
            std::uint8_t mask) {
    TileFragments& f = out.fragments;
    const std::size_t k = f.count++;
    f.x[k] = std::uint16_t(x - tile.x0), f.y[k] = std::uint16_t(y - tile.y0), f.triangle[k] = id;
    f.lambda1[k] = lambda1, f.lambda2[k] = lambda2;
    out.sample_mask[k] = mask;
}

}  // namespace

void BlendFragments::reserve(int tile_side, int samples) {
    fragments.reserve(tile_side);  // room for one per sample
    capacity = std::size_t(tile_side) * tile_side * samples;
    sample_mask.resize(capacity);
}

std::size_t max_blend_fragments(const RasterTriangle& t, const TileRect& tile) {
    const int width = std::min<int>(t.px_max + 1, tile.x1) - std::max<int>(t.px_min, tile.x0);
    const int height = std::min<int>(t.py_max + 1, tile.y1) - std::max<int>(t.py_min, tile.y0);
    return width > 0 && height > 0 ? std::size_t(width) * std::size_t(height) : 0;
}

void rasterize_blended(const RasterTriangle& t, std::uint32_t triangle_id, const TileRect& tile,
                       const TileBuffers& opaque, BlendFragments& out, RasterCounters& counters) {
    const std::optional<TriangleInTile> placed = place_in_tile(t, tile);
    if (!placed) return;
    TriangleInTile p = *placed;
    EdgeStepper* e = p.e;
    for (int y = p.y_begin; y < p.y_end; ++y) {
        std::int64_t w0 = e[0].row, w1 = e[1].row, w2 = e[2].row;
        std::size_t index = std::size_t(y - tile.y0) * opaque.side + (p.x_begin - tile.x0);
        for (int x = p.x_begin; x < p.x_end; ++x, ++index) {
            if ((w0 | w1 | w2) >= 0) {
                ++counters.fragments;
                const float lambda1 = float(w1 - e[1].bias) * t.inv_area;
                const float lambda2 = float(w2 - e[2].bias) * t.inv_area;
                if (window_depth(t, lambda1, lambda2) < opaque.depth[index]) {
                    ++counters.depth_passed;
                    append(out, x, y, tile, triangle_id, lambda1, lambda2, 1);
                }
            }
            w0 += e[0].step_x, w1 += e[1].step_x, w2 += e[2].step_x;
        }
        for (int k = 0; k < 3; ++k) e[k].row += e[k].step_y;
    }
}

void rasterize_blended(const RasterTriangle& t, std::uint32_t triangle_id, const TileRect& tile,
                       const TileSamples& opaque, BlendFragments& out, RasterCounters& counters) {
    const std::optional<TriangleInTile> placed = place_in_tile(t, tile);
    if (!placed) return;
    TriangleInTile p = *placed;
    EdgeStepper* e = p.e;
    const SampleEdgeOffsets offset = sample_edge_offsets(p.e);
    for (int y = p.y_begin; y < p.y_end; ++y) {
        std::int64_t w0 = e[0].row, w1 = e[1].row, w2 = e[2].row;
        std::size_t index = std::size_t(kMsaaSamples) * (std::size_t(y - tile.y0) * opaque.side + (p.x_begin - tile.x0));
        for (int x = p.x_begin; x < p.x_end; ++x, index += kMsaaSamples) {
            std::uint8_t mask = 0;
            for (int s = 0; s < kMsaaSamples; ++s) {
                const std::int64_t s0 = w0 + offset[0][s], s1 = w1 + offset[1][s], s2 = w2 + offset[2][s];
                if ((s0 | s1 | s2) < 0) continue;
                ++counters.fragments;
                const float z = window_depth(t, float(s1 - e[1].bias) * t.inv_area, float(s2 - e[2].bias) * t.inv_area);
                if (z < opaque.depth[index + s]) mask |= std::uint8_t(1u << s);
            }
            if (mask != 0) {
                ++counters.depth_passed;
                // At the pixel centre: the unbiased edge values there, as screen_barycentrics().
                append(out, x, y, tile, triangle_id, float(w1 - e[1].bias) * t.inv_area,
                       float(w2 - e[2].bias) * t.inv_area, mask);
            }
            w0 += e[0].step_x, w1 += e[1].step_x, w2 += e[2].step_x;
        }
        for (int k = 0; k < 3; ++k) e[k].row += e[k].step_y;
    }
}

}  // namespace tessera::raster
