// glTF nodes and animations (gltf_animation.hpp): reading the rig, sampling
// animation channels, and evaluating node poses.
#include "scene/gltf/gltf_animation.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include "scene/framing.hpp"
#include "scene/gltf/gltf_geometry.hpp"
#include "scene/gltf/gltf_import.hpp"
#include "scene/gltf/gltf_skin.hpp"

namespace tessera::gltf {
namespace {

std::string node_label(const tinygltf::Model& model, std::size_t n) {
    std::string label = "nodes[" + std::to_string(n) + "]";
    if (!model.nodes[n].name.empty()) label += " '" + model.nodes[n].name + "'";
    return label;
}

std::string number(double value) {
    std::ostringstream out;
    out << value;
    return out.str();
}

bool all_finite(const std::vector<double>& values) {
    return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(float(v)); });
}

// Rest TRS or matrix, as gltf_import.cpp's node walk reads them (it has checked
// the nodes it walks; nodes outside the scene are checked here).
RigNode read_node(const tinygltf::Model& model, std::size_t n, const std::string& source) {
    const tinygltf::Node& node = model.nodes[n];
    const std::string label = node_label(model, n);
    RigNode rig;
    const auto check = [&](const std::vector<double>& values, std::size_t size, const char* what) {
        if (values.empty()) return false;
        if (values.size() != size)
            fail(source, label + " has a " + what + " of " + std::to_string(values.size()) + " numbers, expected " +
                             std::to_string(size));
        if (!all_finite(values)) fail(source, label + " has a " + what + " that is not finite");
        return true;
    };
    if (check(node.matrix, 16, "matrix")) {
        glm::dmat4 matrix;
        std::copy(node.matrix.begin(), node.matrix.end(), glm::value_ptr(matrix));
        rig.matrix = glm::mat4(matrix);
        return rig;
    }
    if (check(node.translation, 3, "translation"))
        rig.translation = glm::vec3(node.translation[0], node.translation[1], node.translation[2]);
    if (check(node.rotation, 4, "rotation")) {
        const glm::quat q(float(node.rotation[3]), float(node.rotation[0]), float(node.rotation[1]), float(node.rotation[2]));
        const float length = glm::length(q);
        if (!(length > 0.0f) || !std::isfinite(length)) fail(source, label + " has a rotation quaternion of length 0 or not finite");
        rig.rotation = q / length;
    }
    if (check(node.scale, 3, "scale")) rig.scale = glm::vec3(node.scale[0], node.scale[1], node.scale[2]);
    return rig;
}

// T · R · S the way gltf_import.cpp's node walk computes it, so that an
// unanimated model posed here has bit for bit the matrices the walk gave.
glm::mat4 local_matrix(const glm::vec3& translation, const glm::quat& rotation, const glm::vec3& scale) {
    return glm::scale(glm::translate(glm::mat4(1.0f), translation) * glm::mat4_cast(rotation), scale);
}

SamplerInterpolation read_interpolation(const std::string& text, const std::string& label, const std::string& source) {
    if (text.empty() || text == "LINEAR") return SamplerInterpolation::linear;
    if (text == "STEP") return SamplerInterpolation::step;
    if (text == "CUBICSPLINE") return SamplerInterpolation::cubic_spline;
    fail(source, label + " has interpolation '" + text + "', expected LINEAR, STEP or CUBICSPLINE");
}

class AnimationReader {
public:
    AnimationReader(const tinygltf::Model& model, const std::string& source, const GltfRig& rig,
                    std::vector<std::string>& warnings)
        : model_(model), source_(source), rig_(rig), warnings_(warnings) {}

    RigAnimation read(std::size_t a) {
        const tinygltf::Animation& animation = model_.animations[a];
        std::string label = "animations[" + std::to_string(a) + "]";
        if (!animation.name.empty()) label += " '" + animation.name + "'";
        RigAnimation result;
        result.name = animation.name;
        // Each sampler's width depends on the channel using it (weights: the target count).
        std::vector<int> sampler_width(animation.samplers.size(), 0);
        std::vector<Path> sampler_path(animation.samplers.size(), Path::translation);
        std::map<std::pair<int, Path>, std::size_t> targeted;
        for (std::size_t c = 0; c < animation.channels.size(); ++c) {
            const tinygltf::AnimationChannel& channel = animation.channels[c];
            const std::string channel_label = label + " channels[" + std::to_string(c) + "]";
            const std::string& path = channel.target_path;
            Path kind;
            if (path == "translation") kind = Path::translation;
            else if (path == "rotation") kind = Path::rotation;
            else if (path == "scale") kind = Path::scale;
            else if (path == "weights") kind = Path::weights;
            else if (path == "pointer") {
                warnings_.push_back(channel_label + " targets a 'pointer' (KHR_animation_pointer): ignored");
                continue;
            } else {
                fail(source_, channel_label + " has target path '" + path + "', expected translation, rotation, scale or weights");
            }
            if (channel.target_node < 0) continue;  // the spec: no node, the channel is ignored (extensions use it)
            if (std::size_t(channel.target_node) >= model_.nodes.size())
                fail(source_, channel_label + " targets node " + std::to_string(channel.target_node) + " but the file has " +
                                  std::to_string(model_.nodes.size()) + " nodes");
            const auto node = std::size_t(channel.target_node);
            if (rig_.nodes[node].matrix)
                fail(source_, channel_label + " animates " + node_label(model_, node) +
                                  ", which is given by a matrix; glTF animates only nodes given by TRS");
            if (channel.sampler < 0 || std::size_t(channel.sampler) >= animation.samplers.size())
                fail(source_, channel_label + " uses sampler " + std::to_string(channel.sampler) + " but the animation has " +
                                  std::to_string(animation.samplers.size()) + " samplers");
            if (!targeted.emplace(std::pair{channel.target_node, kind}, c).second)
                fail(source_, channel_label + " animates " + node_label(model_, node) + " " + path +
                                  " again; glTF allows one channel per node and path in an animation");
            int width = kind == Path::rotation ? 4 : 3;
            if (kind == Path::weights) {
                width = int(rig_.nodes[node].weights.size());
                if (width == 0)
                    fail(source_, channel_label + " animates the morph weights of " + node_label(model_, node) +
                                      ", which has no mesh with morph targets");
            }
            const auto s = std::size_t(channel.sampler);
            if (sampler_width[s] != 0 && (sampler_width[s] != width || sampler_path[s] != kind))
                fail(source_, channel_label + " uses sampler " + std::to_string(s) +
                                  " for values of another kind than an earlier channel does");
            sampler_width[s] = width;
            sampler_path[s] = kind;
            result.channels.push_back(RigChannel{channel.target_node, kind, channel.sampler});
        }
        result.samplers.resize(animation.samplers.size());
        for (std::size_t s = 0; s < animation.samplers.size(); ++s) {
            if (sampler_width[s] == 0) continue;  // used by no channel
            result.samplers[s] = read_sampler(animation.samplers[s], label + " samplers[" + std::to_string(s) + "]",
                                              sampler_width[s], sampler_path[s]);
            result.duration = std::max(result.duration, double(result.samplers[s].times.back()));
        }
        return result;
    }

private:
    RigSampler read_sampler(const tinygltf::AnimationSampler& sampler, const std::string& label, int width, Path path) {
        RigSampler result;
        result.width = width;
        result.interpolation = read_interpolation(sampler.interpolation, label, source_);
        result.times = read_accessor_floats(model_, sampler.input, source_, label + " input", TINYGLTF_TYPE_SCALAR,
                                            {TINYGLTF_COMPONENT_TYPE_FLOAT});
        if (result.times.empty()) fail(source_, label + " input has no key times");
        for (std::size_t k = 0; k < result.times.size(); ++k) {
            const float t = result.times[k];
            if (!std::isfinite(t) || t < 0.0f)
                fail(source_, label + " input time [" + std::to_string(k) + "] is " + number(t) + ", expected a finite number >= 0");
            if (k > 0 && !(t > result.times[k - 1]))
                fail(source_, label + " input times are not strictly increasing: [" + std::to_string(k) + "] = " + number(t) +
                                  " after " + number(result.times[k - 1]));
        }
        const bool rotation = path == Path::rotation;
        if (rotation) {
            result.values = read_accessor_floats(model_, sampler.output, source_, label + " output", TINYGLTF_TYPE_VEC4,
                                                 {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
                                                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT,
                                                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                                                 true);
        } else if (path == Path::weights) {
            result.values = read_accessor_floats(model_, sampler.output, source_, label + " output", TINYGLTF_TYPE_SCALAR,
                                                 {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
                                                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT,
                                                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                                                 true);
        } else {
            result.values = read_accessor_floats(model_, sampler.output, source_, label + " output", TINYGLTF_TYPE_VEC3,
                                                 {TINYGLTF_COMPONENT_TYPE_FLOAT});
        }
        const std::size_t per_key = std::size_t(width) * (result.interpolation == SamplerInterpolation::cubic_spline ? 3 : 1);
        if (result.values.size() != result.times.size() * per_key) {
            const std::size_t element = path == Path::weights ? 1 : std::size_t(width);  // floats per accessor element
            fail(source_, label + " has " + std::to_string(result.times.size()) + " key times but " +
                              std::to_string(result.values.size() / element) + " output elements; expected " +
                              std::to_string(result.times.size() * per_key / element) + " (" +
                              std::to_string(per_key / element) + " per key)");
        }
        for (std::size_t i = 0; i < result.values.size(); ++i)
            if (!std::isfinite(result.values[i]))
                fail(source_, label + " output value [" + std::to_string(i) + "] is not finite");
        if (rotation) {
            const std::size_t value_offset = result.interpolation == SamplerInterpolation::cubic_spline ? 4 : 0;
            for (std::size_t k = 0; k < result.times.size(); ++k) {
                const float* q = &result.values[k * per_key + value_offset];
                if (!(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3] > 0.0f))
                    fail(source_, label + " key " + std::to_string(k) + " is a rotation quaternion of length 0");
            }
        }
        return result;
    }

    const tinygltf::Model& model_;
    const std::string& source_;
    const GltfRig& rig_;
    std::vector<std::string>& warnings_;
};

// Appendix C's slerp of unit quaternions (x, y, z, w), along the shorter arc.
void slerp(const float* a, const float* b, double u, float* out) {
    double dot = 0.0;
    for (int i = 0; i < 4; ++i) dot += double(a[i]) * double(b[i]);
    const double sign = dot < 0.0 ? -1.0 : 1.0;
    dot = std::min(std::abs(dot), 1.0);
    double wa = 1.0 - u, wb = u;
    if (dot < 1.0 - 1e-6) {  // nearly equal: the lerp is as good and sin(angle) is not tiny
        const double angle = std::acos(dot);
        wa = std::sin(angle * (1.0 - u)) / std::sin(angle);
        wb = std::sin(angle * u) / std::sin(angle);
    }
    double q[4], length = 0.0;
    for (int i = 0; i < 4; ++i) q[i] = wa * a[i] + sign * wb * b[i], length += q[i] * q[i];
    length = std::sqrt(length);
    for (int i = 0; i < 4; ++i) out[i] = float(q[i] / length);
}

void normalize_quaternion(float* q) {
    const double length = std::sqrt(double(q[0]) * q[0] + double(q[1]) * q[1] + double(q[2]) * q[2] + double(q[3]) * q[3]);
    if (!(length > 0.0)) {
        q[0] = q[1] = q[2] = 0.0f, q[3] = 1.0f;  // a spline through zero: no rotation rather than NaN
        return;
    }
    for (int i = 0; i < 4; ++i) q[i] = float(q[i] / length);
}

}  // namespace

bool node_deforms_mesh(const tinygltf::Model& model, int node_index) {
    const tinygltf::Node& node = model.nodes[std::size_t(node_index)];
    if (node.mesh < 0 || std::size_t(node.mesh) >= model.meshes.size()) return false;
    if (node.skin >= 0) return true;
    const tinygltf::Mesh& mesh = model.meshes[std::size_t(node.mesh)];
    return std::any_of(mesh.primitives.begin(), mesh.primitives.end(),
                       [](const tinygltf::Primitive& p) { return !p.targets.empty(); });
}

void sample(const RigSampler& sampler, double seconds, bool is_rotation, float* out) {
    const std::vector<float>& t = sampler.times;
    const auto width = std::size_t(sampler.width);
    const bool cubic = sampler.interpolation == SamplerInterpolation::cubic_spline;
    const std::size_t per_key = cubic ? 3 * width : width;
    const std::size_t value_offset = cubic ? width : 0;  // a cubic key is in-tangent, value, out-tangent
    const auto value = [&](std::size_t k) { return &sampler.values[k * per_key + value_offset]; };
    const auto copy = [&](const float* from) {
        std::copy(from, from + width, out);
        if (is_rotation) normalize_quaternion(out);
    };
    if (seconds <= double(t.front())) return copy(value(0));
    if (seconds >= double(t.back())) return copy(value(t.size() - 1));
    // The key interval [t[k], t[k+1]) holding the time.
    const std::size_t k = std::size_t(std::upper_bound(t.begin(), t.end(), seconds,
                                                       [](double s, float key) { return s < double(key); }) -
                                      t.begin()) - 1;
    if (sampler.interpolation == SamplerInterpolation::step) return copy(value(k));
    const double span = double(t[k + 1]) - double(t[k]);
    const double u = (seconds - double(t[k])) / span;
    if (!cubic) {
        if (is_rotation) return slerp(value(k), value(k + 1), u, out);
        for (std::size_t i = 0; i < width; ++i) out[i] = float((1.0 - u) * value(k)[i] + u * value(k + 1)[i]);
        return;
    }
    // Appendix C: p(u) = (2u³ − 3u² + 1)·v_k + td·(u³ − 2u² + u)·b_k + (−2u³ + 3u²)·v_k+1 + td·(u³ − u²)·a_k+1,
    // b_k the out-tangent of key k, a_k+1 the in-tangent of key k + 1, td the interval.
    const double u2 = u * u, u3 = u2 * u;
    const float* out_tangent = value(k) + width;
    const float* in_tangent = value(k + 1) - width;
    for (std::size_t i = 0; i < width; ++i)
        out[i] = float((2 * u3 - 3 * u2 + 1) * value(k)[i] + span * (u3 - 2 * u2 + u) * out_tangent[i] +
                       (-2 * u3 + 3 * u2) * value(k + 1)[i] + span * (u3 - u2) * in_tangent[i]);
    if (is_rotation) normalize_quaternion(out);
}

void evaluate_pose(const GltfRig& rig, int animation, double seconds, NodePose& pose) {
    const std::size_t n = rig.nodes.size();
    pose.world.assign(n, glm::mat4(1.0f));
    pose.weights.resize(n);
    pose.translation.resize(n);
    pose.rotation.resize(n);
    pose.scale.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const RigNode& node = rig.nodes[i];
        pose.weights[i].assign(node.weights.begin(), node.weights.end());
        pose.translation[i] = node.translation;
        pose.rotation[i] = node.rotation;
        pose.scale[i] = node.scale;
    }
    if (animation >= 0) {
        const RigAnimation& clip = rig.animations[std::size_t(animation)];
        for (const RigChannel& channel : clip.channels) {
            const RigSampler& sampler = clip.samplers[std::size_t(channel.sampler)];
            const auto node = std::size_t(channel.node);
            switch (channel.path) {
                case Path::translation: sample(sampler, seconds, false, &pose.translation[node].x); break;
                case Path::scale: sample(sampler, seconds, false, &pose.scale[node].x); break;
                case Path::weights: sample(sampler, seconds, false, pose.weights[node].data()); break;
                case Path::rotation: {
                    float q[4];  // glTF's x, y, z, w
                    sample(sampler, seconds, true, q);
                    pose.rotation[node] = glm::quat(q[3], q[0], q[1], q[2]);
                    break;
                }
            }
        }
    }
    for (const int index : rig.node_order) {
        const auto i = std::size_t(index);
        const RigNode& node = rig.nodes[i];
        const glm::mat4 local = node.matrix ? *node.matrix : local_matrix(pose.translation[i], pose.rotation[i], pose.scale[i]);
        pose.world[i] = node.parent >= 0 ? pose.world[std::size_t(node.parent)] * local : local;
    }
}

void apply_pose(const GltfRig& rig, const NodePose& pose, const glm::mat4& placement, std::vector<Mesh>& meshes,
                std::uint32_t first_mesh, std::vector<Object>& objects, std::uint32_t first_object) {
    for (const DeformedMesh& deformed : rig.deformed) deform_mesh(rig, deformed, pose, meshes[first_mesh + deformed.mesh]);
    for (std::size_t o = 0; o < rig.object_nodes.size(); ++o) {
        Object& object = objects[first_object + o];
        // The spec: a skinned mesh is placed by its joints alone.
        object.model = (rig.object_skinned[o] ? placement : placement * pose.world[std::size_t(rig.object_nodes[o])]) *
                       rig.object_instance[o];
    }
}

std::string list_animations(const GltfRig& rig) {
    std::string list;
    for (std::size_t a = 0; a < rig.animations.size(); ++a) {
        list += (a ? ", " : "") + std::to_string(a);
        if (!rig.animations[a].name.empty()) list += " '" + rig.animations[a].name + "'";
        list += " (" + number(rig.animations[a].duration) + " s)";
    }
    return list.empty() ? "none" : list;
}

int find_animation(const GltfRig& rig, const std::string& selector, const std::string& what) {
    if (rig.animations.empty()) fail(rig.source, "has no animations (" + what + ")");
    if (selector.empty()) return 0;
    if (selector.size() < 10 && std::all_of(selector.begin(), selector.end(), [](unsigned char c) { return std::isdigit(c); })) {
        const auto index = std::stoul(selector);
        if (index < rig.animations.size()) return int(index);
    } else {
        for (std::size_t a = 0; a < rig.animations.size(); ++a)
            if (rig.animations[a].name == selector) return int(a);
    }
    fail(rig.source, what + " '" + selector + "' names no animation of the file; its animations: " + list_animations(rig));
}

std::shared_ptr<const GltfRig> read_rig(const tinygltf::Model& model, const std::string& source, GltfContent& content,
                                        const std::vector<int>& object_nodes, const std::vector<glm::mat4>& object_instances,
                                        const std::vector<MeshSource>& mesh_sources) {
    bool deforms = false;
    for (std::size_t n = 0; n < model.nodes.size() && !deforms; ++n) deforms = node_deforms_mesh(model, int(n));
    if (!deforms && model.animations.empty()) return nullptr;  // nothing moves: the walk's result stands

    auto rig = std::make_shared<GltfRig>();
    rig->source = source;
    const std::size_t n = model.nodes.size();
    rig->nodes.resize(n);
    for (std::size_t i = 0; i < n; ++i) rig->nodes[i] = read_node(model, i, source);
    for (std::size_t i = 0; i < n; ++i)
        for (const int child : model.nodes[i].children) {
            if (child < 0 || std::size_t(child) >= n)
                fail(source, node_label(model, i) + " has child " + std::to_string(child) + " but the file has " +
                                 std::to_string(n) + " nodes");
            if (rig->nodes[std::size_t(child)].parent >= 0 || std::size_t(child) == i)
                fail(source, node_label(model, std::size_t(child)) + " has two parents (or is its own); glTF nodes form trees");
            rig->nodes[std::size_t(child)].parent = int(i);
        }
    // Parents before children: depth first from every root. Nodes on a cycle are
    // never reached (and never used: the walk refused any the scene reaches).
    for (std::size_t i = 0; i < n; ++i) {
        if (rig->nodes[i].parent >= 0) continue;
        std::vector<int> stack{int(i)};
        while (!stack.empty()) {
            const int node = stack.back();
            stack.pop_back();
            rig->node_order.push_back(node);
            for (const int child : model.nodes[std::size_t(node)].children) stack.push_back(child);
        }
    }

    rig->skins = read_skins(model, source);
    for (std::size_t i = 0; i < n; ++i) {
        const tinygltf::Node& node = model.nodes[i];
        RigNode& rig_node = rig->nodes[i];
        if (node.skin >= 0 && node.mesh >= 0) {
            if (std::size_t(node.skin) >= rig->skins.size())
                fail(source, node_label(model, i) + " uses skin " + std::to_string(node.skin) + " but the file has " +
                                 std::to_string(rig->skins.size()) + " skins");
            rig_node.skin = node.skin;
        }
        if (node.mesh < 0 || std::size_t(node.mesh) >= model.meshes.size()) continue;
        const std::size_t targets = morph_target_count(model, node.mesh, source);
        if (targets == 0) continue;
        const std::vector<double>& mesh_weights = model.meshes[std::size_t(node.mesh)].weights;
        const std::vector<double>& weights = node.weights.empty() ? mesh_weights : node.weights;
        if (!weights.empty() && weights.size() != targets)
            fail(source, node_label(model, i) + " has " + std::to_string(weights.size()) + " morph weights for the " +
                             std::to_string(targets) + " morph targets of its mesh");
        if (!all_finite(weights)) fail(source, node_label(model, i) + " has morph weights that are not finite");
        rig_node.weights.assign(targets, 0.0f);
        for (std::size_t t = 0; t < weights.size(); ++t) rig_node.weights[t] = float(weights[t]);
    }

    rig->object_nodes = object_nodes;
    rig->object_instance = object_instances;
    rig->object_skinned.assign(object_nodes.size(), false);
    std::vector<bool> deformed(content.meshes.size(), false);
    for (std::size_t o = 0; o < content.objects.size(); ++o) {
        const int node = object_nodes[o];
        const std::uint32_t mesh = content.objects[o].mesh;
        rig->object_skinned[o] = rig->nodes[std::size_t(node)].skin >= 0;
        if (!node_deforms_mesh(model, node) || deformed[mesh]) continue;  // deformed meshes are one node's own
        deformed[mesh] = true;
        const int skin = rig->nodes[std::size_t(node)].skin;
        rig->deformed.push_back(read_deformed_mesh(model, source, mesh, content.meshes[mesh], mesh_sources[mesh], node,
                                                   skin >= 0 ? &rig->skins[std::size_t(skin)] : nullptr));
    }

    AnimationReader reader(model, source, *rig, content.warnings);
    for (std::size_t a = 0; a < model.animations.size(); ++a) rig->animations.push_back(reader.read(a));

    // The rest pose, by the same evaluation every later pose uses.
    NodePose pose;
    evaluate_pose(*rig, -1, 0.0, pose);
    apply_pose(*rig, pose, glm::mat4(1.0f), content.meshes, 0, content.objects, 0);
    content.bounds = Bounds{};
    for (const Object& object : content.objects) {
        Bounds mesh_bounds;
        for (const glm::vec3& p : content.meshes[object.mesh].positions) mesh_bounds.add(p);
        content.bounds.add(mesh_bounds.transformed(object.model));
    }
    return rig;
}

}  // namespace tessera::gltf
