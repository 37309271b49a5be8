#include <cmath>

#include <nlohmann/json.hpp>

#include "check/atomic_file.hpp"
#include "check/report.hpp"

namespace tessera::check {

namespace {

// JSON has no infinity: an unset ceiling is null.
nlohmann::json finite_or_null(double value) { return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(); }

nlohmann::json thresholds_json(const Thresholds& t) {
    return {{"fail", t.fail},
            {"fail_relative", t.fail_relative},
            {"fail_pixels", t.fail_pixels},
            {"fail_ratio", t.fail_ratio},
            {"warn", t.warn},
            {"warn_relative", t.warn_relative},
            {"warn_pixels", t.warn_pixels},
            {"warn_ratio", t.warn_ratio},
            {"max_error", finite_or_null(t.max_error)},
            {"max_warn_pixels", t.max_warn_pixels ? nlohmann::json(*t.max_warn_pixels) : nlohmann::json()},
            {"max_warn_ratio", t.max_warn_ratio ? nlohmann::json(*t.max_warn_ratio) : nlohmann::json()},
            {"perceptual", t.perceptual}};
}

nlohmann::json scene_json(const SceneResult& r) {
    nlohmann::json scene = {{"name", r.name},
                            {"scene", r.scene.string()},
                            {"golden", r.golden.string()},
                            {"golden_kind", r.golden_kind == GoldenKind::exr ? "exr" : "png"},
                            {"status", std::string(status_name(r.status))},
                            {"reason", r.reason},
                            {"width", r.width},
                            {"height", r.height},
                            {"msaa", r.msaa},
                            {"render_ms", r.render_ms},
                            {"compare_ms", r.compare_ms},
                            {"thresholds", thresholds_json(r.thresholds)},
                            {"images",
                             {{"expected", r.images.expected},
                              {"actual", r.images.actual},
                              {"diff", r.images.diff},
                              {"diff_scale", r.images.diff_scale}}},
                            {"update", r.update}};
    if (r.compared) {
        const Metrics& m = r.metrics;
        scene["metrics"] = {{"pixels", m.pixels},
                            {"max_error", m.max_error},
                            {"max_x", m.max_x},
                            {"max_y", m.max_y},
                            {"max_channel", m.max_channel},
                            {"mean_error", m.mean_error},
                            {"rms_error", m.rms_error},
                            {"psnr", finite_or_null(m.psnr)},
                            {"pixels_over_fail", m.pixels_over_fail},
                            {"pixels_over_warn", m.pixels_over_warn},
                            {"perceptual_fail", m.perceptual_fail >= 0 ? nlohmann::json(m.perceptual_fail) : nlohmann::json()}};
    } else {
        scene["metrics"] = nullptr;
    }
    return scene;
}

}  // namespace

std::string json_summary(const CheckRun& run) {
    nlohmann::json counts = nlohmann::json::object();
    for (Status s : {Status::pass, Status::warn, Status::fail, Status::missing, Status::error})
        counts[std::string(status_name(s))] = run.count(s);
    counts["updated"] = run.updated();
    nlohmann::json scenes = nlohmann::json::array();
    for (const SceneResult& r : run.scenes) scenes.push_back(scene_json(r));
    const nlohmann::json summary = {{"format", "tessera-check-summary/1"},
                                    {"exit_status", run.exit_status()},
                                    {"seconds", run.seconds},
                                    {"isa", run.isa},
                                    {"threads", run.threads},
                                    {"counts", counts},
                                    {"scenes", scenes}};
    return summary.dump(2) + "\n";
}

void write_json_summary(const CheckRun& run, const std::filesystem::path& path) {
    write_text_atomically(path, json_summary(run));
}

}  // namespace tessera::check
