// summary.json: written by every run, read back by `tessera check --merge`.
// Each record's fields are listed once, in a function template that a writer
// and a reader both walk, so that the two cannot disagree on a name.
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include "check/atomic_file.hpp"
#include "check/report.hpp"
#include "io/input_file.hpp"
#include "io/nesting_depth.hpp"

namespace tessera::check {

namespace fs = std::filesystem;

namespace {

constexpr const char* kSummaryFormat = "tessera-check-summary/1";

// Writes each field into a JSON object. JSON has no infinity: an unset ceiling
// (or the PSNR of identical images) is null.
struct JsonWriter {
    nlohmann::json& out;
    void operator()(const char* key, const double& v) { out[key] = std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }
    void operator()(const char* key, const std::optional<double>& v) { out[key] = v ? nlohmann::json(*v) : nlohmann::json(); }
    void operator()(const char* key, const std::string& v) { out[key] = v; }
    void operator()(const char* key, const fs::path& v) { out[key] = v.string(); }
    template <typename Number>
        requires std::is_integral_v<Number>
    void operator()(const char* key, const Number& v) { out[key] = v; }
};

// Reads each field back; a field of the wrong type or a missing one throws
// std::runtime_error naming it (the caller adds the file).
struct JsonReader {
    const nlohmann::json& in;
    const nlohmann::json& at(const char* key) const {
        if (!in.is_object() || !in.contains(key)) throw std::runtime_error(std::string("no \"") + key + "\" field");
        return in.at(key);
    }
    template <typename Value>
    Value as(const char* key) const {
        try {
            return at(key).get<Value>();
        } catch (const nlohmann::json::exception&) {
            throw std::runtime_error(std::string("\"") + key + "\" has the wrong type: " + at(key).dump());
        }
    }
    void operator()(const char* key, double& v) {
        v = at(key).is_null() ? std::numeric_limits<double>::infinity() : as<double>(key);
    }
    void operator()(const char* key, std::optional<double>& v) {
        v = at(key).is_null() ? std::nullopt : std::optional<double>(as<double>(key));
    }
    void operator()(const char* key, std::string& v) { v = as<std::string>(key); }
    void operator()(const char* key, fs::path& v) { v = as<std::string>(key); }
    template <typename Number>
        requires std::is_integral_v<Number>
    void operator()(const char* key, Number& v) { v = as<Number>(key); }
};

// Const for the writer, mutable for the reader.
template <typename Io, typename T>
void thresholds_fields(Io& io, T& t) {
    io("fail", t.fail);
    io("fail_relative", t.fail_relative);
    io("fail_pixels", t.fail_pixels);
    io("fail_ratio", t.fail_ratio);
    io("warn", t.warn);
    io("warn_relative", t.warn_relative);
    io("warn_pixels", t.warn_pixels);
    io("warn_ratio", t.warn_ratio);
    io("max_error", t.max_error);
    io("max_warn_pixels", t.max_warn_pixels);
    io("max_warn_ratio", t.max_warn_ratio);
    io("perceptual", t.perceptual);
}

template <typename Io, typename M>
void metrics_fields(Io& io, M& m) {
    io("pixels", m.pixels);
    io("ignored_pixels", m.ignored_pixels);
    io("max_error", m.max_error);
    io("max_x", m.max_x);
    io("max_y", m.max_y);
    io("max_channel", m.max_channel);
    io("mean_error", m.mean_error);
    io("rms_error", m.rms_error);
    io("psnr", m.psnr);
    io("pixels_over_fail", m.pixels_over_fail);
    io("pixels_over_warn", m.pixels_over_warn);
    io("perceptual_fail", m.perceptual_fail);  // -1: not run
}

template <typename Io, typename I>
void images_fields(Io& io, I& i) {
    io("expected", i.expected);
    io("actual", i.actual);
    io("diff", i.diff);
    io("diff_scale", i.diff_scale);
}

// The scalar fields of a scene record; golden_kind, status, thresholds, images
// and metrics are objects or enums that scene_json / scene_from_json handle.
template <typename Io, typename R>
void scene_fields(Io& io, R& r) {
    io("name", r.name);
    io("scene", r.scene);
    io("golden", r.golden);
    io("reason", r.reason);
    io("width", r.width);
    io("height", r.height);
    io("msaa", r.msaa);
    io("render_ms", r.render_ms);
    io("compare_ms", r.compare_ms);
    io("update", r.update);
}

constexpr const char* kGoldenKind = "golden_kind";
constexpr const char* kStatus = "status";
constexpr const char* kThresholds = "thresholds";
constexpr const char* kImages = "images";
constexpr const char* kMetrics = "metrics";

template <typename Object, typename Fields>
nlohmann::json write_object(const Object& object, Fields fields) {
    nlohmann::json out = nlohmann::json::object();
    JsonWriter writer{out};
    fields(writer, object);
    return out;
}

nlohmann::json scene_json(const SceneResult& r) {
    nlohmann::json scene = write_object(r, [](auto& io, auto& x) { scene_fields(io, x); });
    scene[kGoldenKind] = r.golden_kind == GoldenKind::exr ? "exr" : "png";
    scene[kStatus] = std::string(status_name(r.status));
    scene[kThresholds] = write_object(r.thresholds, [](auto& io, auto& x) { thresholds_fields(io, x); });
    scene[kImages] = write_object(r.images, [](auto& io, auto& x) { images_fields(io, x); });
    if (r.compared) {
        scene[kMetrics] = write_object(r.metrics, [](auto& io, auto& x) { metrics_fields(io, x); });
        if (r.metrics.perceptual_fail < 0) scene[kMetrics]["perceptual_fail"] = nullptr;
    } else {
        scene[kMetrics] = nullptr;
    }
    return scene;
}

SceneResult scene_from_json(const nlohmann::json& scene) {
    SceneResult r;
    JsonReader reader{scene};
    scene_fields(reader, r);
    const std::string kind = reader.as<std::string>(kGoldenKind);
    if (kind != "png" && kind != "exr") throw std::runtime_error("unknown golden_kind \"" + kind + "\"");
    r.golden_kind = kind == "exr" ? GoldenKind::exr : GoldenKind::png;
    const std::string status = reader.as<std::string>(kStatus);
    bool known = false;
    for (Status s : {Status::error, Status::fail, Status::missing, Status::warn, Status::pass})
        if (status_name(s) == status) r.status = s, known = true;
    if (!known) throw std::runtime_error("scene \"" + r.name + "\": unknown status \"" + status + "\"");
    JsonReader thresholds{reader.at(kThresholds)};
    thresholds_fields(thresholds, r.thresholds);
    JsonReader images{reader.at(kImages)};
    images_fields(images, r.images);
    const nlohmann::json& metrics = reader.at(kMetrics);
    r.compared = !metrics.is_null();
    if (r.compared) {
        nlohmann::json with_perceptual = metrics;
        if (with_perceptual.contains("perceptual_fail") && with_perceptual["perceptual_fail"].is_null())
            with_perceptual["perceptual_fail"] = -1;
        JsonReader reader_m{with_perceptual};
        metrics_fields(reader_m, r.metrics);
    }
    return r;
}

}  // namespace

std::string json_summary(const CheckRun& run) {
    nlohmann::json counts = nlohmann::json::object();
    for (Status s : {Status::pass, Status::warn, Status::fail, Status::missing, Status::error})
        counts[std::string(status_name(s))] = run.count(s);
    counts["updated"] = run.updated();
    nlohmann::json scenes = nlohmann::json::array();
    for (const SceneResult& r : run.scenes) scenes.push_back(scene_json(r));
    const nlohmann::json summary = {{"format", kSummaryFormat},
                                    {"exit_status", run.exit_status()},
                                    {"seconds", run.seconds},
                                    {"isa", run.isa},
                                    {"threads", run.threads},
                                    {"shard", batch::shard_text(run.shard)},
                                    {"suite_scenes", run.suite_scenes},
                                    {"counts", counts},
                                    {"scenes", scenes}};
    return summary.dump(2) + "\n";
}

void write_json_summary(const CheckRun& run, const std::filesystem::path& path) {
    write_text_atomically(path, json_summary(run));
}

// What json_summary writes: 4 levels, ~1 KB a scene (256 MB is ~250k scenes).
constexpr std::size_t kMaxSummaryDepth = 16;
constexpr std::uint64_t kMaxSummaryBytes = 256ull << 20;

CheckRun read_json_summary(const std::filesystem::path& path) {
    std::string text;
    try {
        // A summary holds a few hundred bytes per scene.
        text = io::read_input_text(path, kMaxSummaryBytes, "summary");
        io::check_json_depth(text, kMaxSummaryDepth, path.string());  // nlohmann's parser recurses per level
    } catch (const std::runtime_error& e) {
        throw SummaryError(e.what());
    }
    CheckRun run;
    try {
        const nlohmann::json summary = nlohmann::json::parse(text);
        JsonReader reader{summary};
        const std::string format = reader.as<std::string>("format");
        if (format != kSummaryFormat)
            throw std::runtime_error("format \"" + format + "\", expected \"" + kSummaryFormat + "\"");
        run.seconds = reader.as<double>("seconds");
        run.isa = reader.as<std::string>("isa");
        run.threads = reader.as<int>("threads");
        run.shard = batch::parse_shard(reader.as<std::string>("shard"));
        run.suite_scenes = reader.as<std::size_t>("suite_scenes");
        const nlohmann::json& scenes = reader.at("scenes");
        if (!scenes.is_array()) throw std::runtime_error("\"scenes\" is not an array");
        for (const nlohmann::json& scene : scenes) run.scenes.push_back(scene_from_json(scene));
    } catch (const std::exception& e) {  // JSON syntax, fields, shard text
        throw SummaryError(path.string() + ": not a tessera check summary: " + e.what());
    }
    return run;
}

}  // namespace tessera::check
