#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "image/resolve.hpp"
#include "simd/lane_padding.hpp"

using namespace tessera;
using simd::Isa;

namespace {

struct Shaded {
    std::vector<float> r, g, b;
    explicit Shaded(std::size_t count) : r(simd::padded_count(count)), g(r.size()), b(r.size()) {}
    shade::RadianceOutputs outputs() { return {r.data(), g.data(), b.data()}; }
};

// Radiance over the whole tonemap range, with zeros, negatives and values
// whose sums round (so that summing in another order would show).
float random_radiance(std::mt19937& rng) {
    std::uniform_real_distribution<float> exponent(-7.0f, 4.0f), unit(0.0f, 1.0f);
    const float u = unit(rng);
    if (u < 0.05f) return 0.0f;
    if (u < 0.1f) return -unit(rng);
    return std::pow(10.0f, exponent(rng)) * (1.0f + unit(rng));
}

}  // namespace

// The vector resolve of a multisampled tile writes the scalar loop's radiance
// (bit for bit: the same pairwise sums) and display bytes, for tiles of every
// size, whole or cut by the image's edge (rows ending mid-vector), with
// samples of the background, of one fragment, or mixed; nothing outside the
// tile is written.
TEST_CASE("resolve_tile_msaa: every ISA writes the scalar loop's radiance and display, bit for bit") {
    constexpr int n = raster::kMsaaSamples;
    std::mt19937 rng(13);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const image::ClearValues clear = image::clear_values(glm::vec3(0.2f, 0.6f, 0.9f));
    int compared = 0;
    for (const bool runs : {false, true}) {
        for (int side = raster::kMinTileSize; side <= raster::kMaxTileSize; side *= 2) {
            for (const glm::ivec2 cut : {glm::ivec2(0, 0), glm::ivec2(1, 3), glm::ivec2(7, 1), glm::ivec2(side - 1, 0)}) {
                const raster::TileRect rect{side, 2 * side, 2 * side - cut.x, 3 * side - cut.y};
                CAPTURE(side);
                CAPTURE(rect.width());
                CAPTURE(rect.height());
                CAPTURE(runs);
                raster::TileSamples samples;
                samples.reset(side);
                // Pixels fully background, fully one fragment (interior), or mixed (edges).
                std::int32_t count = 0;
                for (int p = 0; p < side * side; ++p) {
                    std::int32_t* f = &samples.fragment[std::size_t(n) * p];
                    // With runs, runs of 8 pixels are background only (as beside
                    // an object), then 8 interior ones, then 8 mixed, at every
                    // offset to the vectors' 8 pixels.
                    const int x = p % side, y = p / side;
                    const int run = runs ? ((x + y) / 8 + y) % 3 : 2;
                    const float kind = run == 0 ? 0.0f : run == 1 ? 0.5f : unit(rng);
                    if (kind < 0.2f) {
                        for (int s = 0; s < n; ++s) f[s] = -1;
                    } else if (kind < 0.6f) {
                        for (int s = 0; s < n; ++s) f[s] = count;
                        ++count;
                    } else {
                        for (int s = 0; s < n; ++s) f[s] = unit(rng) < 0.25f ? -1 : count + int(unit(rng) * 2);
                        count += 2;
                    }
                }
                Shaded input(std::size_t(count) + 2);
                for (std::size_t k = 0; k < input.r.size(); ++k)
                    input.r[k] = random_radiance(rng), input.g[k] = random_radiance(rng), input.b[k] = random_radiance(rng);
                auto resolve = [&](Isa isa) {
                    RenderedImage image;
                    image.width = rect.x1 + 3, image.height = rect.y1 + 2;
                    image.display.assign(3 * std::size_t(image.width) * image.height, 7);
                    image.radiance.assign(3 * std::size_t(image.width) * image.height, -7.0f);
                    Shaded shaded = input;
                    image::resolve_tile_msaa(samples, rect, std::size_t(count) + 2, shaded.outputs(), clear, isa, image);
                    return image;
                };
                const RenderedImage reference = resolve(Isa::scalar);
                for (Isa isa : {Isa::sse4, Isa::avx2, Isa::avx512}) {
                    CAPTURE(simd::isa_name(isa));
                    if (!simd::isa_supported(isa)) {
                        MESSAGE("skipped: " << simd::isa_name(isa) << " is not supported by this CPU");
                        continue;
                    }
                    const RenderedImage image = resolve(isa);
                    CHECK(image.display == reference.display);
                    CHECK(std::memcmp(image.radiance.data(), reference.radiance.data(), image.radiance.size() * 4) == 0);
                    ++compared;
                }
                // The reference itself: the mean of samples' radiance, nothing outside the tile.
                int outside = 0, wrong = 0;
                for (int y = 0; y < reference.height; ++y)
                    for (int x = 0; x < reference.width; ++x) {
                        const std::size_t i = 3 * (std::size_t(y) * reference.width + x);
                        if (x < rect.x0 || x >= rect.x1 || y < rect.y0 || y >= rect.y1) {
                            outside += reference.display[i] != 7 || reference.radiance[i] != -7.0f;
                            continue;
                        }
                        const std::int32_t* f = &samples.fragment[std::size_t(n) * ((y - rect.y0) * side + (x - rect.x0))];
                        double sum = 0, magnitude = 0;  // float rounding is relative to the terms' size
                        for (int s = 0; s < n; ++s) {
                            const float v = f[s] >= 0 ? input.g[f[s]] : clear.radiance.g;
                            sum += v, magnitude += std::abs(v);
                        }
                        wrong += std::abs(reference.radiance[i + 1] - sum / n) > 1e-6 * magnitude;
                    }
                CHECK(outside == 0);
                CHECK(wrong == 0);
            }
        }
    }
    CHECK(compared > 0);
}
