// scenes/turntable.toml's frames against golden/turntable/frame_NNNN.png: the
// sphere grid from 45° round, from behind, and from 45° short of the front
// again (frame 0, the front, is golden/turntable.png, checked with every scene),
// compared by the check library under the golden suite's thresholds
// (tests/golden/check.toml). Regenerate with
//   build/tessera render scenes/turntable.toml --frames 30-210:90 -o golden/turntable/frame_{frame:04}.png
#include <doctest/doctest.h>

#include <algorithm>

#include "batch/frames.hpp"
#include "check/compare.hpp"
#include "check/suite.hpp"
#include "tessera/animation.hpp"
#include "tessera/renderer.hpp"
#include "test_paths.hpp"

using namespace tessera;

TEST_CASE("turntable frames 30, 120 and 210 match their golden images") {
    const check::Suite suite = check::load_manifest(test::source_dir() / "tests" / "golden" / "check.toml", {});
    const auto entry =
        std::find_if(suite.scenes.begin(), suite.scenes.end(), [](const auto& e) { return e.name == "turntable"; });
    REQUIRE(entry != suite.scenes.end());
    Scene scene = load_scene_file(test::scene_path("turntable.toml"));
    REQUIRE(scene_frame_count(scene) == 240);
    Renderer renderer;
    for (const int frame : {30, 120, 210}) {
        const std::string name = batch::expand_output_pattern("frame_{frame:04}", "", frame);
        SUBCASE(name.c_str()) {
            set_scene_frame(scene, frame);
            const RenderedImage& image = renderer.render(scene);
            const OIIO::ImageBuf golden =
                check::read_golden(test::source_dir() / "golden" / "turntable" / (name + ".png"));
            const check::Comparison result = check::compare_images(check::actual_image(image, check::GoldenKind::png),
                                                                   golden, entry->thresholds, check::GoldenKind::png);
            CHECK_MESSAGE((result.status == check::Status::pass || result.status == check::Status::warn),
                          name << ": " << result.reason);
            MESSAGE(name << ": " << check::status_name(result.status) << " " << result.reason);
        }
    }
}
