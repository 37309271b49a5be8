// Where the tests find the repository's scenes and golden images, and where they may write.
#pragma once

#include <algorithm>
#include <filesystem>
#include <string_view>
#include <vector>

namespace tessera::test {

inline std::filesystem::path source_dir() { return TESSERA_SOURCE_DIR; }
inline std::filesystem::path scene_path(const char* name) { return source_dir() / "scenes" / name; }
// Every scene file in scenes/, sorted by name.
inline std::vector<std::filesystem::path> scene_files(const std::filesystem::path& folder = source_dir() / "scenes") {
    std::vector<std::filesystem::path> scenes;
    for (const auto& entry : std::filesystem::directory_iterator(folder))
        if (entry.path().extension() == ".toml") scenes.push_back(entry.path());
    std::sort(scenes.begin(), scenes.end());
    return scenes;
}
// The shared sample models (glTF), beside the checkout; tests that need them
// skip, saying so, when the folder is absent.
inline std::filesystem::path assets_dir() { return source_dir() / ".." / "shared" / "assets"; }
// Scenes rendering the sample models: scenes/gltf/<name>.toml, golden/gltf/<name>.png.
inline std::vector<std::filesystem::path> gltf_scene_files() { return scene_files(source_dir() / "scenes" / "gltf"); }
// A folder in the build tree for files the tests write.
inline std::filesystem::path output_dir(const char* name) {
    const std::filesystem::path dir = std::filesystem::path(TESSERA_BINARY_DIR) / "test_output" / name;
    std::filesystem::create_directories(dir);
    return dir;
}

}  // namespace tessera::test
