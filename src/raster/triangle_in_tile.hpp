// What every scalar rasterizer loop (one sample, 4× MSAA, blended) starts
// from: the part of a tile a set-up triangle's pixel box covers, with its three
// edges stepped from that part's first pixel centre; and the window depth the
// loops test, from the screen-space barycentrics.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>

#include "raster/msaa/msaa_pattern.hpp"
#include "raster/raster_limits.hpp"
#include "raster/tile_rasterizer.hpp"
#include "raster/triangle_setup.hpp"

namespace tessera::raster {

// The pixel block of the tile a triangle can cover, and its edges stepped from
// the block's first pixel centre.
struct TriangleInTile {
    int x_begin, x_end, y_begin, y_end;  // image pixel coordinates
    EdgeStepper e[3];                    // edge k is opposite corner k: its value is corner k's weight × area
};

[[gnu::always_inline]] inline std::optional<TriangleInTile> place_in_tile(const RasterTriangle& t,
                                                                          const TileRect& tile) {
    const int x_begin = std::max<int>(t.px_min, tile.x0), x_end = std::min<int>(t.px_max + 1, tile.x1);
    const int y_begin = std::max<int>(t.py_min, tile.y0), y_end = std::min<int>(t.py_max + 1, tile.y1);
    if (x_begin >= x_end || y_begin >= y_end) return std::nullopt;
    const std::int64_t px = std::int64_t(x_begin) * kSubpixelScale + kSubpixelScale / 2;
    const std::int64_t py = std::int64_t(y_begin) * kSubpixelScale + kSubpixelScale / 2;
    return TriangleInTile{x_begin, x_end, y_begin, y_end,
                          {EdgeStepper(t.x[1], t.y[1], t.x[2], t.y[2], px, py),
                           EdgeStepper(t.x[2], t.y[2], t.x[0], t.y[0], px, py),
                           EdgeStepper(t.x[0], t.y[0], t.x[1], t.y[1], px, py)}};
}

// Depth is linear in screen space; kept >= 0 (and -0 made +0) so that depths
// also order like their bit patterns, which the SIMD kernels rely on.
inline float window_depth(const RasterTriangle& t, float lambda1, float lambda2) {
    const float z = t.depth[0] + lambda1 * (t.depth[1] - t.depth[0]) + lambda2 * (t.depth[2] - t.depth[0]);
    return z > 0.0f ? z : 0.0f;
}

// E is affine: at sample s it is E at the pixel centre plus offset[k][s], the
// edge's steps scaled by the sample's offset (in 1/256 pixel, so step / 256 is exact).
using SampleEdgeOffsets = std::array<std::array<std::int64_t, kMsaaSamples>, 3>;
inline SampleEdgeOffsets sample_edge_offsets(const EdgeStepper (&e)[3]) {
    SampleEdgeOffsets offset;
    for (int k = 0; k < 3; ++k)
        for (int s = 0; s < kMsaaSamples; ++s)
            offset[k][s] = (e[k].step_x / kSubpixelScale) * kSampleOffsetX[s] +
                           (e[k].step_y / kSubpixelScale) * kSampleOffsetY[s];
    return offset;
}

}  // namespace tessera::raster
