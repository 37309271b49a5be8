// A small glTF file of the tests' own for materials and textures: one quad
// (two triangles, normal +Z) with TEXCOORD_0 and TEXCOORD_1, its material,
// textures, samplers and images given as JSON by the test.
#pragma once

#include <cstring>
#include <string>
#include <vector>

#include "scene/gltf_test_files.hpp"

namespace tessera::test {

// The quad's corners: (−1, −1), (1, −1), (1, 1), (−1, 1) at z = 0.
inline constexpr float kQuadUv0[] = {0, 1, 1, 1, 1, 0, 0, 0};        // TEXCOORD_0: the whole image
inline constexpr float kQuadUv1[] = {0, 0, 0.5f, 0, 0.5f, 0.5f, 0, 0.5f};  // TEXCOORD_1: its top-left quarter

inline std::vector<std::uint8_t> quad_buffer() {
    std::vector<std::uint8_t> bytes;
    const auto floats = [&bytes](std::initializer_list<float> values) { append_floats(bytes, values); };
    floats({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0});  // 0: positions
    floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1});      // 48: normals
    for (const float f : kQuadUv0) floats({f});        // 96: TEXCOORD_0
    for (const float f : kQuadUv1) floats({f});        // 128: TEXCOORD_1
    bytes.insert(bytes.end(), {0, 0, 1, 0, 2, 0, 0, 0, 2, 0, 3, 0});  // 160: u16 indices
    return bytes;
}

// `material`: the material object; textures, samplers, images: the arrays'
// contents; extensions_used: the list's contents.
inline std::string quad_gltf(const std::string& material, const std::string& textures, const std::string& images,
                             const std::string& samplers = "", const std::string& extensions_used = "",
                             const std::string& attributes = R"("POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2, "TEXCOORD_1": 3)") {
    std::string text = R"({
  "asset": {"version": "2.0"},)";
    if (!extensions_used.empty()) text += R"(
  "extensionsUsed": [)" + extensions_used + "],";
    text += R"(
  "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {)" + attributes + R"(}, "indices": 4, "material": 0}]}],
  "materials": [)" + material + R"(],
  "textures": [)" + textures + R"(],
  "images": [)" + images + R"(],)";
    if (!samplers.empty()) text += R"(
  "samplers": [)" + samplers + "],";
    text += R"(
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
    {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
    {"bufferView": 3, "componentType": 5126, "count": 4, "type": "VEC2"},
    {"bufferView": 4, "componentType": 5123, "count": 6, "type": "SCALAR"}
  ],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 48},
    {"buffer": 0, "byteOffset": 96, "byteLength": 32}, {"buffer": 0, "byteOffset": 128, "byteLength": 32},
    {"buffer": 0, "byteOffset": 160, "byteLength": 12}
  ],
  "buffers": [{"byteLength": 172, "uri": "data:application/octet-stream;base64,)" + base64(quad_buffer()) + R"("}]
})";
    return text;
}

// The 2×2 PNG of gltf_test_files.hpp as an image entry.
inline std::string png_image() { return R"({"uri": "data:image/png;base64,)" + std::string(kTestPngBase64) + R"("})"; }
// Any bytes as an image entry with a MIME type.
inline std::string data_image(const std::vector<std::uint8_t>& bytes, const std::string& mime) {
    return R"({"uri": "data:)" + mime + ";base64," + base64(bytes) + R"("})";
}

}  // namespace tessera::test
