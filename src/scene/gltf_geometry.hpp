// glTF mesh primitives to tessera Meshes, with every accessor checked against
// its buffer view and buffer before a byte is read (gltf_import.hpp says what
// is supported). Used by gltf_import.cpp; fail() by the importer's other files too.
#pragma once

#include <string>

#include <tiny_gltf.h>

#include "tessera/scene.hpp"

namespace tessera::gltf {

// Throws SceneError "source: message".
[[noreturn]] void fail(const std::string& source, const std::string& message);

// The result of converting one primitive: a mesh, or nothing for points and lines.
struct PrimitiveMesh {
    bool is_surface = false;
    Mesh mesh;
};

// `label` names the primitive in messages, e.g. "meshes[2] 'Body' primitives[0]".
// Mesh::uvs come from TEXCOORD_<texcoord_set> (the set its material's maps read).
PrimitiveMesh read_primitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                             const std::string& source, const std::string& label, int texcoord_set = 0);

}  // namespace tessera::gltf
