#include "check/runner.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <stdexcept>
#include <utility>

#include "check/atomic_file.hpp"
#include "scene/scene_validation.hpp"
#include "tessera/image_io.hpp"
#include "tessera/scene.hpp"

namespace tessera::check {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

fs::path with_extension_added(const fs::path& stem, const char* extension) {
    fs::path path = stem;
    path += extension;
    return path;
}

// The golden a scene is compared with: <stem>.exr if there is one, else <stem>.png; where neither exists,
// the one --update would write.
fs::path golden_for(const SceneEntry& entry, GoldenFormat new_format) {
    const fs::path exr = with_extension_added(entry.golden_stem, ".exr");
    const fs::path png = with_extension_added(entry.golden_stem, ".png");
    std::error_code ignored;
    if (fs::exists(exr, ignored)) return exr;
    if (fs::exists(png, ignored)) return png;
    return new_format == GoldenFormat::exr ? exr : png;
}

struct SceneRun {
    const SceneEntry& entry;
    const RunOptions& options;
    Renderer& renderer;
};

// Loads, renders, compares; writes the report's images and, when asked, the golden.
SceneResult check_scene(const SceneRun& run) {
    const SceneEntry& entry = run.entry;
    SceneResult r;
    r.name = entry.name;
    r.scene = entry.scene;
    r.thresholds = entry.thresholds;
    r.golden = golden_for(entry, run.options.new_golden_format);
    r.golden_kind = golden_kind_for(r.golden);

    const Clock::time_point start = Clock::now();
    const RenderedImage* image = nullptr;
    try {
        Scene scene = load_scene_file(entry.scene);
        if (entry.width > 0) scene.width = entry.width;
        if (entry.height > 0) scene.height = entry.height;
        if (entry.msaa > 0) scene.msaa = entry.msaa;
        if (static_cast<long long>(scene.width) * scene.height > kMaxImagePixels)
            throw std::invalid_argument(entry.scene.string() + ": image size " + std::to_string(scene.width) + "x" +
                                        std::to_string(scene.height) + " (after the suite's overrides) is over " +
                                        std::to_string(kMaxImagePixels) + " pixels");
        validate_scene(scene);  // the renderer trusts its input
        r.width = scene.width;
        r.height = scene.height;
        r.msaa = scene.msaa;
        image = &run.renderer.render(scene);
    } catch (const std::exception& e) {
        r.status = Status::error;
        r.reason = e.what();
        r.render_ms = ms_since(start);
        return r;
    }
    r.render_ms = ms_since(start);

    const Clock::time_point compare_start = Clock::now();
    const fs::path& report = run.options.report_dir;
    const std::string base = "images/" + entry.name;
    const auto report_png = [&](const OIIO::ImageBuf& buffer, const char* suffix) {
        const std::string link = base + suffix;
        write_png_atomically(buffer, report / link);
        return link;
    };
    const OIIO::ImageBuf display = actual_image(*image, GoldenKind::png);
    std::vector<std::uint8_t> ignored_pixels;
    try {
        ignored_pixels = ignore_mask(entry.ignore, r.width, r.height);
    } catch (const std::runtime_error& e) {  // an unreadable mask, or one of another size
        r.status = Status::error;
        r.reason = e.what();
        r.compare_ms = ms_since(compare_start);
        return r;
    }

    std::error_code ignored;
    if (!fs::exists(r.golden, ignored)) {
        r.status = Status::missing;
        r.reason = "no golden image: " + r.golden.string();
        r.images.actual = report_png(display, ".actual.png");
    } else {
        try {
            const OIIO::ImageBuf golden = read_golden(r.golden, image->width, image->height);
            const OIIO::ImageBuf actual = actual_image(*image, r.golden_kind);
            const Comparison comparison =
                compare_images(actual, golden, entry.thresholds, r.golden_kind, ignored_pixels);
            r.status = comparison.status;
            r.reason = comparison.reason;
            r.compared = comparison.compared;
            r.metrics = comparison.metrics;
            const bool identical = comparison.compared && comparison.metrics.max_error == 0 &&
                                   comparison.metrics.ignored_pixels == 0;
            if (identical) {  // one image stands for both: a PNG golden linked (or copied) into the report
                if (r.golden_kind == GoldenKind::png) {
                    r.images.expected = base + ".golden.png";
                    link_or_copy_file_atomically(r.golden, report / r.images.expected);
                } else {
                    r.images.expected = report_png(display, ".actual.png");
                }
                r.images.actual = r.images.expected;
            } else {
                if (r.golden_kind == GoldenKind::png) {
                    r.images.expected = base + ".expected.png";
                    copy_file_atomically(r.golden, report / r.images.expected);
                } else {
                    r.images.expected = report_png(display_preview(golden, r.golden_kind), ".expected.png");
                }
                r.images.actual = report_png(display, ".actual.png");
                if (comparison.compared) {
                    r.images.diff_scale = heat_map_scale(entry.thresholds, comparison.metrics);
                    r.images.diff = report_png(diff_heat_map(actual, golden, r.images.diff_scale, ignored_pixels),
                                               ".diff.png");
                }
            }
        } catch (const std::runtime_error& e) {  // an unreadable golden fails the scene; the others go on
            if (r.status == Status::error) {
                r.status = Status::fail;
                r.reason = e.what();
            } else {
                throw;  // the report folder is unwritable: nothing else will work either
            }
        }
    }

    const UpdateMode update = run.options.update;
    const bool differs = r.status == Status::fail || r.status == Status::missing || r.status == Status::warn ||
                         (r.compared && (r.metrics.max_error > 0 || r.metrics.ignored_pixels > 0));
    const bool update_this = (update == UpdateMode::failed && (r.status == Status::fail || r.status == Status::missing)) ||
                             (update == UpdateMode::missing && r.status == Status::missing) ||
                             (update == UpdateMode::named && differs && matches_any(r.name, run.options.update_names));
    if (update_this) {
        fs::create_directories(r.golden.parent_path(), ignored);
        write_image(*image, r.golden);  // atomic: a temporary file renamed into place
        r.update = (r.status == Status::missing ? "added " : "updated ") + r.golden.string() +
                   (r.status == Status::missing ? "" : " (it differed: " + r.reason + ")");
    }
    r.compare_ms = ms_since(compare_start);
    return r;
}

bool is_report_image(const std::string& name) {
    for (const char* suffix : {".expected.png", ".actual.png", ".diff.png", ".golden.png"})
        if (name.ends_with(suffix)) return true;
    return false;
}

// Images an earlier run wrote (and only those: the folder may be the user's), so that none outlives its scene,
// then the folders of nested scene names ("images/gltf/") that this leaves empty.
void remove_stale_report_images(const fs::path& images) {
    std::error_code error;
    std::vector<fs::path> stale, folders;
    for (auto it = fs::recursive_directory_iterator(images, error); !error && it != fs::recursive_directory_iterator();
         it.increment(error)) {
        if (it->is_directory(error)) folders.push_back(it->path());
        else if (is_report_image(it->path().filename().string())) stale.push_back(it->path());
    }
    for (const fs::path& path : stale) fs::remove(path, error);
    // Deepest first; fs::remove leaves a folder that still holds something.
    std::sort(folders.begin(), folders.end(), [](const fs::path& a, const fs::path& b) {
        return std::distance(a.begin(), a.end()) > std::distance(b.begin(), b.end());
    });
    for (const fs::path& folder : folders)
        if (fs::is_empty(folder, error)) fs::remove(folder, error);
}

// How bad a result is, for ordering within a status: first how much of the image is beyond the
// fail tolerance, then how far the largest difference goes past it. Mismatched sizes are worst.
std::pair<double, double> severity(const SceneResult& r) {
    constexpr double kWorst = std::numeric_limits<double>::infinity();
    if (!r.compared) return {kWorst, kWorst};
    const double tolerance = r.thresholds.fail > 0 ? r.thresholds.fail : 1e-12;
    return {double(r.metrics.pixels_over_fail) / double(std::max<std::int64_t>(r.metrics.pixels, 1)),
            r.metrics.max_error / tolerance};
}

}  // namespace

void remove_report_images(const fs::path& report_dir) { remove_stale_report_images(report_dir / "images"); }

int CheckRun::count(Status status) const {
    return int(std::count_if(scenes.begin(), scenes.end(), [&](const SceneResult& r) { return r.status == status; }));
}

int CheckRun::updated() const {
    return int(std::count_if(scenes.begin(), scenes.end(), [](const SceneResult& r) { return !r.update.empty(); }));
}

int CheckRun::exit_status() const {
    for (const SceneResult& r : scenes)
        if (r.status == Status::error ||
            ((r.status == Status::fail || r.status == Status::missing) && r.update.empty()))
            return 1;
    return 0;
}

CheckRun run_check(const std::vector<SceneEntry>& scenes, const RunOptions& options, const Progress& progress) {
    std::error_code error;
    remove_stale_report_images(options.report_dir / "images");
    fs::create_directories(options.report_dir / "images", error);
    if (error)
        throw std::runtime_error(options.report_dir.string() + ": cannot create the report folder: " + error.message());

    // The radiance image costs memory bandwidth: keep it only when an EXR golden is read or may be written.
    RenderSettings settings = options.settings;
    settings.keep_radiance = false;
    for (const SceneEntry& entry : scenes)
        if (golden_kind_for(golden_for(entry, options.new_golden_format)) == GoldenKind::exr)
            settings.keep_radiance = true;
    Renderer renderer(settings);  // one thread pool and one frame memory for every scene

    CheckRun run;
    run.suite_scenes = scenes.size();  // the caller that takes a shard of a suite says so afterwards
    run.isa = renderer.isa_name();
    run.threads = renderer.threads();
    const Clock::time_point start = Clock::now();
    for (std::size_t i = 0; i < scenes.size(); ++i) {
        run.scenes.push_back(check_scene({scenes[i], options, renderer}));
        if (progress) progress(i, scenes.size(), run.scenes.back());
    }
    run.seconds = ms_since(start) / 1000.0;
    return run;
}

std::vector<const SceneResult*> worst_first(const CheckRun& run) {
    std::vector<const SceneResult*> order;
    for (const SceneResult& r : run.scenes) order.push_back(&r);
    std::stable_sort(order.begin(), order.end(), [](const SceneResult* a, const SceneResult* b) {
        if (a->status != b->status) return a->status < b->status;
        return severity(*a) > severity(*b);
    });
    return order;
}

}  // namespace tessera::check
