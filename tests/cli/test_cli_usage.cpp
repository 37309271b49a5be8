// Tests for src/cli/usage.cpp and output_paths.cpp through both binaries: every
// usage error is one line `tessera: error: ...` and exit status 2, with a
// suggestion for a mistyped command or option, whichever binary defines the
// command; scene files are chosen by extension; -o makes its folders; output
// paths are checked before the work starts; --help shows the defaults.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "cli/usage.hpp"
#include "cli_runner.hpp"
#include "test_paths.hpp"

namespace fs = std::filesystem;

namespace {

using tessera::test::CliRun;
using tessera::test::run_tessera;

constexpr std::string_view kSmallScene =
    "[output]\nwidth = 48\nheight = 32\n"
    "[camera]\nposition = [0, 0, 4]\ntarget = [0, 0, 0]\n"
    "[[lights]]\nposition = [3, 3, 5]\ncolor = [40, 40, 40]\n"
    "[[objects]]\nmesh = \"sphere\"\n";

fs::path small_scene(const fs::path& dir) {
    const fs::path scene = dir / "small.toml";
    std::ofstream(scene) << kSmallScene;
    return scene;
}

// Exit status 2 and exactly this one line on stderr.
void check_usage_error(const CliRun& run, const std::string& line) {
    CHECK(run.status == 2);
    CHECK(run.err == "tessera: error: " + line + "\n");
}

}  // namespace

TEST_CASE("edit distance and the nearest name") {
    CHECK(tessera::cli::edit_distance("rendr", "render") == 1);
    CHECK(tessera::cli::edit_distance("widht", "width") == 1);  // a swap of neighbours is one slip
    CHECK(tessera::cli::edit_distance("", "abc") == 3);
    CHECK(tessera::cli::edit_distance("check", "check") == 0);
    const std::vector<std::string> commands{"render", "bench", "contact-sheet", "check"};
    CHECK(tessera::cli::closest_name("rendr", commands) == "render");
    CHECK(tessera::cli::closest_name("chek", commands) == "check");
    CHECK(tessera::cli::closest_name("contactsheet", commands) == "contact-sheet");
    CHECK_FALSE(tessera::cli::closest_name("paint", commands).has_value());
    CHECK_FALSE(tessera::cli::closest_name("x", {"-o"}).has_value());
    const std::vector<std::string> options{"--width", "--height", "--threads", "-o", "--output"};
    CHECK(tessera::cli::closest_name("--widht", options) == "--width");
    CHECK(tessera::cli::closest_name("--hieght", options) == "--height");
    CHECK(tessera::cli::closest_name("--thread", options) == "--threads");
    CHECK_FALSE(tessera::cli::closest_name("--colour", options).has_value());
}

TEST_CASE("a mistyped command or option is one line, exit 2, with the nearest real name") {
    const fs::path dir = tessera::test::output_dir("cli_usage_names");
    const std::string scene = small_scene(dir).string();
    const std::string out = (dir / "out.png").string();

    check_usage_error(run_tessera(dir, "rendr", {scene, "-o", out}),
                      "'rendr' is not a tessera command; did you mean 'render'?");
    check_usage_error(run_tessera(dir, "chek", {}), "'chek' is not a tessera command; did you mean 'check'?");
    check_usage_error(run_tessera(dir, "paint", {}),
                      "'paint' is not a tessera command; the commands are render, bench, contact-sheet or check");
    check_usage_error(run_tessera(dir, "", {}),
                      "a command is required: render, bench, contact-sheet or check (see 'tessera --help')");
    check_usage_error(run_tessera(dir, "render", {scene, "-o", out, "--widht", "20"}),
                      "render: unknown option '--widht'; did you mean '--width'?");
    check_usage_error(run_tessera(dir, "render", {scene, "-o", out, "--widht=20"}),
                      "render: unknown option '--widht'; did you mean '--width'?");
    check_usage_error(run_tessera(dir, "render", {scene, "-o", out, "--colour"}),
                      "render: unknown option '--colour' (see 'tessera render --help')");
    // The commands of tessera-tools, run through tessera.
    check_usage_error(run_tessera(dir, "bench", {scene, "--framez", "3"}),
                      "bench: unknown option '--framez'; did you mean '--frames'?");
    check_usage_error(run_tessera(dir, "check", {"check.toml", "--quite"}),
                      "check: unknown option '--quite'; did you mean '--quiet'?");
    check_usage_error(run_tessera(dir, "contact-sheet", {"a.png", "-o", out, "--colums", "3"}),
                      "contact-sheet: unknown option '--colums'; did you mean '--columns'?");
    CHECK_FALSE(fs::exists(out));
}

TEST_CASE("every other command-line mistake is one line and exit 2 too") {
    const fs::path dir = tessera::test::output_dir("cli_usage_values");
    const std::string scene = small_scene(dir).string();
    const std::string out = (dir / "out.png").string();

    check_usage_error(run_tessera(dir, "render", {scene}),
                      "render: --output is required (see 'tessera render --help')");
    check_usage_error(run_tessera(dir, "render", {scene, "-o", out, "--width", "0"}),
                      "render: --width: Value 0 not in range 1 to 16384 (see 'tessera render --help')");
    check_usage_error(run_tessera(dir, "render", {scene, "-o", out, "--msaa", "3"}),
                      "render: --msaa: 3 not in {1,4} (see 'tessera render --help')");
    check_usage_error(run_tessera(dir, "bench", {}), "bench: scene is required (see 'tessera bench --help')");
    check_usage_error(run_tessera(dir, "render", {scene, "-o", out, "--time", "1", "--frames", "0-3"}),
                      "--time renders one moment and --frames a range of them; give one of the two");
    check_usage_error(run_tessera(dir, "render", {scene, "-o", out, "--isa", "neon"}),
                      "unknown ISA 'neon' (expected auto, scalar, sse4, avx2 or avx512)");
    check_usage_error(run_tessera(dir, "render", {scene, "-o", (dir / "out.jpg").string()}),
                      (dir / "out.jpg").string() + ": unsupported output format (expected .png or .exr)");
    CHECK_FALSE(fs::exists(out));
}

TEST_CASE("a scene's type comes from its extension, anything else is refused by name before it is read") {
    const fs::path dir = tessera::test::output_dir("cli_scene_extension");
    const std::string out = (dir / "out.png").string();
    for (const char* name : {"model.obj", "model.ply", "picture.png", "scene", "scene.tomll"}) {
        const fs::path file = dir / name;
        std::ofstream(file) << kSmallScene;  // valid TOML inside: the name alone decides
        CAPTURE(file);
        const std::string line = file.string() + ": not a scene file (expected .toml, .gltf or .glb)";
        check_usage_error(run_tessera(dir, "render", {file.string(), "-o", out}), line);
        check_usage_error(run_tessera(dir, "bench", {file.string(), "--frames", "1"}), line);
    }
    // Any case of the right extension is a scene.
    const fs::path upper = dir / "UPPER.TOML";
    std::ofstream(upper) << kSmallScene;
    const CliRun run = run_tessera(dir, "render", {upper.string(), "-o", out});
    CHECK_MESSAGE(run.status == 0, run.err);
    CHECK(fs::exists(out));
}

TEST_CASE("-o makes missing folders, unwritable outputs fail at once, before any work") {
    const fs::path dir = tessera::test::output_dir("cli_output_paths");
    const std::string scene = small_scene(dir).string();
    fs::remove_all(dir / "new");

    SUBCASE("-o into folders that do not exist yet") {
        const fs::path image = dir / "new" / "deeper" / "small.png";
        const CliRun run = run_tessera(dir, "render", {scene, "-o", image.string(), "-o",
                                                       (dir / "new" / "{scene}" / "f{frame}.exr").string()});
        CHECK_MESSAGE(run.status == 0, run.err);
        CHECK(fs::exists(image));
        CHECK(fs::exists(dir / "new" / "small" / "f0.exr"));
    }
    SUBCASE("-o under a file") {
        std::ofstream(dir / "plain_file") << "x";
        const std::string image = (dir / "plain_file" / "x.png").string();
        const CliRun run = run_tessera(dir, "render", {scene, "-o", image});
        CHECK(run.status == 2);
        CHECK(run.err.rfind("tessera: error: " + image + ": cannot write the output image: cannot create the folder '" +
                                (dir / "plain_file").string() + "'", 0) == 0);
        CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
    }
    SUBCASE("-o naming a folder") {
        fs::create_directories(dir / "folder.png");
        check_usage_error(run_tessera(dir, "render", {scene, "-o", (dir / "folder.png").string()}),
                          (dir / "folder.png").string() + ": cannot write the output image: it is a folder");
    }
    SUBCASE("--log into a missing folder") {
        const std::string log = (dir / "missing" / "log.jsonl").string();
        check_usage_error(run_tessera(dir, "render", {scene, "-o", (dir / "logged.png").string(), "--log", log}),
                          log + ": cannot write the --log file: the folder '" + (dir / "missing").string() +
                              "' does not exist");
        CHECK_FALSE(fs::exists(dir / "logged.png"));
    }
    SUBCASE("bench --trace and --heatmap: refused before the timed frames, not after them") {
        const std::string trace = (dir / "missing" / "trace.json").string();
        const auto start = std::chrono::steady_clock::now();
        // A million frames would take many minutes: only a check before them returns at once.
        const CliRun run = run_tessera(dir, "bench", {scene, "--frames", "100000", "--warmup", "100000", "--trace", trace});
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        check_usage_error(run, trace + ": cannot write the --trace file: the folder '" + (dir / "missing").string() +
                                   "' does not exist");
        CHECK(run.out.empty());
        CHECK(seconds < 20.0);
        const std::string heatmap = (dir / "missing" / "heat.png").string();
        check_usage_error(run_tessera(dir, "bench", {scene, "--frames", "1", "--heatmap", heatmap}),
                          heatmap + ": cannot write the --heatmap image: the folder '" + (dir / "missing").string() +
                              "' does not exist");
    }
    SUBCASE("check's report folder") {
        std::ofstream(dir / "report_is_a_file") << "x";
        const std::string report = (dir / "report_is_a_file").string();
        check_usage_error(run_tessera(dir, "check", {scene, "--golden", dir.string(), "--report", report}),
                          report + ": cannot write the report: it is a file, not a folder");
    }
}

TEST_CASE("--help of every command lists its options with their defaults, and scenes are not TOML only") {
    const fs::path dir = tessera::test::output_dir("cli_usage_help");
    CliRun run = run_tessera(dir, "render", {"--help"});
    CHECK(run.status == 0);
    CHECK(run.out.find(".gltf/.glb") != std::string::npos);
    CHECK(run.out.find("(TOML)") == std::string::npos);
    CHECK(run.out.find("--threads INT:INT in [0 - 1024]=0") != std::string::npos);
    CHECK(run.out.find("--tile-size INT=") != std::string::npos);
    CHECK(run.out.find("--isa TEXT=auto") != std::string::npos);
    CHECK(run.out.find("--width INT:INT in [1 - 16384]") != std::string::npos);
    CHECK(run.out.find("--width INT:INT in [1 - 16384]=") == std::string::npos);  // 0 (the scene's) is not shown
    CHECK(run.out.find("=[]") == std::string::npos);
    run = run_tessera(dir, "bench", {"--help"});
    CHECK(run.status == 0);
    CHECK(run.out.find("--frames INT:INT in [1 - 100000]=30") != std::string::npos);
    CHECK(run.out.find("--warmup INT:INT in [0 - 100000]=3") != std::string::npos);
    CHECK(run.out.find("=time") != std::string::npos);  // --heatmap-metric
    CHECK(run.out.find("(TOML)") == std::string::npos);
    run = run_tessera(dir, "contact-sheet", {"--help"});
    CHECK(run.out.find("--columns INT:INT in [1 - 1000]=6") != std::string::npos);
    CHECK(run.out.find("--tile-width INT:INT in [8 - 4096]=320") != std::string::npos);
    run = run_tessera(dir, "check", {"--help"});
    CHECK(run.out.find("--new-golden-format TEXT:{png,exr}=png") != std::string::npos);
}
