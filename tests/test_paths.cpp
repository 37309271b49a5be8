// The paths CMake configured (tests/CMakeLists.txt): the only test file compiled with them.
#include "test_paths.hpp"

namespace tessera::test {

std::filesystem::path source_dir() { return TESSERA_SOURCE_DIR; }
std::filesystem::path binary_dir() { return TESSERA_BINARY_DIR; }
std::filesystem::path configured_assets_dir() { return TESSERA_ASSETS_DIR; }
std::filesystem::path configured_gltf_scenes_dir() { return TESSERA_GLTF_SCENES_DIR; }

}  // namespace tessera::test
