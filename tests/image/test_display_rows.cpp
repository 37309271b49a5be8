// Where the display kernels' stores meet the image: a tile row of RGB8 starts
// at any byte of a cache line, the vector loops store 8 pixels (24 bytes) at a
// time and the rows' tails pixel by pixel, and 8-pixel groups may hold no
// covered pixel at all. These tests put tiles at every alignment of their
// first byte to a cache line, at every width (rows ending mid-vector), against
// the image's right and bottom edges, with background runs of every length at
// every offset, and hold every ISA to the scalar path byte for byte, with
// nothing outside the tile written (clear_tile too).
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <vector>

#include "image/resolve.hpp"
#include "simd/lane_padding.hpp"

using namespace tessera;
using simd::Isa;

namespace {

constexpr std::uint8_t kUntouched = 7;

struct Shaded {
    std::vector<float> r, g, b;
    explicit Shaded(std::size_t count) : r(simd::padded_count(count)), g(r.size()), b(r.size()) {}
    shade::RadianceOutputs outputs() { return {r.data(), g.data(), b.data()}; }
};

// A blank image `width` × `height` whose display bytes are all kUntouched.
RenderedImage blank_image(int width, int height) {
    RenderedImage image;
    image.width = width, image.height = height;
    image.display.assign(3 * std::size_t(width) * height, kUntouched);
    return image;
}

// Display bytes outside `rect` that are not kUntouched.
int touched_outside(const RenderedImage& image, const raster::TileRect& rect) {
    int touched = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            if (x >= rect.x0 && x < rect.x1 && y >= rect.y0 && y < rect.y1) continue;
            for (int c = 0; c < 3; ++c) touched += image.display[3 * (std::size_t(y) * image.width + x) + c] != kUntouched;
        }
    return touched;
}

// The rects below: x0 from 0 to 63 (3·x0 mod 64 takes every residue a row of
// RGB8 can start at, the image's rows being 64-byte multiples when its width
// is), every width from 1 to the tile side, some touching the image's right or
// bottom edge.
struct Placement {
    raster::TileRect rect;
    int image_width, image_height;
};

std::vector<Placement> placements(int side) {
    std::vector<Placement> out;
    for (int x0 = 0; x0 < 64; ++x0) {
        const int width = 1 + (x0 * 7) % side;  // every width over the x0s (side ≤ 64)
        const int height = 1 + (x0 * 5) % side;
        const bool at_right = x0 % 3 == 0, at_bottom = x0 % 4 == 0;
        const raster::TileRect rect{x0, 2, x0 + width, 2 + height};
        out.push_back({rect, at_right ? rect.x1 : 128, at_bottom ? rect.y1 : rect.y1 + 3});
    }
    for (int width = 1; width <= side; ++width) {  // every width at two alignments, at the right edge
        out.push_back({raster::TileRect{0, 0, width, 3}, width, 4});
        out.push_back({raster::TileRect{21, 1, 21 + width, 4}, 21 + width, 4});
    }
    return out;
}

// `count` colours from HDR blacks to well past white (red and blue), and in [0, 1] (green).
Shaded random_colours(std::size_t count, std::mt19937& rng) {
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), exponent(-5.0f, 2.0f);
    Shaded shaded(count);
    for (std::size_t k = 0; k < count; ++k)
        shaded.r[k] = std::pow(10.0f, exponent(rng)), shaded.g[k] = unit(rng), shaded.b[k] = std::pow(10.0f, exponent(rng));
    return shaded;
}

// resolve(isa) of every SIMD ISA this CPU has against resolve(Isa::scalar),
// which must touch nothing outside `rect`. Returns the ISAs compared.
template <class Resolve>
int check_every_isa_as_scalar(const Resolve& resolve, const raster::TileRect& rect) {
    const RenderedImage reference = resolve(Isa::scalar);
    CHECK(touched_outside(reference, rect) == 0);
    int compared = 0;
    for (const Isa isa : {Isa::sse4, Isa::avx2, Isa::avx512}) {
        if (!simd::isa_supported(isa)) continue;
        CAPTURE(simd::isa_name(isa));
        CHECK(resolve(isa).display == reference.display);
        ++compared;
    }
    return compared;
}

}  // namespace

TEST_CASE("resolve_tile: background runs at every offset, every width and alignment, image edges: every ISA as scalar") {
    constexpr int kSide = 32;
    std::mt19937 rng(21);
    const image::ClearValues clear = image::clear_values(glm::vec3(0.25f, 0.5f, 0.75f));
    int compared = 0, background_groups = 0;
    for (const Placement& place : placements(kSide)) {
        const raster::TileRect& rect = place.rect;
        CAPTURE(rect.x0);
        CAPTURE(rect.width());
        CAPTURE(rect.height());
        CAPTURE(place.image_width);
        raster::TileBuffers tile;
        tile.reset(kSide);
        // Row y: covered but for a background run of length 1 + y % 17 starting
        // at (3·y + x0) % width (runs cross the 8-pixel groups at every offset);
        // every 5th row all background, every 7th all covered.
        std::size_t count = 0;
        for (int y = 0; y < rect.height(); ++y) {
            const int run_start = (3 * y + rect.x0) % rect.width(), run_length = 1 + y % 17;
            for (int x = 0; x < rect.width(); ++x) {
                bool covered = !(x >= run_start && x < run_start + run_length);
                if (y % 5 == 4) covered = false;
                if (y % 7 == 6) covered = true;
                if (covered) tile.depth[std::size_t(y) * kSide + x] = 0.5f, ++count;
            }
            for (int x = 0; x + 8 <= rect.width(); x += 8) {
                bool all_background = true;
                for (int i = 0; i < 8; ++i) all_background &= !tile.covered(std::size_t(y) * kSide + x + i);
                background_groups += all_background;
            }
        }
        const Shaded input = random_colours(count, rng);
        const auto resolve = [&](Isa isa) {
            RenderedImage image = blank_image(place.image_width, place.image_height);
            Shaded shaded = input;
            image::resolve_tile(tile, rect, count, shaded.outputs(), clear, isa, image);
            return image;
        };
        compared += check_every_isa_as_scalar(resolve, rect);
    }
    CHECK(background_groups > 100);  // whole 8-pixel groups of background, at many offsets
    CHECK(compared > 0);
}

TEST_CASE("clear_tile: the clear colour over exactly the tile, at every width and alignment, image edges") {
    const image::ClearValues clear = image::clear_values(glm::vec3(0.1f, 0.9f, 0.4f));
    for (const int side : {32, 64}) {
        for (const Placement& place : placements(side)) {
            const raster::TileRect& rect = place.rect;
            CAPTURE(rect.x0);
            CAPTURE(rect.width());
            CAPTURE(rect.height());
            RenderedImage image = blank_image(place.image_width, place.image_height);
            image::clear_tile(rect, clear, image);
            int wrong = 0;
            for (int y = rect.y0; y < rect.y1; ++y)
                for (int x = rect.x0; x < rect.x1; ++x)
                    for (int c = 0; c < 3; ++c)
                        wrong += image.display[3 * (std::size_t(y) * image.width + x) + c] != clear.display[c];
            CHECK(wrong == 0);
            CHECK(touched_outside(image, rect) == 0);
        }
    }
}

TEST_CASE("resolve_tile_msaa: every width and alignment, image edges: every ISA as scalar") {
    constexpr int kSide = 32, n = raster::kMsaaSamples;
    std::mt19937 rng(22);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const image::ClearValues clear = image::clear_values(glm::vec3(0.6f, 0.3f, 0.1f));
    int compared = 0;
    for (const Placement& place : placements(kSide)) {
        const raster::TileRect& rect = place.rect;
        CAPTURE(rect.x0);
        CAPTURE(rect.width());
        CAPTURE(rect.height());
        raster::TileSamples samples;
        samples.reset(kSide);
        // Background runs as above (all four samples -1), the rest one fragment
        // per pixel or, every third pixel, mixed samples.
        std::int32_t count = 0;
        for (int y = 0; y < rect.height(); ++y) {
            const int run_start = (3 * y + rect.x0) % rect.width(), run_length = 1 + y % 17;
            for (int x = 0; x < rect.width(); ++x) {
                std::int32_t* f = &samples.fragment[std::size_t(n) * (std::size_t(y) * kSide + x)];
                if (x >= run_start && x < run_start + run_length) {
                    for (int s = 0; s < n; ++s) f[s] = -1;
                } else if (x % 3 == 2) {
                    for (int s = 0; s < n; ++s) f[s] = unit(rng) < 0.3f ? -1 : count + s % 2;
                    count += 2;
                } else {
                    for (int s = 0; s < n; ++s) f[s] = count;
                    ++count;
                }
            }
        }
        const Shaded input = random_colours(std::size_t(count) + 1, rng);
        const auto resolve = [&](Isa isa) {
            RenderedImage image = blank_image(place.image_width, place.image_height);
            Shaded shaded = input;
            image::resolve_tile_msaa(samples, rect, std::size_t(count) + 1, shaded.outputs(), clear, isa, image);
            return image;
        };
        compared += check_every_isa_as_scalar(resolve, rect);
    }
    CHECK(compared > 0);
}
