// Small glTF files the tests build in memory: one document with every feature
// the importer maps (a node hierarchy, indexed/non-indexed/strip/line
// primitives, a textured material, a camera, three KHR lights), as .gltf with
// its buffer in a data URI, as .glb, or with an external .bin. Bad-input tests
// break copies of it.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

namespace tessera::test {

inline std::string base64(const std::vector<std::uint8_t>& bytes) {
    static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string text;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::uint32_t n = std::uint32_t(bytes[i]) << 16 | (i + 1 < bytes.size() ? bytes[i + 1] << 8 : 0) |
                                (i + 2 < bytes.size() ? bytes[i + 2] : 0);
        text += kDigits[n >> 18 & 63];
        text += kDigits[n >> 12 & 63];
        text += i + 1 < bytes.size() ? kDigits[n >> 6 & 63] : '=';
        text += i + 2 < bytes.size() ? kDigits[n & 63] : '=';
    }
    return text;
}

// A 2×2 RGB PNG: red, green on the top row; blue, white below.
inline constexpr std::string_view kTestPngBase64 =
    "iVBORw0KGgoAAAANSUhEUgAAAAIAAAACCAIAAAD91JpzAAAAEklEQVR4nGP4z8DAAMIM/4EAAB/uBfsL2WiLAAAAAElFTkSuQmCC";

// Appends the floats' bytes (little-endian, as glTF buffers hold them on this machine).
inline void append_floats(std::vector<std::uint8_t>& bytes, std::initializer_list<float> values) {
    for (const float v : values) {
        std::uint8_t b[4];
        std::memcpy(b, &v, 4);
        bytes.insert(bytes.end(), b, b + 4);
    }
}

// The test document's binary buffer (180 bytes), laid out as its buffer views say.
inline std::vector<std::uint8_t> test_gltf_buffer() {
    std::vector<std::uint8_t> bytes;
    const auto floats = [&bytes](std::initializer_list<float> values) { append_floats(bytes, values); };
    floats({0, 0, 0, 1, 0, 0, 0, 1, 0});  // 0: triangle positions
    floats({0, 0, 1, 0, 0, 1, 0, 0, 1});  // 36: its normals
    floats({0, 0, 1, 0, 0, 1});           // 72: its uvs
    bytes.insert(bytes.end(), {0, 0, 1, 0, 2, 0, 0, 0});  // 96: u16 indices 0 1 2, padded to 104
    floats({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 1, 1, 0, 0});  // 104: two unindexed triangles
    bytes.insert(bytes.end(), {0, 1, 2, 0});  // 176: u8 strip indices
    return bytes;
}

// The test document. buffer_uri: a data URI or file name; empty = the GLB's BIN chunk.
inline std::string test_gltf_json(const std::string& buffer_uri) {
    const std::string buffer = buffer_uri.empty() ? R"({"byteLength": 180})"
                                                  : R"({"byteLength": 180, "uri": ")" + buffer_uri + R"("})";
    return R"({
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_lights_punctual"],
  "scene": 0,
  "scenes": [{"nodes": [0, 2, 3, 4, 5, 6]}],
  "nodes": [
    {"name": "root", "translation": [1, 2, 3], "children": [1]},
    {"name": "child", "rotation": [0, 0.70710678, 0, 0.70710678], "scale": [2, 2, 2], "mesh": 0},
    {"name": "camera", "translation": [0, 0, 10], "camera": 0},
    {"name": "spot", "translation": [0, 5, 0], "rotation": [-0.70710678, 0, 0, 0.70710678],
     "extensions": {"KHR_lights_punctual": {"light": 0}}},
    {"name": "point", "translation": [3, 0, 0], "extensions": {"KHR_lights_punctual": {"light": 1}}},
    {"name": "sun", "extensions": {"KHR_lights_punctual": {"light": 2}}},
    {"name": "second", "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -4, 0, 1], "mesh": 0}
  ],
  "meshes": [{"name": "parts", "primitives": [
    {"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0},
    {"attributes": {"POSITION": 4}},
    {"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 5, "mode": 5, "material": 0},
    {"attributes": {"POSITION": 0}, "mode": 1}
  ]}],
  "materials": [{"name": "painted", "alphaMode": "BLEND",
    "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.4, 0.6, 0.5], "metallicFactor": 0.3, "roughnessFactor": 0.7,
      "baseColorTexture": {"index": 0}, "metallicRoughnessTexture": {"index": 1}},
    "normalTexture": {"index": 1, "scale": 0.5}, "occlusionTexture": {"index": 1, "strength": 0.8},
    "emissiveFactor": [1, 0.5, 0], "emissiveTexture": {"index": 0}}],
  "textures": [{"source": 0, "sampler": 0}, {"source": 0}],
  "samplers": [{"wrapS": 33071, "wrapT": 10497}],
  "images": [{"uri": "data:image/png;base64,)" +
           std::string(kTestPngBase64) + R"("}],
  "cameras": [{"type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1, "aspectRatio": 2.0}}],
  "extensions": {"KHR_lights_punctual": {"lights": [
    {"type": "spot", "color": [1, 0.5, 0.25], "intensity": 4, "range": 20,
     "spot": {"innerConeAngle": 0.1, "outerConeAngle": 0.5}},
    {"type": "point", "intensity": 2},
    {"type": "directional", "color": [0.5, 0.5, 0.5], "intensity": 3}
  ]}},
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
    {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"},
    {"bufferView": 3, "componentType": 5123, "count": 3, "type": "SCALAR"},
    {"bufferView": 4, "componentType": 5126, "count": 6, "type": "VEC3"},
    {"bufferView": 5, "componentType": 5121, "count": 4, "type": "SCALAR"}
  ],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 36},
    {"buffer": 0, "byteOffset": 36, "byteLength": 36},
    {"buffer": 0, "byteOffset": 72, "byteLength": 24},
    {"buffer": 0, "byteOffset": 96, "byteLength": 6},
    {"buffer": 0, "byteOffset": 104, "byteLength": 72},
    {"buffer": 0, "byteOffset": 176, "byteLength": 4}
  ],
  "buffers": [)" + buffer + R"(]
})";
}

// The test document as .gltf text with its buffer embedded.
inline std::string embedded_test_gltf() {
    return test_gltf_json("data:application/octet-stream;base64," + base64(test_gltf_buffer()));
}

// A .glb: 12-byte header, a JSON chunk and a BIN chunk, each padded to 4 bytes.
inline std::vector<std::uint8_t> make_glb(std::string json, std::vector<std::uint8_t> bin) {
    while (json.size() % 4 != 0) json += ' ';
    while (bin.size() % 4 != 0) bin.push_back(0);
    // Starting from the magic rather than inserting it into an empty vector:
    // g++ 12 warns falsely (-Wstringop-overflow) about that insert.
    std::vector<std::uint8_t> glb = {'g', 'l', 'T', 'F'};
    const auto u32 = [&glb](std::uint32_t v) {
        for (int i = 0; i < 4; ++i) glb.push_back(std::uint8_t(v >> (8 * i)));
    };
    u32(2);
    u32(std::uint32_t(12 + 8 + json.size() + 8 + bin.size()));
    u32(std::uint32_t(json.size()));
    u32(0x4E4F534A);  // "JSON"
    glb.insert(glb.end(), json.begin(), json.end());
    u32(std::uint32_t(bin.size()));
    u32(0x004E4942);  // "BIN\0"
    glb.insert(glb.end(), bin.begin(), bin.end());
    return glb;
}

inline std::vector<std::uint8_t> test_glb() { return make_glb(test_gltf_json(""), test_gltf_buffer()); }

// `text` with the first `from` replaced by `to` (the tests' way to break one thing).
inline std::string replaced(std::string text, std::string_view from, std::string_view to) {
    const std::size_t at = text.find(from);
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

inline void write_bytes(const std::filesystem::path& path, std::string_view bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}
inline void write_bytes(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes) {
    write_bytes(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace tessera::test
