#include "scene/gltf/gltf_materials.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "scene/gltf/gltf_geometry.hpp"

namespace tessera::gltf {
namespace {

// As gltf_import.cpp labels things: "materials[2] 'Name'".
std::string quoted(const std::string& text) {
    std::string result(1, '\'');  // not "'" + text + "'": g++ 12 warns falsely (-Wrestrict) about that
    result += text;
    result += '\'';
    return result;
}

std::string indexed(const char* array, std::size_t index, const std::string& name) {
    std::string label(array);  // appended piece by piece, for the same false warning
    label += '[';
    label += std::to_string(index);
    label += ']';
    if (!name.empty()) label += ' ', label += quoted(name);
    return label;
}

float unit_factor(double value, const std::string& what, const std::string& source) {
    if (!(value >= 0.0 && value <= 1.0)) fail(source, what + " is " + std::to_string(value) + ", expected a number in [0, 1]");
    return float(value);
}

// alphaMode, alphaCutoff and the base colour's alpha factor.
void read_alpha(const tinygltf::Material& m, const tinygltf::PbrMetallicRoughness& pbr, const std::string& label,
                const std::string& source, Material& material) {
    const double alpha = pbr.baseColorFactor.size() == 4 ? pbr.baseColorFactor[3] : 1.0;
    if (!(alpha >= 0.0 && alpha <= 1.0))
        fail(source, label + " baseColorFactor alpha is " + std::to_string(alpha) + ", expected a number in [0, 1]");
    material.alpha_factor = float(alpha);
    if (m.alphaMode == "MASK") {
        if (!(m.alphaCutoff >= 0.0 && std::isfinite(float(m.alphaCutoff))))
            fail(source, label + " alphaCutoff is " + std::to_string(m.alphaCutoff) + ", expected a finite number >= 0");
        material.alpha_mode = AlphaMode::mask;
        material.alpha_cutoff = float(m.alphaCutoff);
    } else if (m.alphaMode == "BLEND") {
        material.alpha_mode = AlphaMode::blend;  // alphaCutoff is ignored, as glTF says
    } else if (m.alphaMode != "OPAQUE") {
        fail(source, label + " alphaMode is " + quoted(m.alphaMode) + ", expected OPAQUE, MASK or BLEND");
    }
}


}  // namespace

Material default_material() {
    Material material;
    material.double_sided = false;
    material.albedo = glm::vec3(1.0f);
    material.metallic = 1.0f;
    material.roughness = 1.0f;
    return material;
}

glm::vec3 color_factor(const std::vector<double>& values, std::size_t expected_size, const std::string& what,
                       bool unit_range, const std::string& source) {
    if (values.size() != expected_size)
        fail(source, what + " has " + std::to_string(values.size()) + " numbers, expected " + std::to_string(expected_size));
    glm::vec3 color;
    for (int c = 0; c < 3; ++c) {
        const double v = values[std::size_t(c)];
        if (!(v >= 0.0 && std::isfinite(float(v))) || (unit_range && v > 1.0))
            fail(source, what + " has " + std::to_string(v) + ", expected numbers in " + (unit_range ? "[0, 1]" : "[0, ∞)"));
        color[c] = float(v);
    }
    return color;
}

Material read_material(const tinygltf::Model& model, std::size_t index, const std::string& source,
                       const TextureSlotMaker& texture_slot, const MaterialUvs& uvs,
                       [[maybe_unused]] std::vector<std::string>& warnings) {
    const tinygltf::Material& m = model.materials[index];
    const std::string label = indexed("materials", index, m.name);
    const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
    Material material;
    material.albedo = color_factor(pbr.baseColorFactor, 4, label + " baseColorFactor", true, source);
    material.metallic = unit_factor(pbr.metallicFactor, label + " metallicFactor", source);
    material.roughness = unit_factor(pbr.roughnessFactor, label + " roughnessFactor", source);
    material.emissive = color_factor(m.emissiveFactor, 3, label + " emissiveFactor", true, source);
    if (const auto strength = m.extensions.find("KHR_materials_emissive_strength"); strength != m.extensions.end()) {
        const tinygltf::Value& value = strength->second.Get("emissiveStrength");
        if (value.IsNumber()) {
            const double s = value.GetNumberAsDouble();
            if (!(s >= 0.0 && std::isfinite(float(s) * std::max({material.emissive.x, material.emissive.y, material.emissive.z}))))
                fail(source, label + " KHR_materials_emissive_strength is " + std::to_string(s) + ", expected a finite number >= 0");
            material.emissive *= float(s);
        }
    }
    using texture::ColorSpace;
    material.albedo_map = texture_slot(pbr.baseColorTexture.index, ColorSpace::srgb, label + " baseColorTexture");
    material.metallic_map = texture_slot(pbr.metallicRoughnessTexture.index, ColorSpace::linear,
                                         label + " metallicRoughnessTexture");
    material.roughness_map = material.metallic_map;  // one texture: metallic in B, roughness in G
    material.metallic_channel = 2;
    material.roughness_channel = 1;
    material.ao_map = texture_slot(m.occlusionTexture.index, ColorSpace::linear, label + " occlusionTexture");
    material.ao_strength = float(m.occlusionTexture.strength);
    material.normal_map = texture_slot(m.normalTexture.index, ColorSpace::linear, label + " normalTexture");
    material.normal_scale = float(m.normalTexture.scale);
    // Without stored tangents: glTF's frame (red along +u, green up the image).
    material.derived_tangent_frame = DerivedTangentFrame::gltf;
    if (!std::isfinite(material.ao_strength) || !std::isfinite(material.normal_scale))
        fail(source, label + ": occlusion strength and normal scale must be finite");
    material.emissive_map = texture_slot(m.emissiveTexture.index, ColorSpace::srgb, label + " emissiveTexture");
    material.double_sided = m.doubleSided;  // glTF's default is false: back faces culled
    read_alpha(m, pbr, label, source, material);
    // Each slot reads its map's texture coordinates (the metallic and roughness maps are one).
    TextureSlot* const slots[kMapCount][2] = {{&material.albedo_map, nullptr},
                                              {&material.metallic_map, &material.roughness_map},
                                              {&material.normal_map, nullptr},
                                              {&material.ao_map, nullptr},
                                              {&material.emissive_map, nullptr}};
    for (std::size_t k = 0; k < kMapCount; ++k)
        for (TextureSlot* slot : slots[k])
            if (slot != nullptr) {
                slot->uv_set = uvs.maps[k].uv_set;
                slot->uv_transformed = uvs.maps[k].transformed;
                slot->uv_transform = uvs.maps[k].transform;
            }
    // KHR_materials_unlit: the base colour is what is shown (Material::unlit).
    material.unlit = m.extensions.count("KHR_materials_unlit") > 0;
    return material;
}

namespace {

// The mapping one textureInfo asks for; `what` names it in messages.
template <class Info>
UvMapping mapping_of(const Info& info, const std::string& what, const std::string& source) {
    UvMapping mapping;
    mapping.set = info.texCoord;
    const auto extension = info.extensions.find("KHR_texture_transform");
    if (extension != info.extensions.end()) {
        const tinygltf::Value& value = extension->second;
        const std::string label = what + " KHR_texture_transform";
        const auto pair = [&](const char* key, glm::vec2 fallback) {
            if (!value.Has(key)) return fallback;
            const tinygltf::Value& array = value.Get(key);
            if (!array.IsArray() || array.ArrayLen() != 2 || !array.Get(0).IsNumber() || !array.Get(1).IsNumber())
                fail(source, label + " " + key + " is not an array of 2 numbers");
            const glm::vec2 v(float(array.Get(0).GetNumberAsDouble()), float(array.Get(1).GetNumberAsDouble()));
            if (!std::isfinite(v.x) || !std::isfinite(v.y)) fail(source, label + " " + key + " is not finite");
            return v;
        };
        const glm::vec2 offset = pair("offset", glm::vec2(0.0f)), scale = pair("scale", glm::vec2(1.0f));
        float rotation = 0.0f;
        if (value.Has("rotation")) {
            const tinygltf::Value& r = value.Get("rotation");
            if (!r.IsNumber() || !std::isfinite(float(r.GetNumberAsDouble())))
                fail(source, label + " rotation is not a finite number");
            rotation = float(r.GetNumberAsDouble());
        }
        if (value.Has("texCoord")) {
            const tinygltf::Value& t = value.Get("texCoord");
            if (!t.IsInt()) fail(source, label + " texCoord is not an integer");
            mapping.set = t.GetNumberAsInt();
        }
        // The extension's GLSL, constructors column by column as glm's.
        const glm::mat3 translation(1, 0, 0, 0, 1, 0, offset.x, offset.y, 1);
        const float c = std::cos(rotation), s = std::sin(rotation);
        const glm::mat3 rotate(c, -s, 0, s, c, 0, 0, 0, 1);
        const glm::mat3 scaling(scale.x, 0, 0, 0, scale.y, 0, 0, 0, 1);
        mapping.transform = translation * rotate * scaling;
        mapping.transformed = true;
    }
    if (mapping.set < 0 || mapping.set > 9)
        fail(source, what + " uses TEXCOORD_" + std::to_string(mapping.set) + "; expected a set from 0 to 9");
    return mapping;
}

}  // namespace

MaterialUvs read_material_uvs(const tinygltf::Model& model, std::size_t material_index, const std::string& source,
                              std::vector<std::string>& warnings) {
    const tinygltf::Material& m = model.materials[material_index];
    const std::string label = indexed("materials", material_index, m.name);
    const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
    std::array<std::optional<UvMapping>, kMapCount> mappings;
    const auto add = [&](std::size_t k, const auto& info, const char* what) {
        if (info.index >= 0) mappings[k] = mapping_of(info, label + " " + what, source);
    };
    add(0, pbr.baseColorTexture, "baseColorTexture");
    add(1, pbr.metallicRoughnessTexture, "metallicRoughnessTexture");
    add(2, m.normalTexture, "normalTexture");
    add(3, m.occlusionTexture, "occlusionTexture");
    add(4, m.emissiveTexture, "emissiveTexture");
    MaterialUvs uvs;
    const auto first = std::find_if(mappings.begin(), mappings.end(), [](const auto& o) { return o.has_value(); });
    if (first == mappings.end()) return uvs;
    const bool all_agree = std::all_of(mappings.begin(), mappings.end(), [&](const auto& o) { return !o || *o == **first; });
    if (all_agree) {
        uvs.baked = **first;  // the fast path: one baked mapping, slots read uvs as they are
        return uvs;
    }
    uvs.baked.set = (*first)->set;
    bool warned = false;
    for (std::size_t k = 0; k < kMapCount; ++k) {
        if (!mappings[k]) continue;
        const UvMapping& mapping = *mappings[k];
        MaterialUvs::Map& map = uvs.maps[k];
        if (mapping.set != uvs.baked.set) {
            if (uvs.second_set < 0) uvs.second_set = mapping.set;
            if (mapping.set == uvs.second_set) {
                map.uv_set = 1;
            } else if (!warned) {
                warnings.push_back(label + ": its maps read three or more texture coordinate sets; those past the "
                                           "second read TEXCOORD_" + std::to_string(uvs.baked.set));
                warned = true;
            }
        }
        map.transformed = mapping.transformed;
        map.transform = mapping.transform;
    }
    return uvs;
}

}  // namespace tessera::gltf
