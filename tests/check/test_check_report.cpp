// The check library's subsets and report folder: --filter, --update NAME...,
// the images an earlier run left, a folder whose links all stay inside it, and
// previews of EXR goldens encoded as the renderer's PNG and tagged sRGB.
#include <doctest/doctest.h>

#include <fstream>
#include <regex>
#include <sstream>

#include <OpenImageIO/imagebufalgo.h>

#include "check/compare.hpp"
#include "check/report.hpp"
#include "check/runner.hpp"
#include "check/suite.hpp"
#include "test_paths.hpp"

using namespace tessera;
namespace fs = std::filesystem;

namespace {

fs::path check_scenes() { return test::source_dir() / "tests" / "check" / "scenes"; }

fs::path fresh_dir(const char* name) {
    const fs::path dir = test::output_dir("check_report") / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string read_bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// ball, cube and more/glint (broken.toml does not load).
check::Suite three_scenes(const fs::path& golden) {
    return check::suite_from_arguments({(check_scenes() / "ball.toml").string(), (check_scenes() / "cube.toml").string(),
                                        (check_scenes() / "more" / "glint.toml").string()},
                                       golden, {}, {});
}

const check::SceneResult& named(const check::CheckRun& run, const std::string& name) {
    for (const check::SceneResult& r : run.scenes)
        if (r.name == name) return r;
    FAIL("no result for " << name);
    return run.scenes.front();
}

// Moves channel 0 of the golden's pixels [x0, x0 + 6) of row y by delta (through float).
void change_golden(const fs::path& golden, int x0, int y, float delta) {
    OIIO::ImageBuf image(golden.string());
    REQUIRE(image.read(0, 0, true, OIIO::TypeDesc::FLOAT));
    for (int x = x0; x < x0 + 6; ++x) {
        float v[3];
        image.getpixel(x, y, v, 3);
        v[0] += delta;
        image.setpixel(x, y, v, 3);
    }
    const bool exr = golden.extension() == ".exr";
    REQUIRE(image.write(golden.string(), exr ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::UINT8));
}

}  // namespace

TEST_CASE("check filter: globs over scene names keep the suite's order, a glob that matches nothing is named") {
    const check::Suite suite = three_scenes("golden");
    const auto names = [](const std::vector<check::SceneEntry>& scenes) {
        std::vector<std::string> out;
        for (const check::SceneEntry& e : scenes) out.push_back(e.name);
        return out;
    };
    CHECK(names(check::filter_scenes(suite.scenes, {"more/*"})) == std::vector<std::string>{"more/glint"});
    CHECK(names(check::filter_scenes(suite.scenes, {"*glint", "ball"})) == std::vector<std::string>{"ball", "more/glint"});
    CHECK(names(check::filter_scenes(suite.scenes, {"*"})).size() == 3);
    try {
        check::filter_scenes(suite.scenes, {"ball", "gltf/*"});
        FAIL("a filter that matches nothing was accepted");
    } catch (const check::ManifestError& e) {
        CHECK(std::string(e.what()) == "--filter 'gltf/*' matches no scene name of the suite");
    }
}

TEST_CASE("check --update NAME...: only the named scenes are updated, whatever they differ by") {
    const fs::path dir = fresh_dir("update_names");
    const check::Suite suite = three_scenes(dir / "golden");
    check::RunOptions options;
    options.report_dir = dir / "report";
    options.update = check::UpdateMode::missing;
    check::run_check(suite.scenes, options);

    change_golden(dir / "golden" / "ball.png", 10, 5, 0.5f);   // fails
    change_golden(dir / "golden" / "cube.png", 10, 5, 0.5f);   // fails
    std::vector<check::SceneEntry> scenes = suite.scenes;
    for (check::SceneEntry& e : scenes)
        if (e.name == "cube") e.thresholds.fail_pixels = e.thresholds.warn_pixels = 6;  // cube: a pass
    options.update = check::UpdateMode::named;
    options.update_names = {"cube", "more/*"};
    const check::CheckRun run = check::run_check(scenes, options);
    CHECK(named(run, "ball").update.empty());  // failing, but not named
    CHECK(named(run, "ball").status == check::Status::fail);
    CHECK(named(run, "cube").status == check::Status::pass);
    CHECK(named(run, "cube").update.starts_with("updated "));  // named, passing within a tolerance: updated
    CHECK(named(run, "more/glint").update.empty());  // named, but bit-identical: nothing to write
    options.update = check::UpdateMode::none;
    const check::CheckRun after = check::run_check(scenes, options);
    CHECK(named(after, "cube").metrics.max_error == 0);
    CHECK(named(after, "ball").status == check::Status::fail);
}

TEST_CASE("check report folder: an earlier run's images and the folders they leave empty are removed, other files kept") {
    const fs::path dir = fresh_dir("stale");
    const check::Suite suite = three_scenes(dir / "golden");
    check::RunOptions options;
    options.report_dir = dir / "report";
    options.update = check::UpdateMode::missing;
    check::run_check(suite.scenes, options);  // every scene missing: an actual image each
    CHECK(fs::exists(options.report_dir / "images" / "more" / "glint.actual.png"));
    std::ofstream(options.report_dir / "notes.txt") << "the user's";
    std::ofstream(options.report_dir / "images" / "keep.txt") << "the user's";

    options.update = check::UpdateMode::none;
    const check::CheckRun run = check::run_check(check::filter_scenes(suite.scenes, {"ball"}), options);
    std::vector<std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(options.report_dir))
        files.push_back(entry.path().lexically_relative(options.report_dir).generic_string());
    std::sort(files.begin(), files.end());
    CHECK(files == std::vector<std::string>{"images", "images/ball.golden.png", "images/keep.txt", "notes.txt"});
    CHECK(run.scenes[0].images.expected == "images/ball.golden.png");
}

TEST_CASE("check report folder: every link stays inside it, so the folder alone is a working report") {
    const fs::path dir = fresh_dir("self_contained");
    const check::Suite suite = three_scenes(dir / "golden");
    check::RunOptions options;
    options.report_dir = dir / "out" / "report";
    options.update = check::UpdateMode::missing;
    check::run_check(suite.scenes, options);
    change_golden(dir / "golden" / "ball.png", 10, 5, 0.5f);
    options.update = check::UpdateMode::none;
    const check::CheckRun run = check::run_check(suite.scenes, options);
    check::write_html_report(run, options.report_dir);

    // The folder moved away from the goldens, as a CI artifact is: every src and href still resolves inside it.
    const fs::path moved = dir / "artifact";
    fs::copy(options.report_dir, moved, fs::copy_options::recursive);
    fs::remove_all(dir / "golden");
    const std::string html = read_bytes(moved / "index.html");
    const std::regex link("(src|href)=\"([^\"]*)\"");
    int images = 0;
    for (auto it = std::sregex_iterator(html.begin(), html.end(), link); it != std::sregex_iterator(); ++it) {
        const std::string target = (*it)[2];
        if (target == "#") continue;
        INFO(target);
        CHECK(target.find("..") == std::string::npos);
        CHECK(target.find(':') == std::string::npos);  // no file:, http: or absolute Windows paths
        CHECK(target.front() != '/');
        CHECK(fs::is_regular_file(moved / target));
        ++images;
    }
    CHECK(images >= 5);  // ball: expected, actual, diff (and the slider's two); cube and glint: their golden
}

TEST_CASE("check report: an EXR golden's preview is the renderer's PNG encoding, and report images are tagged sRGB") {
    const fs::path dir = fresh_dir("exr_preview");
    const check::Suite suite =
        check::suite_from_arguments({(check_scenes() / "ball.toml").string()}, dir / "golden", {}, {});
    check::RunOptions options;
    options.report_dir = dir / "report";
    options.new_golden_format = check::GoldenFormat::exr;
    options.update = check::UpdateMode::missing;
    check::run_check(suite.scenes, options);
    const fs::path exr = dir / "golden" / "ball.exr";
    REQUIRE(fs::exists(exr));
    change_golden(exr, 0, 0, 4.0f);  // six pixels of the top row much brighter
    options.update = check::UpdateMode::none;
    const check::CheckRun run = check::run_check(suite.scenes, options);
    const check::SceneResult& r = run.scenes[0];
    REQUIRE(r.status == check::Status::fail);

    OIIO::ImageBuf expected((options.report_dir / r.images.expected).string());
    OIIO::ImageBuf actual((options.report_dir / r.images.actual).string());
    REQUIRE(expected.read(0, 0, true, OIIO::TypeDesc::UINT8));
    REQUIRE(actual.read(0, 0, true, OIIO::TypeDesc::UINT8));
    // The render's PNG holds 8-bit display values of its float radiance, the preview those of the golden's
    // half radiance: the same encoding, so at most one step apart where the radiance agrees.
    const OIIO::ImageBuf difference = OIIO::ImageBufAlgo::absdiff(expected, actual, OIIO::ROI(0, 96, 1, 64));
    const OIIO::ImageBufAlgo::PixelStats stats = OIIO::ImageBufAlgo::computePixelStats(difference);
    for (int c = 0; c < 3; ++c) CHECK(stats.max[c] <= 1.0f / 255.0f + 1e-6f);
    float top[3], below[3];
    expected.getpixel(2, 0, top, 3);
    actual.getpixel(2, 0, below, 3);
    CHECK(top[0] > below[0]);  // the brighter golden shows brighter

    // Tagged sRGB (an sRGB chunk), not as linear light (gAMA 1.0, which browsers would show washed out).
    for (const std::string& image : {r.images.expected, r.images.actual, r.images.diff}) {
        INFO(image);
        const std::string png = read_bytes(options.report_dir / image);
        CHECK(png.find("sRGB") != std::string::npos);
        CHECK(png.find(std::string("gAMA\x00\x01\x86\xa0", 8)) == std::string::npos);
        CHECK(OIIO::ImageBuf((options.report_dir / image).string()).spec().get_string_attribute("oiio:ColorSpace") ==
              "sRGB");
    }
}
