// WebP and AVIF textures (EXT_texture_webp, EXT_texture_avif): decoded into
// level 0 with straight alpha, and a file that does not decode gives one
// line naming its source.
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "texture/texture.hpp"
#include "texture/webp_avif_test_images.hpp"

using namespace tessera;
using namespace tessera::texture;

namespace {

// 3×2 RGBA: distinct colours, alpha from 40 to 255 (never 0: see encode_webp_lossless).
std::vector<std::uint8_t> test_rgba() {
    return {255, 0, 0, 255, 0, 255, 0, 200, 0, 0, 255, 120, 255, 255, 255, 40, 30, 60, 90, 255, 128, 128, 128, 128};
}

std::string decode_error(const std::vector<std::uint8_t>& bytes) {
    try {
        (void)Texture::decode(bytes, "images[3] 'bark' ('bark.webp')", ColorSpace::srgb);
    } catch (const TextureError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("WebP: a lossless image decodes to its exact bytes, alpha straight") {
    const std::vector<std::uint8_t> rgba = test_rgba();
    const std::vector<std::uint8_t> webp = test::encode_webp_lossless(rgba, 3, 2);
    REQUIRE(webp.size() > 12);
    CHECK(Texture::can_decode(webp));
    const Texture texture = Texture::decode(webp, "webp", ColorSpace::linear);
    REQUIRE(texture.width() == 3);
    REQUIRE(texture.height() == 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x) {
            const auto bytes = texture.texel_bytes(0, x, y);
            for (int c = 0; c < 4; ++c) CHECK(bytes[std::size_t(c)] == rgba[std::size_t((y * 3 + x) * 4 + c)]);
        }
}

TEST_CASE("AVIF: an image decodes to its colours within the codec's loss, alpha straight") {
    const std::vector<std::uint8_t> rgba = test_rgba();
    const std::vector<std::uint8_t> avif = test::encode_avif(rgba, 3, 2);
    if (avif.empty()) {
        MESSAGE("skipped: this libavif has no AV1 encoder");
        return;
    }
    CHECK(Texture::can_decode(avif));
    const Texture texture = Texture::decode(avif, "avif", ColorSpace::linear);
    REQUIRE(texture.width() == 3);
    REQUIRE(texture.height() == 2);
    int worst = 0;
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x) {
            const auto bytes = texture.texel_bytes(0, x, y);
            for (int c = 0; c < 4; ++c)
                worst = std::max(worst, std::abs(int(bytes[std::size_t(c)]) - int(rgba[std::size_t((y * 3 + x) * 4 + c)])));
        }
    MESSAGE("AVIF worst step error " << worst);
    CHECK(worst <= 12);
}

TEST_CASE("WebP and AVIF that do not decode: one line naming the image") {
    std::vector<std::uint8_t> webp = test::encode_webp_lossless(test_rgba(), 3, 2);
    // The RIFF header kept, the bitstream cut short.
    std::vector<std::uint8_t> truncated(webp.begin(), webp.begin() + 20);
    std::string message = decode_error(truncated);
    INFO(message);
    CHECK(message.starts_with("images[3] 'bark' ('bark.webp'): "));
    CHECK(message.find('\n') == std::string::npos);
    // Garbage after a valid signature.
    std::vector<std::uint8_t> garbage = {'R', 'I', 'F', 'F', 20, 0, 0, 0, 'W', 'E', 'B', 'P', 'V', 'P', '8', ' ', 1, 2, 3, 4};
    message = decode_error(garbage);
    CHECK(message.find("WebP") != std::string::npos);
    const std::vector<std::uint8_t> bad_avif = {0, 0, 0, 20, 'f', 't', 'y', 'p', 'a', 'v', 'i', 'f', 0, 0, 0, 0, 'm', 'i', 'f', '1'};
    message = decode_error(bad_avif);
    INFO(message);
    CHECK(message.starts_with("images[3] 'bark' ('bark.webp'): "));
    CHECK(message.find("AVIF") != std::string::npos);
}
