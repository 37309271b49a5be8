#include <doctest/doctest.h>

#include <cstring>
#include <random>

#include "raster_test_util.hpp"

using namespace tessera;

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
        auto t = raster::setup_triangle({image, image},
                                        {test::clip_for_screen(a.x, a.y, depth(rng), 1, image, image),
                                         test::clip_for_screen(b.x, b.y, depth(rng), 1, image, image),
                                         test::clip_for_screen(c.x, c.y, depth(rng), 1, image, image)},
                                        {0, 1, 2});
        if (t) triangles.push_back(*t);
    }
    const raster::TileRect tile{64, 64, 64 + kTile, 64 + kTile};

    raster::TileBuffers reference;
    reference.reset(kTile);
    raster::RasterCounters reference_counts;
    for (std::uint32_t i = 0; i < triangles.size(); ++i)
        raster::rasterize_triangle(triangles[i], i, tile, reference, reference_counts);
    REQUIRE(reference_counts.fragments > 10000);

    for (simd::Isa isa : {simd::Isa::sse4, simd::Isa::avx2, simd::Isa::avx512}) {
        CAPTURE(simd::isa_name(isa));
        if (!simd::isa_supported(isa)) {
            MESSAGE("skipped: " << simd::isa_name(isa) << " is not supported by this CPU");
            continue;
        }
        raster::TileBuffers buffers;
        buffers.reset(kTile);
        raster::RasterCounters counts;
        for (std::uint32_t i = 0; i < triangles.size(); ++i)
            raster::rasterize_triangle(isa, triangles[i], i, tile, buffers, counts);
        CHECK(counts.fragments == reference_counts.fragments);
        CHECK(counts.depth_passed == reference_counts.depth_passed);
        int mismatches = 0;
        for (std::size_t p = 0; p < std::size_t(kTile) * kTile; ++p) {
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
