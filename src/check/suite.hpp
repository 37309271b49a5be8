// A check suite: which scenes, their golden images, thresholds and output
// overrides. Made from a manifest (check.toml) or from command-line arguments.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "check/ignore_regions.hpp"
#include "check/thresholds.hpp"

namespace tessera::check {

// A manifest or command line that cannot be used. what() reads
// "file:line:column: message" for manifests, as scene-file errors do.
class ManifestError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// One scene to check.
struct SceneEntry {
    std::string name;                 // the scene's path below the suite's scene root, without extension ("gltf/helmet")
    std::filesystem::path scene;      // the scene file (TOML, .gltf or .glb)
    std::filesystem::path golden_stem;  // golden folder / name; the golden is golden_stem + ".png" or ".exr"
    Thresholds thresholds;
    IgnoreRegions ignore;             // pixels left out of the comparison ([[override]] ignore, ignore_mask)
    int width = 0;                    // 0: the scene's own output size / MSAA
    int height = 0;
    int msaa = 0;
};

enum class GoldenFormat { png, exr };  // what --update writes where no golden exists yet

struct Suite {
    std::vector<SceneEntry> scenes;   // in the order given (patterns expanded, sorted within a pattern)
    GoldenFormat new_golden_format = GoldenFormat::png;
    std::filesystem::path report_dir; // from the manifest; empty: the command's default
};

// What the command line sets for every scene (the manifest's per-scene overrides still win).
struct SuiteDefaults {
    std::vector<std::pair<std::string, double>> thresholds;  // manifest key names and values, applied in order
    bool perceptual = false;
    int width = 0, height = 0, msaa = 0;
};

// Reads check.toml (format: docs/check.md, and the comment at the top of
// manifest.cpp). Throws ManifestError.
Suite load_manifest(const std::filesystem::path& manifest, const SuiteDefaults& command_line);

// Scene files (or glob patterns) checked against golden_dir/<name>.png|.exr.
// scene_root: names are relative to it; empty: the deepest folder holding every scene.
Suite suite_from_arguments(const std::vector<std::string>& scene_patterns, const std::filesystem::path& golden_dir,
                           const std::filesystem::path& scene_root, const SuiteDefaults& command_line);

// The scenes whose names match any of the glob patterns (fnmatch: * also
// matches '/'), in suite order: --filter. Throws ManifestError naming a pattern
// that matches no scene.
std::vector<SceneEntry> filter_scenes(const std::vector<SceneEntry>& scenes, const std::vector<std::string>& patterns);

// Whether `name` matches any of the glob patterns.
bool matches_any(const std::string& name, const std::vector<std::string>& patterns);

// Sets one threshold by its manifest key ("fail", "fail_pixels", ...). Throws
// std::invalid_argument for an unknown key or a value out of range.
void set_threshold(Thresholds& thresholds, std::string_view key, double value);
bool is_threshold_key(std::string_view key);

}  // namespace tessera::check
