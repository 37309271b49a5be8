// glTF materials to tessera Materials: the metallic-roughness factors,
// KHR_materials_emissive_strength, doubleSided and alphaMode, every number
// checked (gltf_import.hpp says what is read). Textures are the importer's:
// it hands over a function that makes a TextureSlot for a texture index.
// Used by gltf_import.cpp only.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "tessera/scene.hpp"
#include "texture/texture.hpp"

namespace tessera::gltf {

// The slot for glTF texture `texture_index` (-1: none) decoded in `color_space`;
// `what` names the use in messages. Throws SceneError for a bad index.
using TextureSlotMaker = std::function<TextureSlot(int texture_index, texture::ColorSpace color_space,
                                                   const std::string& what)>;

// glTF's default material (spec §3.9.6): white, fully metallic and rough, single-sided.
Material default_material();

// Which texture coordinates a map reads: TEXCOORD_<set>, then
// KHR_texture_transform's uv' = T·R·S·(u, v, 1).
struct UvMapping {
    int set = 0;
    glm::mat3 transform{1.0f};  // column-major, as the extension's GLSL
    bool transformed = false;
    bool operator==(const UvMapping&) const = default;
};

// How a material's maps (base colour, metallic-roughness, normal, occlusion,
// emissive: kMapCount, in that order) get their texture coordinates. When all
// maps agree (the common case) their mapping is baked into Mesh::uvs at
// import (exact: an affine map of the uvs commutes with interpolation, so
// derivatives and mip levels follow) and the slots read uvs as they are.
// Otherwise Mesh::uvs holds the first map's set untransformed, Mesh::uvs1 a
// second set if a map reads one, and each slot says which it reads and its
// own transform, applied when sampling. A third set is not supported: its maps
// read the first map's set, with a warning.
inline constexpr std::size_t kMapCount = 5;
struct MaterialUvs {
    UvMapping baked;      // into Mesh::uvs
    int second_set = -1;  // TEXCOORD_n read into Mesh::uvs1, or -1
    struct Map {
        int uv_set = 0;  // TextureSlot::uv_set
        bool transformed = false;
        glm::mat3 transform{1.0f};
    };
    std::array<Map, kMapCount> maps{};
};
MaterialUvs read_material_uvs(const tinygltf::Model& model, std::size_t material_index, const std::string& source,
                              std::vector<std::string>& warnings);

// materials[index] of the model, its slots reading the texture coordinates
// `uvs` says; warnings gets one line for what is drawn differently from the
// file's intent.
Material read_material(const tinygltf::Model& model, std::size_t index, const std::string& source,
                       const TextureSlotMaker& texture_slot, const MaterialUvs& uvs, std::vector<std::string>& warnings);

// The first 3 of `values` (which must hold expected_size numbers) as a colour,
// each finite and >= 0, and <= 1 when unit_range. `what` names it in messages.
glm::vec3 color_factor(const std::vector<double>& values, std::size_t expected_size, const std::string& what,
                       bool unit_range, const std::string& source);

}  // namespace tessera::gltf
