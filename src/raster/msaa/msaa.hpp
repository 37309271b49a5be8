// 4× multisampling: per-sample coverage and depth, and the fragments a pixel
// is shaded with. The fragment shader runs once per pixel per visible
// triangle (not per sample), as a GPU's multisampling does.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "raster/msaa/msaa_pattern.hpp"
#include "raster/raster_limits.hpp"
#include "raster/tile_rasterizer.hpp"
#include "raster/triangle_setup.hpp"
#include "simd/isa.hpp"

namespace tessera::raster {

// Per-sample results of rasterizing one tile: sample s of tile pixel p at
// [kMsaaSamples · p + s]. Owned by a worker and reused from tile to tile.
struct TileSamples {
    int side = 0;
    std::vector<float> depth;             // window depth of the nearest fragment, 1 = cleared
    std::vector<std::uint32_t> triangle;  // its triangle id, where depth < 1
    // Which of the tile's fragments (TileFragments) colours the sample; -1: background.
    std::vector<std::int32_t> fragment;
    // The tile-relative pixel box [x0, x1) × [y0, y1) outside which every
    // depth is 1: the union of the boxes the rasterizers worked in since
    // reset() (empty: x0 > x1). Code that writes depth itself widens it with
    // mark_written(). reset() and list_fragments() touch only this box, so
    // the background of a tile costs little.
    int written_x0 = kEmptyBoxLow, written_y0 = kEmptyBoxLow, written_x1 = kEmptyBoxHigh, written_y1 = kEmptyBoxHigh;
    void mark_written(int x0, int y0, int x1, int y1) {
        written_x0 = std::min(written_x0, x0), written_y0 = std::min(written_y0, y0);
        written_x1 = std::max(written_x1, x1), written_y1 = std::max(written_y1, y1);
    }
    // Clears depth to 1 (allocates only when the side grows; otherwise clears
    // only the written box). depth and triangle are padded past the last pixel
    // for the vector kernels.
    void reset(int tile_side);

    static constexpr int kEmptyBoxLow = 1 << 30, kEmptyBoxHigh = -(1 << 30);
};

// The pixels' fragments: one per pixel and distinct triangle among its
// covered samples, pixels in row-major order, a pixel's fragments in the order
// of their first sample. λ1 λ2: the screen-space barycentrics at the pixel
// centre, extrapolated where the triangle misses it — GL's interpolation of
// varyings not qualified `centroid`, as in the reference shader.
struct TileFragments {
    std::vector<std::uint16_t> x, y;  // tile-relative pixel
    std::vector<std::uint32_t> triangle;
    std::vector<float> lambda1, lambda2;
    std::vector<const RasterTriangle*> source;  // the triangle of each, for collect_fragments()
    std::size_t count = 0;
    void reserve(int tile_side);
};

// Rasterizes one triangle's samples into the part of the tile it covers:
// int64 edge functions, the top-left rule per sample, depth test LESS per
// sample. counters.fragments counts covered samples. With a fragment test
// (masked materials) it runs once per pixel, at the pixel centre as the
// shader would, when the first of the triangle's samples there passes the
// depth test; discarding drops all the triangle's samples in that pixel.
void rasterize_triangle_msaa(const RasterTriangle& t, std::uint32_t triangle_id, const TileRect& tile,
                             TileSamples& samples, RasterCounters& counters, const FragmentTest* test = nullptr);
// The same with the ISA's vector kernel (msaa_kernels.hpp) where every edge
// value fits in int32, the scalar loop otherwise and for Isa::scalar:
// bit-identical samples and counters either way. No fragment test: with one,
// call the scalar loop above (its test runs per pixel, in sample order).
void rasterize_triangle_msaa(simd::Isa isa, const RasterTriangle& t, std::uint32_t triangle_id, const TileRect& tile,
                             TileSamples& samples, RasterCounters& counters);

// λ1, λ2 of a set-up triangle at a point given in fixed point (image space).
inline std::array<float, 2> screen_barycentrics(const RasterTriangle& t, std::int64_t px, std::int64_t py) {
    // As the rasterizer computes them: λ1 = E(2→0)/area, λ2 = E(0→1)/area.
    return {float(edge_function(t.x[2], t.y[2], t.x[0], t.y[0], px, py)) * t.inv_area,
            float(edge_function(t.x[0], t.y[0], t.x[1], t.y[1], px, py)) * t.inv_area};
}

// Whether a fixed-point point is inside a set-up triangle, by the top-left rule.
bool covers_point(const RasterTriangle& t, std::int64_t px, std::int64_t py);

// The first half of collect_fragments(): sets samples.fragment and lists the
// fragments' pixels and triangles (x, y, triangle, count), a pixel at a time
// from a table, without the branches of the loop below (msaa_list_kernel.hpp;
// this copy is baseline SSE2). Outside the written box it only stores -1;
// inside, it skips 4 background pixels at a time.
void list_fragments(const TileRect& rect, TileSamples& samples, TileFragments& out);
// The same with the ISA's copy (the one above for Isa::scalar).
void list_fragments(simd::Isa isa, const TileRect& rect, TileSamples& samples, TileFragments& out);

// λ1, λ2 of out's fragments at their pixel centres, whose triangles are
// out.source: with the ISA's kernel (msaa_fragment_kernels.hpp), bit-identical
// to screen_barycentrics(), which Isa::scalar calls.
void fragment_barycentrics(simd::Isa isa, const TileRect& rect, TileFragments& out);

// Lists the fragments of a width × height tile from its samples and sets
// samples.fragment. triangle_of(id) gives the RasterTriangle of a triangle id.
template <class TriangleOf>
void collect_fragments(simd::Isa isa, const TileRect& rect, TileSamples& samples, TriangleOf&& triangle_of,
                       TileFragments& out) {
    list_fragments(isa, rect, samples, out);
    // Each shaded at its pixel's centre. Every fragment looks its triangle up:
    // a branch that reused the last one mispredicted at each change of
    // triangle, every few fragments.
    for (std::size_t k = 0; k < out.count; ++k) out.source[k] = &triangle_of(out.triangle[k]);
    fragment_barycentrics(isa, rect, out);
}

// The plain loop collect_fragments() must match (tests compare them).
template <class TriangleOf>
void collect_fragments_reference(const TileRect& rect, TileSamples& samples, TriangleOf&& triangle_of, TileFragments& out) {
    out.count = 0;
    for (int y = 0; y < rect.height(); ++y) {
        for (int x = 0; x < rect.width(); ++x) {
            const std::size_t first = std::size_t(kMsaaSamples) * (std::size_t(y) * samples.side + x);
            const std::size_t pixel_fragments = out.count;
            for (int s = 0; s < kMsaaSamples; ++s) {
                samples.fragment[first + s] = -1;
                if (!(samples.depth[first + s] < 1.0f)) continue;
                const std::uint32_t id = samples.triangle[first + s];
                std::size_t k = pixel_fragments;
                while (k < out.count && out.triangle[k] != id) ++k;
                samples.fragment[first + s] = std::int32_t(k);
                if (k < out.count) continue;
                // A new triangle in this pixel: shaded at the pixel centre.
                const RasterTriangle& t = triangle_of(id);
                const auto [l1, l2] =
                    screen_barycentrics(t, std::int64_t(rect.x0 + x) * kSubpixelScale + kSubpixelScale / 2,
                                        std::int64_t(rect.y0 + y) * kSubpixelScale + kSubpixelScale / 2);
                out.x[k] = std::uint16_t(x), out.y[k] = std::uint16_t(y), out.triangle[k] = id;
                out.lambda1[k] = l1, out.lambda2[k] = l2;
                ++out.count;
            }
        }
    }
}

}  // namespace tessera::raster
