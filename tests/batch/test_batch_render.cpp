// `tessera render --frames/--shard/--skip-existing/--log` through the real
// binary: frames of a range are the frames rendered alone, shards (given or
// from Slurm's and Kubernetes' variables) cover a range exactly once,
// resuming renders only what is missing, and the per-frame record.
#include <sys/stat.h>
#include <sys/wait.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "batch/frames.hpp"
#include "cli_runner.hpp"
#include "test_paths.hpp"

namespace fs = std::filesystem;

namespace {

using Run = tessera::test::CliRun;
using tessera::test::read_file;

// `ENV tessera render ARGS`, output captured beside `dir`.
Run tessera_render(const fs::path& dir, const std::vector<std::string>& args, const std::string& env = "") {
    return tessera::test::run_tessera(dir, "render", args, env);
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A small animated scene: the camera orbits, an object turns and changes
// colour, a light dims: every frame differs.
constexpr std::string_view kAnimatedScene =
    "[output]\nwidth = 48\nheight = 32\n"
    "[camera]\nposition = [0, 1, 5]\ntarget = [0, 0, 0]\n"
    "[[lights]]\nposition = [3, 3, 5]\ncolor = [40, 40, 40]\n"
    "[[objects]]\nmesh = \"cube\"\nscale = 0.8\n"
    "[[objects]]\nmesh = \"sphere\"\nscale = 0.5\ntranslate = [1.5, 0, 0]\n"
    "[animation]\nframes = 24\n[animation.orbit]\nturns = 0.5\n"
    "[[animation.objects]]\nobject = 0\nkeys = [ { frame = 0, rotate = [0, 0, 0], color = [1, 0, 0] },"
    " { frame = 23, rotate = [30, 90, 0], color = [0, 0, 1] } ]\n"
    "[[animation.lights]]\nlight = 0\ninterpolation = \"smooth\"\nkeys = [ { frame = 0, color = [40, 40, 40] },"
    " { frame = 23, color = [5, 5, 5] } ]\n";

fs::path fresh_dir(const char* name) {
    const fs::path dir = tessera::test::output_dir(name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

fs::path write_scene(const fs::path& dir) {
    const fs::path scene = dir / "anim.toml";
    std::ofstream(scene) << kAnimatedScene;
    return scene;
}

std::string frame_name(int frame) { return tessera::batch::expand_output_pattern("f_{frame:03}.png", "", frame); }

// The PNG of each frame of 0-22:3, rendered in one process: the reference the shards are held to.
std::map<int, std::string> reference_frames(const fs::path& dir, const fs::path& scene) {
    const fs::path out = dir / "reference";
    fs::create_directories(out);
    const Run run = tessera_render(dir, {scene.string(), "--frames", "0-22:3", "-o", (out / "f_{frame:03}.png").string()});
    REQUIRE_MESSAGE(run.status == 0, run.err);
    std::map<int, std::string> frames;
    for (int f = 0; f <= 21; f += 3) frames[f] = read_file(out / frame_name(f));
    return frames;
}

// Every reference frame exists in `out` once, bit-identical, and nothing else does.
void check_complete(const fs::path& out, const std::map<int, std::string>& reference) {
    std::size_t files = 0;
    for (const auto& entry : fs::directory_iterator(out))
        if (entry.path().extension() == ".png") ++files;
    CHECK(files == reference.size());
    for (const auto& [frame, bytes] : reference) {
        INFO("frame " << frame << " in " << out.string());
        CHECK(read_file(out / frame_name(frame)) == bytes);
    }
}

// How many records the JSON Lines log holds for each frame.
std::map<int, int> logged_frames(const fs::path& log) {
    std::map<int, int> frames;
    std::istringstream lines(read_file(log));
    for (std::string line; std::getline(lines, line);) {
        const std::size_t at = line.find("\"frame\": ");
        REQUIRE(at != std::string::npos);
        ++frames[std::stoi(line.substr(at + 9))];
        CHECK(contains(line, "\"triangles\": "));
        CHECK(contains(line, "\"fragments\": "));
        CHECK(contains(line, "\"ms\": "));
        CHECK(contains(line, "\"file\": \""));
    }
    return frames;
}

}  // namespace

TEST_CASE("a frame of a range is bit-identical to the same frame rendered alone, without --frames, frame 0") {
    const fs::path dir = fresh_dir("batch_frames");
    const fs::path scene = write_scene(dir);
    const Run all = tessera_render(dir, {scene.string(), "--frames", "0-23", "-o", (dir / "all_{frame:02}.png").string()});
    REQUIRE_MESSAGE(all.status == 0, all.err);
    // Off a terminal: one line per frame.
    CHECK(contains(all.out, "frame 0: " + (dir / "all_00.png").string()));
    CHECK(contains(all.out, "(24/24)"));
    for (const int frame : {0, 11, 23}) {
        const std::string alone = (dir / ("alone_" + std::to_string(frame) + ".png")).string();
        const Run one = tessera_render(dir, {scene.string(), "--frames", std::to_string(frame), "-o", alone});
        REQUIRE_MESSAGE(one.status == 0, one.err);
        const std::string in_range = read_file(dir / tessera::batch::expand_output_pattern("all_{frame:02}.png", "", frame));
        CHECK(!in_range.empty());
        CHECK_MESSAGE(read_file(alone) == in_range, "frame " << frame);
    }
    // The frames do move: the test above could fail.
    CHECK(read_file(dir / "all_00.png") != read_file(dir / "all_11.png"));
    CHECK(read_file(dir / "all_11.png") != read_file(dir / "all_23.png"));
    const Run plain = tessera_render(dir, {scene.string(), "-o", (dir / "plain.png").string()});
    REQUIRE_MESSAGE(plain.status == 0, plain.err);
    CHECK(plain.out.empty());  // a plain render stays quiet
    CHECK(read_file(dir / "plain.png") == read_file(dir / "all_00.png"));
}

TEST_CASE("--shard I/N for N = 1, 2, 3, 7: every frame of 0-22:3 rendered exactly once, as in one process") {
    const fs::path dir = fresh_dir("batch_shards");
    const fs::path scene = write_scene(dir);
    const std::map<int, std::string> reference = reference_frames(dir, scene);
    for (const int n : {1, 2, 3, 7}) {
        const fs::path out = dir / std::string("n").append(std::to_string(n));  // (not "n" + ...: GCC 12 -Wrestrict false positive)
        fs::create_directories(out);
        for (int i = 1; i <= n; ++i) {
            const std::string shard = std::to_string(i) + "/" + std::to_string(n);
            const Run run = tessera_render(dir, {scene.string(), "--frames", "0-22:3", "--shard", shard, "--log",
                                                 (out / "log.jsonl").string(), "-o", (out / "f_{frame:03}.png").string()});
            REQUIRE_MESSAGE(run.status == 0, run.err);
            // 8 frames: parts of 8/n, rounded up for the first 8 mod n.
            const int expected = 8 / n + (i - 1 < 8 % n ? 1 : 0);
            CHECK(contains(run.out, "shard " + shard + " (from --shard " + shard + "): " + std::to_string(expected) +
                                        " of 8 frames"));
        }
        check_complete(out, reference);
        const std::map<int, int> logged = logged_frames(out / "log.jsonl");
        CHECK(logged.size() == reference.size());
        for (const auto& [frame, count] : logged) CHECK_MESSAGE(count == 1, "frame " << frame << " with N = " << n);
    }
}

TEST_CASE("the shard from a Slurm array task (--array=1-4) or a Kubernetes Indexed Job (3 completions)") {
    const fs::path dir = fresh_dir("batch_environment");
    const fs::path scene = write_scene(dir);
    const std::map<int, std::string> reference = reference_frames(dir, scene);
    const fs::path slurm = dir / "slurm";
    fs::create_directories(slurm);
    for (int task = 1; task <= 4; ++task) {
        const std::string env = "SLURM_ARRAY_TASK_ID=" + std::to_string(task) +
                                " SLURM_ARRAY_TASK_MIN=1 SLURM_ARRAY_TASK_MAX=4 SLURM_ARRAY_TASK_COUNT=4";
        const Run run = tessera_render(dir, {scene.string(), "--frames", "0-22:3", "-o", (slurm / "f_{frame:03}.png").string()}, env);
        REQUIRE_MESSAGE(run.status == 0, run.err);
        CHECK(contains(run.out, "shard " + std::to_string(task) + "/4 (from SLURM_ARRAY_TASK_ID=" + std::to_string(task) +
                                    " (min 1, step 1, count 4)): 2 of 8 frames"));
    }
    check_complete(slurm, reference);
    const fs::path k8s = dir / "k8s";
    fs::create_directories(k8s);
    for (int index = 0; index < 3; ++index) {
        const Run run = tessera_render(dir, {scene.string(), "--frames", "0-22:3", "--shard-count", "3", "-o",
                                             (k8s / "f_{frame:03}.png").string()},
                                       "JOB_COMPLETION_INDEX=" + std::to_string(index));
        REQUIRE_MESSAGE(run.status == 0, run.err);
        CHECK(contains(run.out, "from JOB_COMPLETION_INDEX=" + std::to_string(index) + " of --shard-count 3"));
    }
    check_complete(k8s, reference);
}

TEST_CASE("--skip-existing re-renders nothing already written, and only what is missing") {
    const fs::path dir = fresh_dir("batch_skip");
    const fs::path scene = write_scene(dir);
    const std::vector<std::string> args{scene.string(), "--frames", "0-22:3", "--skip-existing", "--log",
                                        (dir / "log.jsonl").string(), "-o", (dir / "f_{frame:03}.png").string()};
    const Run first = tessera_render(dir, args);
    REQUIRE_MESSAGE(first.status == 0, first.err);
    CHECK(logged_frames(dir / "log.jsonl").size() == 8);
    // A file is replaced by rename when written: an unchanged inode means not rewritten.
    const auto inode = [&](int frame) {
        struct stat info {};
        REQUIRE(::stat((dir / frame_name(frame)).c_str(), &info) == 0);
        return info.st_ino;
    };
    std::map<int, ino_t> before;
    for (int f = 0; f <= 21; f += 3) before[f] = inode(f);
    fs::remove(dir / "log.jsonl");
    fs::remove(dir / frame_name(9));  // as if the task was pre-empted before frame 9 was written
    const Run resumed = tessera_render(dir, args);
    REQUIRE_MESSAGE(resumed.status == 0, resumed.err);
    CHECK(contains(resumed.out, "skipped 7 frames already written; rendered 1"));
    CHECK(contains(resumed.out, "frame 3: " + (dir / frame_name(3)).string() + " present, skipped"));
    CHECK(logged_frames(dir / "log.jsonl") == std::map<int, int>{{9, 1}});
    for (int f = 0; f <= 21; f += 3)
        if (f != 9) CHECK_MESSAGE(inode(f) == before[f], "frame " << f << " was rewritten");
    CHECK(fs::is_regular_file(dir / frame_name(9)));
    fs::remove(dir / "log.jsonl");
    const Run again = tessera_render(dir, args);
    REQUIRE_MESSAGE(again.status == 0, again.err);
    CHECK(contains(again.out, "skipped 8 frames already written; rendered 0"));
    const bool nothing_logged = !fs::exists(dir / "log.jsonl") || read_file(dir / "log.jsonl").empty();
    CHECK(nothing_logged);
}

TEST_CASE("batch mistakes: a clear line and a non-zero exit, before or without rendering") {
    const fs::path dir = fresh_dir("batch_errors");
    const fs::path scene = write_scene(dir);
    const std::string out = (dir / "f_{frame:03}.png").string();
    const auto error_for = [&](const std::vector<std::string>& args, const std::string& env = "") {
        const Run run = tessera_render(dir, args, env);
        CHECK(run.status != 0);
        return run.err;
    };
    CHECK(contains(error_for({scene.string(), "--frames", "0-3", "-o", (dir / "same.png").string()}),
                   "with several frames every -o must contain {frame} or {frame:0N}"));
    CHECK(contains(error_for({scene.string(), "--frames", "20-30", "-o", out}),
                   scene.string() + ": --frames asks for frame 24, but the animation has frames 0-23"));
    CHECK_FALSE(fs::exists(dir / frame_name(20)));  // checked before the first frame is rendered
    const fs::path still = dir / "still.toml";
    std::ofstream(still) << "[output]\nwidth = 8\nheight = 8\n[camera]\nposition = [0, 0, 5]\ntarget = [0, 0, 0]\n";
    CHECK(contains(error_for({still.string(), "--frames", "0-1", "-o", out}),
                   "but the scene has no [animation] (only frame 0)"));
    CHECK(contains(error_for({scene.string(), "--frames", "0-3", "--shard", "5/4", "-o", out}),
                   "--shard '5/4': I counts from 1 and must be in 1..N"));
    CHECK(contains(error_for({scene.string(), "--frames", "3-1", "-o", out}), "the last frame is before the first"));
    CHECK(contains(error_for({scene.string(), "-o", (dir / "x_{frame:3}.png").string()}), "unsupported placeholder"));
    CHECK(contains(error_for({scene.string(), "-o", out}, "SLURM_ARRAY_TASK_ID=3"),
                   "SLURM_ARRAY_TASK_MIN is not set"));
}

TEST_CASE("--shard splits the scenes of a multi-scene call: each rendered once") {
    const fs::path dir = fresh_dir("batch_scene_shards");
    std::vector<std::string> args;
    for (const char* name : {"a", "b", "c"}) {
        const fs::path scene = dir / (std::string(name) + ".toml");
        std::ofstream(scene) << "[output]\nwidth = 8\nheight = 8\n[camera]\nposition = [0, 0, 5]\ntarget = [0, 0, 0]\n";
        args.push_back(scene.string());
    }
    args.insert(args.end(), {"-o", (dir / "{scene}.png").string(), "--shard"});
    args.push_back("1/2");
    const Run first = tessera_render(dir, args);
    REQUIRE_MESSAGE(first.status == 0, first.err);
    CHECK(contains(first.out, "shard 1/2 (from --shard 1/2): 2 of 3 frames"));
    CHECK(contains(first.out, "rendered 2 of 2 scenes"));
    CHECK(fs::exists(dir / "a.png"));
    CHECK_FALSE(fs::exists(dir / "b.png"));
    CHECK(fs::exists(dir / "c.png"));
    args.back() = "2/2";
    const Run second = tessera_render(dir, args);
    REQUIRE_MESSAGE(second.status == 0, second.err);
    CHECK(contains(second.out, "rendered 1 of 1 scenes"));
    CHECK(fs::exists(dir / "b.png"));
}
