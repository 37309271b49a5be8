// `tessera render FILE.gltf --time SECONDS` and `--frames A-B` on a glTF file's
// own animation, through the real binary: poses differ, a frame of a range is
// bit-identical to the frame alone and to --time frame / 24, bad values are
// refused with one clear line.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "cli_runner.hpp"
#include "scene/gltf_animation_files.hpp"
#include "test_paths.hpp"

namespace fs = std::filesystem;
using tessera::test::read_file;

namespace {

tessera::test::CliRun render(const fs::path& dir, std::vector<std::string> args) {
    args.insert(args.end(), {"--width", "96", "--height", "64", "--threads", "2"});
    return tessera::test::run_tessera(dir, "render", args);
}

}  // namespace

TEST_CASE("tessera render FILE.gltf --time and --frames play the file's animation") {
    const fs::path dir = tessera::test::output_dir("cli_gltf_animation");
    fs::remove_all(dir / "frames");
    fs::create_directories(dir / "frames");
    const fs::path model = dir / "strip.gltf";
    std::ofstream(model) << tessera::test::skinned_strip_gltf();
    const std::string path = model.string();

    REQUIRE(render(dir, {path, "-o", (dir / "rest.png").string()}).status == 0);
    REQUIRE(render(dir, {path, "--time", "1", "-o", (dir / "t1.png").string()}).status == 0);
    REQUIRE(render(dir, {path, "--time", "0.5", "--animation", "bend", "-o", (dir / "t05.png").string()}).status == 0);
    CHECK(read_file(dir / "rest.png") != read_file(dir / "t1.png"));  // the strip bends
    CHECK(read_file(dir / "t05.png") != read_file(dir / "t1.png"));

    // 24 fps over the 1 s animation: frames 0-24. Frame 12 is 0.5 s; frame 24 the end.
    const tessera::test::CliRun range =
        render(dir, {path, "--frames", "0-24:4", "-o", (dir / "frames" / "f_{frame:02}.png").string()});
    REQUIRE_MESSAGE(range.status == 0, range.err);
    CHECK(fs::exists(dir / "frames" / "f_00.png"));
    CHECK(fs::exists(dir / "frames" / "f_24.png"));
    CHECK(read_file(dir / "frames" / "f_12.png") == read_file(dir / "t05.png"));
    CHECK(read_file(dir / "frames" / "f_24.png") == read_file(dir / "t1.png"));
    // Frame 12 alone, after no other frame: the same bytes as in the range.
    REQUIRE(render(dir, {path, "--frames", "12", "-o", (dir / "alone_{frame}.png").string()}).status == 0);
    CHECK(read_file(dir / "alone_12.png") == read_file(dir / "frames" / "f_12.png"));

    const tessera::test::CliRun past = render(dir, {path, "--frames", "25", "-o", (dir / "x_{frame}.png").string()});
    CHECK(past.status != 0);
    CHECK(past.err.find("frames 0-24") != std::string::npos);
}

TEST_CASE("tessera render --time and --animation refuse bad values with one line") {
    const fs::path dir = tessera::test::output_dir("cli_gltf_animation_errors");
    const fs::path model = dir / "strip.gltf";
    std::ofstream(model) << tessera::test::skinned_strip_gltf();
    const std::string path = model.string(), out = (dir / "x.png").string();
    const auto error_of = [&](std::vector<std::string> args) {
        const tessera::test::CliRun run = render(dir, args);
        CHECK(run.status != 0);
        CHECK_FALSE(fs::exists(out));
        return run.err;
    };
    CHECK(error_of({path, "--time", "nan", "-o", out}) ==
          "tessera: error: " + path + ": --time nan: expected a finite number of seconds >= 0\n");
    CHECK(error_of({path, "--time", "-0.5", "-o", out}) ==
          "tessera: error: " + path + ": --time -0.5: expected a finite number of seconds >= 0\n");
    CHECK(error_of({path, "--time", "soon", "-o", out}) == "tessera: error: --time 'soon': expected a number of seconds\n");
    CHECK(error_of({path, "--time", "1", "--animation", "walk", "-o", out}) ==
          "tessera: error: " + path + ": --animation 'walk' names no animation of the file; its animations: 0 'bend' (1 s)\n");
    CHECK(error_of({path, "--animation", "0", "-o", out}).find("--animation chooses what --time or --frames plays") !=
          std::string::npos);
    CHECK(error_of({path, "--time", "1", "--frames", "0-3", "-o", (dir / "x_{frame}.png").string()}) ==
          "tessera: error: --time renders one moment and --frames a range of them; give one of the two\n");
    const fs::path scene = dir / "scene.toml";
    std::ofstream(scene) << "[camera]\nposition = [0, 1, 6]\ntarget = [0, 1, 0]\n[[models]]\nfile = \"strip.gltf\"\n";
    CHECK(error_of({scene.string(), "--time", "1", "--animation", "0", "-o", out}) ==
          "tessera: error: " + scene.string() + ": --animation selects a glTF file's animation; in a TOML scene each "
          "[[models]] entry chooses its own with 'animation'\n");
    const fs::path still = dir / "still.gltf";
    std::ofstream(still) << tessera::test::embedded_test_gltf();
    CHECK(error_of({still.string(), "--time", "1", "-o", out}).find("no glTF model in the scene has an animation") !=
          std::string::npos);
}
