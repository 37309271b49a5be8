// Which glTF extensions the importer understands, and what happens to the
// others: a file that lists an unknown one in extensionsRequired is refused,
// naming it (drawing it without would be wrong, as the spec says); one that
// is only used (extensionsUsed) is ignored with a one-line warning.
// Used by gltf_import.cpp only.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <tiny_gltf.h>

namespace tessera::gltf {

// The extensions read (gltf_import.hpp says how).
inline constexpr std::string_view kSupportedExtensions[] = {
    "EXT_mesh_gpu_instancing",
    "EXT_meshopt_compression",
    "EXT_texture_avif",
    "EXT_texture_webp",
    "KHR_draco_mesh_compression",
    "KHR_lights_punctual",
    "KHR_materials_emissive_strength",
    "KHR_materials_unlit",
    "KHR_meshopt_compression",
    "KHR_mesh_quantization",
    "KHR_texture_transform",
};

// Material extensions that change shading beyond the reference shader: a
// file that uses them is drawn without them, with one warning each saying so.
inline constexpr std::string_view kIgnoredShadingExtensions[] = {
    "KHR_materials_anisotropy", "KHR_materials_clearcoat",    "KHR_materials_ior",
    "KHR_materials_iridescence", "KHR_materials_sheen",       "KHR_materials_specular",
    "KHR_materials_transmission", "KHR_materials_volume",
};

bool is_supported_extension(std::string_view name);

// Throws SceneError "source: ..." naming the first required extension that is
// not supported; appends one warning per used extension that is ignored.
void check_extensions(const tinygltf::Model& model, const std::string& source, std::vector<std::string>& warnings);

}  // namespace tessera::gltf
