// check.toml: a golden-image suite for `tessera check`. Paths are relative to
// the manifest's folder. Any key not listed is an error (a typo should not
// silently loosen a test).
//
//   scenes = ["scenes/*.toml", "extra/lamp.glb"]  # required: scene files or glob patterns (* ? [..]);
//                                    # each must match at least one file
//   golden = "golden"                # required: the folder of golden images, <name>.png or <name>.exr
//   scene_root = "scenes"            # a scene's name is its path below this folder without extension,
//                                    # e.g. "gltf/helmet" -> golden/gltf/helmet.png; default: the
//                                    # deepest folder holding every scene
//   new_golden_format = "png"        # "png" | "exr": what --update writes where no golden exists yet
//   report = "check-report"          # the report folder (default: ./check-report; --report wins)
//   width = 640                      # override every scene's output size and samples per pixel
//   height = 360
//   msaa = 4
//
//   [thresholds]                     # for every scene: keys and meaning in check/thresholds.hpp
//   fail = 0.0098                    # per-channel tolerance (PNG: display value in [0, 1]; EXR: radiance)
//   fail_pixels = 9                  # pixels allowed beyond it (and/or fail_ratio, a fraction of the image)
//   fail_relative = 0                # also relative to the mean of the two values (both must be exceeded)
//   warn = 0.0059                    # a lower level: warn_pixels / warn_ratio beyond it make a warning,
//   warn_relative = 0                #   max_warn_pixels / max_warn_ratio beyond it a failure
//   max_error = 0.0333               # hard ceiling on the largest difference
//   perceptual = false               # also apply Yee's perceptual test (fail_pixels / fail_ratio allowed)
//
//   [[override]]                     # any number; they apply in order, after [thresholds]
//   scenes = "gltf/*"                # required: a scene name or glob over names, or an array of them;
//                                    # each must match at least one scene
//   fail_pixels = 20                 # any [thresholds] key, and width / height / msaa
//   ignore = [[0, 0, 40, 12]]        # pixels not compared: [x, y, width, height] rectangles, row 0 at the top
//   ignore_mask = "masks/clock.png"  # and/or a mask image the render's size: white pixels are not compared
//
// Threshold options on the command line apply after [thresholds] and before the overrides.
#include <fnmatch.h>
#include <glob.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>

#include <toml++/toml.h>

#include "check/suite.hpp"
#include "io/input_file.hpp"
#include "io/nesting_depth.hpp"
#include "tessera/scene.hpp"

namespace tessera::check {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kNumericThresholdKeys[] = {
    "fail", "fail_relative", "fail_pixels", "fail_ratio", "warn", "warn_relative", "warn_pixels",
    "warn_ratio", "max_error", "max_warn_pixels", "max_warn_ratio"};

bool has_wildcard(const std::string& pattern) { return pattern.find_first_of("*?[") != std::string::npos; }

// The files a pattern names, sorted; throws std::invalid_argument when none.
std::vector<fs::path> expand_pattern(const std::string& pattern) {
    if (!has_wildcard(pattern)) {
        std::error_code error;
        if (!fs::is_regular_file(pattern, error)) throw std::invalid_argument(pattern + ": no such scene file");
        return {fs::path(pattern)};
    }
    glob_t matches{};
    const int status = ::glob(pattern.c_str(), 0, nullptr, &matches);
    std::vector<fs::path> files;
    if (status == 0)
        for (std::size_t i = 0; i < matches.gl_pathc; ++i)
            if (fs::is_regular_file(matches.gl_pathv[i])) files.emplace_back(matches.gl_pathv[i]);
    ::globfree(&matches);
    if (files.empty()) throw std::invalid_argument("'" + pattern + "' matches no scene file");
    return files;  // glob sorts
}

fs::path normal_absolute(const fs::path& path) { return fs::absolute(path).lexically_normal(); }

fs::path common_folder(const std::vector<fs::path>& files) {
    fs::path common = files.front().parent_path();
    for (const fs::path& file : files) {
        const fs::path folder = file.parent_path();
        while (!common.empty() && folder.lexically_relative(common).string().starts_with(".."))
            common = common.parent_path() == common ? fs::path() : common.parent_path();
    }
    return common;
}

// Names every scene, or throws std::invalid_argument for a scene outside the root or two scenes with one name.
std::vector<SceneEntry> name_scenes(const std::vector<fs::path>& files, fs::path root, const fs::path& golden_dir) {
    if (root.empty()) root = common_folder(files);
    std::vector<SceneEntry> scenes;
    std::map<std::string, fs::path> seen;
    for (const fs::path& file : files) {
        const fs::path relative = file.lexically_relative(root);
        if (relative.empty() || relative.string().starts_with(".."))
            throw std::invalid_argument(file.string() + " is not inside the scene root " + root.string());
        const std::string name = relative.parent_path().empty()
                                     ? relative.stem().string()
                                     : (relative.parent_path() / relative.stem()).generic_string();
        const auto [at, inserted] = seen.emplace(name, file);
        if (!inserted) {
            if (at->second == file) continue;  // named twice: checked once
            throw std::invalid_argument("two scenes have the name '" + name + "' (" + at->second.string() + " and " +
                                        file.string() + "): their golden images would be the same file");
        }
        SceneEntry entry;
        entry.name = name;
        entry.scene = file;
        entry.golden_stem = golden_dir / name;
        scenes.push_back(std::move(entry));
    }
    return scenes;
}

void apply_defaults(std::vector<SceneEntry>& scenes, const SuiteDefaults& defaults) {
    for (SceneEntry& scene : scenes) {
        for (const auto& [key, value] : defaults.thresholds) set_threshold(scene.thresholds, key, value);
        if (defaults.perceptual) scene.thresholds.perceptual = true;
        if (defaults.width) scene.width = defaults.width;
        if (defaults.height) scene.height = defaults.height;
        if (defaults.msaa) scene.msaa = defaults.msaa;
    }
}

// A manifest lists scenes by pattern: a page of TOML.
constexpr std::uint64_t kMaxManifestBytes = 16ull << 20;

class ManifestReader {
public:
    explicit ManifestReader(const fs::path& manifest) : manifest_(manifest), source_(manifest.string()) {}

    Suite read(const SuiteDefaults& defaults) {
        toml::table root;
        try {
            const std::string text = io::read_input_text(manifest_, kMaxManifestBytes, "check manifest");
            io::check_toml_depth(text, io::kMaxTomlDepth, source_);  // toml++ recurses per level
            root = toml::parse(text, source_);
        } catch (const io::InputFileError& error) {
            throw ManifestError(error.what());
        } catch (const toml::parse_error& error) {
            const toml::source_position where = error.source().begin;
            throw ManifestError(source_ + ":" + std::to_string(where.line) + ":" + std::to_string(where.column) +
                                ": " + std::string(error.description()));
        }
        const fs::path base = manifest_.parent_path();
        for (const auto& [key, node] : root) {
            static const std::set<std::string_view> known = {"scenes", "golden", "scene_root", "new_golden_format",
                                                             "report", "width", "height", "msaa", "thresholds",
                                                             "override"};
            if (!known.contains(key.str()))
                fail_at(key.source(), "unknown key '" + std::string(key.str()) +
                                          "' (expected scenes, golden, scene_root, new_golden_format, report, width, "
                                          "height, msaa, [thresholds] or [[override]])");
        }

        const toml::node* scenes_node = root.get("scenes");
        if (!scenes_node) fail_at({}, "missing required key 'scenes' (scene files or glob patterns)");
        std::vector<fs::path> files;
        for (const toml::node* pattern : string_or_array(*scenes_node, "scenes")) {
            const std::string text = pattern->value<std::string>().value();
            try {
                for (const fs::path& file : expand_pattern((base / text).string()))
                    files.push_back(normal_absolute(file));
            } catch (const std::invalid_argument& e) {
                fail_at(pattern->source(), e.what());
            }
        }
        const fs::path golden = normal_absolute(base / required_string(root, "golden"));
        fs::path scene_root;
        if (const toml::node* node = root.get("scene_root")) scene_root = normal_absolute(base / string_of(*node, "scene_root"));

        Suite suite;
        try {
            suite.scenes = name_scenes(files, scene_root, golden);
        } catch (const std::invalid_argument& e) {
            fail_at(scenes_node->source(), e.what());
        }
        if (const toml::node* node = root.get("new_golden_format")) {
            const std::string format = string_of(*node, "new_golden_format");
            if (format != "png" && format != "exr")
                fail_at(node->source(), "expected \"png\" or \"exr\" for 'new_golden_format', got \"" + format + "\"");
            suite.new_golden_format = format == "exr" ? GoldenFormat::exr : GoldenFormat::png;
        }
        if (const toml::node* node = root.get("report")) suite.report_dir = base / string_of(*node, "report");

        Thresholds base_thresholds;
        if (const toml::node* node = root.get("thresholds")) {
            const toml::table* table = node->as_table();
            if (!table) fail_type(*node, "a table", "thresholds");
            read_thresholds(*table, base_thresholds, "thresholds", {});
        }
        int width = 0, height = 0, msaa = 0;
        read_size(root, "", width, height, msaa);
        for (SceneEntry& scene : suite.scenes) {
            scene.thresholds = base_thresholds;
            scene.width = width;
            scene.height = height;
            scene.msaa = msaa;
        }
        apply_defaults(suite.scenes, defaults);

        if (const toml::node* node = root.get("override")) {
            const toml::array* overrides = node->as_array();
            if (!overrides || !overrides->is_array_of_tables()) fail_type(*node, "an array of tables [[override]]", "override");
            for (const toml::node& item : *overrides) read_override(*item.as_table(), suite.scenes);
        }
        return suite;
    }

private:
    [[noreturn]] void fail_at(const toml::source_region& where, const std::string& message) const {
        if (where.begin.line == 0) throw ManifestError(source_ + ": " + message);
        throw ManifestError(source_ + ":" + std::to_string(where.begin.line) + ":" +
                            std::to_string(where.begin.column) + ": " + message);
    }
    [[noreturn]] void fail_type(const toml::node& node, std::string_view expected, std::string_view name) const {
        fail_at(node.source(), "expected " + std::string(expected) + " for '" + std::string(name) + "', got " +
                                   std::string(toml::impl::node_type_friendly_names[size_t(node.type())]));
    }

    std::string string_of(const toml::node& node, std::string_view name) const {
        const auto value = node.value<std::string>();
        if (!node.is_string() || !value) fail_type(node, "a string", name);
        return *value;
    }
    std::string required_string(const toml::table& table, std::string_view key) const {
        const toml::node* node = table.get(key);
        if (!node) fail_at({}, "missing required key '" + std::string(key) + "'");  // (only the root has required keys)
        return string_of(*node, key);
    }
    std::vector<const toml::node*> string_or_array(const toml::node& node, std::string_view name) const {
        std::vector<const toml::node*> items;
        if (node.is_string()) {
            items.push_back(&node);
        } else if (const toml::array* array = node.as_array()) {
            for (const toml::node& item : *array) {
                if (!item.is_string()) fail_type(item, "a string", name);
                items.push_back(&item);
            }
            if (items.empty()) fail_at(node.source(), "'" + std::string(name) + "' is empty");
        } else {
            fail_type(node, "a string or an array of strings", name);
        }
        return items;
    }

    double number_of(const toml::node& node, std::string_view name) const {
        if (!node.is_number()) fail_type(node, "a number", name);
        return *node.value<double>();
    }

    // The threshold keys of `table` (skipping `extra_keys`, which the caller reads).
    void read_thresholds(const toml::table& table, Thresholds& thresholds, std::string_view table_name,
                         const std::set<std::string_view>& extra_keys) const {
        for (const auto& [key, node] : table) {
            const std::string name = std::string(table_name) + "." + std::string(key.str());
            if (extra_keys.contains(key.str())) continue;
            if (key.str() == "perceptual") {
                if (!node.is_boolean()) fail_type(node, "true or false", name);
                thresholds.perceptual = *node.value<bool>();
                continue;
            }
            if (!is_threshold_key(key.str()))
                fail_at(key.source(), "unknown key '" + name +
                                          "' (expected fail, fail_relative, fail_pixels, fail_ratio, warn, "
                                          "warn_relative, warn_pixels, warn_ratio, max_error, max_warn_pixels, "
                                          "max_warn_ratio or perceptual)");
            try {
                set_threshold(thresholds, key.str(), number_of(node, name));
            } catch (const std::invalid_argument& e) {
                fail_at(node.source(), std::string(e.what()) + " for '" + name + "'");
            }
        }
    }

    void read_size(const toml::table& table, std::string_view prefix, int& width, int& height, int& msaa) const {
        const auto read = [&](std::string_view key, int& out, int low, int high) {
            const toml::node* node = table.get(key);
            if (!node) return;
            const std::string name = std::string(prefix) + std::string(key);
            if (!node->is_integer()) fail_type(*node, "an integer", name);
            const long long value = *node->value<long long>();
            if (value < low || value > high)
                fail_at(node->source(), "expected '" + name + "' to be in " + std::to_string(low) + ".." +
                                            std::to_string(high) + ", got " + std::to_string(value));
            out = int(value);
        };
        read("width", width, 1, kMaxImageDimension);
        read("height", height, 1, kMaxImageDimension);
        read("msaa", msaa, 1, 4);
        if (const toml::node* node = table.get("msaa"); node && msaa != 1 && msaa != 4)
            fail_at(node->source(), "expected '" + std::string(prefix) + "msaa' to be 1 or 4, got " + std::to_string(msaa));
    }

    void read_override(const toml::table& table, std::vector<SceneEntry>& scenes) const {
        const toml::node* patterns = table.get("scenes");
        if (!patterns) fail_at(table.source(), "missing required key 'override.scenes' (scene names or glob patterns)");
        std::vector<SceneEntry*> matched;
        for (const toml::node* pattern : string_or_array(*patterns, "override.scenes")) {
            const std::string text = *pattern->value<std::string>();
            std::size_t count = 0;
            for (SceneEntry& scene : scenes) {
                if (::fnmatch(text.c_str(), scene.name.c_str(), 0) != 0) continue;
                ++count;
                if (std::find(matched.begin(), matched.end(), &scene) == matched.end()) matched.push_back(&scene);
            }
            if (count == 0) fail_at(pattern->source(), "'" + text + "' matches no scene name");
        }
        int width = 0, height = 0, msaa = 0;
        read_size(table, "override.", width, height, msaa);
        std::optional<std::vector<IgnoreRect>> rects;
        if (const toml::node* node = table.get("ignore")) rects = read_rects(*node);
        std::optional<fs::path> mask;
        if (const toml::node* node = table.get("ignore_mask")) {
            mask = normal_absolute(manifest_.parent_path() / string_of(*node, "override.ignore_mask"));
            std::error_code error;
            if (!fs::is_regular_file(*mask, error)) fail_at(node->source(), mask->string() + ": no such mask image");
        }
        for (SceneEntry* scene : matched) {
            read_thresholds(table, scene->thresholds, "override",
                            {"scenes", "width", "height", "msaa", "ignore", "ignore_mask"});
            if (width) scene->width = width;
            if (height) scene->height = height;
            if (msaa) scene->msaa = msaa;
            if (rects) scene->ignore.rects = *rects;  // a later override's list replaces an earlier one
            if (mask) scene->ignore.mask = *mask;
        }
    }

    // ignore = [[x, y, width, height], ...]: integers, x, y >= 0, width, height >= 1.
    std::vector<IgnoreRect> read_rects(const toml::node& node) const {
        const toml::array* list = node.as_array();
        if (!list) fail_type(node, "an array of [x, y, width, height] arrays", "override.ignore");
        std::vector<IgnoreRect> rects;
        for (const toml::node& item : *list) {
            const toml::array* rect = item.as_array();
            if (!rect || rect->size() != 4)
                fail_at(item.source(), "expected [x, y, width, height] (4 integers, pixels, row 0 at the top) in "
                                       "'override.ignore'");
            long long v[4];
            for (int i = 0; i < 4; ++i) {
                const toml::node& n = *rect->get(std::size_t(i));
                if (!n.is_integer()) fail_type(n, "an integer", "override.ignore");
                v[i] = *n.value<long long>();
                const long long low = i < 2 ? 0 : 1;
                if (v[i] < low || v[i] > kMaxImageDimension)
                    fail_at(n.source(), std::string("expected ") + (i < 2 ? "x and y" : "width and height") +
                                            " in 'override.ignore' to be in " + std::to_string(low) + ".." +
                                            std::to_string(kMaxImageDimension) + ", got " + std::to_string(v[i]));
            }
            rects.push_back({int(v[0]), int(v[1]), int(v[2]), int(v[3])});
        }
        return rects;
    }

    fs::path manifest_;
    std::string source_;
};

}  // namespace

bool matches_any(const std::string& name, const std::vector<std::string>& patterns) {
    return std::any_of(patterns.begin(), patterns.end(),
                       [&](const std::string& p) { return ::fnmatch(p.c_str(), name.c_str(), 0) == 0; });
}

std::vector<SceneEntry> filter_scenes(const std::vector<SceneEntry>& scenes, const std::vector<std::string>& patterns) {
    for (const std::string& pattern : patterns)
        if (std::none_of(scenes.begin(), scenes.end(),
                         [&](const SceneEntry& s) { return ::fnmatch(pattern.c_str(), s.name.c_str(), 0) == 0; }))
            throw ManifestError("--filter '" + pattern + "' matches no scene name of the suite");
    std::vector<SceneEntry> kept;
    for (const SceneEntry& scene : scenes)
        if (matches_any(scene.name, patterns)) kept.push_back(scene);
    return kept;
}

bool is_threshold_key(std::string_view key) {
    return std::find(std::begin(kNumericThresholdKeys), std::end(kNumericThresholdKeys), key) !=
           std::end(kNumericThresholdKeys);
}

void set_threshold(Thresholds& t, std::string_view key, double value) {
    if (!std::isfinite(value) || value < 0)
        throw std::invalid_argument("expected a finite number >= 0, got " + std::to_string(value));
    if (key.ends_with("_ratio") && value > 1)
        throw std::invalid_argument("expected a fraction of the image in [0, 1], got " + std::to_string(value));
    if (key == "fail") t.fail = value;
    else if (key == "fail_relative") t.fail_relative = value;
    else if (key == "fail_pixels") t.fail_pixels = value;
    else if (key == "fail_ratio") t.fail_ratio = value;
    else if (key == "warn") t.warn = value;
    else if (key == "warn_relative") t.warn_relative = value;
    else if (key == "warn_pixels") t.warn_pixels = value;
    else if (key == "warn_ratio") t.warn_ratio = value;
    else if (key == "max_error") t.max_error = value;
    else if (key == "max_warn_pixels") t.max_warn_pixels = value;
    else if (key == "max_warn_ratio") t.max_warn_ratio = value;
    else throw std::invalid_argument("unknown threshold '" + std::string(key) + "'");
}

Suite load_manifest(const fs::path& manifest, const SuiteDefaults& command_line) {
    std::error_code error;
    if (!fs::exists(manifest, error)) throw ManifestError(manifest.string() + ": cannot open manifest");
    return ManifestReader(manifest).read(command_line);
}

Suite suite_from_arguments(const std::vector<std::string>& scene_patterns, const fs::path& golden_dir,
                           const fs::path& scene_root, const SuiteDefaults& command_line) {
    std::vector<fs::path> files;
    Suite suite;
    try {
        for (const std::string& pattern : scene_patterns)
            for (const fs::path& file : expand_pattern(pattern)) files.push_back(normal_absolute(file));
        if (files.empty()) throw std::invalid_argument("no scene files given");
        suite.scenes = name_scenes(files, scene_root.empty() ? fs::path() : normal_absolute(scene_root),
                                   normal_absolute(golden_dir));
        apply_defaults(suite.scenes, command_line);
    } catch (const std::invalid_argument& e) {
        throw ManifestError(e.what());
    }
    return suite;
}

}  // namespace tessera::check
