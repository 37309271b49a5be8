// Building raster-stage triangles straight from screen positions.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <random>
#include <vector>

#include <glm/vec2.hpp>

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

// Triangle setup straight from fixed-point corners (24.8, image y down), for
// `samples` samples per pixel (1, or raster::kMsaaSamples).
inline std::optional<raster::RasterTriangle> fixed_triangle(std::array<glm::ivec2, 3> p, int image,
                                                            const std::array<float, 3>& depth, int samples = 1) {
    std::array<raster::ScreenVertex, 3> corners;
    for (int k = 0; k < 3; ++k) corners[k] = {p[k].x, p[k].y, depth[k], 0};
    return raster::setup_triangle({image, image}, corners, {0, 1, 2}, samples);
}

// A mesh of tiny triangles as the demo's spheres make them: an (n + 1)² grid of
// points from (28, 28) px, `pitch` apart in fixed point, two of every three
// jittered by up to ±60/256 px (the others stay on the grid: ties), two
// triangles per quad, every edge shared. Then a second layer of the same
// triangles, alternately behind the first and at depth 0.5, crossing it at
// depth ties now and then. `first_layer` gets the first layer's size.
inline std::vector<raster::RasterTriangle> jittered_mesh(std::mt19937& rng, int pitch, int n, int image, int samples,
                                                        std::size_t& first_layer) {
    std::uniform_int_distribution<int> jitter(-60, 60);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<glm::ivec2> grid;
    std::vector<float> depth;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            glm::ivec2 p{28 * 256 + i * pitch, 28 * 256 + j * pitch};
            if ((i + j) % 3) p += glm::ivec2{jitter(rng), jitter(rng)};
            grid.push_back(p);
            depth.push_back(0.3f + 0.4f * unit(rng));
        }
    std::vector<raster::RasterTriangle> triangles;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            for (const auto& [u, v, w] : {std::array<int, 3>{a, b, d}, std::array<int, 3>{a, d, c}})
                if (auto t = fixed_triangle({grid[u], grid[v], grid[w]}, image, {depth[u], depth[v], depth[w]}, samples))
                    triangles.push_back(*t);
        }
    first_layer = triangles.size();
    for (std::size_t i = 0; i < first_layer; ++i) {
        raster::RasterTriangle t = triangles[i];
        for (float& z : t.depth) z = i % 2 ? z + 0.1f : 0.5f;
        triangles.push_back(t);
    }
    return triangles;
}

}  // namespace tessera::test
