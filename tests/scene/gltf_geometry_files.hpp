// Small glTF files for issue 31's geometry and cameras, built in memory:
// instancing, cameras, points and lines, quantized morph targets. Used by
// tests/scene/test_gltf_instancing_cameras.cpp and the bad-input rows of
// tests/robustness/bad_scenes.hpp, which break copies of them.
#pragma once

#include <cmath>
#include <string>

#include "scene/gltf_animation_files.hpp"

namespace tessera::test {

// One triangle drawn by node 0 with three instances: translations (0,0,0),
// (10,0,0), (0,10,0); rotations identity, 90° about Z, identity; scales 1, 1, 2.
// The node itself moves everything by (0, 0, -5). The arguments are each attribute's count.
inline std::string instanced_triangle_gltf(int translations = 3, int rotations = 3, int scales = 3) {
    GltfBufferBuilder b;
    const int positions = b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
    const int t = b.floats({0, 0, 0, 10, 0, 0, 0, 10, 0}, "VEC3", std::size_t(translations));
    const float h = std::sqrt(0.5f);
    const int r = b.floats({0, 0, 0, 1, 0, 0, h, h, 0, 0, 0, 1}, "VEC4", std::size_t(rotations));
    const int s = b.floats({1, 1, 1, 1, 1, 1, 2, 2, 2}, "VEC3", std::size_t(scales));
    return R"({
  "asset": {"version": "2.0"},
  "extensionsUsed": ["EXT_mesh_gpu_instancing"],
  "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0, "translation": [0, 0, -5], "extensions": {"EXT_mesh_gpu_instancing": {"attributes":
    {"TRANSLATION": )" + std::to_string(t) + R"(, "ROTATION": )" + std::to_string(r) + R"(, "SCALE": )" +
           std::to_string(s) + R"(}}}}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": )" + std::to_string(positions) + R"(}}]}],
  )" + b.json() + "\n}";
}

// A triangle and three cameras: 0 perspective 'unplaced' (placed by node 1 all the
// same: the tests take that away), 1 orthographic
// 'flat' (xmag 4, ymag 2, znear 0, zfar 20; node 2 at z = 7), 2 'spare' placed by no node.
inline std::string cameras_gltf() {
    GltfBufferBuilder b;
    const int positions = b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
    return R"({
  "asset": {"version": "2.0"},
  "scenes": [{"nodes": [0, 1, 2]}],
  "nodes": [{"mesh": 0}, {"camera": 0, "translation": [0, 0, 5]}, {"camera": 1, "translation": [0, 0, 7]}],
  "cameras": [{"name": "unplaced", "type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1}},
              {"name": "flat", "type": "orthographic", "orthographic": {"xmag": 4, "ymag": 2, "znear": 0, "zfar": 20}},
              {"name": "spare", "type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1}}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": )" + std::to_string(positions) + R"(}}]}],
  )" + b.json() + "\n}";
}

// Four vertices of a unit square drawn as POINTS, LINES, LINE_LOOP and LINE_STRIP (one primitive each).
inline std::string points_and_lines_gltf() {
    GltfBufferBuilder b;
    const int positions = b.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3", 4);
    const auto primitive = [&](int mode) {
        return R"({"attributes": {"POSITION": )" + std::to_string(positions) + R"(}, "mode": )" + std::to_string(mode) + "}";
    };
    return R"({
  "asset": {"version": "2.0"},
  "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [)" + primitive(0) + "," + primitive(1) + "," + primitive(2) + "," + primitive(3) + R"(]}],
  )" + b.json() + "\n}";
}

// A triangle of plain SHORT positions (units of 1/100, dequantized by the node's
// scale 0.01) with one plain SHORT morph target moving vertex 2 by +50 units in Z,
// weight 1; KHR_mesh_quantization used and required. Each VEC3 is padded to 8 bytes
// (byteStride 8), as glTF's 4-byte element alignment asks.
inline std::string quantized_morph_gltf() {
    GltfBufferBuilder b;
    const int positions = b.signed_shorts({0, 0, 0, 0, 100, 0, 0, 0, 0, 100, 0, 0}, "VEC3", 3, false);
    const int delta = b.signed_shorts({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 50, 0}, "VEC3", 3, false);
    const std::string text = R"({
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_mesh_quantization"],
  "extensionsRequired": ["KHR_mesh_quantization"],
  "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0, "scale": [0.01, 0.01, 0.01]}],
  "meshes": [{"weights": [1], "primitives": [{"attributes": {"POSITION": )" + std::to_string(positions) +
                             R"(}, "targets": [{"POSITION": )" + std::to_string(delta) + R"(}]}]}],
  )" + b.json() + "\n}";
    std::string strided = text;
    for (std::size_t at = strided.find("\"byteLength\": 24}"); at != std::string::npos;
         at = strided.find("\"byteLength\": 24}", at + 1))
        strided.replace(at, 17, "\"byteLength\": 24, \"byteStride\": 8}");
    return strided;
}

}  // namespace tessera::test
