// What moves in a glTF file: its node tree (rest TRS), skins, morph targets and
// animations, kept beside the imported meshes so that a model can be posed
// again at any time, from this rest data alone (a pose is a pure function of
// the time: the same time gives the same meshes bit for bit, whatever was posed
// before). gltf_animation.cpp reads animations and evaluates node poses;
// gltf_skin.cpp reads skins and morph targets and deforms meshes on the CPU.
//
// The glTF 2.0 rules followed (spec §3.7.3 morph targets, §3.7.4 skins, §3.11
// animations, Appendix C interpolation):
// - Morph targets: POSITION, NORMAL and TANGENT (xyz) deltas, weighted by the
//   node's weights, else the mesh's, else 0; added before skinning.
// - Skins: skin matrix = Σ weight_i · world(joint_i) · inverseBindMatrix_i over
//   every JOINTS_n/WEIGHTS_n set; the skinned mesh's own node transform is
//   ignored (§3.7.4), so posed vertices are in the file's world space and the
//   object's model matrix is the model's placement alone. This is the brief's
//   inverse(world(mesh node)) · world(joint) · IBM followed by the mesh node's
//   world, without the inverse (which a zero-scale node would not have).
//   Normals go through the cofactor of the skin matrix's 3×3 (its inverse
//   transpose up to a positive factor; right for non-uniform and mirroring
//   scales), tangents through the 3×3 itself; both renormalized, tangent w kept.
//   A vertex whose weights sum to 0 stays at its morphed rest position; other
//   weights are divided by their sum (quantized weights rarely sum to exactly 1).
// - Animations: channels on translation, rotation, scale and weights; samplers
//   LINEAR (rotations by the spec's slerp, shortest path), STEP and
//   CUBICSPLINE (Hermite with the file's tangents × the key interval;
//   rotations normalized after). Before the first key a sampler holds its
//   first value, after the last its last.
// Cameras and lights stay where the rest pose puts them.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "tessera/scene.hpp"

namespace tinygltf {
class Model;
}

namespace tessera {

struct GltfContent;

namespace gltf {

// A node's local transform at rest: a matrix (never animated: the spec forbids
// animating nodes given by a matrix), or translation · rotation · scale.
struct RigNode {
    int parent = -1;  // index into GltfRig::nodes; -1 = a root
    std::optional<glm::mat4> matrix;
    glm::vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // unit length
    glm::vec3 scale{1.0f};
    // Morph weights at rest (node.weights, else its mesh's weights, else zeros);
    // as many as its mesh has targets, empty for a node without a morphed mesh.
    std::vector<float> weights;
    int skin = -1;  // the skin its mesh is bound to
};

struct RigSkin {
    std::vector<int> joints;                   // node indices
    std::vector<glm::mat4> inverse_bind;       // one per joint (identity when the file gives none)
};

// One GltfContent mesh a node deforms (a skin, or morph targets): its rest
// vertices and what moves them. Its Mesh is posed from these, in place.
struct DeformedMesh {
    std::uint32_t mesh = 0;  // index into GltfContent::meshes
    int node = 0;            // the node placing it (whose weights and skin apply)
    std::vector<glm::vec3> positions;  // at rest (before morphing), object space
    std::vector<glm::vec3> normals;    // empty when flat_normals
    std::vector<glm::vec4> tangents;   // empty when the mesh has none
    // Per morph target (as many as the node's weights), one delta per vertex; an
    // attribute a target leaves out is empty.
    std::vector<std::vector<glm::vec3>> position_deltas, normal_deltas, tangent_deltas;
    // Skinning: influences_per_vertex = 4 × the JOINTS_n/WEIGHTS_n sets; 0 = not skinned.
    int influences_per_vertex = 0;
    std::vector<std::uint32_t> joints;  // index into the skin's joints, influences_per_vertex per vertex
    std::vector<float> weights;         // normalized to sum 1 (or all 0), likewise
    // The primitive has no NORMAL: its vertices are split per triangle and its
    // normals are the posed triangles' face normals (glTF's flat shading).
    bool flat_normals = false;
};

enum class Path : std::uint8_t { translation, rotation, scale, weights };
enum class SamplerInterpolation : std::uint8_t { linear, step, cubic_spline };

struct RigSampler {
    std::vector<float> times;  // seconds, >= 0, strictly increasing
    // Per key: `width` floats (3, 4 or the target count), or for CUBICSPLINE
    // 3 × width: in-tangent, value, out-tangent.
    std::vector<float> values;
    int width = 0;
    SamplerInterpolation interpolation = SamplerInterpolation::linear;
};

struct RigChannel {
    int node = 0;
    Path path = Path::translation;
    int sampler = 0;  // index into RigAnimation::samplers
};

struct RigAnimation {
    std::string name;
    std::vector<RigSampler> samplers;
    std::vector<RigChannel> channels;
    double duration = 0.0;  // seconds: the last key time of any sampler
};

}  // namespace gltf

// Everything needed to pose a glTF model again (see the top of this file).
struct GltfRig {
    std::string source;  // the file, for messages
    std::vector<gltf::RigNode> nodes;
    std::vector<int> node_order;  // every node in a tree, parents before children
    std::vector<gltf::RigSkin> skins;
    std::vector<gltf::DeformedMesh> deformed;
    std::vector<int> object_nodes;    // per GltfContent::objects entry: the node placing it
    std::vector<bool> object_skinned;  // per object: its mesh is skinned (model = placement alone)
    std::vector<glm::mat4> object_instance;  // per object: its EXT_mesh_gpu_instancing transform, after the node's
    std::vector<gltf::RigAnimation> animations;
};

namespace gltf {

// What read_rig needs from the importer's node walk.
struct MeshSource {
    int mesh = 0;       // the glTF mesh and primitive a GltfContent mesh was converted from
    int primitive = 0;
    std::vector<std::uint32_t> vertex_sources;  // PrimitiveMesh::vertex_sources
};

// True when `node` places a mesh that must get its own copy (not shared with
// other nodes): it is skinned or has morph targets.
bool node_deforms_mesh(const tinygltf::Model& model, int node);

// Reads the file's skins, morph targets and animations, checking each against
// the file (a SceneError naming what is wrong otherwise), and poses `content`
// at rest: deformed meshes posed, objects' model matrices recomputed by this
// file's node evaluation, bounds recomputed. Returns null when nothing can
// move (no skins, morph targets or animations). `object_nodes`, `object_instances` and
// `mesh_sources` run in parallel with content.objects and content.meshes.
// Warnings (animation channels on unsupported paths) go to content.warnings.
std::shared_ptr<const GltfRig> read_rig(const tinygltf::Model& model, const std::string& source, GltfContent& content,
                                        const std::vector<int>& object_nodes, const std::vector<glm::mat4>& object_instances,
                                        const std::vector<MeshSource>& mesh_sources);

// The animation `selector` names: an index or a name; empty = the first.
// Throws SceneError "source: ..." listing the file's animations when none matches.
int find_animation(const GltfRig& rig, const std::string& selector, const std::string& what);
// "0 'Walk' (1.25 s), 1 'Run' (0.8 s)", or "none".
std::string list_animations(const GltfRig& rig);

// A sampler's value at `seconds` (width floats written to `out`); rotations
// (width 4, is_rotation) come out unit length. Exposed for the tests.
void sample(const RigSampler& sampler, double seconds, bool is_rotation, float* out);

// Node world transforms (file space) with `animation` (-1 = none) at `seconds`
// applied to the rest pose, and the nodes' morph weights. Sized to the nodes.
struct NodePose {
    std::vector<glm::mat4> world;
    std::vector<std::vector<float>> weights;
    // Scratch: the local TRS being animated (kept to reuse its memory).
    std::vector<glm::vec3> translation, scale;
    std::vector<glm::quat> rotation;
};
void evaluate_pose(const GltfRig& rig, int animation, double seconds, NodePose& pose);

// Writes `pose` into the model's meshes and objects: meshes[first_mesh + m]
// for every deformed mesh m (same vertex count as at rest: no reallocation),
// objects[first_object + o].model = placement × world(node), or placement for
// a skinned one.
void apply_pose(const GltfRig& rig, const NodePose& pose, const glm::mat4& placement, std::vector<Mesh>& meshes,
                std::uint32_t first_mesh, std::vector<Object>& objects, std::uint32_t first_object);

// One deformed mesh posed (morph, then skin) into `out`, whose arrays have the
// rest sizes. Exposed for the tests.
void deform_mesh(const GltfRig& rig, const DeformedMesh& deformed, const NodePose& pose, Mesh& out);

}  // namespace gltf
}  // namespace tessera
