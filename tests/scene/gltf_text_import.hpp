// A glTF document held in a string, imported as a file of that name would be, for the
// glTF tests: the content, or the SceneError's message ("(accepted)" when there is none).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "scene/gltf/gltf_import.hpp"

namespace tessera::test {

inline GltfContent import_gltf_text(const std::string& text, const std::string& name = "test.gltf",
                                    const std::filesystem::path& base_dir = "") {
    const auto* bytes = reinterpret_cast<const std::uint8_t*>(text.data());
    return import_gltf({bytes, text.size()}, name, base_dir);
}

inline std::string gltf_import_error(const std::string& text, const std::string& name = "bad.gltf",
                                     const std::filesystem::path& base_dir = "") {
    try {
        import_gltf_text(text, name, base_dir);
    } catch (const SceneError& e) {
        return e.what();
    }
    return "(accepted)";
}

}  // namespace tessera::test
