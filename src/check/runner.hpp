// Running a check suite: render every scene with one renderer, compare each
// with its golden image, write the images the report shows, and optionally
// update golden images.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "batch/shard.hpp"
#include "check/compare.hpp"
#include "check/suite.hpp"
#include "tessera/renderer.hpp"

namespace tessera::check {

// --update writes goldens for fail + missing; =missing only missing; --update NAME... (named) for the scenes
// RunOptions::update_names matches, whatever they differ by (not errors, not bit-identical renders).
enum class UpdateMode { none, failed, missing, named };

struct RunOptions {
    std::filesystem::path report_dir;  // created; the images an earlier run left in images/ are removed
    RenderSettings settings;           // threads, tile size, ISA (keep_radiance is decided per suite)
    UpdateMode update = UpdateMode::none;
    std::vector<std::string> update_names;  // UpdateMode::named: scene names or glob patterns over them
    GoldenFormat new_golden_format = GoldenFormat::png;
};

// The report's images of one scene, relative to the report folder and inside it ("" where there is none),
// so that the folder works on its own (a CI artifact): a bit-identical scene's golden is linked or copied in.
struct ReportImages {
    std::string expected;
    std::string actual;
    std::string diff;
    double diff_scale = 0;  // the difference that shows at full brightness in the heat map
};

struct SceneResult {
    std::string name;
    std::filesystem::path scene;
    std::filesystem::path golden;   // the golden compared with (or that --update would create)
    GoldenKind golden_kind = GoldenKind::png;
    Thresholds thresholds;
    Status status = Status::error;
    std::string reason;             // why not a pass: the error message, the missing path, what differed
    bool compared = false;          // metrics are valid
    Metrics metrics;
    int width = 0, height = 0, msaa = 1;  // as rendered
    double render_ms = 0;           // loading and rendering the scene
    double compare_ms = 0;          // reading the golden, comparing, writing report images and goldens
    ReportImages images;
    std::string update;             // what --update did, or ""
};

struct CheckRun {
    std::vector<SceneResult> scenes;  // in the suite's order
    batch::Shard shard;               // the part of the suite these scenes are (1/1: all of it)
    std::size_t suite_scenes = 0;     // the scenes of the whole suite, of which `shard` took `scenes`
    double seconds = 0;
    std::string isa;
    int threads = 0;
    int count(Status status) const;
    int updated() const;
    // 0 when every scene passed or warned (or was updated), else 1.
    int exit_status() const;
};

// Called after each scene: its index (0-based), the scene count, its result.
using Progress = std::function<void(std::size_t index, std::size_t count, const SceneResult& result)>;

// Renders and compares every scene of `scenes`, in order; a scene that fails to
// load or render is an error and the others go on. Throws only when the report
// folder cannot be made.
CheckRun run_check(const std::vector<SceneEntry>& scenes, const RunOptions& options, const Progress& progress = {});

// Removes the report images (*.expected.png, *.actual.png, *.diff.png,
// *.golden.png) an earlier run left under report_dir/images, and the folders
// that leaves empty; nothing else.
void remove_report_images(const std::filesystem::path& report_dir);

// Results ordered as a report lists them: errors, failures, missing, warnings,
// passes; within each, the largest share of pixels beyond the fail tolerance first, then the
// largest difference relative to that tolerance.
std::vector<const SceneResult*> worst_first(const CheckRun& run);

}  // namespace tessera::check
