// The blend pass's rasterizer: against the opaque depth, no depth write, every
// passing fragment kept in order, with the opaque rasterizer's coverage and λ.
#include <doctest/doctest.h>

#include "raster/blend_raster.hpp"
#include "raster/msaa/msaa.hpp"
#include "raster/tile_rasterizer.hpp"

using namespace tessera;
using namespace tessera::raster;

namespace {

RasterTriangle triangle_at_depth(float depth) {
    const geometry::Viewport viewport{32, 32};
    const auto at = [](float x, float y) { return glm::vec4((x / 32) * 2 - 1, 1 - (y / 32) * 2, 0, 1); };
    auto t = setup_triangle(viewport, {at(2.3f, 1.7f), at(29.1f, 6.2f), at(9.4f, 27.8f)}, {0, 1, 2});
    REQUIRE(t);
    t->depth = {depth, depth, depth};
    return *t;
}

const TileRect kTile{0, 0, 32, 32};

}  // namespace

TEST_CASE("blend raster: the opaque rasterizer's pixels and barycentrics, behind-opaque fragments dropped") {
    const RasterTriangle t = triangle_at_depth(0.5f);
    TileBuffers opaque;
    opaque.reset(32);
    RasterCounters counters;
    TileBuffers drawn;
    drawn.reset(32);
    rasterize_triangle(t, 7, kTile, drawn, counters);
    BlendFragments fragments;
    fragments.reserve(32, 1);
    rasterize_blended(t, 7, kTile, opaque, fragments, counters);
    std::size_t k = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            const std::size_t p = std::size_t(y) * 32 + x;
            if (!drawn.covered(p)) continue;
            REQUIRE(k < fragments.count());
            CHECK(fragments.fragments.x[k] == x);
            CHECK(fragments.fragments.y[k] == y);
            CHECK(fragments.fragments.lambda1[k] == drawn.lambda1[p]);
            CHECK(fragments.fragments.lambda2[k] == drawn.lambda2[p]);
            CHECK(fragments.sample_mask[k] == 1);
            ++k;
        }
    CHECK(k == fragments.count());
    CHECK(k > 100);
    CHECK(opaque.depth[16 * 32 + 12] == 1.0f);  // no depth written
    // A second triangle's fragments follow the first's; behind the opaque depth none come.
    for (std::size_t p = 0; p < 32 * 32; ++p) opaque.depth[p] = p < 16 * 32 ? 0.25f : 1.0f;  // top half nearer
    const std::size_t before = fragments.count();
    rasterize_blended(t, 8, kTile, opaque, fragments, counters);
    for (std::size_t i = before; i < fragments.count(); ++i) {
        CHECK(fragments.fragments.y[i] >= 16);
        CHECK(fragments.fragments.triangle[i] == 8);
    }
    CHECK(fragments.count() > before);
    CHECK(max_blend_fragments(t, kTile) >= k);
}

TEST_CASE("blend raster, 4x MSAA: one fragment per pixel, a mask of the samples in front of the opaque depth") {
    const RasterTriangle t = triangle_at_depth(0.5f);
    TileSamples opaque;
    opaque.reset(32);
    TileSamples drawn;
    drawn.reset(32);
    RasterCounters counters;
    rasterize_triangle_msaa(t, 3, kTile, drawn, counters);
    for (std::size_t i = 0; i < opaque.depth.size(); i += 2) opaque.depth[i] = 0.1f;  // samples 0 and 2 hidden
    BlendFragments fragments;
    fragments.reserve(32, kMsaaSamples);
    rasterize_blended(t, 3, kTile, opaque, fragments, counters);
    std::size_t k = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            std::uint8_t expected = 0;
            for (int s = 0; s < kMsaaSamples; ++s)
                if (drawn.depth[kMsaaSamples * (std::size_t(y) * 32 + x) + s] < 1.0f && s % 2 == 1)
                    expected |= std::uint8_t(1u << s);
            if (expected == 0) continue;
            REQUIRE(k < fragments.count());
            CHECK(fragments.fragments.x[k] == x);
            CHECK(fragments.fragments.y[k] == y);
            CHECK(fragments.sample_mask[k] == expected);
            ++k;
        }
    CHECK(k == fragments.count());
    CHECK(k > 100);
}
