// glTF geometry as real exporters write it (issue #14): KHR_mesh_quantization,
// sparse accessors and accessors without a buffer view, EXT_meshopt_compression
// and KHR_draco_mesh_compression. Each test makes its small file with
// gltf_compressed_files.hpp (the compressed ones with the same libraries the
// importer decodes with) and compares what is read with the plain file; the
// last reads a filtered stream through the accessor reader directly.
#include <algorithm>
#include <array>

#include <doctest/doctest.h>
#include <tiny_gltf.h>

#include "scene/gltf/gltf_accessors.hpp"
#include "scene/gltf_compressed_files.hpp"
#include "scene/gltf/gltf_compression.hpp"
#include "scene/gltf/gltf_import.hpp"
#include "test_paths.hpp"

using namespace tessera;

namespace {

GltfContent import_bytes(const std::string& bytes, const std::string& name = "test.gltf") {
    const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
    return import_gltf({data, bytes.size()}, name, "");
}

std::string error_of(const std::string& bytes) {
    try {
        import_bytes(bytes, "bad.gltf");
    } catch (const SceneError& e) {
        return e.what();
    }
    return "(accepted)";
}

const Mesh& only_mesh(const GltfContent& content) {
    REQUIRE(content.meshes.size() == 1);
    return content.meshes[0];
}

// Values of `values` (components per element) stored as T every `stride` bytes, each mapped by `to_stored`.
template <typename T, typename F>
std::size_t add_strided(test::BinaryBuffer& bin, const float* values, std::size_t count, int components,
                        std::size_t stride, F to_stored) {
    std::vector<std::uint8_t> bytes(count * stride, 0);
    for (std::size_t i = 0; i < count; ++i)
        for (int c = 0; c < components; ++c) {
            const T stored = T(to_stored(values[i * std::size_t(components) + std::size_t(c)]));
            std::memcpy(&bytes[i * stride + std::size_t(c) * sizeof(T)], &stored, sizeof(T));
        }
    return bin.add(bytes);
}

const float* flat(const std::vector<glm::vec2>& v) { return &v[0].x; }
const float* flat(const std::vector<glm::vec3>& v) { return &v[0].x; }
const float* flat(const std::vector<glm::vec4>& v) { return &v[0].x; }

// The grid with KHR_mesh_quantization's storage: positions as SHORT (× 1000,
// not normalized), normals as normalized BYTE, tangents as normalized SHORT,
// uvs as normalized UNSIGNED_SHORT — or, with `other`, positions as normalized
// UNSIGNED_BYTE (× 127), normals as normalized SHORT, tangents as normalized
// BYTE and uvs as BYTE (× 100, not normalized). `lists` sets the extension lists.
std::string quantized_grid(const test::GridMesh& grid, bool other, const std::string& lists) {
    test::BinaryBuffer bin;
    const std::size_t count = grid.positions.size();
    const auto round_to = [](float scale) { return [scale](float v) { return std::lround(v * scale); }; };
    std::size_t p, n, g, t;
    std::string accessors;
    if (!other) {
        p = add_strided<std::int16_t>(bin, flat(grid.positions), count, 3, 8, round_to(1000.0f));
        n = add_strided<std::int8_t>(bin, flat(grid.normals), count, 3, 4, round_to(127.0f));
        g = add_strided<std::int16_t>(bin, flat(grid.tangents), count, 4, 8, round_to(32767.0f));
        t = add_strided<std::uint16_t>(bin, flat(grid.uvs), count, 2, 4, round_to(65535.0f));
        accessors = test::accessor_json(0, 5122, count, "VEC3") + ", " + test::accessor_json(1, 5120, count, "VEC3", true) +
                    ", " + test::accessor_json(2, 5122, count, "VEC4", true) + ", " +
                    test::accessor_json(3, 5123, count, "VEC2", true);
    } else {
        p = add_strided<std::uint8_t>(bin, flat(grid.positions), count, 3, 4,
                                      [](float v) { return std::lround(std::max(v, 0.0f) * 127.0f); });
        n = add_strided<std::int16_t>(bin, flat(grid.normals), count, 3, 8, round_to(32767.0f));
        g = add_strided<std::int8_t>(bin, flat(grid.tangents), count, 4, 4, round_to(127.0f));
        t = add_strided<std::int8_t>(bin, flat(grid.uvs), count, 2, 4, round_to(100.0f));
        accessors = test::accessor_json(0, 5121, count, "VEC3", true) + ", " +
                    test::accessor_json(1, 5122, count, "VEC3", true) + ", " +
                    test::accessor_json(2, 5120, count, "VEC4", true) + ", " + test::accessor_json(3, 5120, count, "VEC2");
    }
    const std::size_t i = bin.add(grid.indices);
    const std::size_t p_stride = other ? 4 : 8, n_stride = other ? 8 : 4, g_stride = other ? 4 : 8;
    return test::one_primitive_gltf(
        lists, R"({"byteLength": )" + std::to_string(bin.bytes.size()) + R"(, "uri": ")" + test::data_uri(bin.bytes) + "\"}",
        test::view_json(0, p, count * p_stride, p_stride) + ", " + test::view_json(0, n, count * n_stride, n_stride) + ", " +
            test::view_json(0, g, count * g_stride, g_stride) + ", " + test::view_json(0, t, count * 4, 4) + ", " +
            test::view_json(0, i, grid.indices.size() * 4),
        accessors + ", " + test::accessor_json(4, 5125, grid.indices.size(), "SCALAR"),
        R"({"attributes": {"POSITION": 0, "NORMAL": 1, "TANGENT": 2, "TEXCOORD_0": 3}, "indices": 4})");
}

const std::string kQuantizationUsed = R"("extensionsUsed": ["KHR_mesh_quantization"], "extensionsRequired": ["KHR_mesh_quantization"],)";

float max_distance(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b, float scale = 1.0f) {
    REQUIRE(a.size() == b.size());
    float worst = 0.0f;
    for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, glm::length(a[i] - b[i] * scale));
    return worst;
}

}  // namespace

TEST_CASE("KHR_mesh_quantization: every component type of the extension's table, normalized as it says") {
    const test::GridMesh grid = test::grid_mesh(4);
    SUBCASE("SHORT positions, normalized BYTE normals, normalized SHORT tangents, normalized UNSIGNED_SHORT uvs") {
        const GltfContent content = import_bytes(quantized_grid(grid, false, kQuantizationUsed));
        CHECK(content.warnings.empty());
        const Mesh& mesh = only_mesh(content);
        CHECK(mesh.indices == grid.indices);
        CHECK(max_distance(mesh.positions, grid.positions, 1000.0f) <= 0.5f * std::sqrt(3.0f));  // integers, not normalized
        for (const glm::vec3& p : mesh.positions) CHECK(p == glm::round(p));
        CHECK(max_distance(mesh.normals, grid.normals) <= 0.5f / 127.0f * std::sqrt(3.0f));
        for (std::size_t v = 0; v < mesh.tangents.size(); ++v) {
            CHECK(glm::length(mesh.tangents[v] - grid.tangents[v]) <= 1e-4f);
            CHECK(mesh.tangents[v].w == grid.tangents[v].w);  // ±32767 / 32767 exactly
        }
        for (std::size_t v = 0; v < mesh.uvs.size(); ++v)
            CHECK(glm::length(mesh.uvs[v] - grid.uvs[v]) <= 0.5f / 65535.0f * std::sqrt(2.0f) + 1e-7f);
    }
    SUBCASE("normalized UNSIGNED_BYTE positions, normalized SHORT normals, normalized BYTE tangents, BYTE uvs") {
        const Mesh mesh = only_mesh(import_bytes(quantized_grid(grid, true, kQuantizationUsed)));
        // x, y in [0, 2] stored as round(127 v) clamp to 255 and read back over 255.
        for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
            const glm::vec3 stored = glm::round(glm::max(grid.positions[v], 0.0f) * 127.0f);
            CHECK(glm::length(mesh.positions[v] - stored / 255.0f) <= 1e-6f);
        }
        CHECK(max_distance(mesh.normals, grid.normals) <= 1e-4f);
        for (std::size_t v = 0; v < mesh.tangents.size(); ++v) CHECK(mesh.tangents[v].w == grid.tangents[v].w);
        for (std::size_t v = 0; v < mesh.uvs.size(); ++v) CHECK(mesh.uvs[v] == glm::round(grid.uvs[v] * 100.0f));
    }
    SUBCASE("without the extension in extensionsUsed the base types apply, and the message says why") {
        CHECK(error_of(quantized_grid(grid, false, "")) ==
              "bad.gltf: meshes[0] 'grid' primitives[0] POSITION (accessor 0) has components of SHORT, expected FLOAT "
              "(other types need KHR_mesh_quantization in extensionsUsed)");
    }
    SUBCASE("types outside the table are refused, naming the accessor") {
        std::string text = quantized_grid(grid, false, kQuantizationUsed);
        const std::string normals = test::replaced(text, R"("componentType": 5120, "count": 25, "type": "VEC3", "normalized": true)",
                                                   R"("componentType": 5121, "count": 25, "type": "VEC3", "normalized": true)");
        CHECK(error_of(normals) == "bad.gltf: meshes[0] 'grid' primitives[0] NORMAL (accessor 1) has components of "
                                  "UNSIGNED_BYTE, expected FLOAT, BYTE, SHORT");
        const std::string unnormalized = test::replaced(text, R"("componentType": 5120, "count": 25, "type": "VEC3", "normalized": true)",
                                                        R"("componentType": 5120, "count": 25, "type": "VEC3")");
        CHECK(error_of(unnormalized) == "bad.gltf: meshes[0] 'grid' primitives[0] NORMAL (accessor 1) holds BYTE values "
                                        "that are not normalized; expected FLOAT or normalized integers");
        const std::string vec2 = test::replaced(text, R"("componentType": 5122, "count": 25, "type": "VEC3")",
                                                R"("componentType": 5122, "count": 25, "type": "VEC2")");
        CHECK(error_of(vec2) == "bad.gltf: meshes[0] 'grid' primitives[0] POSITION (accessor 0) is VEC2, expected VEC3");
    }
}

namespace {

// Three vertices in a buffer view (accessor 0) and these sparse substitutions
// for POSITION, and the primitive's TEXCOORD_0 (accessor 1) without a buffer view.
std::string sparse_triangle(const std::string& position_accessor) {
    test::BinaryBuffer bin;
    bin.add(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});       // 0: base positions
    bin.add(std::vector<std::uint16_t>{1, 2});                     // 36: sparse indices
    bin.add(std::vector<float>{5, 0, 0, 0, 7, 0});                 // 40: sparse values
    return test::one_primitive_gltf(
        "", R"({"byteLength": 64, "uri": ")" + test::data_uri(bin.bytes) + "\"}",
        test::view_json(0, 0, 36) + ", " + test::view_json(0, 36, 4) + ", " + test::view_json(0, 40, 24),
        position_accessor + ", " + test::accessor_json(-1, 5126, 3, "VEC2"),
        R"({"attributes": {"POSITION": 0, "TEXCOORD_0": 1}})");
}

std::string sparse_json(const std::string& count, const std::string& indices_view, const std::string& index_type = "5123",
                        const std::string& values_offset = "0") {
    return R"(, "sparse": {"count": )" + count + R"(, "indices": {"bufferView": )" + indices_view +
           R"(, "componentType": )" + index_type + R"(}, "values": {"bufferView": 2, "byteOffset": )" + values_offset + "}}";
}

}  // namespace

TEST_CASE("sparse accessors and accessors without a buffer view") {
    SUBCASE("sparse over a buffer view: the base with elements 1 and 2 replaced") {
        const Mesh mesh = only_mesh(import_bytes(sparse_triangle(test::accessor_json(0, 5126, 3, "VEC3", false, sparse_json("2", "1")))));
        CHECK(mesh.positions == std::vector<glm::vec3>{{0, 0, 0}, {5, 0, 0}, {0, 7, 0}});
        CHECK(mesh.uvs == std::vector<glm::vec2>(3, glm::vec2(0.0f)));  // no buffer view: zeros
    }
    SUBCASE("sparse over zeros (no buffer view)") {
        const Mesh mesh = only_mesh(import_bytes(sparse_triangle(test::accessor_json(-1, 5126, 3, "VEC3", false, sparse_json("2", "1")))));
        CHECK(mesh.positions == std::vector<glm::vec3>{{0, 0, 0}, {5, 0, 0}, {0, 7, 0}});
    }
    SUBCASE("u8 and u32 sparse indices") {
        // The u16 indices 1, 2 read as u8 are 1, 0: not increasing. Read as u32 (one index): 0x00020001.
        CHECK(error_of(sparse_triangle(test::accessor_json(0, 5126, 3, "VEC3", false, sparse_json("2", "1", "5121")))) ==
              "bad.gltf: meshes[0] 'grid' primitives[0] POSITION (accessor 0) sparse indices do not strictly increase: "
              "0 at [1] follows 1");
        const Mesh mesh = only_mesh(import_bytes(sparse_triangle(test::accessor_json(0, 5126, 3, "VEC3", false, sparse_json("1", "1", "5121")))));
        CHECK(mesh.positions[1] == glm::vec3(5, 0, 0));
        CHECK(error_of(sparse_triangle(test::accessor_json(0, 5126, 3, "VEC3", false, sparse_json("1", "1", "5125")))) ==
              "bad.gltf: meshes[0] 'grid' primitives[0] POSITION (accessor 0) sparse index 131073 at [0] is out of range; "
              "the accessor has 3 elements");
    }
    SUBCASE("bad sparse data is refused, naming the accessor") {
        const auto error = [](const std::string& sparse) {
            return error_of(sparse_triangle(test::accessor_json(0, 5126, 3, "VEC3", false, sparse)));
        };
        CHECK(error(sparse_json("4", "1")) ==
              "bad.gltf: meshes[0] 'grid' primitives[0] POSITION (accessor 0) has sparse.count 4, expected 1 to 3 (its count)");
        CHECK(error(sparse_json("0", "1")).find("has sparse.count 0, expected 1 to 3") != std::string::npos);
        CHECK(error(sparse_json("2", "1", "5126")) ==
              "bad.gltf: meshes[0] 'grid' primitives[0] POSITION (accessor 0) has sparse indices of FLOAT, expected "
              "UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
        CHECK(error(sparse_json("2", "1", "5123", "12")) ==
              "bad.gltf: meshes[0] 'grid' primitives[0] POSITION (accessor 0) sparse values is out of range: 2 values of "
              "12 bytes every 12 from byteOffset 12 do not fit bufferView 2 (24 bytes)");
        CHECK(error(sparse_json("2", "7")) ==
              "bad.gltf: meshes[0] 'grid' primitives[0] POSITION (accessor 0) sparse indices uses bufferView 7 but the file has 3");
        // Index 2 substituted in a 2-element accessor: the u16 indices are 1, 2.
        const std::string two = test::replaced(
            sparse_triangle(test::accessor_json(0, 5126, 2, "VEC3", false, sparse_json("2", "1"))), R"("count": 3, "type": "VEC2")",
            R"("count": 2, "type": "VEC2")");
        CHECK(error_of(two) == "bad.gltf: meshes[0] 'grid' primitives[0] POSITION (accessor 0) sparse index 2 at [1] is out "
                               "of range; the accessor has 2 elements");
    }
    SUBCASE("an accessor without a buffer view claiming a huge count is refused before allocating") {
        const std::string text = test::replaced(sparse_triangle(test::accessor_json(0, 5126, 3, "VEC3")),
                                                R"("count": 3, "type": "VEC2")", R"("count": 4000000000, "type": "VEC2")");
        CHECK(error_of(text) == "bad.gltf: meshes[0] 'grid' primitives[0] TEXCOORD_0 (accessor 1) has no bufferView and "
                                "4000000000 elements; at most 16777216 are read from an accessor without data");
    }
}

namespace {

// Triangles as corner positions, each rotated to start at its smallest corner (winding kept).
std::vector<std::array<glm::vec3, 3>> triangles_of(const Mesh& mesh) {
    std::vector<std::array<glm::vec3, 3>> triangles;
    const auto less = [](const glm::vec3& a, const glm::vec3& b) {
        return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
    };
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        std::array<glm::vec3, 3> c = {mesh.positions[mesh.indices[t]], mesh.positions[mesh.indices[t + 1]],
                                      mesh.positions[mesh.indices[t + 2]]};
        while (less(c[1], c[0]) || less(c[2], c[0])) std::rotate(c.begin(), c.begin() + 1, c.end());
        triangles.push_back(c);
    }
    return triangles;
}

}  // namespace

TEST_CASE("EXT_meshopt_compression: every mode and filter decodes to the plain file's mesh") {
    const test::GridMesh grid = test::grid_mesh(8);
    const Mesh plain = only_mesh(import_bytes(test::plain_grid_gltf(grid)));
    const auto check_against_plain = [&](const Mesh& mesh) {
        CHECK(mesh.positions == plain.positions);  // ATTRIBUTES without a filter is lossless
        // The TRIANGLES codec keeps the triangles' order but may rotate each one's corners (winding kept).
        CHECK(triangles_of(mesh) == triangles_of(plain));
        REQUIRE(mesh.normals.size() == plain.normals.size());
        for (std::size_t v = 0; v < mesh.normals.size(); ++v) {
            // 8-bit octahedral: within a few degrees; BYTE normalized storage, not renormalized.
            CHECK(glm::dot(glm::normalize(mesh.normals[v]), plain.normals[v]) > 0.998f);
            CHECK(glm::length(mesh.tangents[v] - plain.tangents[v]) < 1e-3f);  // 16-bit octahedral
            CHECK(mesh.tangents[v].w == plain.tangents[v].w);
            CHECK(glm::length(mesh.uvs[v] - plain.uvs[v]) < 1e-4f);  // 15-bit mantissa
        }
    };
    SUBCASE("in a .glb with a fallback buffer without data (gltfpack's layout); TRIANGLES indices") {
        const GltfContent content = import_bytes(test::as_text(test::meshopt_grid_glb(grid)), "grid.glb");
        CHECK(content.warnings.empty());
        check_against_plain(only_mesh(content));
    }
    SUBCASE("INDICES mode") {
        check_against_plain(only_mesh(import_bytes(test::as_text(test::meshopt_grid_glb(grid, true)), "grid.glb")));
    }
    SUBCASE("in a .gltf: buffer 0 a data URI, the fallback buffer without uri and without the fallback flag") {
        test::GltfParts parts = test::meshopt_grid_parts(grid);
        std::string text = test::replaced(parts.json, R"({"byteLength": )" + std::to_string(parts.bin.size()) + "}",
                                          R"({"byteLength": )" + std::to_string(parts.bin.size()) + R"(, "uri": ")" +
                                              test::data_uri(parts.bin) + "\"}");
        text = test::replaced(text, R"(, "extensions": {"EXT_meshopt_compression": {"fallback": true}})", "");
        check_against_plain(only_mesh(import_bytes(text)));
    }
}

TEST_CASE("KHR_meshopt_compression: codec version 0 decodes as EXT's, and a stream that is not what its header says is refused") {
    const test::GridMesh grid = test::grid_mesh(8);
    const Mesh plain = only_mesh(import_bytes(test::plain_grid_gltf(grid)));
    const GltfContent content = import_bytes(test::as_text(test::khr_meshopt_grid_glb(grid)), "grid.glb");
    CHECK(content.warnings.empty());
    CHECK(only_mesh(content).positions == plain.positions);
    CHECK(triangles_of(only_mesh(content)) == triangles_of(plain));
    // A version 0 stream under a version 1 header goes to meshopt_codec_v1.cpp (version 1 itself:
    // test_meshopt_codec_v1.cpp and test_gltf_meshopt_khr.cpp), which finds it does not fit.
    const std::string error = error_of(test::as_text(test::khr_meshopt_grid_glb(grid, 1)));
    CHECK(error.find("bad.gltf: bufferView 0 KHR_meshopt_compression: the ATTRIBUTES data (") == 0);
    CHECK(error.find(" bytes): ") != std::string::npos);
    CHECK(error_of(test::as_text(test::khr_meshopt_grid_glb(grid, 2))).find("the stream uses attribute codec version 2") !=
          std::string::npos);
    // A compressed stream's offset past its buffer.
    test::GltfParts parts = test::meshopt_grid_parts(grid);
    parts.json = test::replaced(parts.json, R"({"buffer": 0, "byteOffset": 0,)", R"({"buffer": 0, "byteOffset": 99999999,)");
    CHECK(error_of(test::as_text(test::make_glb(parts.json, parts.bin)))
              .find("bad.gltf: bufferView 0 EXT_meshopt_compression spans bytes 99999999 + ") == 0);
}

TEST_CASE("KHR_draco_mesh_compression: the same triangles as the plain file, within Draco's quantization") {
    const test::GridMesh grid = test::grid_mesh(8);
    const Mesh plain = only_mesh(import_bytes(test::plain_grid_gltf(grid)));
    const GltfContent content = import_bytes(test::as_text(test::draco_grid_glb(grid)), "grid.glb");
    CHECK(content.warnings.empty());
    const Mesh& mesh = only_mesh(content);
    // Positions: 14 bits over the 2-unit extent, so within 2 / 2^14 per axis of the plain ones.
    const float tolerance = 2.0f / 16384.0f * std::sqrt(3.0f);
    const auto decoded = triangles_of(mesh), expected = triangles_of(plain);
    REQUIRE(decoded.size() == expected.size());
    for (const auto& want : expected) {
        const bool found = std::any_of(decoded.begin(), decoded.end(), [&](const std::array<glm::vec3, 3>& got) {
            return glm::length(got[0] - want[0]) <= tolerance && glm::length(got[1] - want[1]) <= tolerance &&
                   glm::length(got[2] - want[2]) <= tolerance;
        });
        CHECK(found);
    }
    // Each decoded vertex carries the attributes of the plain vertex at its position.
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
        std::size_t nearest = 0;
        for (std::size_t p = 1; p < plain.positions.size(); ++p)
            if (glm::length(plain.positions[p] - mesh.positions[v]) < glm::length(plain.positions[nearest] - mesh.positions[v]))
                nearest = p;
        CHECK(glm::length(plain.positions[nearest] - mesh.positions[v]) <= tolerance);
        CHECK(glm::dot(glm::normalize(mesh.normals[v]), plain.normals[nearest]) > 0.999f);  // 10 bits
        CHECK(glm::length(mesh.uvs[v] - plain.uvs[nearest]) <= 1.0f / 4096.0f);            // 12 bits over [0, 1]
        CHECK(mesh.tangents[v] == plain.tangents[nearest]);                                  // not quantized
    }
}

TEST_CASE("EXT_meshopt_compression QUATERNION filter and plain integer vectors, read through the accessor reader") {
    // Five unit quaternions (animation rotations as gltfpack stores them), and JOINTS-style u16 VEC4s.
    std::vector<glm::vec4> rotations;
    for (int i = 0; i < 5; ++i) {
        const float angle = 0.4f * float(i) + 0.1f;
        rotations.push_back(glm::normalize(glm::vec4(std::sin(angle) * glm::normalize(glm::vec3(1, 2, 3 - i)), std::cos(angle))));
    }
    std::vector<std::int16_t> filtered(rotations.size() * 4);
    meshopt_encodeFilterQuat(filtered.data(), rotations.size(), 8, 12, &rotations[0].x);
    std::vector<unsigned char> encoded(meshopt_encodeVertexBufferBound(rotations.size(), 8));
    encoded.resize(meshopt_encodeVertexBuffer(encoded.data(), encoded.size(), filtered.data(), rotations.size(), 8));
    test::BinaryBuffer bin;
    const std::size_t joints_offset = bin.add(std::vector<std::uint16_t>{1, 2, 3, 4, 500, 6, 7, 8});
    const std::size_t encoded_offset = bin.add(encoded.data(), encoded.size());
    const std::string json = test::one_primitive_gltf(
        R"("extensionsUsed": ["EXT_meshopt_compression"], "extensionsRequired": ["EXT_meshopt_compression"],)",
        R"({"byteLength": )" + std::to_string(bin.bytes.size()) + R"(}, {"byteLength": 40})",
        test::view_json(1, 0, 40, 8,
                        R"({"buffer": 0, "byteOffset": )" + std::to_string(encoded_offset) + R"(, "byteLength": )" +
                            std::to_string(encoded.size()) + R"(, "byteStride": 8, "count": 5, "mode": "ATTRIBUTES", "filter": "QUATERNION"})") +
            ", " + test::view_json(0, joints_offset, 16),
        test::accessor_json(0, 5122, 5, "VEC4", true) + ", " + test::accessor_json(1, 5123, 2, "VEC4"),
        R"({"attributes": {"POSITION": 0}})");
    const std::vector<std::uint8_t> glb = test::make_glb(json, bin.bytes);

    const gltf::ParseInput input = gltf::prepare_for_tinygltf(glb, true);
    REQUIRE(input.fallback_buffers == std::vector<int>{1});
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    REQUIRE(loader.LoadBinaryFromMemory(&model, &err, &warn, input.bytes.data(), unsigned(input.bytes.size()), ""));
    gltf::decode_compressed_geometry(model, "rotations.glb", input.fallback_buffers);
    const std::string source = "rotations.glb";
    const gltf::AccessorReader reader(model, source);
    const std::vector<glm::vec4> read = gltf::read_vectors<4>(
        reader.check(0, "rotations", {TINYGLTF_TYPE_VEC4, {TINYGLTF_COMPONENT_TYPE_SHORT}, true}));
    REQUIRE(read.size() == rotations.size());
    for (std::size_t i = 0; i < read.size(); ++i) {
        CAPTURE(i);
        CHECK(std::abs(glm::dot(read[i], rotations[i])) > 0.9999f);  // 12 bits per component; q and -q are one rotation
    }
    const gltf::AccessorRule joints{TINYGLTF_TYPE_VEC4, {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                                    false, true};
    CHECK(gltf::read_uints(reader.check(1, "joints", joints)) == std::vector<std::uint32_t>{1, 2, 3, 4, 500, 6, 7, 8});
}

namespace {

struct MeshSummary {
    std::size_t triangles = 0;
    double area = 0.0;  // world space
    Bounds bounds;
};

MeshSummary summary(const GltfContent& content) {
    MeshSummary s;
    for (const Object& object : content.objects) {
        const Mesh& mesh = content.meshes[object.mesh];
        s.triangles += mesh.indices.size() / 3;
        for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            glm::vec3 p[3];
            for (int c = 0; c < 3; ++c) p[c] = glm::vec3(object.model * glm::vec4(mesh.positions[mesh.indices[t + std::size_t(c)]], 1.0f));
            s.area += 0.5 * double(glm::length(glm::cross(p[1] - p[0], p[2] - p[0])));
        }
    }
    s.bounds = content.bounds;
    return s;
}

}  // namespace

TEST_CASE("real exporters' compressed files: BoomBox's geometry from gltfpack -c (meshopt) and gltf-pipeline -d (Draco)") {
    const std::filesystem::path models = tessera::test::source_dir() / "tests" / "scene" / "models";
    // gltfpack drops the uvs and tangents of a material without textures (and merges the
    // vertices that then coincide); gltf-pipeline keeps every attribute.
    for (const std::string name : {"BoomBox_geometry_meshopt.glb", "BoomBox_geometry_draco.glb"}) {
        CAPTURE(name);
        const GltfContent content = import_gltf_file(models / name);
        CHECK(content.warnings.empty());
        REQUIRE(content.meshes.size() == 1);
        const Mesh& mesh = content.meshes[0];
        CHECK(mesh.normals.size() == mesh.positions.size());
        if (name.find("draco") != std::string::npos) {
            CHECK(mesh.positions.size() == 3575);
            CHECK(mesh.tangents.size() == mesh.positions.size());
            CHECK(mesh.uvs.size() == mesh.positions.size());
        }
        CHECK(summary(content).triangles == 6036);
    }
}

// The same files against the uncompressed original in the sample models (Skipped without them).
TEST_CASE("real exporters' compressed files: the geometry of BoomBox.gltf from the sample models, within quantization") {
    if (test::skip_without_assets()) return;
    const std::filesystem::path models = tessera::test::source_dir() / "tests" / "scene" / "models";
    const MeshSummary want = summary(import_gltf_file(test::assets_dir() / "gltf" / "BoomBox" / "BoomBox.gltf"));
    for (const std::string name : {"BoomBox_geometry_meshopt.glb", "BoomBox_geometry_draco.glb"}) {
        CAPTURE(name);
        const MeshSummary got = summary(import_gltf_file(models / name));
        CHECK(got.triangles == want.triangles);
        const float size = glm::length(want.bounds.max - want.bounds.min);
        CHECK(glm::length(got.bounds.min - want.bounds.min) < 0.002f * size);  // quantization, not lost geometry
        CHECK(glm::length(got.bounds.max - want.bounds.max) < 0.002f * size);
        CHECK(got.area == doctest::Approx(want.area).epsilon(0.005));
    }
}
