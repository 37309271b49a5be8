// Rasterizing blended triangles (AlphaMode::blend). They are drawn after the
// opaque ones, against the opaque depth: a fragment passes where it is nearer
// (LESS) than the opaque surface, but writes no depth, and every passing
// fragment is kept — not only the nearest — in the order its triangles are
// drawn, for the blend (image/blend.hpp) to composite one over the other.
#pragma once

#include <cstdint>
#include <vector>

#include "raster/msaa/msaa.hpp"
#include "raster/tile_rasterizer.hpp"

namespace tessera::raster {

// A tile's blended fragments in drawing order: a triangle's fragments follow
// the previous triangle's, its own in row-major pixel order.
struct BlendFragments {
    // Tile-relative pixel, triangle, and λ1 λ2 at the pixel centre (with 4×
    // MSAA extrapolated where the triangle misses the centre, as for opaque
    // fragments: GL's rule for inputs not qualified `centroid`).
    TileFragments fragments;
    // Per fragment, bit s: sample s is covered and in front of the opaque depth
    // (one sample per pixel: bit 0).
    std::vector<std::uint8_t> sample_mask;
    std::size_t capacity = 0;  // side² × samples

    void reserve(int tile_side, int samples);
    std::size_t count() const { return fragments.count; }
    void clear() { fragments.count = 0; }
};

// Fragments triangle t can add in the tile at most (its pixel box there).
std::size_t max_blend_fragments(const RasterTriangle& t, const TileRect& tile);

// Appends triangle t's fragments in the tile that pass LESS against the opaque
// depth; `out` must have room for max_blend_fragments(t, tile) more. One sample
// per pixel: the same coverage (top-left rule), λ and depth as rasterize_triangle.
void rasterize_blended(const RasterTriangle& t, std::uint32_t triangle_id, const TileRect& tile,
                       const TileBuffers& opaque, BlendFragments& out, RasterCounters& counters);
// 4× MSAA: coverage and depth per sample, as rasterize_triangle_msaa; one
// fragment per pixel where any sample passes.
void rasterize_blended(const RasterTriangle& t, std::uint32_t triangle_id, const TileRect& tile,
                       const TileSamples& opaque, BlendFragments& out, RasterCounters& counters);

}  // namespace tessera::raster
