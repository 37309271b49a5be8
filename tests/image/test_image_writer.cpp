#include <doctest/doctest.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "image/resolve.hpp"
#include "shade/pbr_reference.hpp"
#include "tessera/image_io.hpp"
#include "test_paths.hpp"

using namespace tessera;

namespace {

RenderedImage gradient_image() {
    RenderedImage image;
    image.width = 7;
    image.height = 5;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < 3; ++c) {
                image.display.push_back(std::uint8_t(10 * x + 40 * y + c));
                image.radiance.push_back(0.25f * x + 3.0f * y + c);  // HDR: above 1 too
            }
    return image;
}

bool leftover_temporaries(const std::filesystem::path& dir) {
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        if (entry.path().string().find(".tmp.") != std::string::npos) return true;
    return false;
}

}  // namespace

TEST_CASE("PNG stores the display values with row 0 at the top") {
    const auto dir = test::output_dir("image_writer");
    const RenderedImage image = gradient_image();
    write_image(image, dir / "gradient.png");
    OIIO::ImageBuf read((dir / "gradient.png").string());
    REQUIRE(read.read(0, 0, true, OIIO::TypeDesc::UINT8));
    REQUIRE(read.spec().width == 7);
    REQUIRE(read.spec().height == 5);
    REQUIRE(read.spec().nchannels == 3);
    std::vector<std::uint8_t> pixels(image.display.size());
    read.get_pixels(read.roi(), OIIO::TypeDesc::UINT8, pixels.data());
    CHECK(pixels == image.display);
    CHECK_FALSE(leftover_temporaries(dir));
}

TEST_CASE("EXR stores scene-linear radiance as half floats") {
    const auto dir = test::output_dir("image_writer");
    const RenderedImage image = gradient_image();
    write_image(image, dir / "gradient.exr");
    OIIO::ImageBuf read((dir / "gradient.exr").string());
    REQUIRE(read.read(0, 0, true, OIIO::TypeDesc::FLOAT));
    CHECK(read.nativespec().format == OIIO::TypeDesc::HALF);
    std::vector<float> pixels(image.radiance.size());
    read.get_pixels(read.roi(), OIIO::TypeDesc::FLOAT, pixels.data());
    for (std::size_t i = 0; i < pixels.size(); ++i) CHECK(pixels[i] == doctest::Approx(image.radiance[i]).epsilon(1e-3));
}

TEST_CASE("AOV planes go to the EXR only, and must cover the image") {
    const auto dir = test::output_dir("image_writer_aov");
    RenderedImage image = gradient_image();
    write_image(image, dir / "plain.png");
    image.aov.depth.assign(std::size_t(image.width) * image.height, 2.5f);
    write_image(image, dir / "depth.png");
    OIIO::ImageBuf plain((dir / "plain.png").string()), with_depth((dir / "depth.png").string());
    REQUIRE(with_depth.read(0, 0, true, OIIO::TypeDesc::UINT8));
    CHECK(with_depth.spec().nchannels == 3);
    CHECK(OIIO::ImageBufAlgo::compare(plain, with_depth, 0.0f, 0.0f).maxerror == 0.0);

    write_image(image, dir / "depth.exr");
    OIIO::ImageBuf exr((dir / "depth.exr").string());
    REQUIRE(exr.read(0, 0, true, OIIO::TypeDesc::FLOAT));
    REQUIRE(exr.spec().nchannels == 4);
    const int z = exr.spec().channelindex("Z");
    REQUIRE(z >= 0);
    CHECK(exr.getchannel(6, 4, 0, z) == 2.5f);
    CHECK(exr.spec().channelindex("R") >= 0);

    image.aov.normal.assign(5, 0.0f);  // not 3 values per pixel
    CHECK_THROWS_WITH_AS(write_image(image, dir / "short_normal.exr"),
                         doctest::Contains("normal plane holds 5 values, not 105"), ImageError);
    CHECK_FALSE(std::filesystem::exists(dir / "short_normal.exr"));
    CHECK_FALSE(leftover_temporaries(dir));
}

TEST_CASE("bad output paths are refused with the path in the message and nothing left behind") {
    const auto dir = test::output_dir("image_writer_bad");
    const RenderedImage image = gradient_image();
    CHECK_THROWS_WITH_AS(write_image(image, dir / "picture.bmpx"), doctest::Contains("picture.bmpx"), ImageError);
    CHECK_THROWS_WITH_AS(write_image(image, dir / "no_such_folder" / "out.png"), doctest::Contains("no_such_folder"),
                         ImageError);
    CHECK_FALSE(leftover_temporaries(dir));
    CHECK(is_supported_image_path("a/b.PNG"));
    CHECK_FALSE(is_supported_image_path("a/b.jpg"));
}

TEST_CASE("an image that cannot be written leaves the previous file intact") {
    const auto dir = test::output_dir("image_writer_keep");
    const auto target = dir / "keep.png";
    write_image(gradient_image(), target);
    const auto size_before = std::filesystem::file_size(target);
    RenderedImage empty;  // nothing rendered: the write is refused
    CHECK_THROWS_AS(write_image(empty, target), ImageError);
    CHECK(std::filesystem::file_size(target) == size_before);
}

TEST_CASE("the background radiance tonemaps back to the clear colour") {
    for (float c : {0.0f, 0.1f, 0.5f, 0.9f}) {
        const glm::vec3 display = shade::display_from_radiance(image::radiance_for_display(glm::vec3(c)));
        CHECK(display.r == doctest::Approx(c).epsilon(1e-5));
    }
    CHECK(std::isfinite(image::radiance_for_display(glm::vec3(1.0f)).r));
}

TEST_CASE("quantization rounds to nearest, clamps, and maps NaN to 0") {
    CHECK(image::quantize_unorm8(0.1f) == 26);  // 25.5 rounds up, as glClearColor(0.1) stores
    CHECK(image::quantize_unorm8(1.0f) == 255);
    CHECK(image::quantize_unorm8(2.0f) == 255);
    CHECK(image::quantize_unorm8(-1.0f) == 0);
    CHECK(image::quantize_unorm8(std::numeric_limits<float>::quiet_NaN()) == 0);
    CHECK(image::quantize_unorm8(0.5f / 255.0f - 1e-4f) == 0);
}
