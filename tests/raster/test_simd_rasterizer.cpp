#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "raster/bin_rasterizer.hpp"
#include "raster/raster_kernels.hpp"
#include "raster_test_util.hpp"

using namespace tessera;

namespace {

// Rasterizes the triangles into `tile` with the scalar int64 loop and with
// every ISA's vector path (a call per triangle, and all as one bin), and checks that the buffers (coverage by the fill
// rule, depth, triangle ids, barycentrics) and the counters are bit-identical.
// Returns the scalar loop's buffers.
raster::TileBuffers check_isas_match_scalar(const std::vector<raster::RasterTriangle>& triangles,
                                            const raster::TileRect& tile) {
    const int side = tile.width();
    raster::TileBuffers reference;
    reference.reset(side);
    raster::RasterCounters reference_counts;
    for (std::uint32_t i = 0; i < triangles.size(); ++i)
        raster::rasterize_triangle(triangles[i], i, tile, reference, reference_counts);

    for (simd::Isa isa : {simd::Isa::sse4, simd::Isa::avx2, simd::Isa::avx512}) {
        CAPTURE(simd::isa_name(isa));
        if (!simd::isa_supported(isa)) {
            MESSAGE("skipped: " << simd::isa_name(isa) << " is not supported by this CPU");
            continue;
        }
        // One call per triangle, and the whole list as one bin (rasterize_bin, as the renderer draws).
        for (const bool whole_bin : {false, true}) {
            CAPTURE(whole_bin);
            raster::TileBuffers buffers;
            buffers.reset(side);
            raster::RasterCounters counts;
            if (whole_bin) {
                std::vector<std::uint32_t> bin(triangles.size());
                for (std::uint32_t i = 0; i < bin.size(); ++i) bin[i] = i;
                raster::rasterize_bin(isa, triangles.data(), bin, 0, tile, buffers, counts);
            } else {
                for (std::uint32_t i = 0; i < triangles.size(); ++i)
                    raster::rasterize_triangle(isa, triangles[i], i, tile, buffers, counts);
            }
            CHECK(counts.fragments == reference_counts.fragments);
            CHECK(counts.depth_passed == reference_counts.depth_passed);
            int mismatches = 0;
            for (std::size_t p = 0; p < std::size_t(side) * side; ++p) {
                const bool covered = reference.covered(p);
                if (covered != buffers.covered(p) ||
                    std::memcmp(&reference.depth[p], &buffers.depth[p], sizeof(float)) != 0 ||
                    (covered && (reference.triangle[p] != buffers.triangle[p] ||
                                 std::memcmp(&reference.lambda1[p], &buffers.lambda1[p], sizeof(float)) != 0 ||
                                 std::memcmp(&reference.lambda2[p], &buffers.lambda2[p], sizeof(float)) != 0)))
                    ++mismatches;
            }
            CHECK(mismatches == 0);
        }
    }
    return reference;
}

}  // namespace

// The vector kernels must leave the tile buffers exactly as the scalar int64
// loop does: same coverage (fill rule), depth, triangle ids and barycentrics.
TEST_CASE("every ISA's rasterizer gives bit-identical tile buffers to the scalar loop") {
    constexpr int kTile = 64;
    std::mt19937 rng(1234);
    std::uniform_real_distribution<float> depth(0.0f, 1.0f);
    // Triangles from sub-pixel slivers to ones larger than the tile, some
    // snapped to pixel centres so that fill-rule ties happen, placed so that
    // they straddle the tile's edges (the tile sits at (64, 64) in a 256² image).
    std::vector<raster::RasterTriangle> triangles;
    while (triangles.size() < 3000) {
        const float size = std::array<float, 4>{2.0f, 6.0f, 20.0f, 90.0f}[triangles.size() % 4];
        std::uniform_real_distribution<float> centre(40.0f, 150.0f), offset(-size, size);
        const float cx = centre(rng), cy = centre(rng);
        auto corner = [&] {
            glm::vec2 p{cx + offset(rng), cy + offset(rng)};
            if (triangles.size() % 3 == 0) p = glm::floor(p) + 0.5f;  // on pixel centres
            return p;
        };
        const glm::vec2 a = corner(), b = corner(), c = corner();
        const int image = 256;
        auto t = test::screen_triangle(a, b, c, image, {depth(rng), depth(rng), depth(rng)});
        if (t) triangles.push_back(*t);
    }
    const raster::TileBuffers reference = check_isas_match_scalar(triangles, {64, 64, 64 + kTile, 64 + kTile});
    int covered = 0;
    for (std::size_t p = 0; p < std::size_t(kTile) * kTile; ++p) covered += reference.covered(p);
    CHECK(covered > kTile * kTile / 2);
}

// Big boxes go through the block hierarchy (whole blocks rejected, accepted
// without edge tests, or tested per pixel; barycentric numerators past int32
// in double; blocks crossed by very long edges in the int64 loop). A block
// wrongly accepted or rejected changes coverage or counts, and a barycentric
// rounded differently from the scalar loop's float(int64) changes its bits.
TEST_CASE("block hierarchy: huge triangles, slivers and ties on block borders match the scalar loop") {
    // A 16384² image: edges thousands of pixels long, edge values far past int32.
    constexpr int kImage = 16384;
    std::mt19937 rng(98765);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int tile_side = 8; tile_side <= 128; tile_side *= 2) {
        CAPTURE(tile_side);
        // Tiles sit on their own grid, as the renderer's do.
        const int x0 = 8192 + 3 * tile_side, y0 = 8192 + 5 * tile_side;
        const raster::TileRect tile{x0, y0, x0 + tile_side, y0 + tile_side};
        auto in_tile = [&](float margin) {
            return glm::vec2{float(x0) - margin + unit(rng) * (tile_side + 2 * margin),
                             float(y0) - margin + unit(rng) * (tile_side + 2 * margin)};
        };
        auto on_centre = [](glm::vec2 p) { return glm::floor(p) + 0.5f; };
        std::vector<raster::RasterTriangle> triangles;
        int kind = 0;
        while (triangles.size() < 1500) {
            glm::vec2 a, b, c;
            switch (kind++ % 5) {
                case 0:
                case 1: {  // large to huge (radius up to 6000 px) around a point near the tile
                    const float radius = std::array<float, 4>{40.0f, 300.0f, 2000.0f, 6000.0f}[kind / 5 % 4];
                    const glm::vec2 p = in_tile(16.0f);
                    auto corner = [&] { return p + radius * glm::vec2{unit(rng) * 2 - 1, unit(rng) * 2 - 1}; };
                    a = corner(), b = corner(), c = corner();
                    if (kind % 3 == 0) a = on_centre(a), b = on_centre(b), c = on_centre(c);
                    break;
                }
                case 2: {  // a sliver up to 0.5-3 px thick, hundreds to thousands of pixels long
                    const glm::vec2 p = in_tile(4.0f);
                    const float angle = unit(rng) * 6.2831853f, length = 100.0f + unit(rng) * 3000.0f;
                    const glm::vec2 along{std::cos(angle), std::sin(angle)}, across{-along.y, along.x};
                    a = p - along * length, b = p + along * length;
                    c = p + along * (length * (unit(rng) * 2 - 1)) + across * (0.5f + unit(rng) * 2.5f);
                    break;
                }
                case 3: {  // a quad split along its diagonal, corners on pixel centres on block borders:
                           // shared edges and axis-aligned edges through centres at block borders tie
                    const int step = 8 * (1 + int(unit(rng) * 4));
                    const glm::vec2 p{float(x0 + 16 * int(unit(rng) * 4) - 16) + 0.5f,
                                      float(y0 + 16 * int(unit(rng) * 4) - 16) + 0.5f};
                    const glm::vec2 q = p + glm::vec2{float(step * (1 + int(unit(rng) * 8))),
                                                      float(step * (1 + int(unit(rng) * 8)))};
                    if (kind % 2) {
                        a = p, b = {q.x, p.y}, c = q;
                    } else {
                        a = p, b = q, c = {p.x, q.y};
                    }
                    break;
                }
                default: {  // huge, with one corner exactly on a pixel centre in the tile and edges at 45°
                    const glm::vec2 p = on_centre(in_tile(0.0f));
                    const float r = float(int(50 + unit(rng) * 3000));
                    a = p, b = p + glm::vec2{r, r}, c = p + glm::vec2{-r, r};
                    if (kind % 2) b.y = -b.y + 2 * p.y, c.y = -c.y + 2 * p.y;
                    break;
                }
            }
            auto t = test::screen_triangle(a, b, c, kImage, {unit(rng), unit(rng), unit(rng)});
            if (t) triangles.push_back(*t);
        }
        const raster::TileBuffers reference = check_isas_match_scalar(triangles, tile);
        int covered = 0;
        for (std::size_t p = 0; p < std::size_t(tile_side) * tile_side; ++p) covered += reference.covered(p);
        CHECK(covered == tile_side * tile_side);
        // The test means something only if many triangles cover the tile with
        // barycentric numerators past int32: count those covering its centre so.
        const std::int64_t cx = std::int64_t(x0 + tile_side / 2) * 256 + 128, cy = std::int64_t(y0 + tile_side / 2) * 256 + 128;
        int past_int32 = 0;
        for (const raster::RasterTriangle& t : triangles) {
            const std::int64_t e0 = raster::edge_function(t.x[1], t.y[1], t.x[2], t.y[2], cx, cy);
            const std::int64_t e1 = raster::edge_function(t.x[2], t.y[2], t.x[0], t.y[0], cx, cy);
            const std::int64_t e2 = raster::edge_function(t.x[0], t.y[0], t.x[1], t.y[1], cx, cy);
            past_int32 += e0 > 0 && e1 > 0 && e2 > 0 && std::max(e1, e2) > (std::int64_t(1) << 31);
        }
        CHECK(past_int32 > 50);
    }
}

using test::fixed_triangle;

// Boxes at most 4 pixels wide go to the stamp kernel (4 × 1, 4 × 2 or 4 × 4
// pixels per vector by ISA): its lanes past the box's right end and rows
// past its bottom read and write back tile memory, so boxes at the tile's
// right and bottom edges matter, as do edges through pixel centres (the
// top-left rule decides), horizontal and vertical edges, tall slivers (many
// stamps) and depth ties between triangles.
TEST_CASE("tiny triangles: the stamp kernel matches the scalar loop, ties and tile borders included") {
    std::mt19937 rng(4242);
    std::uniform_int_distribution<int> subpixel(0, 255), coin(0, 3);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int tile_side : {8, 16, 32, 64}) {
        CAPTURE(tile_side);
        const int image = 4 * tile_side, x0 = tile_side, y0 = 2 * tile_side;
        const raster::TileRect tile{x0, y0, x0 + tile_side, y0 + tile_side};
        std::uniform_int_distribution<int> pixel(x0 - 3, x0 + tile_side + 1);
        std::vector<raster::RasterTriangle> triangles;
        int narrow = 0;
        for (int kind = 0; triangles.size() < 6000; ++kind) {
            // An anchor pixel in or just outside the tile, often against its right or bottom edge.
            glm::ivec2 anchor{pixel(rng), pixel(rng) + (y0 - x0)};
            if (kind % 4 == 1) anchor.x = x0 + tile_side - 1 - coin(rng);
            if (kind % 4 == 2) anchor.y = y0 + tile_side - 1 - coin(rng);
            // Corners within a box up to 4 px wide and 1-12 px tall; on pixel centres
            // (128 + 256 k) a third of the time, on pixel corners sometimes.
            const int tall = kind % 5 == 0 ? 12 : 4;
            std::uniform_int_distribution<int> dx(-256, 3 * 256), dy(-256, tall * 256 - 256);
            auto corner = [&] {
                glm::ivec2 p{anchor.x * 256 + dx(rng), anchor.y * 256 + dy(rng)};
                if (kind % 3 == 0) p = p / 256 * 256 + 128;
                else if (kind % 7 == 0) p = p / 256 * 256;
                return p;
            };
            std::array<glm::ivec2, 3> p{corner(), corner(), corner()};
            if (kind % 6 == 4) p[1].y = p[0].y;  // a horizontal edge (top or bottom)
            if (kind % 6 == 5) p[1].x = p[0].x;  // a vertical edge (left or right)
            // Depth: a plane, or one shared value so that later triangles tie with earlier ones.
            const std::array<float, 3> depth =
                kind % 4 == 3 ? std::array<float, 3>{0.5f, 0.5f, 0.5f} : std::array<float, 3>{unit(rng), unit(rng), unit(rng)};
            const auto t = fixed_triangle(p, image, depth);
            if (!t) continue;
            triangles.push_back(*t);
            narrow += t->px_max - t->px_min < raster::kStampWidth;
        }
        const raster::TileBuffers reference = check_isas_match_scalar(triangles, tile);
        int covered = 0;
        for (std::size_t p = 0; p < std::size_t(tile_side) * tile_side; ++p) covered += reference.covered(p);
        CHECK(covered > tile_side * tile_side / 2);
        CHECK(narrow > 4000);  // most of them take the stamp
    }
}

// Tiny triangles (corners within 16 px of each other) up to 16 px wide take
// 8- and 16-wide stamps (a row per AVX2 vector, two rows per AVX-512 one; 16
// px as two AVX2 or four SSE vectors across): their lanes reach up to 15
// pixels past the box's first column, into the next row or the buffers'
// padding at the tile's right edge, so boxes against the tile's right and
// bottom edges matter; corners as far apart as a tiny triangle allows give the
// largest edge values the int32 setup meets; corners on pixel centres and
// axis-aligned edges give top-left-rule ties; a shared depth gives depth ties.
TEST_CASE("tiny triangles up to 16 px wide: 8- and 16-wide stamps match the scalar loop") {
    std::mt19937 rng(8086);
    std::uniform_int_distribution<int> coin(0, 3);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    constexpr int kSpan = raster::kTinySpan - 1;  // the farthest apart a tiny triangle's corners may be
    for (int tile_side : {8, 16, 32, 64}) {
        CAPTURE(tile_side);
        const int image = 4 * tile_side, x0 = tile_side, y0 = 2 * tile_side;
        const raster::TileRect tile{x0, y0, x0 + tile_side, y0 + tile_side};
        std::uniform_int_distribution<int> pixel(x0 - 8, x0 + tile_side + 1);
        std::vector<raster::RasterTriangle> triangles;
        int width_5_to_8 = 0, width_9_to_16 = 0, widest = 0;
        for (int kind = 0; triangles.size() < 6000; ++kind) {
            // An anchor in or just outside the tile, often a box's width from its right or bottom edge.
            glm::ivec2 anchor{pixel(rng), pixel(rng) + (y0 - x0)};
            const int wide = 4 + kind % 13;  // box widths 4 to 16
            if (kind % 4 == 1) anchor.x = x0 + tile_side - wide + coin(rng);
            if (kind % 4 == 2) anchor.y = y0 + tile_side - 4 + coin(rng);
            std::uniform_int_distribution<int> dx(0, std::min(wide * 256, kSpan)), dy(0, kind % 5 == 0 ? kSpan : 6 * 256);
            auto corner = [&] {
                glm::ivec2 p{anchor.x * 256 + dx(rng), anchor.y * 256 + dy(rng)};
                if (kind % 3 == 0) p = p / 256 * 256 + 128;  // on pixel centres
                else if (kind % 7 == 0) p = p / 256 * 256;   // on pixel corners
                return p;
            };
            std::array<glm::ivec2, 3> p{corner(), corner(), corner()};
            if (kind % 6 == 4) p[1].y = p[0].y;  // a horizontal edge (top or bottom)
            if (kind % 6 == 5) p[1].x = p[0].x;  // a vertical edge (left or right)
            if (kind % 11 == 0) {                // the widest span a tiny triangle has, both ways
                p[1] = p[0] + glm::ivec2{kSpan, kind % 2 ? kSpan / 3 : 0};
                p[2] = p[0] + glm::ivec2{kind % 4 < 2 ? kSpan / 2 : 0, kSpan};
            }
            const std::array<float, 3> depth =
                kind % 4 == 3 ? std::array<float, 3>{0.5f, 0.5f, 0.5f} : std::array<float, 3>{unit(rng), unit(rng), unit(rng)};
            const auto t = fixed_triangle(p, image, depth);
            if (!t) continue;
            triangles.push_back(*t);
            const int width = std::min<int>(t->px_max + 1, tile.x1) - std::max<int>(t->px_min, tile.x0);
            width_5_to_8 += width >= 5 && width <= 8;
            width_9_to_16 += width >= 9;
            widest = std::max(widest, t->px_max - t->px_min + 1);
        }
        const raster::TileBuffers reference = check_isas_match_scalar(triangles, tile);
        int covered = 0;
        for (std::size_t p = 0; p < std::size_t(tile_side) * tile_side; ++p) covered += reference.covered(p);
        CHECK(covered > tile_side * tile_side / 2);
        CHECK(width_5_to_8 > 1000);  // the 8-wide stamps
        if (tile_side >= 16) CHECK(width_9_to_16 > 500);  // and the 16-wide ones
        CHECK(widest == 16);  // the widest box a tiny triangle has
    }
}

// A mesh of tiny triangles as the demo's spheres make them (~1.3 px²): a
// jittered grid of quads, two triangles each, every edge shared, so every
// pixel centre on an edge belongs to exactly one of its two triangles.
TEST_CASE("a mesh of tiny triangles sharing edges: every ISA matches the scalar loop") {
    constexpr int kTile = 32, kImage = 128;
    std::mt19937 rng(77);
    // Grid steps in fixed point: 1.25, 1.5, 2 px (4-wide stamps), 5 px (8-wide), 11 px (16-wide).
    for (int pitch : {320, 384, 512, 1280, 2816}) {
        CAPTURE(pitch);
        const int n = 40 * 256 / pitch + 1;  // past the tile's far side
        std::size_t first_layer = 0;
        const std::vector<raster::RasterTriangle> triangles = test::jittered_mesh(rng, pitch, n, kImage, 1, first_layer);
        const raster::TileBuffers reference = check_isas_match_scalar(triangles, {32, 32, 32 + kTile, 32 + kTile});
        int covered = 0;
        for (std::size_t p = 0; p < std::size_t(kTile) * kTile; ++p) covered += reference.covered(p);
        CHECK(covered == kTile * kTile);  // the mesh is watertight over the tile
    }
}
