// glTF mesh primitives to tessera Meshes, with every accessor checked against
// its buffer view and buffer before a byte is read (gltf_import.hpp says what
// is supported). Used by gltf_import.cpp; fail() by the importer's other files too.
#pragma once

#include <initializer_list>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "tessera/scene.hpp"

namespace tessera::gltf {

// Throws SceneError "source: message".
[[noreturn]] void fail(const std::string& source, const std::string& message);

// The result of converting one primitive: a mesh (triangles, points or lines:
// Mesh::topology; points and lines without NORMAL keep no normals).
struct PrimitiveMesh {
    bool is_surface = false;  // false: not drawn (LINES with an odd vertex count), counted as skipped
    Mesh mesh;
    // Without NORMAL, flat normals split the vertices per triangle: the glTF
    // vertex each Mesh vertex copies (what morph targets and skin weights
    // index). Empty when the Mesh's vertices are the glTF vertices.
    std::vector<std::uint32_t> vertex_sources;
};

// `label` names the primitive in messages, e.g. "meshes[2] 'Body' primitives[0]".
// Mesh::uvs come from TEXCOORD_<texcoord_set> (the set its material's maps read),
// Mesh::uvs1 from TEXCOORD_<second_texcoord_set> where that is >= 0 (gltf_materials.hpp, MaterialUvs).
PrimitiveMesh read_primitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                             const std::string& source, const std::string& label, int texcoord_set = 0,
                             int second_texcoord_set = -1);

// Accessor `index` read as floats after the same checks as a primitive's
// attributes: element i's component c at [i × components + c], normalized
// integers mapped by glTF's rules, other integers as their value. `type` is a
// TINYGLTF_TYPE_* (SCALAR, VEC2..VEC4, MAT4); its component type must be one
// of `component_types`; integers must be normalized when
// `integers_need_normalized`. `what` names it in messages. For skins and
// animations (gltf_animation.cpp).
std::vector<float> read_accessor_floats(const tinygltf::Model& model, int index, const std::string& source,
                                        const std::string& what, int type, std::initializer_list<int> component_types,
                                        bool integers_need_normalized = false);

}  // namespace tessera::gltf
