#include "cli/check_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "batch/shard.hpp"
#include "check/merge.hpp"
#include "check/report.hpp"
#include "check/runner.hpp"
#include "cli/output_paths.hpp"
#include "cli/usage.hpp"

namespace tessera::cli {

namespace fs = std::filesystem;

namespace {

// Scene i of n and the time left, on one rewritten line when stderr is a terminal; plain lines otherwise.
class ProgressLine {
public:
    explicit ProgressLine(bool quiet) : quiet_(quiet), terminal_(::isatty(STDERR_FILENO) == 1) {}

    void operator()(std::size_t index, std::size_t count, const check::SceneResult& r) {
        if (quiet_) return;
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        const double left = elapsed / double(index + 1) * double(count - index - 1);
        if (terminal_) {
            std::fprintf(stderr, "\r\033[K[%zu/%zu] %s %s, %.0f s left", index + 1, count,
                         std::string(check::status_name(r.status)).c_str(), r.name.c_str(), left);
            if (index + 1 == count) std::fputc('\n', stderr);
        } else {
            std::fprintf(stderr, "[%zu/%zu] %s %s (%.0f ms)\n", index + 1, count,
                         std::string(check::status_name(r.status)).c_str(), r.name.c_str(), r.render_ms + r.compare_ms);
        }
        std::fflush(stderr);
    }

private:
    bool quiet_;
    bool terminal_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// A scene file or manifest, as opposed to a scene name (names have no extension).
bool is_input_path(const std::string& value) {
    std::string extension = fs::path(value).extension().string();
    for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
    return extension == ".toml" || extension == ".gltf" || extension == ".glb";
}

check::Suite load_suite(const CheckCommand& cmd) {
    if (cmd.golden_dir.empty()) {
        if (cmd.inputs.size() != 1)
            throw check::ManifestError("expected one manifest (check.toml), or scene files with --golden DIR");
        if (!cmd.scene_root.empty())
            throw check::ManifestError("--scene-root is for scene files given with --golden; a manifest has scene_root");
        return check::load_manifest(cmd.inputs.front(), cmd.defaults);
    }
    check::Suite suite = check::suite_from_arguments(cmd.inputs, cmd.golden_dir, cmd.scene_root, cmd.defaults);
    suite.new_golden_format = cmd.new_golden_format == "exr" ? check::GoldenFormat::exr : check::GoldenFormat::png;
    return suite;
}

void print_summary(const check::CheckRun& run, const fs::path& report_dir) {
    for (const check::SceneResult* r : check::worst_first(run)) {
        if (r->status == check::Status::pass && r->update.empty()) continue;
        std::fprintf(r->status == check::Status::warn ? stdout : stderr, "%s\n", check::describe(*r).c_str());
    }
    std::printf("check: %d passed, %d warned, %d failed, %d missing, %d errors of %zu scenes in %.1f s",
                run.count(check::Status::pass), run.count(check::Status::warn), run.count(check::Status::fail),
                run.count(check::Status::missing), run.count(check::Status::error), run.scenes.size(), run.seconds);
    if (run.updated() > 0) std::printf("; %d golden images written", run.updated());
    std::printf("\nreport: %s\n", (report_dir / "index.html").string().c_str());
}

void write_reports(const CheckCommand& cmd, const check::CheckRun& run, const fs::path& report_dir) {
    check::write_html_report(run, report_dir);
    check::write_junit_report(run, cmd.junit_path.empty() ? report_dir / "junit.xml" : fs::path(cmd.junit_path));
    check::write_json_summary(run, cmd.json_path.empty() ? report_dir / "summary.json" : fs::path(cmd.json_path));
}

// --merge: the shards' reports become the report of one run.
int run_merge(const CheckCommand& cmd) {
    const bool render_options = !cmd.defaults.thresholds.empty() || cmd.defaults.perceptual ||
                                cmd.defaults.width > 0 || cmd.defaults.height > 0 || cmd.defaults.msaa > 0;
    if (render_options) {
        std::fprintf(stderr, "tessera: error: --merge reads the shards' results; thresholds and --width/--height/"
                             "--msaa apply when the shards run\n");
        return kCheckUsageError;
    }
    const fs::path report_dir = cmd.report_dir.empty() ? fs::path("check-report") : fs::path(cmd.report_dir);
    std::vector<fs::path> shard_dirs(cmd.inputs.begin(), cmd.inputs.end());
    check::CheckRun run;
    try {
        run = check::merge_shard_reports(shard_dirs, report_dir);
    } catch (const check::MergeError& e) {
        std::fprintf(stderr, "tessera: error: %s\n", e.what());
        return kCheckUsageError;
    }
    write_reports(cmd, run, report_dir);
    std::printf("merged %zu shard reports\n", shard_dirs.size());
    print_summary(run, report_dir);
    return run.exit_status();
}

}  // namespace

CLI::App* add_check_command(CLI::App& app, CheckCommand& cmd) {
    CLI::App* check = app.add_subcommand(
        "check", "Render scenes and compare each with its golden image; write an HTML, JUnit and JSON report");
    // Not ->required(): inputs after a bare --update arrive as its values, and run_check moves them back.
    check->add_option("input", cmd.inputs,
                      "A manifest (check.toml), or with --golden scene files / glob patterns (quoted), or with --merge "
                      "the shards' report folders");
    CLI::Option* golden = check->add_option("-g,--golden", cmd.golden_dir, "Golden image folder: <name>.png or <name>.exr per scene");
    CLI::Option* scene_root = check->add_option("--scene-root", cmd.scene_root,
                      "With --golden: names are scene paths below this folder (default: the deepest common folder)");
    check->add_option("-r,--report", cmd.report_dir, "Report folder (default: the manifest's report, else check-report)");
    check->add_option("--junit", cmd.junit_path, "JUnit XML file (default: REPORT/junit.xml)");
    check->add_option("--json", cmd.json_path, "JSON summary file (default: REPORT/summary.json)");
    CLI::Option* update =
        check->add_option("--update", cmd.update,
                          "Write golden images, atomically: bare, for failing and missing scenes; =missing, only "
                          "missing ones; NAME... (scene names or quoted globs), for those scenes whatever they differ by")
            ->expected(0, CLI::detail::expected_max_vector_size)
            ->allow_extra_args(true)
            ->delimiter(',');
    cmd.update_option = update;
    check->add_option("--filter", cmd.filters,
                      "Check only the scenes whose names match one of these globs (e.g. 'gltf/*'; repeatable)")
        ->delimiter(',');
    check->add_option("--new-golden-format", cmd.new_golden_format, "With --golden: png or exr for new golden images")
        ->check(CLI::IsMember({"png", "exr"}));
    check->add_flag("-q,--quiet", cmd.quiet, "No progress lines");
    // Sharding as `tessera render` does it (src/batch/shard.hpp); --merge puts the shards' reports together.
    CLI::Option* shard = check->add_option(
        "--shard", cmd.shard,
        "Check only part I of N (1-based) of the scenes: every N-th from the I-th; default: from "
        "SLURM_ARRAY_TASK_ID/_MIN/_COUNT/_STEP, or JOB_COMPLETION_INDEX with --shard-count");
    CLI::Option* shard_count =
        check->add_option("--shard-count", cmd.shard_count, "The number of parts, N, for JOB_COMPLETION_INDEX");
    CLI::Option* merge = check->add_flag(
        "--merge", cmd.merge,
        "The inputs are the report folders of every shard of one run: merge their summary.json files and "
        "images into one report (-r, --junit, --json) as one unsharded run writes it");
    merge->excludes(shard)->excludes(shard_count)->excludes(golden)->excludes(scene_root)->excludes(update);

    const auto threshold = [&](const char* flag, const char* key, const char* help) {
        check->add_option_function<double>(
            flag, [&cmd, key](double value) { cmd.defaults.thresholds.emplace_back(key, value); }, help);
    };
    threshold("--fail", "fail", "Per-channel tolerance; PNG: display value in [0,1], EXR: radiance (default 1.5/255)");
    threshold("--fail-pixels", "fail_pixels", "Pixels allowed beyond --fail");
    threshold("--fail-ratio", "fail_ratio", "Fraction of the image allowed beyond --fail");
    threshold("--fail-relative", "fail_relative", "Also beyond this fraction of the mean value to count");
    threshold("--warn", "warn", "Lower tolerance for warnings (default 0: any difference)");
    threshold("--warn-pixels", "warn_pixels", "Pixels allowed beyond --warn before a warning");
    threshold("--warn-ratio", "warn_ratio", "Fraction allowed beyond --warn before a warning");
    threshold("--warn-relative", "warn_relative", "Also beyond this fraction of the mean value to count");
    threshold("--max-error", "max_error", "Hard ceiling on the largest difference");
    threshold("--max-warn-pixels", "max_warn_pixels", "Pixels beyond --warn that fail the scene");
    threshold("--max-warn-ratio", "max_warn_ratio", "Fraction beyond --warn that fails the scene");
    check->add_flag("--perceptual", cmd.defaults.perceptual, "Also apply Yee's perceptual test");

    no_default_shown(check->add_option("--width", cmd.defaults.width, "Override every scene's image width"))
        ->check(CLI::Range(1, kMaxImageDimension));
    no_default_shown(check->add_option("--height", cmd.defaults.height, "Override every scene's image height"))
        ->check(CLI::Range(1, kMaxImageDimension));
    no_default_shown(check->add_option("--msaa", cmd.defaults.msaa, "Override every scene's samples per pixel, 1 or 4"))
        ->check(CLI::IsMember({1, 4}));
    check->add_option("--threads", cmd.settings.threads, "Worker threads (0 = one per hardware thread)")
        ->check(CLI::Range(0, 1024));
    check->add_option("--tile-size", cmd.settings.tile_size, "Screen tile side in pixels (power of two, 8-256)");
    check->add_option("--isa", cmd.settings.isa, "SIMD kernels: auto, scalar, sse4, avx2, avx512");
    return check;
}

int run_check(CheckCommand& cmd) {
    // --update's values: "missing", scene names, or inputs that followed a bare --update.
    std::vector<std::string> update_names;
    const bool update_given = cmd.update_option != nullptr && cmd.update_option->count() > 0;
    check::UpdateMode update_mode = update_given ? check::UpdateMode::failed : check::UpdateMode::none;
    bool mode_word = false;
    for (const std::string& value : cmd.update) {
        if (value.empty()) continue;
        if (value == "failed" || value == "missing") {
            mode_word = true;
            update_mode = value == "missing" ? check::UpdateMode::missing : check::UpdateMode::failed;
        } else if (is_input_path(value)) {
            cmd.inputs.push_back(value);
        } else {
            update_names.push_back(value);
        }
    }
    if (mode_word && !update_names.empty()) {
        std::fprintf(stderr, "tessera: error: --update takes 'missing' or scene names, not both\n");
        return kCheckUsageError;
    }
    if (!update_names.empty()) update_mode = check::UpdateMode::named;
    if (cmd.inputs.empty()) {
        std::fprintf(stderr, "tessera: error: check: expected a manifest (check.toml), or scene files with --golden "
                             "DIR, or report folders with --merge\n");
        return kCheckUsageError;
    }
    if (cmd.merge) {
        if (update_given || !cmd.filters.empty()) {
            std::fprintf(stderr, "tessera: error: --merge puts finished shards together: --update and --filter apply "
                                 "when the shards run\n");
            return kCheckUsageError;
        }
        return run_merge(cmd);
    }
    check::Suite suite;
    batch::ShardChoice shard;
    try {
        suite = load_suite(cmd);
        if (!cmd.filters.empty()) suite.scenes = check::filter_scenes(suite.scenes, cmd.filters);
        for (const std::string& name : update_names)
            if (std::none_of(suite.scenes.begin(), suite.scenes.end(),
                             [&](const check::SceneEntry& e) { return check::matches_any(e.name, {name}); }))
                throw check::ManifestError("--update '" + name + "' matches no scene name" +
                                           (cmd.filters.empty() ? "" : " that --filter keeps") + " of the suite");
        shard = batch::choose_shard(cmd.shard, cmd.shard_count, batch::process_environment());
    } catch (const std::exception& e) {  // ManifestError, threshold values out of range, ShardError
        std::fprintf(stderr, "tessera: error: %s\n", e.what());
        return kCheckUsageError;
    }
    const std::size_t suite_scenes = suite.scenes.size();
    if (shard.sharded()) {
        suite.scenes = batch::take_shard(suite.scenes, shard.shard);
        std::printf("shard %s (from %s): %zu of %zu scenes\n", batch::shard_text(shard.shard).c_str(),
                    shard.origin.c_str(), suite.scenes.size(), suite_scenes);
        std::fflush(stdout);
    }
    check::RunOptions options;
    options.report_dir = !cmd.report_dir.empty() ? fs::path(cmd.report_dir)
                         : !suite.report_dir.empty() ? suite.report_dir
                                                     : fs::path("check-report");
    // Shards of one array must not write one report: without --report each takes a folder of its own.
    if (cmd.report_dir.empty() && shard.shard.count > 1)
        options.report_dir /= "shard_" + std::to_string(shard.shard.index + 1);
    // The report's files are written after every scene has rendered: refuse an unwritable place now.
    try {
        check_writable_folder(options.report_dir.string(), "the report");
        if (!cmd.junit_path.empty()) check_writable_file(cmd.junit_path, "the --junit file");
        if (!cmd.json_path.empty()) check_writable_file(cmd.json_path, "the --json file");
    } catch (const UsageError& e) {
        print_error(e.what());
        return kCheckUsageError;
    }
    options.settings = cmd.settings;
    options.update = update_mode;
    options.update_names = update_names;
    options.new_golden_format = suite.new_golden_format;
    ProgressLine progress(cmd.quiet);
    check::CheckRun run;
    try {
        run = check::run_check(suite.scenes, options, std::ref(progress));
    } catch (const std::invalid_argument& e) {  // the renderer refused --isa or --tile-size: bad usage
        std::fprintf(stderr, "tessera: error: %s\n", e.what());
        return kCheckUsageError;
    }

    run.shard = shard.shard;
    run.suite_scenes = suite_scenes;

    write_reports(cmd, run, options.report_dir);
    print_summary(run, options.report_dir);
    return run.exit_status();
}

}  // namespace tessera::cli
