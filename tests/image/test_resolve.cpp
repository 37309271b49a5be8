#include <doctest/doctest.h>

#include <bit>
#include <cmath>
#include <random>
#include <vector>

#include "image/resolve.hpp"
#include "simd/lane_padding.hpp"

using namespace tessera;
using simd::Isa;

namespace {

// A tile's shaded fragments as the renderer hands them to resolve: three
// padded channel arrays (resolve overwrites them, so each run gets a copy).
struct Shaded {
    std::vector<float> r, g, b;
    explicit Shaded(std::size_t count) : r(simd::padded_count(count)), g(r.size()), b(r.size()) {}
    shade::RadianceOutputs outputs() { return {r.data(), g.data(), b.data()}; }
};

// Radiance as a frame has it, with a few values on the 8-bit steps' edges,
// zeros and out-of-range values mixed in.
float random_radiance(std::mt19937& rng) {
    std::uniform_real_distribution<float> exponent(-7.0f, 3.0f), unit(0.0f, 1.0f);
    const float u = unit(rng);
    if (u < 0.05f) return 0.0f;
    if (u < 0.08f) return -unit(rng);
    if (u < 0.3f) {  // next to a step
        const double l = std::pow((std::floor(unit(rng) * 255.0f) + 0.5) / 255.0, 2.2);
        float c = float(l / (1.0 - l));
        for (int i = int(unit(rng) * 4); i > 0; --i) c = std::nextafter(c, u < 0.2f ? INFINITY : -INFINITY);
        return c;
    }
    return std::pow(10.0f, exponent(rng));
}

std::uint8_t channel(const RenderedImage& image, int x, int y, int c) {
    return image.display[3 * (std::size_t(y) * image.width + x) + c];
}

}  // namespace

// resolve_tile writes each covered pixel's reference 8-bit colour, and the
// clear colour elsewhere, whatever the ISA; the radiance image gets each
// covered pixel's shaded value and the background's elsewhere, bit for bit;
// pixels outside the tile stay put.
TEST_CASE("resolve_tile: every ISA writes the reference's 8-bit colours and the shaded radiance") {
    constexpr int kSide = 32;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const image::ClearValues clear = image::clear_values(glm::vec3(0.1f, 0.2f, 0.3f));
    // A whole tile (rows of whole vectors), and one clipped at the image's edge (rows ending mid-vector).
    for (const raster::TileRect rect : {raster::TileRect{kSide, 2 * kSide, 2 * kSide, 3 * kSide},
                                        raster::TileRect{kSide, 2 * kSide, 2 * kSide - 3, 3 * kSide - 7}})
    for (float coverage : {0.0f, 0.3f, 0.9f, 1.0f}) {
        CAPTURE(coverage);
        CAPTURE(rect.width());
        raster::TileBuffers tile;
        tile.reset(kSide);
        std::size_t count = 0;
        for (int y = 0; y < rect.height(); ++y)
            for (int x = 0; x < rect.width(); ++x)
                if (unit(rng) < coverage) tile.depth[std::size_t(y) * kSide + x] = 0.5f, ++count;
        Shaded input(count);
        for (std::size_t k = 0; k < count; ++k)
            input.r[k] = random_radiance(rng), input.g[k] = random_radiance(rng), input.b[k] = random_radiance(rng);
        for (Isa isa : {Isa::scalar, Isa::sse4, Isa::avx2, Isa::avx512}) {
            if (!simd::isa_supported(isa)) continue;
            CAPTURE(simd::isa_name(isa));
            RenderedImage image;
            image.width = rect.x1 + 5, image.height = rect.y1 + 2;
            image.display.assign(3 * std::size_t(image.width) * image.height, 7);
            image.radiance.assign(3 * std::size_t(image.width) * image.height, -7.0f);
            Shaded shaded = input;
            image::resolve_tile(tile, rect, count, shaded.outputs(), clear, isa, image);
            int wrong = 0, wrong_radiance = 0, outside_touched = 0;
            std::size_t k = 0;
            for (int y = 0; y < image.height; ++y)
                for (int x = 0; x < image.width; ++x) {
                    const bool inside = x >= rect.x0 && x < rect.x1 && y >= rect.y0 && y < rect.y1;
                    const std::size_t i = 3 * (std::size_t(y) * image.width + x);
                    if (!inside) {
                        for (int c = 0; c < 3; ++c)
                            outside_touched += channel(image, x, y, c) != 7 || image.radiance[i + c] != -7.0f;
                        continue;
                    }
                    const bool covered = tile.covered(std::size_t(y - rect.y0) * kSide + (x - rect.x0));
                    for (int c = 0; c < 3; ++c) {
                        const float* plane = c == 0 ? input.r.data() : c == 1 ? input.g.data() : input.b.data();
                        const std::uint8_t expected =
                            covered ? image::unorm8_from_radiance_reference(plane[k]) : clear.display[c];
                        wrong += channel(image, x, y, c) != expected;
                        const float radiance = covered ? plane[k] : clear.radiance[c];
                        wrong_radiance += std::bit_cast<std::uint32_t>(image.radiance[i + c]) !=
                                          std::bit_cast<std::uint32_t>(radiance);
                    }
                    k += covered;
                }
            CHECK(wrong == 0);
            CHECK(wrong_radiance == 0);
            CHECK(outside_touched == 0);
        }
    }
}

// With 4× MSAA a pixel is the rounded mean of its samples' 8-bit values.
TEST_CASE("resolve_tile_msaa: every ISA averages the samples' reference 8-bit colours") {
    constexpr int kSide = 16, n = raster::kMsaaSamples;
    const raster::TileRect rect{0, 0, kSide, kSide};
    std::mt19937 rng(6);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const image::ClearValues clear = image::clear_values(glm::vec3(0.5f, 0.0f, 1.0f));
    raster::TileSamples samples;
    samples.reset(kSide);
    const std::size_t count = 300;
    std::uniform_int_distribution<std::int32_t> fragment(-1, std::int32_t(count) - 1);
    for (std::int32_t& f : samples.fragment) f = unit(rng) < 0.3f ? -1 : fragment(rng);
    Shaded input(count);
    for (std::size_t k = 0; k < count; ++k)
        input.r[k] = random_radiance(rng), input.g[k] = random_radiance(rng), input.b[k] = random_radiance(rng);
    for (Isa isa : {Isa::scalar, Isa::sse4, Isa::avx2, Isa::avx512}) {
        if (!simd::isa_supported(isa)) continue;
        CAPTURE(simd::isa_name(isa));
        RenderedImage image;
        image.width = image.height = kSide;
        image.display.assign(3 * kSide * kSide, 0);
        Shaded shaded = input;
        image::resolve_tile_msaa(samples, rect, count, shaded.outputs(), clear, isa, image);
        int wrong = 0;
        for (int y = 0; y < kSide; ++y)
            for (int x = 0; x < kSide; ++x)
                for (int c = 0; c < 3; ++c) {
                    const float* plane = c == 0 ? input.r.data() : c == 1 ? input.g.data() : input.b.data();
                    unsigned sum = 0;
                    for (int s = 0; s < n; ++s) {
                        const std::int32_t f = samples.fragment[std::size_t(n) * (y * kSide + x) + s];
                        sum += f >= 0 ? image::unorm8_from_radiance_reference(plane[f]) : clear.display[c];
                    }
                    wrong += channel(image, x, y, c) != (sum + 2) / 4;
                }
        CHECK(wrong == 0);
    }
}
