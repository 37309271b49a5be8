#include <doctest/doctest.h>

#include <array>
#include <vector>

#include "image/resolve.hpp"
#include "raster/msaa/msaa.hpp"
#include "raster_test_util.hpp"

using namespace tessera;

namespace {

constexpr int kSize = 4;  // a 4×4 image, one tile

std::optional<raster::RasterTriangle> msaa_triangle(glm::vec2 a, glm::vec2 b, glm::vec2 c) {
    return raster::setup_triangle({kSize, kSize},
                                  {test::clip_for_screen(a.x, a.y, 0.5f, 1, kSize, kSize),
                                   test::clip_for_screen(b.x, b.y, 0.5f, 1, kSize, kSize),
                                   test::clip_for_screen(c.x, c.y, 0.5f, 1, kSize, kSize)},
                                  {0, 1, 2}, raster::kMsaaSamples);
}

struct MsaaTile {
    raster::TileSamples samples;
    raster::TileFragments fragments;
    explicit MsaaTile(const raster::RasterTriangle& t) {
        samples.reset(kSize);
        fragments.reserve(kSize);
        raster::RasterCounters counters;
        raster::rasterize_triangle_msaa(t, 7, {0, 0, kSize, kSize}, samples, counters);
        raster::collect_fragments(simd::best_supported_isa(), {0, 0, kSize, kSize}, samples,
                                  [&](std::uint32_t) -> const raster::RasterTriangle& { return t; }, fragments);
    }
    bool covered(int x, int y, int s) const { return samples.depth[4 * (y * kSize + x) + s] < 1.0f; }
};

}  // namespace

// Image space, y down from the pixel's top: s0 (0.375, 0.875), s1 (0.875, 0.625),
// s2 (0.125, 0.375), s3 (0.625, 0.125) — GL's pattern, which GL gives y up from
// the pixel's bottom. A tiny triangle around one of them covers that sample of
// pixel (1, 2) and nothing else, and no pixel centre.
TEST_CASE("4x MSAA: a tiny triangle around one sample position covers exactly that sample") {
    const std::array<glm::vec2, 4> position = {glm::vec2(0.375f, 0.875f), glm::vec2(0.875f, 0.625f),
                                               glm::vec2(0.125f, 0.375f), glm::vec2(0.625f, 0.125f)};
    for (int target = 0; target < 4; ++target) {
        CAPTURE(target);
        const glm::vec2 p = glm::vec2(1, 2) + position[target];
        const glm::vec2 a = p + glm::vec2(-0.05f, -0.05f), b = p + glm::vec2(0.06f, -0.05f), c = p + glm::vec2(0, 0.06f);
        CHECK_FALSE(test::screen_triangle(a, b, c, kSize).has_value());  // one sample per pixel: culled at setup
        const auto t = msaa_triangle(a, b, c);
        REQUIRE(t.has_value());
        const MsaaTile tile(*t);
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x)
                for (int s = 0; s < 4; ++s) CHECK(tile.covered(x, y, s) == (x == 1 && y == 2 && s == target));
        // One fragment, shaded at the pixel centre although the triangle misses it
        // (extrapolated, as GL interpolates varyings not qualified centroid).
        REQUIRE(tile.fragments.count == 1);
        CHECK(tile.fragments.x[0] == 1);
        CHECK(tile.fragments.y[0] == 2);
        const auto at_centre = raster::screen_barycentrics(*t, 256 + 128, 2 * 256 + 128);
        CHECK(tile.fragments.lambda1[0] == at_centre[0]);
        CHECK(tile.fragments.lambda2[0] == at_centre[1]);
        const auto at_sample = raster::screen_barycentrics(*t, std::int64_t(p.x * 256), std::int64_t(p.y * 256));
        CHECK(at_sample != at_centre);  // so the checks above tell the two apart

    }
}

TEST_CASE("4x MSAA: pixels fully inside a triangle shade at their centre, as without MSAA") {
    const glm::vec2 a(0.2f, 0.1f), b(3.9f, 0.7f), c(1.1f, 3.95f);
    const auto one = test::screen_triangle(a, b, c, kSize);
    const auto four = msaa_triangle(a, b, c);
    REQUIRE(one.has_value());
    REQUIRE(four.has_value());
    raster::TileBuffers buffers;
    buffers.reset(kSize);
    raster::RasterCounters counters;
    raster::rasterize_triangle(*one, 7, {0, 0, kSize, kSize}, buffers, counters);
    const MsaaTile tile(*four);
    int full = 0;
    for (std::size_t k = 0; k < tile.fragments.count; ++k) {
        const int x = tile.fragments.x[k], y = tile.fragments.y[k];
        const std::size_t pixel = std::size_t(y) * kSize + x;
        if (!buffers.covered(pixel)) continue;  // shaded at a sample instead
        CAPTURE(x);
        CAPTURE(y);
        full += tile.covered(x, y, 0) && tile.covered(x, y, 1) && tile.covered(x, y, 2) && tile.covered(x, y, 3);
        CHECK(tile.fragments.lambda1[k] == buffers.lambda1[pixel]);
        CHECK(tile.fragments.lambda2[k] == buffers.lambda2[pixel]);
    }
    CHECK(full >= 2);
}

// A white triangle on black whose vertical edge x = 1.5 halves pixel column 1:
// samples 0 and 2 (x = 1.375, 1.125) are in, 1 and 3 (1.875, 1.625) out.
TEST_CASE("4x MSAA: a pixel half covered by an edge resolves to the mean of its samples") {
    const auto t = msaa_triangle({1.5f, -8.0f}, {1.5f, 12.0f}, {-12.0f, 2.0f});
    REQUIRE(t.has_value());
    MsaaTile tile(*t);
    for (int y = 0; y < kSize; ++y) {
        CHECK((tile.covered(0, y, 0) && tile.covered(0, y, 1) && tile.covered(0, y, 2) && tile.covered(0, y, 3)));
        CHECK((tile.covered(1, y, 0) && !tile.covered(1, y, 1) && tile.covered(1, y, 2) && !tile.covered(1, y, 3)));
        CHECK_FALSE((tile.covered(2, y, 0) || tile.covered(2, y, 1) || tile.covered(2, y, 2) || tile.covered(2, y, 3)));
    }
    REQUIRE(tile.fragments.count == 2 * kSize);
    // Every fragment shaded with a radiance that tonemaps to display white.
    constexpr float kWhite = 1e7f;
    std::vector<float> r(64, kWhite), g(64, kWhite), b(64, kWhite);
    const image::ClearValues black = image::clear_values(glm::vec3(0.0f));
    RenderedImage image;
    image.width = image.height = kSize;
    image.display.assign(3 * kSize * kSize, 99);
    image.radiance.assign(3 * kSize * kSize, -1.0f);
    image::resolve_tile_msaa(tile.samples, {0, 0, kSize, kSize}, tile.fragments.count, {r.data(), g.data(), b.data()},
                             black, simd::Isa::scalar, image);
    for (int y = 0; y < kSize; ++y) {
        const std::size_t row = 3 * std::size_t(y) * kSize;
        CHECK(int(image.display[row + 0]) == 255);
        CHECK(int(image.display[row + 3]) == 128);  // (255 + 0 + 255 + 0 + 2) / 4: halves round up
        CHECK(int(image.display[row + 6]) == 0);
        CHECK(image.radiance[row + 0] == kWhite);
        CHECK(image.radiance[row + 3] == kWhite / 2);
        CHECK(image.radiance[row + 6] == 0.0f);
    }
}
