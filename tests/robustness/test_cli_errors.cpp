// The tessera binary on bad input: a non-zero exit, one clear line on stderr
// (file:line:column for scene errors), no output file, and no earlier file lost.
// Also several scenes in one call, with {scene} in the output names, and
// --aov beside PNG output.
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "cli_runner.hpp"
#include "robustness/bad_scenes.hpp"
#include "scene/gltf_test_files.hpp"
#include "test_paths.hpp"

namespace fs = std::filesystem;

namespace {

using Run = tessera::test::CliRun;
using tessera::test::quoted;
using tessera::test::read_file;

void write_file(const fs::path& path, std::string_view text) {
    std::ofstream(path, std::ios::binary).write(text.data(), std::streamsize(text.size()));
}

// Runs `tessera render ARGS` with stdout and stderr captured in files beside `dir`.
Run tessera_render(const fs::path& dir, const std::vector<std::string>& args) {
    return tessera::test::run_tessera(dir, "render", args);
}

// A quick valid scene: a small image of one lit sphere.
constexpr std::string_view kSmallScene =
    "[output]\nwidth = 48\nheight = 32\n"
    "[camera]\nposition = [0, 0, 4]\ntarget = [0, 0, 0]\n"
    "[[lights]]\nposition = [3, 3, 5]\ncolor = [40, 40, 40]\n"
    "[[objects]]\nmesh = \"sphere\"\n";

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

// The line of `err` about `scene`, or "".
std::string error_line_for(const std::string& err, const std::string& scene) {
    const std::string prefix = "tessera: error: " + scene + ":";
    std::istringstream lines(err);
    for (std::string line; std::getline(lines, line);)
        if (line.rfind(prefix, 0) == 0) return line;
    return "";
}

std::string with_file_name(std::string_view expected, const std::string& file) {
    std::string text(expected);
    for (std::size_t at = text.find('@'); at != std::string::npos; at = text.find('@', at + file.size()))
        text.replace(at, 1, file);
    return text;
}

// Every row of the table in one call (a process start costs more than a bad
// scene), which also shows that one failing scene does not stop the others;
// a few rows alone, for the exit status of a single scene.
TEST_CASE("the CLI refuses every bad scene file with its position and a non-zero exit") {
    const fs::path dir = tessera::test::output_dir("cli_bad_scenes");
    std::vector<std::string> args;
    for (const tessera::test::BadScene& row : tessera::test::bad_scenes()) {
        const fs::path scene = dir / (std::string(row.name) + ".toml");
        write_file(scene, row.text);
        fs::remove(dir / (std::string(row.name) + ".png"));
        args.push_back(scene.string());
    }
    args.push_back("-o");
    args.push_back((dir / "{scene}.png").string());
    const Run run = tessera_render(dir, args);
    CHECK(run.status == 1);
    const std::size_t rows = tessera::test::bad_scenes().size();
    CHECK(contains(run.err, "rendered 0 of " + std::to_string(rows) + " scenes; failed: "));
    for (const tessera::test::BadScene& row : tessera::test::bad_scenes()) {
        const std::string row_name = row.name;
        CAPTURE(row_name);
        const std::string scene = (dir / (row_name + ".toml")).string();
        const std::string line = error_line_for(run.err, scene);
        CHECK_MESSAGE(!line.empty(), "no error line for " << scene << " in:\n" << run.err);
        for (std::string_view part : row.expected) {
            const std::string wanted = with_file_name(part, scene);
            CHECK_MESSAGE(contains(line, wanted), "'" << wanted << "' not in: " << line);
        }
        CHECK_FALSE(fs::exists(dir / (row_name + ".png")));
    }

    for (const char* name : {"unclosed_table_header", "unknown_camera_key", "too_many_pixels", "fov_zero"}) {
        const std::string row_name = name;
        CAPTURE(row_name);
        const std::string scene = (dir / (row_name + ".toml")).string();
        const Run single = tessera_render(dir, {scene, "-o", (dir / (row_name + ".png")).string()});
        CHECK(single.status == 1);
        CHECK_MESSAGE(single.err.rfind("tessera: error: " + scene + ":", 0) == 0, single.err);
        CHECK(std::count(single.err.begin(), single.err.end(), '\n') == 1);  // one line
        CHECK_FALSE(fs::exists(dir / (row_name + ".png")));
    }
}

TEST_CASE("the CLI refuses every bad glTF file with its path and a non-zero exit") {
    const fs::path dir = tessera::test::output_dir("cli_bad_gltf");
    std::vector<std::string> args;
    const std::vector<tessera::test::BadGltf> rows = tessera::test::bad_gltf_files();
    for (const tessera::test::BadGltf& row : rows) {
        const fs::path file = dir / (row.name + row.extension);
        write_file(file, row.bytes);
        fs::remove(dir / (row.name + ".png"));
        args.push_back(file.string());
    }
    args.push_back("-o");
    args.push_back((dir / "{scene}.png").string());
    const Run run = tessera_render(dir, args);
    CHECK(run.status == 1);
    CHECK(contains(run.err, "rendered 0 of " + std::to_string(rows.size()) + " scenes; failed: "));
    for (const tessera::test::BadGltf& row : rows) {
        CAPTURE(row.name);
        const std::string file = (dir / (row.name + row.extension)).string();
        const std::string line = error_line_for(run.err, file);
        CHECK_MESSAGE(!line.empty(), "no error line for " << file << " in:\n" << run.err);
        for (const std::string& part : row.expected) {
            const std::string wanted = with_file_name(part, file);
            CHECK_MESSAGE(contains(line, wanted), "'" << wanted << "' not in: " << line);
        }
        CHECK_FALSE(fs::exists(dir / (row.name + ".png")));
    }
}

TEST_CASE("the CLI renders a .glb on its own") {
    const fs::path dir = tessera::test::output_dir("cli_gltf");
    const fs::path model = dir / "document.glb";
    write_file(model, [] {
        const std::vector<std::uint8_t> bytes = tessera::test::test_glb();
        return std::string(bytes.begin(), bytes.end());
    }());
    fs::remove(dir / "document.png");
    const Run run = tessera_render(dir, {model.string(), "-o", (dir / "document.png").string(), "--width", "64"});
    CHECK_MESSAGE(run.status == 0, run.err);
    CHECK(fs::exists(dir / "document.png"));
}

TEST_CASE("the CLI's --camera picks a glTF file's camera by index or name, and refuses one it does not have") {
    const fs::path dir = tessera::test::output_dir("cli_gltf_camera");
    const fs::path model = dir / "document.gltf";
    write_file(model, tessera::test::embedded_test_gltf());
    const std::string out = (dir / "document.png").string();
    for (const char* selector : {"0", "camera"}) {  // the unnamed camera goes by its node's name
        fs::remove(out);
        const Run run = tessera_render(dir, {model.string(), "-o", out, "--width", "32", "--camera", selector});
        CHECK_MESSAGE(run.status == 0, run.err);
        CHECK(fs::exists(out));
    }
    fs::remove(out);
    const Run wrong = tessera_render(dir, {model.string(), "-o", out, "--camera", "7"});
    CHECK(wrong.status == 1);
    CHECK(contains(wrong.err, "document.gltf: --camera '7' names no camera of the file; its cameras: 0 'camera' (perspective)"));
    CHECK_FALSE(fs::exists(out));
}

TEST_CASE("the CLI refuses bad files, arguments and sizes") {
    const fs::path dir = tessera::test::output_dir("cli_bad_arguments");
    const fs::path scene = dir / "small.toml";
    write_file(scene, kSmallScene);
    const std::string out = (dir / "out.png").string();

    SUBCASE("a missing scene file") {
        const Run run = tessera_render(dir, {(dir / "nonexistent.toml").string(), "-o", out});
        CHECK(run.status == 1);
        CHECK(contains(run.err, "nonexistent.toml: cannot open scene file"));
    }
    SUBCASE("a folder as the scene file") {
        const Run run = tessera_render(dir, {dir.string(), "-o", out});
        CHECK(run.status == 1);
        CHECK(contains(run.err, "cannot read scene file: it is a folder, not a regular file"));
    }
    SUBCASE("an unsupported output format") {
        const Run run = tessera_render(dir, {scene.string(), "-o", (dir / "out.jpg").string()});
        CHECK(run.status == 2);  // a usage error: refused before any work
        CHECK(contains(run.err, "out.jpg: unsupported output format"));
    }
    SUBCASE("--width and --height at the limit per side but too many pixels together") {
        const Run run = tessera_render(dir, {scene.string(), "-o", out, "--width", "16384", "--height", "16384"});
        CHECK(run.status == 1);
        CHECK(contains(run.err, "image size 16384x16384 (after --width/--height) is 268435456 pixels; at most "
                                "134217728 are allowed"));
    }
    SUBCASE("an override too large, zero or negative") {
        for (const char* value : {"16385", "0", "-3", "1e9", "wide"}) {
            const std::string value_text = value;
            CAPTURE(value_text);
            const Run run = tessera_render(dir, {scene.string(), "-o", out, "--width", value});
            CHECK(run.status > 0);
            CHECK(contains(run.err, "--width"));
        }
    }
    SUBCASE("a bad ISA or tile size is an error, not a crash") {
        Run run = tessera_render(dir, {scene.string(), "-o", out, "--isa", "neon"});
        CHECK(run.status == 2);
        CHECK(contains(run.err, "unknown ISA 'neon'"));
        run = tessera_render(dir, {scene.string(), "-o", out, "--tile-size", "48"});
        CHECK(run.status == 2);
        CHECK(contains(run.err, "tile size must be a power of two"));
    }
    SUBCASE("an unknown AOV name, or AOVs without an EXR output") {
        const fs::path exr = dir / "aov.exr";
        fs::remove(exr);
        fs::remove(out);
        Run run = tessera_render(dir, {scene.string(), "-o", exr.string(), "--aov", "depth,colour"});
        CHECK(run.status == 2);
        CHECK(contains(run.err, "unknown AOV 'colour' in 'depth,colour' (expected a comma-separated list of depth, "
                                "normal, albedo, roughness, metallic, position, object_id, material_id, shadow)"));
        CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
        CHECK_FALSE(fs::exists(exr));
        run = tessera_render(dir, {scene.string(), "-o", out, "--aov", "depth"});
        CHECK(run.status == 2);
        CHECK(contains(run.err, "--aov needs an .exr output"));
        CHECK_FALSE(fs::exists(out));
    }
    SUBCASE("no output file") {
        const Run run = tessera_render(dir, {scene.string()});
        CHECK(run.status > 0);
        CHECK(contains(run.err, "--output"));
    }
}

TEST_CASE("a failed render or write never loses the file already at the output path") {
    const fs::path dir = tessera::test::output_dir("cli_nothing_lost");
    const fs::path good = dir / "good.toml", bad = dir / "bad.toml";
    write_file(good, kSmallScene);
    write_file(bad, "[camera]\nposition = [0, 0, 5]\ntarget = [0, 0, 5]\n");
    const fs::path image = dir / "picture.png";
    fs::remove(image);
    REQUIRE(tessera_render(dir, {good.string(), "-o", image.string()}).status == 0);
    const std::string before = read_file(image);
    REQUIRE(before.size() > 8);

    SUBCASE("a scene that fails to load") {
        const Run run = tessera_render(dir, {bad.string(), "-o", image.string()});
        CHECK(run.status == 1);
        CHECK(contains(run.err, "expected 'camera.target' to differ"));
    }
    SUBCASE("an output path that is a folder, written after the good file") {
        const fs::path folder = dir / "folder.exr";
        fs::create_directories(folder);
        const Run run = tessera_render(dir, {good.string(), "-o", image.string(), "-o", folder.string()});
        CHECK(run.status == 2);  // refused before rendering
        CHECK(contains(run.err, "folder.exr"));
        CHECK(fs::is_directory(folder));
    }
    SUBCASE("an output folder that does not exist is made") {
        fs::remove_all(dir / "missing");
        const Run run = tessera_render(dir, {good.string(), "-o", (dir / "missing" / "x.png").string()});
        CHECK(run.status == 0);
        CHECK(fs::exists(dir / "missing" / "x.png"));
        fs::remove_all(dir / "missing");
    }
    CHECK(read_file(image) == before);
    for (const auto& entry : fs::directory_iterator(dir))
        CHECK_MESSAGE(!contains(entry.path().filename().string(), ".tmp"), "left behind: " << entry.path());
}

TEST_CASE("several scenes in one call: {scene} names the outputs, a failure does not stop the others") {
    const fs::path dir = tessera::test::output_dir("cli_several_scenes");
    const fs::path a = dir / "alpha.toml", b = dir / "broken.toml", c = dir / "gamma.toml";
    write_file(a, kSmallScene);
    write_file(b, std::string(kSmallScene) + "[[objects]]\nmesh = \"teapot\"\n");
    write_file(c, std::string(kSmallScene) + "[[objects]]\nmesh = \"cube\"\ntranslate = [1, 0, 0]\n");
    for (const char* stem : {"alpha", "broken", "gamma"}) {
        fs::remove(dir / (std::string(stem) + ".png"));
        fs::remove(dir / (std::string(stem) + ".exr"));
    }
    const std::string png = (dir / "{scene}.png").string(), exr = (dir / "{scene}.exr").string();

    SUBCASE("all good") {
        const Run run = tessera_render(dir, {a.string(), c.string(), "-o", png, "-o", exr});
        CHECK(run.status == 0);
        CHECK(contains(run.out, "rendered 2 of 2 scenes"));
        for (const char* name : {"alpha.png", "alpha.exr", "gamma.png", "gamma.exr"}) CHECK(fs::exists(dir / name));
        CHECK(read_file(dir / "alpha.png") != read_file(dir / "gamma.png"));
    }
    SUBCASE("one bad scene in the middle") {
        const Run run = tessera_render(dir, {a.string(), b.string(), c.string(), "-o", png});
        CHECK(run.status == 1);
        CHECK(contains(run.err, b.string() + ":"));
        CHECK(contains(run.err, "unknown mesh 'teapot'"));
        CHECK(contains(run.err, "rendered 2 of 3 scenes; failed: " + b.string()));
        CHECK(fs::exists(dir / "alpha.png"));
        CHECK(fs::exists(dir / "gamma.png"));
        CHECK_FALSE(fs::exists(dir / "broken.png"));
    }
    SUBCASE("every -o must contain {scene}") {
        const Run run = tessera_render(dir, {a.string(), c.string(), "-o", png, "-o", (dir / "fixed.exr").string()});
        CHECK(run.status == 2);
        CHECK(contains(run.err, "with several scenes every -o must contain {scene}"));
        CHECK_FALSE(fs::exists(dir / "alpha.png"));  // refused before rendering anything
    }
    SUBCASE("two scenes with the same stem") {
        fs::create_directories(dir / "other");
        write_file(dir / "other" / "alpha.toml", kSmallScene);
        const Run run = tessera_render(dir, {a.string(), (dir / "other" / "alpha.toml").string(), "-o", png});
        CHECK(run.status == 2);
        CHECK(contains(run.err, "two scene files have the stem 'alpha'"));
    }
    SUBCASE("one scene: {scene} is optional, and replaced when given") {
        CHECK(tessera_render(dir, {a.string(), "-o", png}).status == 0);
        CHECK(fs::exists(dir / "alpha.png"));
        const Run run = tessera_render(dir, {c.string(), "-o", (dir / "plain.png").string()});
        CHECK(run.status == 0);
        CHECK(run.out.empty());  // no summary line for a single scene
        CHECK(fs::exists(dir / "plain.png"));
    }
}

TEST_CASE("--aov adds channels to the EXR and leaves the PNG as it was") {
    const fs::path dir = tessera::test::output_dir("cli_aov");
    const fs::path scene = dir / "small.toml";
    write_file(scene, kSmallScene);
    REQUIRE(tessera_render(dir, {scene.string(), "-o", (dir / "plain.png").string(), "-o",
                                 (dir / "plain.exr").string()}).status == 0);
    // The scene file after --aov stays a scene: one list per --aov.
    const Run run = tessera_render(dir, {"--aov", "depth,normal,albedo", "--aov", "roughness,metallic,position",
                                         scene.string(), "-o", (dir / "aov.png").string(), "-o",
                                         (dir / "aov.exr").string()});
    CHECK(run.status == 0);
    CHECK(run.err.empty());
    CHECK(read_file(dir / "aov.png") == read_file(dir / "plain.png"));
    CHECK(fs::file_size(dir / "aov.exr") > fs::file_size(dir / "plain.exr"));
}

// The CLI loads a model that several scenes of one call place once: with
// --stats each scene reports the textures it decoded, and only the first decodes any.
TEST_CASE("the CLI imports a model shared by several scenes once") {
    const fs::path dir = tessera::test::output_dir("cli_model_cache");
    tessera::test::write_bytes(dir / "model.glb", tessera::test::test_glb());
    const std::string scene = std::string(kSmallScene) + "[[models]]\nfile = \"model.glb\"\n";
    write_file(dir / "first.toml", scene);
    write_file(dir / "second.toml", scene);
    const Run run = tessera_render(dir, {(dir / "first.toml").string(), (dir / "second.toml").string(), "-o",
                                         (dir / "{scene}.png").string(), "--stats", "--threads", "1"});
    REQUIRE_MESSAGE(run.status == 0, run.err);
    const std::size_t first = run.out.find("images: 2 textures");
    const std::size_t second = run.out.find("images: 0 textures");
    CHECK_MESSAGE(first != std::string::npos, run.out);
    CHECK_MESSAGE(second != std::string::npos, run.out);
    CHECK(first < second);
    CHECK(run.out.find("images: 2 textures", first + 1) == std::string::npos);
    CHECK(fs::exists(dir / "first.png"));
    CHECK(fs::exists(dir / "second.png"));
}

// --environment and [environment] with a bad image: one line naming the image, exit 1, no output.
TEST_CASE("the CLI refuses missing, truncated, non-HDR and mis-sized environment images") {
    const fs::path dir = tessera::test::output_dir("cli_bad_environment");
    const fs::path scene = dir / "small.toml";
    write_file(scene, kSmallScene);
    const std::string exr = read_file(tessera::test::source_dir() / "scenes" / "environments" / "studio_256.exr");
    write_file(dir / "truncated.exr", exr.substr(0, 500));
    write_file(dir / "text.hdr", "not an image\n");
    write_file(dir / "wide.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 1000000\n");
    write_file(dir / "empty.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 0 +X 0\n");
    for (const char* name : {"missing.hdr", "truncated.exr", "text.hdr", "wide.hdr", "empty.hdr"}) {
        const std::string image = (dir / name).string();
        CAPTURE(image);
        fs::remove(dir / "out.png");
        const Run run = tessera_render(dir, {scene.string(), "--environment", image, "-o", (dir / "out.png").string()});
        CHECK(run.status == 1);
        CHECK_MESSAGE((contains(run.err, "tessera: error: ") && contains(run.err, image)), run.err);
        CHECK_FALSE(fs::exists(dir / "out.png"));
    }
    // The same from a scene file, with its position.
    const fs::path with_environment = dir / "with_environment.toml";
    write_file(with_environment, std::string(kSmallScene) + "[environment]\nfile = \"wide.hdr\"\n");
    const Run run = tessera_render(dir, {with_environment.string(), "-o", (dir / "out.png").string()});
    CHECK(run.status == 1);
    CHECK_MESSAGE((contains(run.err, with_environment.string() + ":13:8: cannot load the environment") &&
                   contains(run.err, "1000000x1")),
                  run.err);
    // And the flags' values.
    for (const std::vector<std::string>& flag : {std::vector<std::string>{"--environment-intensity", "nan"},
                                                 {"--environment-intensity", "-2"}, {"--exposure", "inf"}, {"--lighting", "studio"}}) {
        const Run bad = tessera_render(dir, {scene.string(), flag[0], flag[1], "-o", (dir / "out.png").string()});
        CHECK(bad.status != 0);
        CHECK_MESSAGE(contains(bad.err, flag[0]), bad.err);
    }
}
