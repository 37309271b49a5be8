// Where the tests find the repository's scenes and golden images, and where they may write.
#pragma once

#include <filesystem>

namespace tessera::test {

inline std::filesystem::path source_dir() { return TESSERA_SOURCE_DIR; }
inline std::filesystem::path scene_path(const char* name) { return source_dir() / "scenes" / name; }
// A folder in the build tree for files the tests write.
inline std::filesystem::path output_dir(const char* name) {
    const std::filesystem::path dir = std::filesystem::path(TESSERA_BINARY_DIR) / "test_output" / name;
    std::filesystem::create_directories(dir);
    return dir;
}

}  // namespace tessera::test
