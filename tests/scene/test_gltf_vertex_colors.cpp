// glTF COLOR_0 (issue #14): VEC3 or VEC4, float or normalized u8/u16, read into
// Mesh::colors (linear RGBA, alpha 1 for VEC3); wrong types refused clearly.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "scene/gltf/gltf_import.hpp"
#include "scene/gltf_test_files.hpp"

using namespace tessera;

namespace {

// One triangle (no NORMAL: flat normals, which split vertices) and a colour
// accessor of every kind; COLOR_0 names accessor `color_accessor`:
// 1 float VEC3, 2 float VEC4, 3 u8 VEC4 normalized, 4 u16 VEC3 normalized,
// 5 float VEC3 out of [0, 1], 6 float VEC3 holding a NaN, 7 u8 VEC4 not normalized, 8 float VEC2.
std::string colored_triangle(int color_accessor) {
    std::vector<std::uint8_t> bytes;
    const auto floats = [&bytes](std::initializer_list<float> values) {
        for (const float v : values) {
            std::uint8_t b[4];
            std::memcpy(b, &v, 4);
            bytes.insert(bytes.end(), b, b + 4);
        }
    };
    const auto u16s = [&bytes](std::initializer_list<std::uint16_t> values) {
        for (const std::uint16_t v : values) bytes.insert(bytes.end(), {std::uint8_t(v & 0xff), std::uint8_t(v >> 8)});
    };
    const float nan = std::numeric_limits<float>::quiet_NaN();
    floats({0, 0, 0, 1, 0, 0, 0, 1, 0});                 // 0: positions
    floats({1, 0, 0, 0, 1, 0, 0, 0, 1});                 // 36: float VEC3
    floats({1, 0, 0, 0.5f, 0, 1, 0, 0.25f, 0, 0, 1, 1});  // 72: float VEC4
    bytes.insert(bytes.end(), {255, 0, 0, 128, 0, 255, 0, 64, 0, 0, 255, 255});  // 120: u8 VEC4
    u16s({65535, 0, 0, 0, 65535, 0, 0, 0, 32768, 0});    // 132: u16 VEC3 (+2 bytes padding)
    floats({1.5f, -0.5f, 0.5f, 0, 0, 0, 0, 0, 0});       // 152: out of range
    floats({0, 0, 0, nan, 0, 0, 0, 0, 0});               // 188: NaN
    const std::string json = R"({
  "asset": {"version": "2.0"},
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "COLOR_0": )" + std::to_string(color_accessor) + R"(}}]}],
  "nodes": [{"mesh": 0}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
    {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC4"},
    {"bufferView": 3, "componentType": 5121, "normalized": true, "count": 3, "type": "VEC4"},
    {"bufferView": 4, "componentType": 5123, "normalized": true, "count": 3, "type": "VEC3"},
    {"bufferView": 5, "componentType": 5126, "count": 3, "type": "VEC3"},
    {"bufferView": 6, "componentType": 5126, "count": 3, "type": "VEC3"},
    {"bufferView": 3, "componentType": 5121, "count": 3, "type": "VEC4"},
    {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"}
  ],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 36},
    {"buffer": 0, "byteOffset": 72, "byteLength": 48}, {"buffer": 0, "byteOffset": 120, "byteLength": 12},
    {"buffer": 0, "byteOffset": 132, "byteLength": 18}, {"buffer": 0, "byteOffset": 152, "byteLength": 36},
    {"buffer": 0, "byteOffset": 188, "byteLength": 36}
  ],
  "buffers": [{"byteLength": )" + std::to_string(bytes.size()) +
                             R"(, "uri": "data:application/octet-stream;base64,)" + test::base64(bytes) + R"("}]
})";
    return json;
}

GltfContent import_text(const std::string& text) {
    return import_gltf({reinterpret_cast<const std::uint8_t*>(text.data()), text.size()}, "colors.gltf", "");
}

std::string error_of(const std::string& text) {
    try {
        import_text(text);
    } catch (const SceneError& e) {
        return e.what();
    }
    return "(accepted)";
}

std::vector<glm::vec4> colors_of(int accessor) {
    const GltfContent content = import_text(colored_triangle(accessor));
    REQUIRE(content.meshes.size() == 1);
    REQUIRE(content.meshes[0].colors.size() == content.meshes[0].positions.size());
    return content.meshes[0].colors;
}

}  // namespace

TEST_CASE("glTF COLOR_0: VEC3 gets alpha 1, VEC4 keeps its alpha, floats as they are") {
    const std::vector<glm::vec4> rgb = colors_of(1);
    CHECK(rgb == std::vector<glm::vec4>{{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}});
    const std::vector<glm::vec4> rgba = colors_of(2);
    CHECK(rgba == std::vector<glm::vec4>{{1, 0, 0, 0.5f}, {0, 1, 0, 0.25f}, {0, 0, 1, 1}});
    CHECK(import_text(colored_triangle(1)).warnings.empty());
}

TEST_CASE("glTF COLOR_0: normalized unsigned bytes and shorts map to [0, 1] (glTF's c / 255, c / 65535)") {
    const std::vector<glm::vec4> u8 = colors_of(3);
    CHECK(u8[0] == glm::vec4(1, 0, 0, 128 / 255.0f));
    CHECK(u8[1] == glm::vec4(0, 1, 0, 64 / 255.0f));
    CHECK(u8[2] == glm::vec4(0, 0, 1, 1));
    const std::vector<glm::vec4> u16 = colors_of(4);
    CHECK(u16[0] == glm::vec4(1, 0, 0, 1));
    CHECK(u16[2] == glm::vec4(0, 0, 32768 / 65535.0f, 1));
}

TEST_CASE("glTF COLOR_0: floats outside [0, 1] are clamped, NaN and wrong types refused with the accessor named") {
    CHECK(colors_of(5)[0] == glm::vec4(1, 0, 0.5f, 1));
    CHECK(error_of(colored_triangle(6)) ==
          "colors.gltf: meshes[0] primitives[0] COLOR_0 (accessor 6) element 1 is not finite; expected colours in [0, 1]");
    CHECK(error_of(colored_triangle(7)) ==
          "colors.gltf: meshes[0] primitives[0] COLOR_0 (accessor 7) holds UNSIGNED_BYTE values that are not "
          "normalized; expected FLOAT or normalized integers");
    CHECK(error_of(colored_triangle(8)) ==
          "colors.gltf: meshes[0] primitives[0] COLOR_0 (accessor 8) is VEC2, expected VEC3 or VEC4");
    CHECK(error_of(colored_triangle(9)).find("COLOR_0 uses accessor 9 but the file has 9 accessors") != std::string::npos);
}
