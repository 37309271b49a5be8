// glTF skins and morph targets (gltf_animation.hpp): reading them, checked,
// and deforming a mesh on the CPU: morph targets, then linear-blend skinning.
#include "scene/gltf/gltf_skin.hpp"

#include <algorithm>
#include <cstring>
#include <cmath>
#include <map>

#include <glm/gtc/type_ptr.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tiny_gltf.h>

#include "scene/gltf/gltf_geometry.hpp"

namespace tessera::gltf {
namespace {

std::string mesh_label(const tinygltf::Model& model, int mesh, int primitive) {
    std::string label = "meshes[" + std::to_string(mesh) + "]";
    if (!model.meshes[std::size_t(mesh)].name.empty()) label += " '" + model.meshes[std::size_t(mesh)].name + "'";
    if (primitive >= 0) label += " primitives[" + std::to_string(primitive) + "]";
    return label;
}

int find_attribute(const std::map<std::string, int>& attributes, const std::string& name) {
    const auto found = attributes.find(name);
    return found == attributes.end() ? -1 : found->second;
}

// The cofactor matrix of m: det(m) · inverse(transpose(m)), defined even where m is singular.
glm::mat3 cofactor(const glm::mat3& m) {
    return glm::mat3(glm::cross(m[1], m[2]), glm::cross(m[2], m[0]), glm::cross(m[0], m[1]));
}

glm::vec3 normalized_or_same(const glm::vec3& v) {
    const float length = glm::length(v);
    return length > 0.0f && std::isfinite(length) ? v / length : v;
}

}  // namespace

std::vector<RigSkin> read_skins(const tinygltf::Model& model, const std::string& source) {
    std::vector<RigSkin> skins(model.skins.size());
    for (std::size_t s = 0; s < model.skins.size(); ++s) {
        const tinygltf::Skin& skin = model.skins[s];
        std::string label = "skins[" + std::to_string(s) + "]";
        if (!skin.name.empty()) label += " '" + skin.name + "'";
        if (skin.joints.empty()) fail(source, label + " has no joints");
        for (std::size_t j = 0; j < skin.joints.size(); ++j)
            if (skin.joints[j] < 0 || std::size_t(skin.joints[j]) >= model.nodes.size())
                fail(source, label + " joint [" + std::to_string(j) + "] is node " + std::to_string(skin.joints[j]) +
                                 " but the file has " + std::to_string(model.nodes.size()) + " nodes");
        if (skin.skeleton >= 0 && std::size_t(skin.skeleton) >= model.nodes.size())
            fail(source, label + " skeleton is node " + std::to_string(skin.skeleton) + " but the file has " +
                             std::to_string(model.nodes.size()) + " nodes");
        skins[s].joints = skin.joints;
        skins[s].inverse_bind.assign(skin.joints.size(), glm::mat4(1.0f));
        if (skin.inverseBindMatrices < 0) continue;  // the spec: identities
        const std::vector<float> matrices =
            read_accessor_floats(model, skin.inverseBindMatrices, source, label + " inverseBindMatrices",
                                 TINYGLTF_TYPE_MAT4, {TINYGLTF_COMPONENT_TYPE_FLOAT});
        if (matrices.size() / 16 < skin.joints.size())
            fail(source, label + " has " + std::to_string(matrices.size() / 16) + " inverseBindMatrices for " +
                             std::to_string(skin.joints.size()) + " joints");
        for (std::size_t j = 0; j < skin.joints.size(); ++j) {
            for (std::size_t i = 0; i < 16; ++i)
                if (!std::isfinite(matrices[16 * j + i]))
                    fail(source, label + " inverseBindMatrices [" + std::to_string(j) + "] is not finite");
            skins[s].inverse_bind[j] = glm::make_mat4(&matrices[16 * j]);  // both column-major
        }
    }
    return skins;
}

std::size_t morph_target_count(const tinygltf::Model& model, int mesh_index, const std::string& source) {
    const tinygltf::Mesh& mesh = model.meshes[std::size_t(mesh_index)];
    const std::size_t count = mesh.primitives.empty() ? 0 : mesh.primitives[0].targets.size();
    for (std::size_t p = 1; p < mesh.primitives.size(); ++p)
        if (mesh.primitives[p].targets.size() != count)
            fail(source, mesh_label(model, mesh_index, int(p)) + " has " + std::to_string(mesh.primitives[p].targets.size()) +
                             " morph targets but primitives[0] has " + std::to_string(count) +
                             "; glTF requires the same number in every primitive");
    if (!mesh.weights.empty() && mesh.weights.size() != count)
        fail(source, mesh_label(model, mesh_index, -1) + " has " + std::to_string(mesh.weights.size()) +
                         " weights for " + std::to_string(count) + " morph targets");
    return count;
}

DeformedMesh read_deformed_mesh(const tinygltf::Model& model, const std::string& source, std::uint32_t mesh,
                                const Mesh& rest, const MeshSource& from, int node, const RigSkin* skin) {
    const tinygltf::Primitive& primitive = model.meshes[std::size_t(from.mesh)].primitives[std::size_t(from.primitive)];
    const std::string label = mesh_label(model, from.mesh, from.primitive);
    DeformedMesh deformed;
    deformed.mesh = mesh;
    deformed.node = node;
    deformed.positions = rest.positions;
    deformed.flat_normals = !from.vertex_sources.empty();
    if (!deformed.flat_normals) deformed.normals = rest.normals;
    deformed.tangents = rest.tangents;
    const std::size_t vertices = rest.positions.size();
    // The glTF vertex a Mesh vertex copies (flat normals split them).
    const auto source_vertex = [&](std::size_t v) { return from.vertex_sources.empty() ? v : std::size_t(from.vertex_sources[v]); };
    const std::size_t gltf_vertices = from.vertex_sources.empty()
                                          ? vertices
                                          : std::size_t(model.accessors[std::size_t(find_attribute(primitive.attributes, "POSITION"))].count);
    // An attribute read as `components` floats per glTF vertex, checked for count.
    const auto read = [&](int accessor, const std::string& what, int type, std::initializer_list<int> component_types,
                          bool normalized) {
        std::vector<float> values = read_accessor_floats(model, accessor, source, label + " " + what, type, component_types, normalized);
        const std::size_t components = type == TINYGLTF_TYPE_VEC4 ? 4 : 3;
        if (values.size() != gltf_vertices * components)
            fail(source, label + " " + what + " has " + std::to_string(values.size() / components) + " elements for " +
                             std::to_string(gltf_vertices) + " positions");
        return values;
    };

    const bool quantized = std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(),
                                     "KHR_mesh_quantization") != model.extensionsUsed.end();
    const std::size_t targets = primitive.targets.size();
    deformed.position_deltas.resize(targets);
    deformed.normal_deltas.resize(targets);
    deformed.tangent_deltas.resize(targets);
    for (std::size_t t = 0; t < targets; ++t) {
        const auto& attributes = primitive.targets[t];
        const std::string target = "targets[" + std::to_string(t) + "] ";
        const auto read_deltas = [&](const char* name, std::vector<glm::vec3>& deltas) {
            const int accessor = find_attribute(attributes, name);
            if (accessor < 0) return;
            // KHR_mesh_quantization lets POSITION deltas be plain (not normalized)
            // bytes and shorts, in the quantized positions' units (gltfpack writes
            // them); NORMAL and TANGENT deltas stay normalized.
            const bool plain_integers = quantized && std::strcmp(name, "POSITION") == 0;
            const std::vector<float> values =
                read(accessor, target + name, TINYGLTF_TYPE_VEC3,
                     {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT},
                     !plain_integers);
            deltas.resize(vertices);
            for (std::size_t v = 0; v < vertices; ++v) {
                const float* d = &values[3 * source_vertex(v)];
                deltas[v] = glm::vec3(d[0], d[1], d[2]);
                if (!std::isfinite(d[0] + d[1] + d[2]))
                    fail(source, label + " " + target + name + " [" + std::to_string(source_vertex(v)) + "] is not finite");
            }
        };
        read_deltas("POSITION", deformed.position_deltas[t]);
        if (!deformed.flat_normals) read_deltas("NORMAL", deformed.normal_deltas[t]);
        if (!deformed.tangents.empty()) read_deltas("TANGENT", deformed.tangent_deltas[t]);
    }

    if (skin == nullptr) return deformed;
    std::vector<std::pair<int, int>> sets;  // JOINTS_n, WEIGHTS_n accessors
    for (int set = 0;; ++set) {
        const int joints = find_attribute(primitive.attributes, "JOINTS_" + std::to_string(set));
        const int weights = find_attribute(primitive.attributes, "WEIGHTS_" + std::to_string(set));
        if (joints < 0 && weights < 0) break;
        if (joints < 0 || weights < 0)
            fail(source, label + " has " + (joints < 0 ? "WEIGHTS_" : "JOINTS_") + std::to_string(set) + " without " +
                             (joints < 0 ? "JOINTS_" : "WEIGHTS_") + std::to_string(set));
        sets.emplace_back(joints, weights);
    }
    if (sets.empty())
        fail(source, label + " is skinned by its node but has no JOINTS_0 and WEIGHTS_0 attributes");
    const std::size_t influences = 4 * sets.size();
    deformed.influences_per_vertex = int(influences);
    deformed.joints.assign(vertices * influences, 0);
    deformed.weights.assign(vertices * influences, 0.0f);
    for (std::size_t s = 0; s < sets.size(); ++s) {
        const std::string set = std::to_string(s);
        // Joint indices are counts, never normalized (read_accessor_floats would scale them).
        if (std::size_t(sets[s].first) < model.accessors.size() && model.accessors[std::size_t(sets[s].first)].normalized)
            fail(source, label + " JOINTS_" + set + " (accessor " + std::to_string(sets[s].first) +
                             ") is normalized; joint indices must not be");
        const std::vector<float> joints =
            read(sets[s].first, "JOINTS_" + set, TINYGLTF_TYPE_VEC4,
                 {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT}, false);
        const std::vector<float> weights =
            read(sets[s].second, "WEIGHTS_" + set, TINYGLTF_TYPE_VEC4,
                 {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                 true);
        for (std::size_t v = 0; v < vertices; ++v) {
            const std::size_t g = source_vertex(v);
            for (std::size_t i = 0; i < 4; ++i) {
                const float weight = weights[4 * g + i];
                const auto joint = std::uint32_t(joints[4 * g + i]);  // exact: u8 and u16 values are floats exactly
                if (!(weight >= 0.0f) || !std::isfinite(weight))
                    fail(source, label + " WEIGHTS_" + set + " of vertex " + std::to_string(g) + " has weight " +
                                     std::to_string(weight) + ", expected a finite number >= 0");
                // An unused influence (weight 0) may name any joint; a used one must exist.
                if (weight > 0.0f && joint >= skin->joints.size())
                    fail(source, label + " JOINTS_" + set + " of vertex " + std::to_string(g) + " names joint " +
                                     std::to_string(joint) + " but its skin has " + std::to_string(skin->joints.size()) +
                                     " joints");
                deformed.joints[v * influences + 4 * s + i] = weight > 0.0f ? joint : 0;
                deformed.weights[v * influences + 4 * s + i] = weight;
            }
        }
    }
    for (std::size_t v = 0; v < vertices; ++v) {
        float* w = &deformed.weights[v * influences];
        double sum = 0.0;
        for (std::size_t i = 0; i < influences; ++i) sum += w[i];
        if (sum > 0.0 && sum != 1.0)
            for (std::size_t i = 0; i < influences; ++i) w[i] = float(w[i] / sum);
    }
    return deformed;
}

void deform_mesh(const GltfRig& rig, const DeformedMesh& d, const NodePose& pose, Mesh& out) {
    const std::vector<float>& morph_weights = pose.weights[std::size_t(d.node)];
    std::vector<glm::mat4> joint_matrices;  // world(joint) · inverseBindMatrix, per joint
    const RigNode& node = rig.nodes[std::size_t(d.node)];
    if (d.influences_per_vertex > 0) {
        const RigSkin& skin = rig.skins[std::size_t(node.skin)];
        joint_matrices.resize(skin.joints.size());
        for (std::size_t j = 0; j < skin.joints.size(); ++j)
            joint_matrices[j] = pose.world[std::size_t(skin.joints[j])] * skin.inverse_bind[j];
    }
    const auto influences = std::size_t(d.influences_per_vertex);
    const bool has_tangents = !d.tangents.empty();
    // Each vertex on its own: the result is the same however the range is split.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, d.positions.size(), 4096), [&](const auto& range) {
        for (std::size_t v = range.begin(); v != range.end(); ++v) {
            glm::vec3 position = d.positions[v];
            glm::vec3 normal = d.flat_normals ? glm::vec3(0.0f) : d.normals[v];
            glm::vec3 tangent = has_tangents ? glm::vec3(d.tangents[v]) : glm::vec3(0.0f);
            for (std::size_t t = 0; t < morph_weights.size(); ++t) {
                const float w = morph_weights[t];
                if (w == 0.0f) continue;
                if (!d.position_deltas[t].empty()) position += w * d.position_deltas[t][v];
                if (!d.normal_deltas[t].empty()) normal += w * d.normal_deltas[t][v];
                if (!d.tangent_deltas[t].empty()) tangent += w * d.tangent_deltas[t][v];
            }
            if (influences > 0) {
                glm::mat4 skin(0.0f);
                bool bound = false;
                for (std::size_t i = 0; i < influences; ++i) {
                    const float w = d.weights[v * influences + i];
                    if (w == 0.0f) continue;
                    skin += w * joint_matrices[d.joints[v * influences + i]];
                    bound = true;
                }
                if (bound) {
                    position = glm::vec3(skin * glm::vec4(position, 1.0f));
                    const glm::mat3 linear(skin);
                    // Inverse transpose up to a factor: the cofactor, its sign fixed for mirroring matrices.
                    const float sign = glm::determinant(linear) < 0.0f ? -1.0f : 1.0f;
                    normal = sign * (cofactor(linear) * normal);
                    tangent = linear * tangent;
                }
            }
            out.positions[v] = position;
            if (!d.flat_normals) out.normals[v] = normalized_or_same(normal);
            if (has_tangents) out.tangents[v] = glm::vec4(normalized_or_same(tangent), d.tangents[v].w);
        }
    });
    if (!d.flat_normals) return;
    // glTF's flat shading of a primitive without normals: each posed triangle's face normal.
    for (std::size_t t = 0; t + 2 < out.positions.size(); t += 3) {
        const glm::vec3 n = glm::cross(out.positions[t + 1] - out.positions[t], out.positions[t + 2] - out.positions[t]);
        const float length = glm::length(n);
        const glm::vec3 unit = length > 0.0f && std::isfinite(length) ? n / length : glm::vec3(0.0f, 0.0f, 1.0f);
        out.normals[t] = out.normals[t + 1] = out.normals[t + 2] = unit;
    }
}

}  // namespace tessera::gltf
