// Where the tests find the repository's scenes and golden images, and where they may write.
#pragma once

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string_view>
#include <vector>

namespace tessera::test {

// The checkout, the build tree, TESSERA_ASSETS_DIR and the sample-model scenes, as CMake
// configured them: defined in test_paths.cpp alone, so that no other test file's compile
// command names an absolute path (a compiler-cache hit across clones and worktrees).
std::filesystem::path source_dir();
std::filesystem::path binary_dir();
std::filesystem::path configured_assets_dir();
std::filesystem::path configured_gltf_scenes_dir();
inline std::filesystem::path scene_path(const char* name) { return source_dir() / "scenes" / name; }
// Every scene file in scenes/, sorted by name.
inline std::vector<std::filesystem::path> scene_files(const std::filesystem::path& folder = source_dir() / "scenes") {
    std::vector<std::filesystem::path> scenes;
    for (const auto& entry : std::filesystem::directory_iterator(folder))
        if (entry.path().extension() == ".toml") scenes.push_back(entry.path());
    std::sort(scenes.begin(), scenes.end());
    return scenes;
}
// The sample models (glTF files in gltf/): the CMake cache variable TESSERA_ASSETS_DIR, by
// default ../shared/assets beside the checkout. TESSERA_ASSETS_DIR in the environment stands
// in for it (tests/assets_skip_test.sh points it to an empty folder).
inline std::filesystem::path assets_dir() {
    if (const char* dir = std::getenv("TESSERA_ASSETS_DIR"); dir && *dir) return dir;
    return configured_assets_dir();
}
// A test case that needs the sample models starts with `if (test::skip_without_assets()) return;`:
// where there are none it prints the line that ctest's SKIP_REGULAR_EXPRESSION
// (tests/CMakeLists.txt) reports as Skipped, and the test case ends there, having checked nothing.
inline bool skip_without_assets() {
    if (std::filesystem::is_directory(assets_dir() / "gltf")) return false;
    std::printf("TESSERA_TEST_SKIPPED: no sample models at %s (TESSERA_ASSETS_DIR)\n", assets_dir().c_str());
    std::fflush(stdout);
    return true;
}
// Scenes rendering the sample models: scenes/gltf/<name>.toml (golden/gltf/<name>.png), or, when
// TESSERA_ASSETS_DIR is not ../shared/assets, copies of them in the build tree naming it.
inline std::filesystem::path gltf_scenes_dir() { return configured_gltf_scenes_dir(); }
inline std::vector<std::filesystem::path> gltf_scene_files() { return scene_files(gltf_scenes_dir()); }
// A folder in the build tree for files the tests write.
inline std::filesystem::path output_dir(const char* name) {
    const std::filesystem::path dir = binary_dir() / "test_output" / name;
    std::filesystem::create_directories(dir);
    return dir;
}

}  // namespace tessera::test
