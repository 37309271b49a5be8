// Building raster-stage triangles straight from screen positions.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "raster/tile_rasterizer.hpp"
#include "raster/triangle_setup.hpp"

namespace tessera::test {

// The clip position that the viewport maps onto image point (x, y) (y down)
// at window depth `depth`, with clip w = `w`.
inline glm::vec4 clip_for_screen(float x, float y, float depth, float w, int width, int height) {
    const float ndc_x = x / float(width) * 2.0f - 1.0f;
    const float ndc_y = 1.0f - y / float(height) * 2.0f;
    const float ndc_z = depth * 2.0f - 1.0f;
    return {ndc_x * w, ndc_y * w, ndc_z * w, w};
}

// Triangle setup of image points a, b, c (y down) of a size×size image, at
// window depths `depths` (corner by corner), with clip w = 1.
inline std::optional<raster::RasterTriangle> screen_triangle(glm::vec2 a, glm::vec2 b, glm::vec2 c, int size,
                                                             const std::array<float, 3>& depths) {
    return raster::setup_triangle({size, size},
                                  {clip_for_screen(a.x, a.y, depths[0], 1, size, size),
                                   clip_for_screen(b.x, b.y, depths[1], 1, size, size),
                                   clip_for_screen(c.x, c.y, depths[2], 1, size, size)},
                                  {0, 1, 2});
}

inline std::optional<raster::RasterTriangle> screen_triangle(glm::vec2 a, glm::vec2 b, glm::vec2 c, int size,
                                                             float depth = 0.5f) {
    return screen_triangle(a, b, c, size, {depth, depth, depth});
}

// 1 for each pixel of a size×size image whose centre the triangle covers.
inline std::vector<int> coverage(const std::optional<raster::RasterTriangle>& t, int size) {
    std::vector<int> covered(std::size_t(size) * size, 0);
    if (!t) return covered;
    raster::TileBuffers buffers;
    buffers.reset(size);
    raster::RasterCounters counters;
    raster::rasterize_triangle(*t, 0, {0, 0, size, size}, buffers, counters);
    for (std::size_t i = 0; i < covered.size(); ++i) covered[i] = buffers.covered(i);
    return covered;
}

}  // namespace tessera::test
