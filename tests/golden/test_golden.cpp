#include <doctest/doctest.h>

#include <algorithm>

#include "check/report.hpp"
#include "check/runner.hpp"
#include "check/suite.hpp"
#include "tessera/renderer.hpp"
#include "test_paths.hpp"

using namespace tessera;

namespace {

std::filesystem::path golden_manifest() { return tessera::test::source_dir() / "tests" / "golden" / "check.toml"; }

// The reports of the golden suite: kept in the build tree, where CI picks them up when a run fails.
std::filesystem::path golden_report_dir(const char* name) { return tessera::test::binary_dir() / name; }

bool is_sample_model_scene(const check::SceneEntry& entry) { return entry.name.starts_with("gltf/"); }

// Renders `scenes`, writes the report to `report_dir` and checks every scene passed.
void check_golden(const std::vector<check::SceneEntry>& scenes, const std::filesystem::path& report_dir) {
    REQUIRE(!scenes.empty());
    check::RunOptions options;
    options.report_dir = report_dir;
    const check::CheckRun run = check::run_check(scenes, options);
    check::write_html_report(run, options.report_dir);
    check::write_junit_report(run, options.report_dir / "junit.xml");
    check::write_json_summary(run, options.report_dir / "summary.json");
    for (const check::SceneResult& r : run.scenes) {
        const bool passed = r.status == check::Status::pass || r.status == check::Status::warn;
        CHECK_MESSAGE(passed, check::describe(r) << " (report: " << (options.report_dir / "index.html").string() << ")");
        MESSAGE(check::describe(r));
    }
    CHECK(run.exit_status() == 0);
}

}  // namespace

// Every scene in scenes/ matches its golden image golden/<name>.png under
// tests/golden/check.toml's thresholds: the same code and manifest as
// `tessera check tests/golden/check.toml`.
TEST_CASE("every scene matches its golden image (tests/golden/check.toml through the check library)") {
    check::Suite suite = check::load_manifest(golden_manifest(), {});
    REQUIRE(std::any_of(suite.scenes.begin(), suite.scenes.end(), [](const auto& e) { return e.name == "spheres"; }));
    std::erase_if(suite.scenes, is_sample_model_scene);
    check_golden(suite.scenes, golden_report_dir("golden_report"));
}

// The same for scenes/gltf/ (golden/gltf/), which render the sample models: Skipped without them.
// Where TESSERA_ASSETS_DIR is another folder, the scenes are the build tree's copies naming it.
TEST_CASE("every sample-model scene (scenes/gltf) matches its golden image (tests/golden/check.toml)") {
    if (test::skip_without_assets()) return;
    check::Suite suite = check::load_manifest(golden_manifest(), {});
    std::erase_if(suite.scenes, [](const check::SceneEntry& e) { return !is_sample_model_scene(e); });
    REQUIRE(!suite.scenes.empty());
    for (check::SceneEntry& entry : suite.scenes) entry.scene = test::gltf_scenes_dir() / entry.scene.filename();
    check_golden(suite.scenes, golden_report_dir("golden_report_gltf"));
}

// The golden thresholds themselves: what they let through and what they catch.
TEST_CASE("golden thresholds: a few pixels a few steps off pass, more or further fail") {
    const check::Suite suite = check::load_manifest(golden_manifest(), {});
    const auto spheres = std::find_if(suite.scenes.begin(), suite.scenes.end(), [](const auto& e) { return e.name == "spheres"; });
    REQUIRE(spheres != suite.scenes.end());
    RenderSettings settings;
    settings.keep_radiance = false;
    Renderer renderer(settings);
    const RenderedImage rendered = renderer.render(load_scene_file(spheres->scene));
    const OIIO::ImageBuf golden = check::read_golden(tessera::test::source_dir() / "golden" / "spheres.png");
    const auto shifted = [&](int pixels, int steps) {
        RenderedImage image = rendered;
        for (int p = 0; p < pixels; ++p) {
            std::uint8_t& value = image.display[std::size_t(p) * 3 * 997 % image.display.size() / 3 * 3];
            value = std::uint8_t(value >= 128 ? value - steps : value + steps);
        }
        const check::Comparison result = check::compare_images(check::actual_image(image, check::GoldenKind::png), golden,
                                                               spheres->thresholds, check::GoldenKind::png);
        MESSAGE(pixels << " pixels " << steps << " steps: " << check::status_name(result.status) << " " << result.reason);
        return result.status;
    };
    CHECK(shifted(0, 0) == check::Status::pass);
    CHECK(shifted(3, 3) == check::Status::warn);   // a glint or two: counted, not failed
    CHECK(shifted(20, 3) == check::Status::fail);  // more pixels than fail_ratio allows
    CHECK(shifted(1, 20) == check::Status::fail);  // one pixel, but beyond max_error
    CHECK(shifted(1000, 2) == check::Status::fail);  // within the fail tolerance, but more than max_warn_ratio of the image
    CHECK(shifted(900, 2) == check::Status::warn);
}
