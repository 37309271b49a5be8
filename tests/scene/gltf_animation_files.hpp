// Small glTF files with skins, morph targets and animations, built in memory
// for the tests (the Khronos samples in ../shared/assets have none): a
// two-bone skinned strip, a morph-target triangle, and a triangle whose node is
// moved by one animation per sampler interpolation. Their expected poses are
// worked out by hand in test_gltf_animation.cpp from the spec's formulas.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "scene/gltf_test_files.hpp"

namespace tessera::test {

// Accessors appended to one buffer (embedded as a data URI), each in its own
// 4-byte-aligned buffer view; json() gives the "buffers", "bufferViews" and
// "accessors" members.
class GltfBufferBuilder {
public:
    // count elements of `type` ("SCALAR", "VEC3", "MAT4", ...) of floats.
    int floats(const std::vector<float>& values, const std::string& type, std::size_t count) {
        const std::size_t offset = begin_view();
        for (const float v : values) {
            std::uint8_t b[4];
            std::memcpy(b, &v, 4);
            bin_.insert(bin_.end(), b, b + 4);
        }
        return add(offset, values.size() * 4, 5126, count, type);
    }
    // Unsigned bytes (JOINTS_n).
    int bytes(const std::vector<std::uint8_t>& values, const std::string& type, std::size_t count) {
        const std::size_t offset = begin_view();
        bin_.insert(bin_.end(), values.begin(), values.end());
        return add(offset, values.size(), 5121, count, type);
    }
    // Unsigned shorts (indices).
    int shorts(const std::vector<std::uint16_t>& values) {
        const std::size_t offset = begin_view();
        for (const std::uint16_t v : values) bin_.insert(bin_.end(), {std::uint8_t(v & 0xFF), std::uint8_t(v >> 8)});
        return add(offset, values.size() * 2, 5123, values.size(), "SCALAR");
    }
    // Signed shorts (quantized attributes, KHR_mesh_quantization), normalized or not.
    int signed_shorts(const std::vector<std::int16_t>& values, const std::string& type, std::size_t count,
                      bool normalized) {
        const std::size_t offset = begin_view();
        for (const std::int16_t v : values) {
            const auto u = std::uint16_t(v);
            bin_.insert(bin_.end(), {std::uint8_t(u & 0xFF), std::uint8_t(u >> 8)});
        }
        const int index = add(offset, values.size() * 2, 5122, count, type);
        if (normalized) accessors_.back().insert(accessors_.back().size() - 1, ", \"normalized\": true");
        return index;
    }
    std::string json() const {
        std::string views, accessors;
        for (std::size_t i = 0; i < views_.size(); ++i) views += (i ? ",\n    " : "") + views_[i];
        for (std::size_t i = 0; i < accessors_.size(); ++i) accessors += (i ? ",\n    " : "") + accessors_[i];
        return "\"buffers\": [{\"byteLength\": " + std::to_string(bin_.size()) +
               ", \"uri\": \"data:application/octet-stream;base64," + base64(bin_) + "\"}],\n  \"bufferViews\": [\n    " +
               views + "\n  ],\n  \"accessors\": [\n    " + accessors + "\n  ]";
    }

private:
    std::size_t begin_view() {
        while (bin_.size() % 4 != 0) bin_.push_back(0);
        return bin_.size();
    }
    int add(std::size_t offset, std::size_t length, int component_type, std::size_t count, const std::string& type) {
        views_.push_back("{\"buffer\": 0, \"byteOffset\": " + std::to_string(offset) + ", \"byteLength\": " +
                         std::to_string(length) + "}");
        accessors_.push_back("{\"bufferView\": " + std::to_string(views_.size() - 1) + ", \"componentType\": " +
                             std::to_string(component_type) + ", \"count\": " + std::to_string(count) +
                             ", \"type\": \"" + type + "\"}");
        return int(accessors_.size() - 1);
    }
    std::vector<std::uint8_t> bin_;
    std::vector<std::string> views_, accessors_;
};

// A strip of two quads up the Y axis, x in ±0.5, rows at y = 0, 1, 2 (vertices
// 0,1 / 2,3 / 4,5; even = left), normals +Z. Row 0 is bound to the root joint
// (node 1, at the origin), row 2 to the tip joint (node 2, at y = 1, a child of
// node 1), row 1 half to each. The mesh node (node 0) is translated by +5 in X,
// which a skinned mesh ignores. Animation 0 'bend' turns the tip joint from no
// rotation at t = 0 to 90° about +Z at t = 1 (LINEAR: slerp).
inline std::string skinned_strip_gltf() {
    GltfBufferBuilder b;
    const int positions = b.floats({-0.5f, 0, 0, 0.5f, 0, 0, -0.5f, 1, 0, 0.5f, 1, 0, -0.5f, 2, 0, 0.5f, 2, 0}, "VEC3", 6);
    const int normals = b.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 6);
    const int joints = b.bytes({0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4", 6);
    const int weights = b.floats({1, 0, 0, 0, 1, 0, 0, 0, 0.5f, 0.5f, 0, 0, 0.5f, 0.5f, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4", 6);
    const int indices = b.shorts({0, 1, 3, 0, 3, 2, 2, 3, 5, 2, 5, 4});
    // Inverse bind matrices (column-major): identity for the root, translate(0, -1, 0) for the tip.
    const int inverse_bind = b.floats({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,  //
                                       1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1},
                                      "MAT4", 2);
    const int times = b.floats({0, 1}, "SCALAR", 2);
    const int rotations = b.floats({0, 0, 0, 1, 0, 0, 0.70710678f, 0.70710678f}, "VEC4", 2);
    return R"({
  "asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0, 1]}],
  "nodes": [
    {"name": "strip", "mesh": 0, "skin": 0, "translation": [5, 0, 0]},
    {"name": "root", "children": [2]},
    {"name": "tip", "translation": [0, 1, 0]}
  ],
  "meshes": [{"name": "strip", "primitives": [{"attributes": {"POSITION": )" +
           std::to_string(positions) + R"(, "NORMAL": )" + std::to_string(normals) + R"(, "JOINTS_0": )" +
           std::to_string(joints) + R"(, "WEIGHTS_0": )" + std::to_string(weights) + R"(}, "indices": )" +
           std::to_string(indices) + R"(}]}],
  "skins": [{"name": "bones", "joints": [1, 2], "skeleton": 1, "inverseBindMatrices": )" + std::to_string(inverse_bind) + R"(}],
  "animations": [{"name": "bend", "channels": [{"sampler": 0, "target": {"node": 2, "path": "rotation"}}],
    "samplers": [{"input": )" + std::to_string(times) + R"(, "output": )" + std::to_string(rotations) +
           R"(, "interpolation": "LINEAR"}]}],
  )" + b.json() + "\n}";
}

// A triangle (0,0,0), (1,0,0), (0,1,0), normals +Z, with two morph targets:
// target 0 moves vertex 2 by +1 in Z (and tilts its normal by (0, -1, 0)),
// target 1 moves vertex 0 by +1 in X. mesh.weights = [0.5, 0]; the node gives
// none, so the rest pose lifts vertex 2 to z = 0.5. Animation 0 'morph' takes
// the weights from [0, 0] at t = 0 to [1, 1] at t = 2 (LINEAR); animation 1
// 'morph_step' is [0, 1] from t = 0 and [1, 0] from t = 1 (STEP).
inline std::string morph_triangle_gltf(const std::string& node_extra = "") {
    GltfBufferBuilder b;
    const int positions = b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
    const int normals = b.floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
    const int lift = b.floats({0, 0, 0, 0, 0, 0, 0, 0, 1}, "VEC3", 3);
    const int tilt = b.floats({0, 0, 0, 0, 0, 0, 0, -1, 0}, "VEC3", 3);
    const int shift = b.floats({1, 0, 0, 0, 0, 0, 0, 0, 0}, "VEC3", 3);
    const int times = b.floats({0, 2}, "SCALAR", 2);
    const int weights = b.floats({0, 0, 1, 1}, "SCALAR", 4);
    const int step_times = b.floats({0, 1}, "SCALAR", 2);
    const int step_weights = b.floats({0, 1, 1, 0}, "SCALAR", 4);
    return R"({
  "asset": {"version": "2.0"},
  "scenes": [{"nodes": [0]}],
  "nodes": [{"name": "morphed", "mesh": 0)" + node_extra + R"(}],
  "meshes": [{"name": "triangle", "weights": [0.5, 0], "primitives": [{"attributes": {"POSITION": )" +
           std::to_string(positions) + R"(, "NORMAL": )" + std::to_string(normals) + R"(},
    "targets": [{"POSITION": )" + std::to_string(lift) + R"(, "NORMAL": )" + std::to_string(tilt) + R"(}, {"POSITION": )" +
           std::to_string(shift) + R"(}]}]}],
  "animations": [
    {"name": "morph", "channels": [{"sampler": 0, "target": {"node": 0, "path": "weights"}}],
     "samplers": [{"input": )" + std::to_string(times) + R"(, "output": )" + std::to_string(weights) + R"(}]},
    {"name": "morph_step", "channels": [{"sampler": 0, "target": {"node": 0, "path": "weights"}}],
     "samplers": [{"input": )" + std::to_string(step_times) + R"(, "output": )" + std::to_string(step_weights) +
           R"(, "interpolation": "STEP"}]}
  ],
  )" + b.json() + "\n}";
}

// A triangle on node 0 ('mover'), a child of node 1 ('parent', translated by
// (0, 0, -1)). Animations of node 0, by name:
// - 'linear': translation (0,0,0) at t = 0 to (2,4,0) at t = 2; scale 1 to 3
//   over the same keys; rotation identity to 90° about +Y;
// - 'step': translation (0,0,0) from t = 0, (1,0,0) from t = 1, (5,0,0) from t = 2;
// - 'cubic': CUBICSPLINE translation, keys t = 0 and t = 2: value (0,0,0) with
//   out-tangent (1,0,0), then in-tangent (2,0,0) and value (4,0,0).
// The bad-input tests give other STEP keys.
inline std::string animated_node_gltf(const std::vector<float>& step_key_times = {0, 1, 2},
                                      const std::vector<float>& step_key_values = {0, 0, 0, 1, 0, 0, 5, 0, 0}) {
    GltfBufferBuilder b;
    const int positions = b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
    const int times = b.floats({0, 2}, "SCALAR", 2);
    const int translations = b.floats({0, 0, 0, 2, 4, 0}, "VEC3", 2);
    const int scales = b.floats({1, 1, 1, 3, 3, 3}, "VEC3", 2);
    const int rotations = b.floats({0, 0, 0, 1, 0, 0.70710678f, 0, 0.70710678f}, "VEC4", 2);
    const int step_times = b.floats(step_key_times, "SCALAR", step_key_times.size());
    const int step_values = b.floats(step_key_values, "VEC3", step_key_values.size() / 3);
    // Per key: in-tangent, value, out-tangent.
    const int cubic_values = b.floats({0, 0, 0, 0, 0, 0, 1, 0, 0, 2, 0, 0, 4, 0, 0, 0, 0, 0}, "VEC3", 6);
    const auto s = [](int i) { return std::to_string(i); };
    return R"({
  "asset": {"version": "2.0"},
  "scenes": [{"nodes": [1]}],
  "nodes": [{"name": "mover", "mesh": 0}, {"name": "parent", "translation": [0, 0, -1], "children": [0]}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": )" + s(positions) + R"(}}]}],
  "animations": [
    {"name": "linear", "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}},
                                    {"sampler": 1, "target": {"node": 0, "path": "scale"}},
                                    {"sampler": 2, "target": {"node": 0, "path": "rotation"}}],
     "samplers": [{"input": )" + s(times) + R"(, "output": )" + s(translations) + R"(},
                  {"input": )" + s(times) + R"(, "output": )" + s(scales) + R"(},
                  {"input": )" + s(times) + R"(, "output": )" + s(rotations) + R"(}]},
    {"name": "step", "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}],
     "samplers": [{"input": )" + s(step_times) + R"(, "output": )" + s(step_values) + R"(, "interpolation": "STEP"}]},
    {"name": "cubic", "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}],
     "samplers": [{"input": )" + s(times) + R"(, "output": )" + s(cubic_values) + R"(, "interpolation": "CUBICSPLINE"}]}
  ],
  )" + b.json() + "\n}";
}

}  // namespace tessera::test
