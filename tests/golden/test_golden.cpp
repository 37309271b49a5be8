#include <doctest/doctest.h>

#include <algorithm>

#include "golden_compare.hpp"
#include "tessera/renderer.hpp"
#include "test_paths.hpp"

using namespace tessera;

// Every scene in scenes/ has a golden image golden/<scene>.png made by
// tools/regenerate_golden.sh; a render that drifts from it fails here.
TEST_CASE("every scene matches its golden image") {
    const std::vector<std::filesystem::path> scenes = test::scene_files();
    REQUIRE_FALSE(scenes.empty());
    Renderer renderer;
    for (const auto& scene_file : scenes) {
        const std::string name = scene_file.stem().string();
        SUBCASE(name.c_str()) {
            const RenderedImage& image = renderer.render(load_scene_file(scene_file));
            const auto result = test::compare_with_golden(image, test::source_dir() / "golden" / (name + ".png"),
                                                          std::filesystem::path(TESSERA_BINARY_DIR) / "golden_failures", name);
            CHECK_MESSAGE(result.passed, name << ": " << result.message);
            MESSAGE(name << ": " << result.message);
        }
    }
}

// scenes/gltf/ renders the shared sample models (golden/gltf/<scene>.png), when they are there.
TEST_CASE("every sample-model scene matches its golden image") {
    if (!std::filesystem::is_directory(test::assets_dir())) {
        MESSAGE("skipped: no sample models at " << test::assets_dir().string());
        return;
    }
    const std::vector<std::filesystem::path> scenes = test::gltf_scene_files();
    REQUIRE_FALSE(scenes.empty());
    Renderer renderer;
    for (const auto& scene_file : scenes) {
        const std::string name = scene_file.stem().string();
        SUBCASE(name.c_str()) {
            const std::filesystem::path golden = test::source_dir() / "golden" / "gltf" / (name + ".png");
            const RenderedImage& image = renderer.render(load_scene_file(scene_file));
            const auto result = test::compare_with_golden(image, golden,
                                                          std::filesystem::path(TESSERA_BINARY_DIR) / "golden_failures",
                                                          "gltf_" + name);
            CHECK_MESSAGE(result.passed, name << ": " << result.message);
            MESSAGE(name << ": " << result.message);
        }
    }
}

// The comparison itself: what it lets through and what it catches.
TEST_CASE("golden comparison: a few pixels a few steps off pass, more or further fail") {
    Renderer renderer;
    const RenderedImage rendered = renderer.render(load_scene_file(test::scene_path("spheres.toml")));
    const std::filesystem::path golden = test::source_dir() / "golden" / "spheres.png";
    const std::filesystem::path failures = std::filesystem::path(TESSERA_BINARY_DIR) / "golden_failures";
    const auto shifted = [&](int pixels, int steps) {
        RenderedImage image = rendered;
        for (int p = 0; p < pixels; ++p) {
            std::uint8_t& value = image.display[std::size_t(p) * 3 * 997 % image.display.size() / 3 * 3];
            value = std::uint8_t(value >= 128 ? value - steps : value + steps);
        }
        const auto result = test::compare_with_golden(image, golden, failures, "comparison_check");
        MESSAGE(pixels << " pixels " << steps << " steps: " << result.message);
        return result.passed;
    };
    CHECK(shifted(0, 0));
    CHECK(shifted(3, 3));         // a glint or two
    CHECK_FALSE(shifted(20, 3));  // more pixels than kGoldenMaxFailFraction allows
    CHECK_FALSE(shifted(1, 20));  // one pixel, but beyond kGoldenMaxError
}
