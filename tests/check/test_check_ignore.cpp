// Ignore regions of the check library (src/check/ignore_regions.hpp): pixels
// left out of a comparison by rectangles or a mask image, as a manifest's
// [[override]] ignore / ignore_mask gives them, through to a run.
#include <doctest/doctest.h>

#include <fstream>

#include <OpenImageIO/imagebufalgo.h>

#include "check/compare.hpp"
#include "check/ignore_regions.hpp"
#include "check/runner.hpp"
#include "check/suite.hpp"
#include "test_paths.hpp"

using namespace tessera;
namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const char* name) {
    const fs::path dir = test::output_dir("check_ignore") / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

OIIO::ImageBuf gray(int width, int height, float value) {
    OIIO::ImageBuf image(OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::FLOAT));
    OIIO::ImageBufAlgo::fill(image, {value, value, value});
    return image;
}

// `image` with the pixels of [x0, x1) × [y0, y1) raised by `delta` in channel 0.
OIIO::ImageBuf changed(const OIIO::ImageBuf& image, int x0, int y0, int x1, int y1, float delta) {
    OIIO::ImageBuf out(image);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            float v[3];
            out.getpixel(x, y, v, 3);
            v[0] += delta;
            out.setpixel(x, y, v, 3);
        }
    return out;
}

std::string manifest_error(const fs::path& manifest) {
    try {
        check::load_manifest(manifest, {});
    } catch (const check::ManifestError& e) {
        return e.what();
    }
    return "(no error)";
}

}  // namespace

TEST_CASE("check ignore regions: rectangles clip to the image, a mask's white pixels, a mask of another size is named") {
    check::IgnoreRegions regions;
    CHECK(check::ignore_mask(regions, 8, 4).empty());
    regions.rects = {{6, 2, 5, 5}, {0, 0, 1, 1}};  // the first reaches past the corner: clipped to 2×2
    std::vector<std::uint8_t> mask = check::ignore_mask(regions, 8, 4);
    REQUIRE(mask.size() == 32);
    CHECK(std::count(mask.begin(), mask.end(), 1) == 5);
    CHECK(mask[0] == 1);
    CHECK(mask[2 * 8 + 6] == 1);
    CHECK(mask[3 * 8 + 7] == 1);
    CHECK(mask[1 * 8 + 6] == 0);

    const fs::path dir = fresh_dir("mask");
    OIIO::ImageBuf image = gray(8, 4, 0.0f);
    const float white[3] = {1, 1, 1}, dim[3] = {0.4f, 1, 1};
    image.setpixel(3, 1, white, 3);
    image.setpixel(4, 1, dim, 3);  // below 0.5 in the first channel: compared
    REQUIRE(image.write((dir / "mask.png").string(), OIIO::TypeDesc::UINT8));
    regions.mask = dir / "mask.png";
    mask = check::ignore_mask(regions, 8, 4);
    CHECK(std::count(mask.begin(), mask.end(), 1) == 6);
    CHECK(mask[1 * 8 + 3] == 1);
    CHECK(mask[1 * 8 + 4] == 0);
    try {
        check::ignore_mask(regions, 9, 4);
        FAIL("a mask of another size was accepted");
    } catch (const std::runtime_error& e) {
        CHECK(std::string(e.what()) == (dir / "mask.png").string() + ": the ignore mask is 8x4, the render 9x4");
    }
}

TEST_CASE("check comparison: ignored pixels count as equal and leave the pixel count") {
    const OIIO::ImageBuf golden = gray(20, 10, 0.5f);  // 200 pixels
    check::IgnoreRegions regions;
    regions.rects = {{0, 0, 10, 10}};  // the left half
    const std::vector<std::uint8_t> ignored = check::ignore_mask(regions, 20, 10);
    check::Thresholds t;
    t.fail = 0.1;
    t.fail_ratio = 0.05;  // 5% of the compared pixels: 5 of 100 (10 of all 200)

    // A large change inside the ignored half: a pass; without the mask, a failure.
    const OIIO::ImageBuf inside = changed(golden, 2, 2, 8, 8, 0.4f);
    CHECK(check::compare_images(inside, golden, t, check::GoldenKind::png).status == check::Status::fail);
    const check::Comparison masked = check::compare_images(inside, golden, t, check::GoldenKind::png, ignored);
    CHECK(masked.status == check::Status::pass);
    CHECK(masked.metrics.pixels == 100);
    CHECK(masked.metrics.ignored_pixels == 100);
    CHECK(masked.metrics.max_error == 0);

    // Outside it, 6 changed pixels are more than 5% of the 100 compared ones (they would be 3% of 200).
    const OIIO::ImageBuf outside = changed(golden, 12, 0, 18, 1, 0.2f);
    const check::Comparison counted = check::compare_images(outside, golden, t, check::GoldenKind::png, ignored);
    CHECK(counted.status == check::Status::fail);
    CHECK(counted.metrics.pixels_over_fail == 6);
    CHECK(check::compare_images(outside, golden, t, check::GoldenKind::png).status == check::Status::warn);
    // The mean is over the compared pixels: 6 pixels × 0.2 in one of 3 channels, over 100 pixels.
    CHECK(counted.metrics.mean_error == doctest::Approx(6 * 0.2 / 300.0).epsilon(1e-3));
    CHECK(counted.metrics.rms_error == doctest::Approx(std::sqrt(6 * 0.04 / 300.0)).epsilon(1e-3));

    // The heat map shows ignored pixels in their own colour, and differences elsewhere as before.
    const OIIO::ImageBuf map = check::diff_heat_map(inside, golden, 0.2, ignored);
    float pixel[3];
    map.getpixel(4, 4, pixel, 3);  // changed, but ignored
    CHECK(pixel[0] == doctest::Approx(check::kIgnoredColor[0]).epsilon(0.01));
    CHECK(pixel[2] == doctest::Approx(check::kIgnoredColor[2]).epsilon(0.01));
    map.getpixel(15, 5, pixel, 3);  // equal, compared: black
    CHECK(pixel[0] + pixel[1] + pixel[2] < 0.05f);
}

TEST_CASE("check manifest: ignore rectangles and masks in overrides, mistakes at line:column") {
    const fs::path dir = fresh_dir("manifest");
    const fs::path scenes = test::source_dir() / "tests" / "check" / "scenes";
    OIIO::ImageBuf mask = gray(96, 64, 0.0f);
    REQUIRE(mask.write((dir / "mask.png").string(), OIIO::TypeDesc::UINT8));
    const auto write = [&](const std::string& overrides) {
        std::ofstream(dir / "check.toml") << "scenes = [\"" << (scenes / "*.toml").string() << "\"]\n"
                                          << "golden = \"golden\"\n" << overrides;
        return dir / "check.toml";
    };
    const check::Suite suite = check::load_manifest(
        write("[[override]]\nscenes = \"ball\"\nignore = [[1, 2, 3, 4], [0, 0, 96, 1]]\nignore_mask = \"mask.png\"\n"
              "[[override]]\nscenes = \"c*\"\nignore = [[5, 5, 1, 1]]\n"),
        {});
    for (const check::SceneEntry& e : suite.scenes) {
        if (e.name == "ball") {
            REQUIRE(e.ignore.rects.size() == 2);
            CHECK(e.ignore.rects[0].x == 1);
            CHECK(e.ignore.rects[0].height == 4);
            CHECK(e.ignore.mask == dir / "mask.png");
        } else if (e.name == "cube") {
            CHECK(e.ignore.rects.size() == 1);
            CHECK(e.ignore.mask.empty());
        } else {
            CHECK(e.ignore.empty());
        }
    }
    const std::string at = (dir / "check.toml").string() + ":";
    CHECK(manifest_error(write("[[override]]\nscenes = \"ball\"\nignore = [[1, 2, 3]]\n")) ==
          at + "5:11: expected [x, y, width, height] (4 integers, pixels, row 0 at the top) in 'override.ignore'");
    CHECK(manifest_error(write("[[override]]\nscenes = \"ball\"\nignore = [[1, 2, 0, 4]]\n")) ==
          at + "5:18: expected width and height in 'override.ignore' to be in 1..16384, got 0");
    CHECK(manifest_error(write("[[override]]\nscenes = \"ball\"\nignore = [[-1, 2, 3, 4]]\n")) ==
          at + "5:12: expected x and y in 'override.ignore' to be in 0..16384, got -1");
    CHECK(manifest_error(write("[[override]]\nscenes = \"ball\"\nignore_mask = \"nope.png\"\n")) ==
          at + "5:15: " + (dir / "nope.png").string() + ": no such mask image");
}

TEST_CASE("check run: an ignored rectangle over a changed patch passes, a mask of another size is an error") {
    const fs::path dir = fresh_dir("run");
    const fs::path scenes = test::source_dir() / "tests" / "check" / "scenes";
    check::Suite suite = check::suite_from_arguments({(scenes / "ball.toml").string()}, dir / "golden", {}, {});
    check::RunOptions options;
    options.report_dir = dir / "report";
    options.update = check::UpdateMode::missing;
    check::run_check(suite.scenes, options);
    options.update = check::UpdateMode::none;
    const fs::path golden = dir / "golden" / "ball.png";
    OIIO::ImageBuf image(golden.string());
    REQUIRE(image.read(0, 0, true, OIIO::TypeDesc::FLOAT));
    REQUIRE(changed(image, 40, 30, 46, 33, 0.5f).write(golden.string(), OIIO::TypeDesc::UINT8));
    CHECK(check::run_check(suite.scenes, options).scenes[0].status == check::Status::fail);

    suite.scenes[0].ignore.rects = {{38, 28, 10, 8}};
    const check::CheckRun run = check::run_check(suite.scenes, options);
    CHECK(run.scenes[0].status == check::Status::pass);
    CHECK(run.scenes[0].metrics.ignored_pixels == 80);
    CHECK(run.scenes[0].metrics.pixels == 96 * 64 - 80);
    // Not bit-identical where ignored: expected, actual and diff are shown, not one image for both.
    CHECK(run.scenes[0].images.expected != run.scenes[0].images.actual);
    CHECK_FALSE(run.scenes[0].images.diff.empty());

    REQUIRE(gray(10, 10, 1.0f).write((dir / "small.png").string(), OIIO::TypeDesc::UINT8));
    suite.scenes[0].ignore.mask = dir / "small.png";
    const check::CheckRun wrong = check::run_check(suite.scenes, options);
    CHECK(wrong.scenes[0].status == check::Status::error);
    CHECK(wrong.scenes[0].reason == (dir / "small.png").string() + ": the ignore mask is 10x10, the render 96x64");
}
