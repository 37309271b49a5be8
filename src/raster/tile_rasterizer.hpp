// Tile rasterization: edge functions in fixed point with the top-left fill
// rule, a 32-bit float depth test (LESS), and the screen-space barycentrics
// of the nearest triangle kept per pixel. Shading happens afterwards, once per
// visible pixel, so hidden fragments cost no shading at all; the result is what
// forward shading with a LESS depth test and no blending would give.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "raster/triangle_setup.hpp"
#include "simd/isa.hpp"

namespace tessera::raster {

// A triangle id no triangle has.
inline constexpr std::uint32_t kNoTriangle = ~std::uint32_t{0};

// A rectangle of pixels, [x0, x1) × [y0, y1).
struct TileRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
};

// Per-pixel results of rasterizing one tile, row-major with a stride of `side`.
// Owned by a worker and reused from tile to tile.
struct TileBuffers {
    int side = 0;
    std::vector<float> depth;               // window depth of the nearest fragment, 1 = cleared
    std::vector<std::uint32_t> triangle;    // its triangle id (as the rasterizer was given it), where covered
    std::vector<float> lambda1, lambda2;    // its screen-space barycentrics of corners 1 and 2, where covered
    // The tile's triangles in the order they were drawn, each once, for its
    // gather (shade/surface_gather.hpp): ids[p] for p < count. The renderer
    // draws the triangle at position p as id p, so that the gather finds a
    // pixel's triangle without a hash table.
    struct TriangleList {
        std::vector<std::uint32_t> ids;  // grown, never shrunk: no allocation per tile
        std::uint32_t count = 0;
        // Room for n more ids, from ids[count] on (count is not advanced).
        std::uint32_t* room_for(std::size_t n) {
            if (count + n > ids.size()) ids.resize(std::max(2 * ids.size(), count + n));
            return ids.data() + count;
        }
        // Appends `id`; returns its position, the id to draw it as.
        std::uint32_t add(std::uint32_t id) {
            *room_for(1) = id;
            return count++;
        }
    } triangles;
    // A fragment passes LESS only with depth < 1, the cleared value, so depth
    // alone says whether a pixel is covered and the other arrays need no clearing.
    bool covered(std::size_t pixel) const { return depth[pixel] < 1.0f; }
    void reset(int tile_side);              // clears depth to 1 and empties `triangles`
};

// Counts of work done, summed over tiles.
struct RasterCounters {
    std::uint64_t fragments = 0;  // pixel centres covered
    std::uint64_t depth_passed = 0;
};

// Perspective-correct barycentrics of corners 1 and 2 from the screen-space
// ones stored per pixel: b_i ∝ λ_i / w_i (attributes are linear in world space,
// not in screen space). inv_w: 1 / clip w of the three corners.
struct Barycentrics {
    float b1, b2;
};
inline Barycentrics perspective_barycentrics(const std::array<float, 3>& inv_w, float lambda1, float lambda2) {
    const float q0 = (1.0f - lambda1 - lambda2) * inv_w[0], q1 = lambda1 * inv_w[1], q2 = lambda2 * inv_w[2];
    const float inv_sum = 1.0f / (q0 + q1 + q2);
    return {q1 * inv_sum, q2 * inv_sum};
}

// A test of each fragment that passes the depth test, before it is written:
// the alpha test of masked materials. keep(context, x, y, λ1, λ2), with (x, y)
// the image pixel and λ1 λ2 the screen-space barycentrics at its centre,
// returns false to discard the fragment: the depth and triangle stay as they
// were, so what lies behind shows.
struct FragmentTest {
    bool (*keep)(const void* context, int x, int y, float lambda1, float lambda2) = nullptr;
    const void* context = nullptr;
};

// Rasterizes one triangle into the part of the tile it covers: the scalar
// reference loop (int64 edge functions, one pixel at a time).
void rasterize_triangle(const RasterTriangle& t, std::uint32_t triangle_id, const TileRect& tile, TileBuffers& buffers,
                        RasterCounters& counters);
// The same with the ISA's vector kernel wherever the edge values fit in int32
// (all but large triangles); bit-identical buffers either way.
void rasterize_triangle(simd::Isa isa, const RasterTriangle& t, std::uint32_t triangle_id, const TileRect& tile,
                        TileBuffers& buffers, RasterCounters& counters);
// The scalar loop with a fragment test (any ISA gives this same result: the
// vector kernels are bit-identical to it, and the test runs per fragment).
void rasterize_triangle(const RasterTriangle& t, std::uint32_t triangle_id, const TileRect& tile, TileBuffers& buffers,
                        RasterCounters& counters, const FragmentTest& test);

}  // namespace tessera::raster
