// GL samplers (texture.hpp, Sampler): wrap per axis with GL_MIRRORED_REPEAT,
// and every magnification and minification filter, by the scalar reference
// against values worked out by hand, and every ISA's kernel against the
// scalar reference (within 1e-5, as sample_trilinear's; it measures 0).
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <doctest/doctest.h>

#include "texture/texture.hpp"

namespace {

using namespace tessera;
using namespace tessera::texture;

// A 4×1 linear texture with red = 0, 1/3, 2/3, 1 (as bytes 0, 85, 170, 255) and green = its index/255.
Texture ramp() {
    const float pixels[] = {0, 0, 0, 1, 85 / 255.0f, 1 / 255.0f, 0, 1, 170 / 255.0f, 2 / 255.0f, 0, 1, 1, 3 / 255.0f, 0, 1};
    return Texture::from_pixels(4, 1, 4, pixels, ColorSpace::linear);
}

float red_at(const Texture& t, float u, float lod, const Sampler& s) { return t.sample({u, 0.5f}, lod, s).r; }

}  // namespace

TEST_CASE("sampler: GL_NEAREST picks the texel whose square holds the point, wrapped per axis") {
    const Texture t = ramp();
    Sampler s;
    s.mag = Filter::nearest;
    CHECK(red_at(t, 0.30f, -1.0f, s) == 85 / 255.0f);  // texel 1 covers [0.25, 0.5)
    CHECK(red_at(t, 1.10f, -1.0f, s) == 0.0f);          // repeat: 0.10 → texel 0
    s.wrap_s = Wrap::clamp_to_edge;
    CHECK(red_at(t, 1.10f, -1.0f, s) == 1.0f);
    CHECK(red_at(t, -3.0f, -1.0f, s) == 0.0f);
    s.wrap_s = Wrap::mirrored_repeat;
    // Mirrored: [1, 2) runs backwards: u = 1.1 → 0.9 of the image → texel 3; 1.3 → 0.7 → texel 2.
    CHECK(red_at(t, 1.10f, -1.0f, s) == 1.0f);
    CHECK(red_at(t, 1.30f, -1.0f, s) == 170 / 255.0f);
    CHECK(red_at(t, -0.10f, -1.0f, s) == 0.0f);   // [−1, 0) mirrors too: 0.1 → texel 0
    CHECK(red_at(t, 2.30f, -1.0f, s) == 85 / 255.0f);  // period 2: as 0.3
    // NaN samples like −∞: no read out of range, for every wrap.
    for (const Wrap w : {Wrap::repeat, Wrap::clamp_to_edge, Wrap::mirrored_repeat}) {
        s.wrap_s = w;
        const float r = red_at(t, std::numeric_limits<float>::quiet_NaN(), -1.0f, s);
        CHECK((r >= 0.0f && r <= 1.0f));
    }
}

TEST_CASE("sampler: GL_LINEAR with GL_MIRRORED_REPEAT blends across the mirrored edge") {
    const Texture t = ramp();
    Sampler s;
    s.wrap_s = Wrap::mirrored_repeat;
    // At u = 1 the mirror's edge: the last texel meets itself, so the value is texel 3 alone.
    CHECK(red_at(t, 1.0f, -1.0f, s) == doctest::Approx(1.0f));
    // u = 1.125 is the centre of the mirrored copy's first texel (texel 3); 1.25 is halfway to texel 2.
    CHECK(red_at(t, 1.125f, -1.0f, s) == doctest::Approx(1.0f));
    CHECK(red_at(t, 1.25f, -1.0f, s) == doctest::Approx((1.0f + 170 / 255.0f) / 2));
    // Wrap per axis: s clamped, t repeated, on a 1×4 column.
    const float column[] = {0, 1, 0.5f, 0.25f};
    const Texture c = Texture::from_pixels(1, 4, 1, column, ColorSpace::linear);
    Sampler per_axis;
    per_axis.wrap_s = Wrap::clamp_to_edge, per_axis.wrap_t = Wrap::repeat;
    CHECK(c.sample({5.0f, 1.125f}, -1.0f, per_axis).r == doctest::Approx(0.0f));  // v wraps to row 0
    per_axis.wrap_t = Wrap::clamp_to_edge;
    CHECK(c.sample({5.0f, 1.125f}, -1.0f, per_axis).r == 64 / 255.0f);  // v clamps to row 3 (0.25 stored as 64)
}

TEST_CASE("sampler: the minification filters choose levels as GL does") {
    // 4×4 with a different constant colour per level: level 0 red 1, level 1 red 0.5 … by construction
    // from_pixels filters level 0, so use a checker whose levels average: level 0 texels 0/1, level 1+ 0.5.
    std::vector<float> pixels;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) pixels.push_back(float((x + y) % 2));
    const Texture t = Texture::from_pixels(4, 4, 1, pixels.data(), ColorSpace::linear);
    REQUIRE(t.level_count() == 3);
    const glm::vec2 on_white(0.375f, 0.125f);  // texel (1, 0): 1 on level 0
    const auto red = [&](float lod, Filter min, Filter mag = Filter::linear) {
        Sampler s;
        s.min = min, s.mag = mag;
        return t.sample(on_white, lod, s).r;
    };
    const float level1 = 128 / 255.0f;  // the 2×2 average 0.5, stored in 8 bits
    // GL_NEAREST / GL_LINEAR as min filters read level 0 however far away.
    CHECK(red(2.0f, Filter::nearest) == 1.0f);
    // *_MIPMAP_NEAREST: level ⌈λ + ½⌉ − 1: λ = 0.4 → 0 (magnified, c = 0.5 for LINEAR mag), 0.6 → 1, 1.4 → 1, 1.6 → 2.
    CHECK(red(0.4f, Filter::nearest_mipmap_nearest, Filter::nearest) == 1.0f);
    CHECK(red(0.6f, Filter::nearest_mipmap_nearest) == level1);
    CHECK(red(1.4f, Filter::nearest_mipmap_nearest) == level1);
    CHECK(red(1.6f, Filter::nearest_mipmap_nearest) == level1);  // level 2 is 0.5 too
    // c = 0.5 with LINEAR magnification and NEAREST_MIPMAP_*: λ = 0.4 magnifies (bilinear on level 0).
    const float bilinear0 = t.sample_bilinear(0, on_white.x, on_white.y, Wrap::repeat).r;
    CHECK(red(0.4f, Filter::nearest_mipmap_nearest) == bilinear0);
    // *_MIPMAP_LINEAR blends ⌊λ⌋ and ⌊λ⌋ + 1: λ = 0.25 with nearest taps → 0.75·1 + 0.25·level1.
    CHECK(red(0.25f, Filter::nearest_mipmap_linear, Filter::nearest) == doctest::Approx(0.75f + 0.25f * level1));
    // The default sampler is sample_trilinear exactly.
    for (const float lod : {-1.0f, 0.0f, 0.3f, 1.0f, 1.7f, 9.0f}) {
        CHECK(t.sample(on_white, lod, Sampler{}).r == t.sample_trilinear(on_white, lod, Wrap::repeat).r);
    }
}

TEST_CASE("sampler: every ISA's general kernel equals the scalar reference for every wrap and filter") {
    constexpr std::size_t kCount = 4000;
    const std::size_t padded = padded_count(kCount);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> coord(-3.0f, 4.0f), lod(-1.0f, 8.0f);
    std::vector<float> u(padded), v(padded), l(padded);
    for (std::size_t i = 0; i < padded; ++i) u[i] = coord(rng), v[i] = coord(rng), l[i] = lod(rng);
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    const std::array specials = {0.0f, 1.0f, 0.5f, 2.0f, -1.0f, 0.5f / 37.0f, nan, inf, -inf, 1e30f};
    for (std::size_t i = 0; i < 400; ++i) {
        u[i] = specials[i % specials.size()], v[i] = specials[(i / specials.size()) % specials.size()];
        l[i] = i % 9 == 0 ? nan : float(int(i % 5)) * 0.5f;  // on the level boundaries and c
    }
    std::vector<float> pixels(37 * 23 * 4);
    for (float& p : pixels) p = std::uniform_real_distribution<float>(0.0f, 1.0f)(rng);
    const Texture texture = Texture::from_pixels(37, 23, 4, pixels.data(), ColorSpace::srgb);
    const TexCoordInputs in{kCount, u.data(), v.data(), l.data()};
    const std::array wraps = {Wrap::repeat, Wrap::clamp_to_edge, Wrap::mirrored_repeat};
    const std::array mins = {Filter::nearest, Filter::linear, Filter::nearest_mipmap_nearest, Filter::linear_mipmap_nearest,
                             Filter::nearest_mipmap_linear, Filter::linear_mipmap_linear};
    int compared = 0;
    for (const Wrap ws : wraps)
        for (const Wrap wt : wraps)
            for (const Filter mag : {Filter::nearest, Filter::linear})
                for (const Filter min : mins) {
                    const Sampler sampler{ws, wt, mag, min};
                    std::array<std::vector<float>, 4> expected;
                    for (auto& c : expected) c.assign(padded, 0.0f);
                    sample(Isa::scalar, texture, sampler, in, {expected[0].data(), expected[1].data(), expected[2].data(),
                                                               expected[3].data()});
                    for (const Isa isa : {Isa::sse4, Isa::avx2, Isa::avx512}) {
                        if (!isa_supported(isa)) continue;
                        CAPTURE(isa_name(isa));
                        const int wrap_s = int(ws), wrap_t = int(wt), mag_filter = int(mag), min_filter = int(min);
                        CAPTURE(wrap_s);
                        CAPTURE(wrap_t);
                        CAPTURE(mag_filter);
                        CAPTURE(min_filter);
                        for (const int channels : {1, 3, 4}) {
                            std::array<std::vector<float>, 4> actual;
                            for (auto& c : actual) c.assign(padded, -7.0f);
                            sample(isa, texture, sampler, in,
                                   {actual[0].data(), channels > 1 ? actual[1].data() : nullptr,
                                    channels > 1 ? actual[2].data() : nullptr, channels > 3 ? actual[3].data() : nullptr});
                            int different = 0;
                            for (int c = 0; c < channels; ++c)
                                for (std::size_t i = 0; i < kCount; ++i)
                                    different += !(std::abs(actual[c][i] - expected[c][i]) <= 1e-5f);
                            CHECK(different == 0);
                            ++compared;
                        }
                    }
                }
    MESSAGE(compared << " sampler × ISA × channel comparisons");
}
