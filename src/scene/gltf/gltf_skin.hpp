// Skins and morph targets of a glTF file (gltf_skin.cpp), for read_rig
// (gltf_animation.cpp). Used by gltf_animation.cpp only.
#pragma once

#include <string>
#include <vector>

#include "scene/gltf/gltf_animation.hpp"

namespace tessera::gltf {

// The file's skins, checked: joints name nodes, inverseBindMatrices (MAT4
// float, at least one per joint, finite) or identities.
std::vector<RigSkin> read_skins(const tinygltf::Model& model, const std::string& source);

// The number of morph targets of glTF mesh `mesh_index` (the same for every
// primitive, as glTF requires), checking mesh.weights against it.
std::size_t morph_target_count(const tinygltf::Model& model, int mesh_index, const std::string& source);

// The deform data of content mesh `rest` (converted from `from`, placed by
// `node`): rest vertices, morph deltas, joints and weights, checked against the
// file and the node's skin. `skin` is null for a node without one.
DeformedMesh read_deformed_mesh(const tinygltf::Model& model, const std::string& source, std::uint32_t mesh,
                                const Mesh& rest, const MeshSource& from, int node, const RigSkin* skin);

}  // namespace tessera::gltf
