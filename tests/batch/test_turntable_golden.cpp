// scenes/turntable.toml's frames against golden/turntable/frame_NNNN.png: the
// sphere grid from 45° round, from behind, and from 45° short of the front
// again (frame 0, the front, is golden/turntable.png, checked with every scene). Regenerate with
//   build/tessera render scenes/turntable.toml --frames 30-210:90 -o golden/turntable/frame_{frame:04}.png
#include <doctest/doctest.h>

#include "batch/frames.hpp"
#include "golden/golden_compare.hpp"
#include "tessera/animation.hpp"
#include "tessera/renderer.hpp"
#include "test_paths.hpp"

using namespace tessera;

TEST_CASE("turntable frames 30, 120 and 210 match their golden images") {
    Scene scene = load_scene_file(test::scene_path("turntable.toml"));
    REQUIRE(scene_frame_count(scene) == 240);
    Renderer renderer;
    for (const int frame : {30, 120, 210}) {
        const std::string name = batch::expand_output_pattern("frame_{frame:04}", "", frame);
        SUBCASE(name.c_str()) {
            set_scene_frame(scene, frame);
            const RenderedImage& image = renderer.render(scene);
            const auto result = test::compare_with_golden(image, test::source_dir() / "golden" / "turntable" / (name + ".png"),
                                                          std::filesystem::path(TESSERA_BINARY_DIR) / "golden_failures",
                                                          "turntable_" + name);
            CHECK_MESSAGE(result.passed, name << ": " << result.message);
            MESSAGE(name << ": " << result.message);
        }
    }
}
