// The check library (src/check/): comparison and classification, manifests
// and their errors, a run over small scenes with every status, --update, EXR
// goldens, and the files a run leaves.
#include <doctest/doctest.h>

#include <fstream>
#include <sstream>

#include <OpenImageIO/imagebufalgo.h>
#include <nlohmann/json.hpp>

#include "check/compare.hpp"
#include "check/report.hpp"
#include "check/runner.hpp"
#include "check/suite.hpp"
#include "test_paths.hpp"

using namespace tessera;
namespace fs = std::filesystem;

namespace {

fs::path check_scenes() { return test::source_dir() / "tests" / "check" / "scenes"; }

// A fresh folder for one test case.
fs::path fresh_dir(const char* name) {
    const fs::path dir = test::output_dir("check") / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

OIIO::ImageBuf gray_image(int width, int height, float value, int channels = 3) {
    OIIO::ImageBuf image(OIIO::ImageSpec(width, height, channels, OIIO::TypeDesc::FLOAT));
    const std::vector<float> fill(std::size_t(channels), value);
    OIIO::ImageBufAlgo::fill(image, fill);
    return image;
}

// `image` with `pixels` pixels (along the first row) moved by `delta` in channel 0.
OIIO::ImageBuf with_changed_pixels(const OIIO::ImageBuf& image, int pixels, float delta) {
    OIIO::ImageBuf changed(image);
    for (int x = 0; x < pixels; ++x) {
        float value[4] = {};
        changed.getpixel(x, 0, value, 4);
        value[0] += delta;
        changed.setpixel(x, 0, value, 4);
    }
    return changed;
}

std::string read_text(const fs::path& path) {
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

void write_text(const fs::path& path, const std::string& text) {
    fs::create_directories(path.parent_path());
    std::ofstream(path) << text;
}

std::string manifest_error(const fs::path& manifest) {
    try {
        check::load_manifest(manifest, {});
    } catch (const check::ManifestError& e) {
        return e.what();
    }
    return "(no error)";
}

const check::SceneResult& result_named(const check::CheckRun& run, const std::string& name) {
    for (const check::SceneResult& r : run.scenes)
        if (r.name == name) return r;
    FAIL("no result for " << name);
    return run.scenes.front();
}

}  // namespace

TEST_CASE("check comparison: tolerances, pixel allowances, warn level and ceiling classify as documented") {
    const OIIO::ImageBuf golden = gray_image(100, 10, 0.5f);  // 1000 pixels
    check::Thresholds t;
    t.fail = 0.1;
    t.warn = 0.01;
    const auto status = [&](const OIIO::ImageBuf& actual) {
        return check::compare_images(actual, golden, t, check::GoldenKind::png).status;
    };
    CHECK(status(golden) == check::Status::pass);
    CHECK(status(with_changed_pixels(golden, 1, 0.005f)) == check::Status::pass);  // below warn
    CHECK(status(with_changed_pixels(golden, 1, 0.05f)) == check::Status::warn);   // beyond warn, within fail
    CHECK(status(with_changed_pixels(golden, 1, 0.2f)) == check::Status::fail);    // beyond fail, none allowed

    t.fail_pixels = 3;  // Playwright's maxDiffPixels
    CHECK(status(with_changed_pixels(golden, 3, 0.2f)) == check::Status::warn);
    CHECK(status(with_changed_pixels(golden, 4, 0.2f)) == check::Status::fail);
    t.fail_ratio = 0.01;  // maxDiffPixelRatio: 10 of 1000 pixels; the larger allowance counts
    CHECK(status(with_changed_pixels(golden, 10, 0.2f)) == check::Status::warn);
    CHECK(status(with_changed_pixels(golden, 11, 0.2f)) == check::Status::fail);

    t.max_error = 0.3;  // the hard ceiling fails one pixel
    CHECK(status(with_changed_pixels(golden, 1, 0.25f)) == check::Status::warn);
    CHECK(status(with_changed_pixels(golden, 1, 0.35f)) == check::Status::fail);

    t.warn_pixels = 5;  // a few pixels beyond warn pass quietly
    CHECK(status(with_changed_pixels(golden, 5, 0.05f)) == check::Status::pass);
    CHECK(status(with_changed_pixels(golden, 6, 0.05f)) == check::Status::warn);
    t.max_warn_ratio = 0.05;  // and too many of them fail
    CHECK(status(with_changed_pixels(golden, 50, 0.05f)) == check::Status::warn);
    CHECK(status(with_changed_pixels(golden, 51, 0.05f)) == check::Status::fail);

    const check::Comparison numbers = check::compare_images(with_changed_pixels(golden, 2, 0.2f), golden, t,
                                                            check::GoldenKind::png);
    CHECK(numbers.compared);
    CHECK(numbers.metrics.pixels == 1000);
    CHECK(numbers.metrics.pixels_over_fail == 2);
    CHECK(numbers.metrics.pixels_over_warn == 2);  // failing pixels are beyond warn too
    CHECK(numbers.metrics.max_error == doctest::Approx(0.2).epsilon(1e-4));
    CHECK(numbers.metrics.max_y == 0);
}

TEST_CASE("check comparison: size and channel differences fail with the reason") {
    const check::Thresholds t;
    const check::Comparison size = check::compare_images(gray_image(8, 8, 0.5f), gray_image(8, 9, 0.5f), t,
                                                         check::GoldenKind::png);
    CHECK(size.status == check::Status::fail);
    CHECK_FALSE(size.compared);
    CHECK(size.reason == "size differs: golden 8x9, render 8x8");
    const check::Comparison rgba = check::compare_images(gray_image(8, 8, 0.5f), gray_image(8, 8, 0.5f, 4), t,
                                                         check::GoldenKind::png);
    CHECK(rgba.status == check::Status::fail);
    CHECK(rgba.reason.find("channels differ: golden has 4") != std::string::npos);
}

TEST_CASE("check comparison: the perceptual test runs and counts visible differences") {
    check::Thresholds t;
    t.fail = 1.0;  // only the perceptual test can fail here
    t.warn = 1.0;
    t.perceptual = true;
    const OIIO::ImageBuf golden = gray_image(64, 64, 0.5f);
    const check::Comparison same = check::compare_images(golden, golden, t, check::GoldenKind::png);
    CHECK(same.status == check::Status::pass);
    CHECK(same.metrics.perceptual_fail == 0);
    OIIO::ImageBuf blotch(golden);
    OIIO::ImageBufAlgo::fill(blotch, {1.0f, 0.0f, 0.0f}, OIIO::ROI(16, 48, 16, 48));
    const check::Comparison visible = check::compare_images(blotch, golden, t, check::GoldenKind::png);
    CHECK(visible.metrics.perceptual_fail > 100);
    CHECK(visible.status == check::Status::fail);
}

TEST_CASE("check manifest: scenes, globs, names below the scene root, thresholds and overrides") {
    const fs::path dir = fresh_dir("manifest");
    const fs::path scenes = check_scenes();
    write_text(dir / "check.toml",
               "scenes = [\"" + scenes.string() + "/ball.toml\", \"" + scenes.string() + "/more/*.toml\", \"" +
                   scenes.string() + "/cube.toml\"]\n"
                   "golden = \"golden\"\nreport = \"out\"\nwidth = 48\nmsaa = 4\n"
                   "[thresholds]\nfail = 0.02\nfail_pixels = 3\nperceptual = true\n"
                   "[[override]]\nscenes = \"more/*\"\nfail = 0.5\nmax_warn_ratio = 0.25\nheight = 40\n");
    const check::Suite suite = check::load_manifest(dir / "check.toml", {{{"warn", 0.001}}, false, 0, 0, 0});
    REQUIRE(suite.scenes.size() == 3);
    CHECK(suite.scenes[0].name == "ball");  // the order given
    CHECK(suite.scenes[1].name == "more/glint");
    CHECK(suite.scenes[2].name == "cube");
    CHECK(suite.scenes[1].golden_stem == dir / "golden" / "more" / "glint");
    CHECK(suite.report_dir == dir / "out");
    CHECK(suite.scenes[0].thresholds.fail == 0.02);
    CHECK(suite.scenes[0].thresholds.fail_pixels == 3);
    CHECK(suite.scenes[0].thresholds.perceptual);
    CHECK(suite.scenes[0].thresholds.warn == 0.001);  // from the command line
    CHECK(suite.scenes[1].thresholds.fail == 0.5);    // the override wins
    CHECK(suite.scenes[1].thresholds.max_warn_ratio == 0.25);
    CHECK(suite.scenes[1].thresholds.fail_pixels == 3);
    CHECK_FALSE(suite.scenes[0].thresholds.max_warn_ratio.has_value());
    CHECK(suite.scenes[0].width == 48);
    CHECK(suite.scenes[0].height == 0);
    CHECK(suite.scenes[1].height == 40);
    CHECK(suite.scenes[2].msaa == 4);
}

TEST_CASE("check manifest: mistakes name the file, line and column") {
    const fs::path dir = fresh_dir("manifest_errors");
    const std::string scenes = check_scenes().string();
    const auto error_for = [&](const std::string& text) {
        write_text(dir / "check.toml", text);
        return manifest_error(dir / "check.toml");
    };
    const std::string file = (dir / "check.toml").string();
    CHECK(error_for("golden = \"g\"\nscenes = [\"" + scenes + "/*.toml\"]\ncolour = 1\n") ==
          file + ":3:1: unknown key 'colour' (expected scenes, golden, scene_root, new_golden_format, report, width, "
                 "height, msaa, [thresholds] or [[override]])");
    CHECK(error_for("golden = \"g\"\nscenes = [\"" + scenes + "/nothing*.toml\"]\n") ==
          file + ":2:11: '" + scenes + "/nothing*.toml' matches no scene file");
    CHECK(error_for("golden = \"g\"\nscenes = \"" + scenes + "/ball.toml\"\n[thresholds]\nfail = \"small\"\n") ==
          file + ":4:8: expected a number for 'thresholds.fail', got string");
    CHECK(error_for("golden = \"g\"\nscenes = \"" + scenes + "/ball.toml\"\n[thresholds]\nfail_ratio = 2\n") ==
          file + ":4:14: expected a fraction of the image in [0, 1], got 2.000000 for 'thresholds.fail_ratio'");
    CHECK(error_for("golden = \"g\"\nscenes = \"" + scenes + "/ball.toml\"\n[[override]]\nscenes = \"bal\"\n") ==
          file + ":4:10: 'bal' matches no scene name");
    CHECK(error_for("golden = \"g\"\nscenes = \"" + scenes + "/ball.toml\"\nmsaa = 2\n") ==
          file + ":3:8: expected 'msaa' to be 1 or 4, got 2");
    CHECK(error_for("scenes = \"" + scenes + "/ball.toml\"\n") == file + ": missing required key 'golden'");
    CHECK(error_for("golden = [1\n").starts_with(file + ":1:"));  // a TOML syntax error
    CHECK(manifest_error(dir / "absent.toml") == (dir / "absent.toml").string() + ": cannot open manifest");
}

TEST_CASE("check run: pass, fail, missing and error in one run, then --update, and the report files") {
    const fs::path dir = fresh_dir("run");
    const fs::path golden = dir / "golden";
    const std::vector<std::string> patterns = {(check_scenes() / "*.toml").string(),
                                               (check_scenes() / "more" / "*.toml").string()};
    const check::Suite suite = check::suite_from_arguments(patterns, golden, {}, {});
    REQUIRE(suite.scenes.size() == 4);  // ball, broken, cube, more/glint
    check::RunOptions options;
    options.report_dir = dir / "report";

    // No goldens yet: --update=missing adds them (not for the scene that does not load).
    options.update = check::UpdateMode::missing;
    const check::CheckRun first = check::run_check(suite.scenes, options);
    CHECK(result_named(first, "ball").status == check::Status::missing);
    CHECK(result_named(first, "broken").status == check::Status::error);
    CHECK(result_named(first, "broken").reason.find("broken.toml:2:1: missing required key 'camera.target'") !=
          std::string::npos);
    CHECK(result_named(first, "ball").update == "added " + (golden / "ball.png").string());
    CHECK(fs::exists(golden / "more" / "glint.png"));
    CHECK_FALSE(fs::exists(golden / "broken.png"));
    CHECK(first.exit_status() == 1);  // the error remains

    // A changed golden fails; the others pass, bit-identical.
    fs::copy_file(golden / "cube.png", golden / "ball.png", fs::copy_options::overwrite_existing);
    options.update = check::UpdateMode::none;
    const check::CheckRun second = check::run_check(suite.scenes, options);
    const check::SceneResult& ball = result_named(second, "ball");
    CHECK(ball.status == check::Status::fail);
    CHECK(ball.metrics.pixels_over_fail > 1000);
    CHECK(result_named(second, "cube").status == check::Status::pass);
    CHECK(result_named(second, "cube").metrics.max_error == 0);
    CHECK(second.exit_status() == 1);
    CHECK(fs::exists(options.report_dir / ball.images.diff));
    CHECK(fs::exists(options.report_dir / ball.images.expected));
    // Identical: one image, the golden linked (or copied) into the report, so that the folder works on its own.
    CHECK(result_named(second, "cube").images.expected == "images/cube.golden.png");
    CHECK(fs::exists(options.report_dir / "images" / "cube.golden.png"));
    const std::vector<const check::SceneResult*> order = check::worst_first(second);
    CHECK(order[0]->name == "broken");
    CHECK(order[1]->name == "ball");

    check::write_html_report(second, options.report_dir);
    check::write_junit_report(second, options.report_dir / "junit.xml");
    check::write_json_summary(second, options.report_dir / "summary.json");
    const std::string html = read_text(options.report_dir / "index.html");
    CHECK(html.find("id=\"scene-ball\" data-status=\"fail\"") < html.find("id=\"scene-cube\" data-status=\"pass\""));
    CHECK(html.find("loading=\"lazy\"") != std::string::npos);
    CHECK(html.find("data:image") == std::string::npos);  // no inlined images
    const std::string junit = read_text(options.report_dir / "junit.xml");
    CHECK(junit.find("tests=\"4\" failures=\"1\" errors=\"1\"") != std::string::npos);
    const nlohmann::json summary = nlohmann::json::parse(read_text(options.report_dir / "summary.json"));
    CHECK(summary["counts"]["fail"] == 1);
    CHECK(summary["counts"]["pass"] == 2);
    CHECK(summary["scenes"].size() == 4);
    CHECK(summary["exit_status"] == 1);

    // --update rewrites the failing golden (never the error's), and then it passes.
    options.update = check::UpdateMode::failed;
    const check::CheckRun third = check::run_check(suite.scenes, options);
    CHECK(result_named(third, "ball").update.starts_with("updated " + (golden / "ball.png").string() + " (it differed: "));
    CHECK(third.exit_status() == 1);  // still the error
    options.update = check::UpdateMode::none;
    std::vector<check::SceneEntry> loadable = suite.scenes;
    std::erase_if(loadable, [](const check::SceneEntry& e) { return e.name == "broken"; });
    const check::CheckRun fourth = check::run_check(loadable, options);
    CHECK(fourth.count(check::Status::pass) == 3);
    CHECK(fourth.exit_status() == 0);
    CHECK_FALSE(fs::exists(options.report_dir / "images" / "ball.diff.png"));  // an earlier run's images are gone
    for (const auto& entry : fs::recursive_directory_iterator(dir))  // every write was renamed into place
        CHECK(entry.path().string().find(".tmp.") == std::string::npos);
}

TEST_CASE("check run: EXR goldens compare scene-linear radiance, and size overrides apply") {
    const fs::path dir = fresh_dir("exr");
    check::Suite suite = check::suite_from_arguments({(check_scenes() / "more" / "glint.toml").string()},
                                                     dir / "golden", {}, {});
    suite.scenes[0].width = 40;
    suite.scenes[0].height = 30;
    check::RunOptions options;
    options.report_dir = dir / "report";
    options.new_golden_format = check::GoldenFormat::exr;
    options.update = check::UpdateMode::missing;
    const check::CheckRun made = check::run_check(suite.scenes, options);
    REQUIRE(made.scenes[0].status == check::Status::missing);
    const fs::path exr = dir / "golden" / "glint.exr";
    REQUIRE(fs::exists(exr));

    options.update = check::UpdateMode::none;
    const check::CheckRun same = check::run_check(suite.scenes, options);
    CHECK(same.scenes[0].status == check::Status::pass);  // bit-identical at half precision
    CHECK(same.scenes[0].golden_kind == check::GoldenKind::exr);
    CHECK(same.scenes[0].width == 40);

    // The glint's peak radiance is above 1: an EXR keeps it, and a change there is seen in radiance units.
    OIIO::ImageBuf golden = check::read_golden(exr);
    float peak[3] = {};
    const OIIO::ImageBufAlgo::PixelStats stats = OIIO::ImageBufAlgo::computePixelStats(golden);
    peak[0] = stats.max[0];
    CHECK(peak[0] > 1.0f);  // beyond what a display value can hold
    golden = OIIO::ImageBufAlgo::mul(golden, 1.05f);  // 5% brighter everywhere
    REQUIRE(golden.write(exr.string(), OIIO::TypeDesc::HALF));
    suite.scenes[0].thresholds.fail = 0.05;  // radiance units
    const check::CheckRun brighter = check::run_check(suite.scenes, options);
    CHECK(brighter.scenes[0].status == check::Status::fail);
    CHECK(brighter.scenes[0].metrics.max_error > 0.05);
    suite.scenes[0].thresholds.fail_relative = 0.1;  // a 5% change is within 10% of the value
    const check::CheckRun relative = check::run_check(suite.scenes, options);
    CHECK(relative.scenes[0].status == check::Status::warn);
    CHECK(fs::exists(options.report_dir / relative.scenes[0].images.expected));  // a tonemapped preview of the EXR
}
