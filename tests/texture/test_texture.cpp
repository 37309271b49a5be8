// Textures: loading, the mip chain, GL sampling rules (scalar reference) and
// the vectorized sampler against it.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <OpenImageIO/imagebuf.h>
#include <tbb/task_arena.h>

#include "texture/texture.hpp"
#include "test_paths.hpp"

namespace {

using namespace tessera;
using namespace tessera::texture;

// A width×height RGBA texture whose texels are all different (up to 5(x + 10y) + c
// = 255, then it wraps): channel c of texel (x, y) is pattern(x, y, c), an 8-bit value.
float pattern_code(float x, float y, int c) { return 5.0f * (x + 10.0f * y) + static_cast<float>(c); }
float pattern(int x, int y, int c) {
    return static_cast<float>(static_cast<int>(pattern_code(static_cast<float>(x), static_cast<float>(y), c)) % 256) /
           255.0f;
}
// The pattern at a point between texel centres (it is linear in x and y), in [0, 1].
glm::vec4 pattern_at(float x, float y) {
    return glm::vec4(pattern_code(x, y, 0), pattern_code(x, y, 1), pattern_code(x, y, 2), pattern_code(x, y, 3)) /
           255.0f;
}
// A value filtered in linear light and stored in 8 bits is within half a step of the exact one.
constexpr float kHalfStep = 0.5f / 255.0f + 1e-6f;

Texture pattern_texture(int width, int height) {
    std::vector<float> pixels;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 4; ++c) pixels.push_back(pattern(x, y, c));
    return Texture::from_pixels(width, height, 4, pixels.data(), ColorSpace::linear);
}

Texture random_texture(int width, int height, unsigned seed, ColorSpace space = ColorSpace::linear) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<float> pixels(static_cast<std::size_t>(width) * height * 4);
    for (float& p : pixels) p = unit(rng);
    return Texture::from_pixels(width, height, 4, pixels.data(), space);
}

// Exactly equal, per channel.
void check_vec4(const glm::vec4& actual, const glm::vec4& expected) {
    for (int c = 0; c < 4; ++c) {
        INFO("channel " << c << ": " << actual[c] << " vs " << expected[c]);
        CHECK(actual[c] == expected[c]);
    }
}

// |a - b| <= tolerance, per channel.
void check_close(const glm::vec4& actual, const glm::vec4& expected, float tolerance) {
    for (int c = 0; c < 4; ++c) {
        INFO("channel " << c << ": " << actual[c] << " vs " << expected[c]);
        CHECK(std::abs(actual[c] - expected[c]) <= tolerance);
    }
}

// u (or v) of the centre of texel i on a side of `size` texels.
float centre(int i, int size) { return (static_cast<float>(i) + 0.5f) / static_cast<float>(size); }

double srgb_formula(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

std::filesystem::path write_png(const std::filesystem::path& path, int width, int height, int channels,
                                const std::vector<float>& pixels) {
    OIIO::ImageBuf buffer(OIIO::ImageSpec(width, height, channels, OIIO::TypeDesc::FLOAT),
                          const_cast<float*>(pixels.data()));
    REQUIRE_MESSAGE(buffer.write(path.string(), OIIO::TypeDesc::UINT8), buffer.geterror());
    return path;
}

// The exception's message, which must name the path.
void check_load_error(const std::filesystem::path& path, const char* expected_words) {
    try {
        (void)Texture::load(path, ColorSpace::srgb);
        FAIL("no TextureError for " << path);
    } catch (const TextureError& e) {
        const std::string message = e.what();
        INFO(message);
        CHECK(message.find(path.string()) != std::string::npos);
        CHECK(message.find(expected_words) != std::string::npos);
    }
}

}  // namespace

TEST_CASE("texture: bilinear at texel centres returns the texel") {
    for (const auto& [width, height] : {std::array{8, 4}, std::array{5, 3}, std::array{1, 1}}) {
        const Texture texture = pattern_texture(width, height);
        for (const Wrap wrap : {Wrap::repeat, Wrap::clamp_to_edge}) {
            for (int y = 0; y < height; ++y) {
                for (int x = 0; x < width; ++x) {
                    INFO(width << "x" << height << " texel " << x << "," << y);
                    const glm::vec4 sample = texture.sample_bilinear(0, centre(x, width), centre(y, height), wrap);
                    // Exact for power-of-two sizes; (i + 0.5)/5·5 may round by an ulp.
                    check_close(sample, texture.texel(0, x, y), 1e-6f);
                    if (width == 8) check_vec4(sample, texture.texel(0, x, y));
                }
            }
        }
    }
}

TEST_CASE("texture: bilinear halfway between texels returns the average") {
    const Texture texture = pattern_texture(8, 4);
    const glm::vec4 t00 = texture.texel(0, 2, 1), t10 = texture.texel(0, 3, 1);
    const glm::vec4 t01 = texture.texel(0, 2, 2), t11 = texture.texel(0, 3, 2);
    // Between columns 2 and 3 on row 1's centre: u = 3/8.
    check_close(texture.sample_bilinear(0, 3.0f / 8.0f, centre(1, 4), Wrap::repeat), (t00 + t10) * 0.5f, 1e-6f);
    // Between rows 1 and 2: v = 2/4.
    check_close(texture.sample_bilinear(0, centre(2, 8), 0.5f, Wrap::repeat), (t00 + t01) * 0.5f, 1e-6f);
    // The middle of the four.
    check_close(texture.sample_bilinear(0, 3.0f / 8.0f, 0.5f, Wrap::clamp_to_edge), (t00 + t10 + t01 + t11) * 0.25f,
                1e-6f);
    // A quarter of the way: weights ¾, ¼.
    check_close(texture.sample_bilinear(0, (2.5f + 0.25f) / 8.0f, centre(1, 4), Wrap::repeat),
                t00 * 0.75f + t10 * 0.25f, 1e-6f);
}

TEST_CASE("texture: repeat wraps to the opposite edge, clamp_to_edge extends the edge") {
    const Texture texture = pattern_texture(8, 4);
    const glm::vec4 left = texture.texel(0, 0, 1), right = texture.texel(0, 7, 1);
    const float v = centre(1, 4);

    // u = 0 is halfway between the first and (wrapped) last column.
    check_close(texture.sample_bilinear(0, 0.0f, v, Wrap::repeat), (left + right) * 0.5f, 1e-6f);
    check_close(texture.sample_bilinear(0, 1.0f, v, Wrap::repeat), (left + right) * 0.5f, 1e-6f);
    // Whole periods away, the same texel; -0.5/8 is the centre of the last column.
    check_vec4(texture.sample_bilinear(0, 3.0f + centre(0, 8), v, Wrap::repeat), left);
    check_vec4(texture.sample_bilinear(0, -2.0f + centre(5, 8), v, Wrap::repeat), texture.texel(0, 5, 1));
    check_close(texture.sample_bilinear(0, -0.5f / 8.0f, v, Wrap::repeat), right, 1e-6f);
    // Rows wrap too: v = 0 averages the first and last row.
    check_close(texture.sample_bilinear(0, centre(3, 8), 0.0f, Wrap::repeat),
                (texture.texel(0, 3, 0) + texture.texel(0, 3, 3)) * 0.5f, 1e-6f);

    check_vec4(texture.sample_bilinear(0, 0.0f, v, Wrap::clamp_to_edge), left);
    check_vec4(texture.sample_bilinear(0, -5.0f, v, Wrap::clamp_to_edge), left);
    check_vec4(texture.sample_bilinear(0, 1.0f, v, Wrap::clamp_to_edge), right);
    check_vec4(texture.sample_bilinear(0, 7.0f, v, Wrap::clamp_to_edge), right);
    check_vec4(texture.sample_bilinear(0, 2.0f, -3.0f, Wrap::clamp_to_edge), texture.texel(0, 7, 0));
    // Half a texel inside the edge is still the edge texel alone.
    check_vec4(texture.sample_bilinear(0, 0.5f / 8.0f, v, Wrap::clamp_to_edge), left);

    // Non-finite coordinates read in range (NaN samples like -∞) and give finite texels.
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    for (const Wrap wrap : {Wrap::repeat, Wrap::clamp_to_edge})
        for (const float u : {nan, inf, -inf, 1e30f, -1e30f}) {
            const glm::vec4 s = texture.sample_trilinear({u, u}, 0.3f, wrap);
            CHECK(std::isfinite(s.r));
        }
}

TEST_CASE("texture: mip chain sizes follow GL (floor of half, down to 1x1)") {
    struct Case {
        int width, height;
        std::vector<std::array<int, 2>> sizes;
    };
    const std::vector<Case> cases = {
        {8, 4, {{8, 4}, {4, 2}, {2, 1}, {1, 1}}},
        {5, 3, {{5, 3}, {2, 1}, {1, 1}}},
        {1, 7, {{1, 7}, {1, 3}, {1, 1}}},
        {1, 1, {{1, 1}}},
        {512, 512, {{512, 512}, {256, 256}, {128, 128}, {64, 64}, {32, 32}, {16, 16}, {8, 8}, {4, 4}, {2, 2}, {1, 1}}},
    };
    for (const Case& c : cases) {
        INFO(c.width << "x" << c.height);
        const Texture texture = pattern_texture(c.width, c.height);
        REQUIRE(texture.level_count() == static_cast<int>(c.sizes.size()));
        std::size_t offset = 0;
        for (int l = 0; l < texture.level_count(); ++l) {
            CHECK(texture.level(l).width == c.sizes[static_cast<std::size_t>(l)][0]);
            CHECK(texture.level(l).height == c.sizes[static_cast<std::size_t>(l)][1]);
            CHECK(texture.level(l).offset == offset);
            offset += static_cast<std::size_t>(texture.level(l).width) * texture.level(l).height;
        }
        CHECK(texture.texels().size() == offset);
    }
}

TEST_CASE("texture: mip levels are box filters of the level above") {
    SUBCASE("even sizes: the 2x2 average") {
        const Texture texture = pattern_texture(8, 4);
        for (int l = 1; l < texture.level_count(); ++l) {
            const MipLevel& level = texture.level(l);
            const MipLevel& parent = texture.level(l - 1);
            for (int y = 0; y < level.height; ++y)
                for (int x = 0; x < level.width; ++x) {
                    INFO("level " << l << " texel " << x << "," << y);
                    // Parent sizes here are even or 1 along each axis.
                    const int x1 = parent.width > 1 ? 2 * x + 1 : 0, y1 = parent.height > 1 ? 2 * y + 1 : 0;
                    const int x0 = parent.width > 1 ? 2 * x : 0, y0 = parent.height > 1 ? 2 * y : 0;
                    const glm::vec4 average = (texture.texel(l - 1, x0, y0) + texture.texel(l - 1, x1, y0) +
                                               texture.texel(l - 1, x0, y1) + texture.texel(l - 1, x1, y1)) *
                                              0.25f;
                    check_close(texture.texel(l, x, y), average, kHalfStep);
                }
        }
        // The pattern is linear, so level 1 texel (i, j) is the pattern at the footprint centre (2i + ½, 2j + ½).
        check_close(texture.texel(1, 1, 1), pattern_at(2.5f, 2.5f), kHalfStep);
        // Level 3 is filtered from the rounded level 2: half a step of rounding per level.
        check_close(texture.texel(3, 0, 0), pattern_at(3.5f, 1.5f), 3.0f * kHalfStep);
    }
    SUBCASE("odd sizes: area-weighted over the covered texels") {
        const Texture texture = pattern_texture(5, 3);
        // 5 -> 2: texel 0 covers [0, 2.5): weights .4, .4, .2; texel 1 covers [2.5, 5): .2, .4, .4.
        // 3 -> 1: each row 1/3. The pattern is linear in x and y.
        check_close(texture.texel(1, 0, 0), pattern_at(0.4f * 0 + 0.4f * 1 + 0.2f * 2, 1.0f), kHalfStep);
        check_close(texture.texel(1, 1, 0), pattern_at(0.2f * 2 + 0.4f * 3 + 0.4f * 4, 1.0f), kHalfStep);
        // The mean is kept at every level: x averages 2, y averages 1.
        check_close(texture.texel(2, 0, 0), pattern_at(2.0f, 1.0f), 2.0f * kHalfStep);
    }
    SUBCASE("the mean of every level is the mean of the level above, up to 8-bit rounding") {
        const Texture texture = random_texture(37, 23, 7);
        const auto mean_of = [&](int l) {
            glm::dvec4 mean(0.0);
            const MipLevel& level = texture.level(l);
            for (int y = 0; y < level.height; ++y)
                for (int x = 0; x < level.width; ++x) mean += glm::dvec4(texture.texel(l, x, y));
            return glm::vec4(mean / (static_cast<double>(level.width) * level.height));
        };
        for (int l = 1; l < texture.level_count(); ++l) check_close(mean_of(l), mean_of(l - 1), kHalfStep);
    }
    SUBCASE("sRGB maps are filtered in linear light, stored sRGB-encoded") {
        // Black and white side by side: the linear mean ½ is sRGB 0.7354 = 187.5/255 → 188,
        // where averaging the encoded values would give 128.
        const std::uint8_t black_white[] = {0, 0, 0, 255, 255, 255};
        const Texture texture = Texture::from_pixels(2, 1, 3, black_white, ColorSpace::srgb);
        CHECK(texture.texel_bytes(1, 0, 0) == std::array<std::uint8_t, 4>{188, 188, 188, 255});
        CHECK(texture.texel(1, 0, 0).r == srgb_decode_table()[188]);
        const Texture linear = Texture::from_pixels(2, 1, 3, black_white, ColorSpace::linear);
        CHECK(linear.texel_bytes(1, 0, 0) == std::array<std::uint8_t, 4>{128, 128, 128, 255});  // 127.5 rounds up
    }
    SUBCASE("the chain is the same with one thread or many") {
        for (const auto& [width, height] : {std::array{512, 256}, std::array{301, 199}}) {  // levels of 16K+ texels run in parallel
            INFO(width << "x" << height);
            const Texture reference = random_texture(width, height, 9, ColorSpace::srgb);
            std::vector<std::uint32_t> one_thread;
            tbb::task_arena(1).execute([&] {
                const Texture texture = random_texture(width, height, 9, ColorSpace::srgb);
                one_thread.assign(texture.texels().begin(), texture.texels().end());
            });
            CHECK(std::equal(one_thread.begin(), one_thread.end(), reference.texels().begin(), reference.texels().end()));
        }
    }
}

TEST_CASE("texture: channels expand to RGBA") {
    const auto unorm = [](int k) { return static_cast<float>(k) / 255.0f; };
    const float grey[] = {unorm(64), unorm(191)};
    const Texture g = Texture::from_pixels(2, 1, 1, grey, ColorSpace::linear);
    check_vec4(g.texel(0, 1, 0), {unorm(191), unorm(191), unorm(191), 1.0f});
    const float grey_alpha[] = {unorm(64), unorm(128)};
    check_vec4(Texture::from_pixels(1, 1, 2, grey_alpha, ColorSpace::linear).texel(0, 0, 0),
               {unorm(64), unorm(64), unorm(64), unorm(128)});
    const float rgb[] = {unorm(25), unorm(51), unorm(77)};
    check_vec4(Texture::from_pixels(1, 1, 3, rgb, ColorSpace::linear).texel(0, 0, 0),
               {unorm(25), unorm(51), unorm(77), 1.0f});
    // Floats are rounded to 8 bits: 0.25·255 = 63.75 → 64, 0.1·255 = 25.5 → 26; out of range clamps.
    const float unrounded[] = {0.25f, 0.1f, -3.0f, 7.0f};
    CHECK(Texture::from_pixels(1, 1, 4, unrounded, ColorSpace::linear).texel_bytes(0, 0, 0) ==
          std::array<std::uint8_t, 4>{64, 26, 0, 255});
    // sRGB decodes colour, never alpha. 0.5 is stored as 128 (127.5 rounds up).
    const float rgba[] = {0.5f, 1.0f, 0.0f, 0.5f};
    check_vec4(Texture::from_pixels(1, 1, 4, rgba, ColorSpace::srgb).texel(0, 0, 0),
               {srgb_decode_table()[128], 1.0f, 0.0f, unorm(128)});
    CHECK(srgb_decode_table()[128] == doctest::Approx(srgb_formula(128 / 255.0)).epsilon(1e-6));
    CHECK_THROWS_AS((void)Texture::from_pixels(0, 4, 1, grey, ColorSpace::linear), TextureError);
    CHECK_THROWS_AS((void)Texture::from_pixels(kMaxTextureSize + 1, 1, 1, grey, ColorSpace::linear), TextureError);
}

TEST_CASE("texture: sRGB decode is the exact transfer function") {
    CHECK(srgb_to_linear(0.0f) == 0.0f);
    CHECK(srgb_to_linear(1.0f) == doctest::Approx(1.0).epsilon(1e-7));
    CHECK(srgb_to_linear(0.5f) == doctest::Approx(0.21404).epsilon(1e-4));
    CHECK(srgb_to_linear(0.04045f) == doctest::Approx(0.04045 / 12.92).epsilon(1e-6));
    for (int i = 0; i <= 255; ++i) {
        const float encoded = static_cast<float>(i) / 255.0f;
        INFO(i);
        CHECK(srgb_to_linear(encoded) == doctest::Approx(srgb_formula(encoded)).epsilon(1e-6));
    }
}

TEST_CASE("texture: 8-bit storage keeps 8-bit images exactly, decodes by table") {
    std::vector<std::uint8_t> bytes(256 * 4);
    for (int k = 0; k < 256; ++k)
        for (int c = 0; c < 4; ++c) bytes[static_cast<std::size_t>(k * 4 + c)] = static_cast<std::uint8_t>((k + 60 * c) % 256);
    for (const ColorSpace space : {ColorSpace::linear, ColorSpace::srgb}) {
        const Texture texture = Texture::from_pixels(256, 1, 4, bytes.data(), space);
        CHECK(texture.memory_bytes() == texture.texels().size() * 4);
        for (int k = 0; k < 256; ++k) {
            INFO("texel " << k << (space == ColorSpace::srgb ? " sRGB" : " linear"));
            const std::array<std::uint8_t, 4> stored = texture.texel_bytes(0, k, 0);
            for (int c = 0; c < 4; ++c) CHECK(stored[static_cast<std::size_t>(c)] == bytes[static_cast<std::size_t>(k * 4 + c)]);
            const glm::vec4 decoded = texture.texel(0, k, 0);
            for (int c = 0; c < 4; ++c) {
                const int byte = stored[static_cast<std::size_t>(c)];
                const double exact = c < 3 && space == ColorSpace::srgb ? srgb_formula(byte / 255.0) : byte / 255.0;
                CHECK(decoded[c] == doctest::Approx(exact).epsilon(1e-6));
            }
        }
    }
}

TEST_CASE("texture: 8-bit encoders round to the nearest step") {
    for (int k = 0; k < 256; ++k) {
        INFO(k);
        CHECK(encode_srgb8(srgb_decode_table()[static_cast<std::size_t>(k)]) == k);
        CHECK(encode_unorm8(unorm8_table()[static_cast<std::size_t>(k)]) == k);
    }
    // Against the exact encode, away from ties (the float rounding of a threshold).
    const auto srgb_encode = [](double x) { return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1 / 2.4) - 0.055; };
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    int checked = 0;
    for (int i = 0; i < 100000; ++i) {
        const float x = unit(rng);
        const double scaled = 255.0 * srgb_encode(x);
        if (std::abs(scaled - std::floor(scaled) - 0.5) < 1e-4) continue;
        ++checked;
        if (encode_srgb8(x) != static_cast<int>(std::lround(scaled))) FAIL_CHECK("x " << x << " → " << scaled);
    }
    CHECK(checked > 99000);
    CHECK(encode_srgb8(-1.0f) == 0);
    CHECK(encode_srgb8(2.0f) == 255);
    CHECK(encode_srgb8(std::numeric_limits<float>::quiet_NaN()) == 0);
}

TEST_CASE("texture: lod from derivatives is log2 of the GL scale factor") {
    const float texel = 1.0f / 256.0f;
    CHECK(lod_from_derivatives(texel, 0, 0, texel, 256, 256) == doctest::Approx(0.0));
    CHECK(lod_from_derivatives(4 * texel, 0, 0, 4 * texel, 256, 256) == doctest::Approx(2.0));
    CHECK(lod_from_derivatives(0, 4 * texel, 4 * texel, 0, 256, 256) == doctest::Approx(2.0));
    // Anisotropic: the longer of the two steps decides.
    CHECK(lod_from_derivatives(texel, 0, 0, 8 * texel, 256, 256) == doctest::Approx(3.0));
    CHECK(lod_from_derivatives(16 * texel, 0, 0, texel, 256, 256) == doctest::Approx(4.0));
    // A diagonal step of one texel along each axis is √2 texels long.
    CHECK(lod_from_derivatives(texel, texel, 0, 0, 256, 256) == doctest::Approx(0.5));
    // Measured in texels of each axis: 2/64 of v on a 64-high texture is 2 texels.
    CHECK(lod_from_derivatives(0, 2.0f / 64.0f, texel, 0, 256, 64) == doctest::Approx(1.0));
    // Magnification: below one texel per pixel, negative.
    CHECK(lod_from_derivatives(texel / 4, 0, 0, texel / 4, 256, 256) == doctest::Approx(-2.0));
}

TEST_CASE("texture: SIMD lod matches the scalar lod") {
    constexpr std::size_t kCount = 500;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> derivative(-0.05f, 0.05f);
    std::vector<std::vector<float>> d(4, std::vector<float>(padded_count(kCount)));
    for (auto& channel : d)
        for (float& value : channel) value = derivative(rng);
    const DerivativeInputs in{kCount, d[0].data(), d[1].data(), d[2].data(), d[3].data()};
    std::vector<float> expected(padded_count(kCount));
    lod_from_derivatives(Isa::scalar, in, 512, 128, expected.data());
    CHECK(expected[7] == lod_from_derivatives(d[0][7], d[1][7], d[2][7], d[3][7], 512, 128));
    for (const Isa isa : {Isa::sse4, Isa::avx2, Isa::avx512}) {
        if (!simd::isa_supported(isa)) continue;
        std::vector<float> actual(padded_count(kCount));
        lod_from_derivatives(isa, in, 512, 128, actual.data());
        float worst = 0.0f;
        for (std::size_t i = 0; i < kCount; ++i) worst = std::max(worst, std::abs(actual[i] - expected[i]));
        CHECK(worst <= 1e-5f);
    }
}

TEST_CASE("texture: trilinear blends the two nearest levels") {
    const Texture texture = random_texture(16, 16, 3);
    const glm::vec2 uv(0.3f, 0.71f);
    const glm::vec4 s0 = texture.sample_bilinear(0, uv.x, uv.y, Wrap::repeat);
    const glm::vec4 s1 = texture.sample_bilinear(1, uv.x, uv.y, Wrap::repeat);
    const glm::vec4 s2 = texture.sample_bilinear(2, uv.x, uv.y, Wrap::repeat);
    check_close(texture.sample_trilinear(uv, 0.5f, Wrap::repeat), (s0 + s1) * 0.5f, 1e-6f);
    check_close(texture.sample_trilinear(uv, 1.25f, Wrap::repeat), s1 * 0.75f + s2 * 0.25f, 1e-6f);
    check_vec4(texture.sample_trilinear(uv, 1.0f, Wrap::repeat), s1);
    // Magnification (lod <= 0) and NaN: level 0 bilinear.
    check_vec4(texture.sample_trilinear(uv, 0.0f, Wrap::repeat), s0);
    check_vec4(texture.sample_trilinear(uv, -3.0f, Wrap::repeat), s0);
    check_vec4(texture.sample_trilinear(uv, std::numeric_limits<float>::quiet_NaN(), Wrap::repeat), s0);
    // Clamped to the last level, the 1x1 mean (both taps on it: exact up to rounding of the weights).
    check_close(texture.sample_trilinear(uv, 100.0f, Wrap::repeat), texture.texel(4, 0, 0), 1e-6f);
    check_close(texture.sample_trilinear(uv, std::numeric_limits<float>::infinity(), Wrap::repeat),
                texture.texel(4, 0, 0), 1e-6f);
}

TEST_CASE("texture: load reads PNG, decodes sRGB, keeps linear data") {
    const std::filesystem::path dir = test::output_dir("texture");
    // 8-bit values k/255, one texel per value.
    const std::vector<float> rgb = {0.0f, 128 / 255.0f, 1.0f, 64 / 255.0f, 200 / 255.0f, 10 / 255.0f};
    const std::filesystem::path path = write_png(dir / "rgb_2x1.png", 2, 1, 3, rgb);

    const Texture linear = Texture::load(path, ColorSpace::linear);
    REQUIRE(linear.width() == 2);
    REQUIRE(linear.height() == 1);
    CHECK(linear.level_count() == 2);
    check_close(linear.texel(0, 0, 0), {0.0f, 128 / 255.0f, 1.0f, 1.0f}, 1e-6f);
    check_close(linear.texel(0, 1, 0), {64 / 255.0f, 200 / 255.0f, 10 / 255.0f, 1.0f}, 1e-6f);

    const Texture srgb = Texture::load(path, ColorSpace::srgb);
    for (int c = 0; c < 3; ++c)
        CHECK(srgb.texel(0, 1, 0)[c] == doctest::Approx(srgb_formula(rgb[3 + static_cast<std::size_t>(c)])).epsilon(1e-5));

    // Grey PNG → RGB, alpha 1.
    const std::filesystem::path grey_path = write_png(dir / "grey_1x2.png", 1, 2, 1, {0.0f, 1.0f});
    check_close(Texture::load(grey_path, ColorSpace::linear).texel(0, 0, 1), {1, 1, 1, 1}, 1e-6f);
    // Straight alpha: colour is not premultiplied on the way in.
    const std::filesystem::path rgba_path = write_png(dir / "rgba_1x1.png", 1, 1, 4, {1.0f, 0.0f, 1.0f, 0.0f});
    check_close(Texture::load(rgba_path, ColorSpace::linear).texel(0, 0, 0), {1, 0, 1, 0}, 1e-6f);
}

TEST_CASE("texture: load errors name the path and the problem") {
    const std::filesystem::path dir = test::output_dir("texture");

    check_load_error(dir / "no_such_texture.png", "cannot open texture: no such file");

    const std::filesystem::path empty = dir / "empty.png";
    std::ofstream(empty, std::ios::binary | std::ios::trunc).close();
    check_load_error(empty, "empty");

    // A valid PNG cut in half: the header reads, the pixel data does not.
    std::vector<float> noise(64 * 64 * 3);
    std::mt19937 rng(5);
    for (float& p : noise) p = std::uniform_real_distribution<float>(0.0f, 1.0f)(rng);
    const std::filesystem::path whole = write_png(dir / "whole.png", 64, 64, 3, noise);
    const std::filesystem::path truncated = dir / "truncated.png";
    {
        std::ifstream in(whole, std::ios::binary);
        std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        std::ofstream(truncated, std::ios::binary | std::ios::trunc).write(bytes.data(), static_cast<std::streamsize>(bytes.size() / 2));
    }
    check_load_error(truncated, "");

    const std::filesystem::path text = dir / "not_an_image.png";
    std::ofstream(text) << "this is not a PNG\n";
    check_load_error(text, "cannot read image");

    // A side above the limit (a 16385x1 grey PNG is small).
    const std::filesystem::path wide = write_png(dir / "too_wide.png", kMaxTextureSize + 1, 1, 1,
                                                 std::vector<float>(kMaxTextureSize + 1, 0.5f));
    check_load_error(wide, "above the limit");

    check_load_error(dir, "not a regular file");
}

TEST_CASE("texture: SIMD trilinear matches the scalar sampler") {
    // Bound: 1e-5 absolute for texel values in [0, 1]; the kernels differ from
    // the reference by FMA contraction only (texture_sampling_simd.cpp).
    constexpr float kTolerance = 1e-5f;
    constexpr std::size_t kCount = 100000;
    constexpr std::size_t kSentinelLanes = 16;
    constexpr float kSentinel = -1234.5f;
    constexpr std::array kSimdIsas{Isa::sse4, Isa::avx2, Isa::avx512};
    std::array<float, kSimdIsas.size()> worst_per_isa{};

    for (const auto& [width, height, srgb] : {std::array{64, 64, 0}, std::array{37, 23, 0}, std::array{1, 5, 0},
                                              std::array{64, 64, 1}, std::array{37, 23, 1}}) {
        const Texture texture = random_texture(width, height, 11, srgb ? ColorSpace::srgb : ColorSpace::linear);
        const float max_lod = static_cast<float>(texture.level_count()) + 1.0f;

        std::mt19937 rng(1234);
        std::uniform_real_distribution<float> coord(-2.0f, 3.0f), lod(-1.0f, max_lod);
        const std::size_t padded = padded_count(kCount);
        std::vector<float> u(padded), v(padded), l(padded);
        for (std::size_t i = 0; i < padded; ++i) {
            u[i] = coord(rng);
            v[i] = coord(rng);
            l[i] = lod(rng);
        }
        // Integer lods and texel-centre / texel-edge coordinates, where floors decide, and non-finite values.
        const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
        const std::array specials = {0.0f, 1.0f, 0.5f, -0.5f, 1.0f / 64.0f, 0.5f / 64.0f, 2.0f, nan, inf, -inf, 1e30f};
        for (std::size_t i = 0; i < 2000; ++i) {
            u[i] = specials[i % specials.size()];
            v[i] = specials[(i / specials.size()) % specials.size()];
            l[i] = static_cast<float>(static_cast<int>(i % 7) - 1);
            if (i % 13 == 0) l[i] = nan;
        }

        for (const Wrap wrap : {Wrap::repeat, Wrap::clamp_to_edge}) {
            const TexCoordInputs in{kCount, u.data(), v.data(), l.data()};
            std::array<std::vector<float>, 4> expected;
            for (auto& channel : expected) channel.assign(padded, 0.0f);
            sample_trilinear(Isa::scalar, texture, wrap, in,
                             {expected[0].data(), expected[1].data(), expected[2].data(), expected[3].data()});

            for (std::size_t k = 0; k < kSimdIsas.size(); ++k) {
                const Isa isa = kSimdIsas[k];
                if (!isa_supported(isa)) continue;
                INFO(isa_name(isa) << ", " << width << "x" << height << (srgb ? " sRGB" : " linear") << ", wrap "
                                   << static_cast<int>(wrap));
                std::array<std::vector<float>, 4> actual;
                for (auto& channel : actual) channel.assign(padded + kSentinelLanes, kSentinel);
                sample_trilinear(isa, texture, wrap, in,
                                 {actual[0].data(), actual[1].data(), actual[2].data(), actual[3].data()});
                float worst = 0.0f;
                std::size_t worst_index = 0;
                for (int c = 0; c < 4; ++c)
                    for (std::size_t i = 0; i < kCount; ++i) {
                        const float error = std::abs(actual[c][i] - expected[c][i]);
                        if (!(error <= worst)) {
                            worst = error;
                            worst_index = i;
                        }
                    }
                INFO("worst at " << worst_index << ": u " << u[worst_index] << " v " << v[worst_index] << " lod "
                                 << l[worst_index]);
                CHECK(worst <= kTolerance);
                worst_per_isa[k] = std::max(worst_per_isa[k], worst);
                bool sentinels_intact = true;
                for (const auto& channel : actual)
                    for (std::size_t i = padded; i < channel.size(); ++i) sentinels_intact &= channel[i] == kSentinel;
                CHECK(sentinels_intact);

                // Fewer channels: R alone, then RGB; the channels not asked for are not written.
                for (const int channels : {1, 3}) {
                    for (auto& channel : actual) channel.assign(padded + kSentinelLanes, kSentinel);
                    sample_trilinear(isa, texture, wrap, in,
                                     {actual[0].data(), channels > 1 ? actual[1].data() : nullptr,
                                      channels > 1 ? actual[2].data() : nullptr, nullptr});
                    float worst_subset = 0.0f;
                    for (int c = 0; c < channels; ++c)
                        for (std::size_t i = 0; i < kCount; ++i)
                            worst_subset = std::max(worst_subset, std::abs(actual[c][i] - expected[c][i]));
                    CHECK(worst_subset <= kTolerance);
                    CHECK(actual[3][0] == kSentinel);
                    if (channels == 1) CHECK(actual[1][0] == kSentinel);
                }
            }
        }
    }
    for (std::size_t k = 0; k < kSimdIsas.size(); ++k) {
        if (isa_supported(kSimdIsas[k]))
            MESSAGE(isa_name(kSimdIsas[k]), ": worst |simd - scalar| ", worst_per_isa[k], " (bound ", kTolerance, ")");
        else
            MESSAGE("skipping ", isa_name(kSimdIsas[k]), ": not supported by this CPU");
    }
}
