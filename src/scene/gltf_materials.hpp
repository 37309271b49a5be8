// glTF materials to tessera Materials: the metallic-roughness factors,
// KHR_materials_emissive_strength, doubleSided and alphaMode, every number
// checked (gltf_import.hpp says what is read). Textures are the importer's:
// it hands over a function that makes a TextureSlot for a texture index.
// Used by gltf_import.cpp only.
#pragma once

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

// materials[index] of the model; warnings gets one line for what is drawn
// differently from the file's intent.
Material read_material(const tinygltf::Model& model, std::size_t index, const std::string& source,
                       const TextureSlotMaker& texture_slot, std::vector<std::string>& warnings);

// Which texture coordinates a material's maps read: TEXCOORD_<set>, then
// KHR_texture_transform's uv' = T·R·S·(u, v, 1). One per material, baked into
// the mesh's uvs at import (exact: an affine map of the uvs commutes with
// interpolation, so derivatives and mip levels follow). Maps that disagree
// get the first map's mapping (base colour, metallic-roughness, normal,
// occlusion, emissive), with a warning.
struct UvMapping {
    int set = 0;
    glm::mat3 transform{1.0f};  // column-major, as the extension's GLSL
    bool transformed = false;
    bool operator==(const UvMapping&) const = default;
};
UvMapping read_uv_mapping(const tinygltf::Model& model, std::size_t material_index, const std::string& source,
                          std::vector<std::string>& warnings);

// The first 3 of `values` (which must hold expected_size numbers) as a colour,
// each finite and >= 0, and <= 1 when unit_range. `what` names it in messages.
glm::vec3 color_factor(const std::vector<double>& values, std::size_t expected_size, const std::string& what,
                       bool unit_range, const std::string& source);

}  // namespace tessera::gltf
