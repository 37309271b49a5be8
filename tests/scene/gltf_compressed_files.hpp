// Small glTF files with compressed or quantized geometry, made by the tests
// with the libraries the importer decodes with (meshoptimizer, Draco): one
// bumpy grid mesh stored plainly, with KHR_mesh_quantization, with
// EXT_meshopt_compression and with KHR_draco_mesh_compression. Used by
// test_gltf_compression.cpp, the bad-glTF table and the fuzz seed writer.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <meshoptimizer.h>

#include "scene/draco_test_encoder.hpp"
#include "scene/gltf_test_files.hpp"

namespace tessera::test {

// (n+1)² vertices on z = 0.2·sin(x)·cos(y) over [0, 2]², 2n² triangles, with
// analytic normals, uvs = xy / 2 and tangents along +x.
struct GridMesh {
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec2> uvs;
    std::vector<glm::vec4> tangents;
    std::vector<std::uint32_t> indices;
};

inline GridMesh grid_mesh(int n = 8) {
    GridMesh grid;
    for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= n; ++i) {
            const float x = 2.0f * float(i) / float(n), y = 2.0f * float(j) / float(n);
            grid.positions.emplace_back(x, y, 0.2f * std::sin(x) * std::cos(y));
            const glm::vec3 dx(1.0f, 0.0f, 0.2f * std::cos(x) * std::cos(y));
            const glm::vec3 dy(0.0f, 1.0f, -0.2f * std::sin(x) * std::sin(y));
            grid.normals.push_back(glm::normalize(glm::cross(dx, dy)));
            grid.uvs.emplace_back(x / 2.0f, y / 2.0f);
            grid.tangents.emplace_back(glm::normalize(dx), j % 2 == 0 ? 1.0f : -1.0f);
        }
    }
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            const auto v = std::uint32_t(j * (n + 1) + i), up = v + std::uint32_t(n + 1);
            grid.indices.insert(grid.indices.end(), {v, v + 1, up + 1, v, up + 1, up});
        }
    }
    return grid;
}

// Bytes of a buffer under construction; each piece starts on a 4-byte boundary.
struct BinaryBuffer {
    std::vector<std::uint8_t> bytes;
    std::size_t add(const void* data, std::size_t size) {
        while (bytes.size() % 4 != 0) bytes.push_back(0);
        const std::size_t offset = bytes.size();
        const auto* p = static_cast<const std::uint8_t*>(data);
        bytes.insert(bytes.end(), p, p + size);
        return offset;
    }
    template <typename T>
    std::size_t add(const std::vector<T>& values) {
        return add(values.data(), values.size() * sizeof(T));
    }
};

inline std::string data_uri(const std::vector<std::uint8_t>& bytes) {
    return "data:application/octet-stream;base64," + base64(bytes);
}

// A glTF with one node placing one mesh of one primitive. Each argument is the
// JSON text inside its array or object; `top` adds top-level members (each
// followed by a comma), e.g. extension lists.
inline std::string one_primitive_gltf(const std::string& top, const std::string& buffers, const std::string& views,
                                      const std::string& accessors, const std::string& primitive) {
    return R"({"asset": {"version": "2.0"}, )" + top + R"(
  "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
  "meshes": [{"name": "grid", "primitives": [)" + primitive + R"(]}],
  "accessors": [)" + accessors + R"(],
  "bufferViews": [)" + views + R"(],
  "buffers": [)" + buffers + "]}";
}

inline std::string view_json(int buffer, std::size_t offset, std::size_t length, std::size_t stride = 0,
                             const std::string& extension = "") {
    std::string json = R"({"buffer": )" + std::to_string(buffer) + R"(, "byteOffset": )" + std::to_string(offset) +
                       R"(, "byteLength": )" + std::to_string(length);
    if (stride) json += R"(, "byteStride": )" + std::to_string(stride);
    if (!extension.empty()) json += R"(, "extensions": {"EXT_meshopt_compression": )" + extension + "}";
    return json + "}";
}

inline std::string accessor_json(int view, int component_type, std::size_t count, const char* type, bool normalized = false,
                                 const std::string& more = "") {
    std::string json = "{";
    if (view >= 0) json += R"("bufferView": )" + std::to_string(view) + ", ";
    json += R"("componentType": )" + std::to_string(component_type) + R"(, "count": )" + std::to_string(count) +
            R"(, "type": ")" + type + "\"";
    if (normalized) json += R"(, "normalized": true)";
    return json + more + "}";
}

// The grid with float attributes and u32 indices: the reference the others are compared with.
inline std::string plain_grid_gltf(const GridMesh& grid) {
    BinaryBuffer bin;
    const std::size_t p = bin.add(grid.positions), n = bin.add(grid.normals), t = bin.add(grid.uvs),
                      g = bin.add(grid.tangents), i = bin.add(grid.indices);
    const std::size_t count = grid.positions.size();
    return one_primitive_gltf(
        "", R"({"byteLength": )" + std::to_string(bin.bytes.size()) + R"(, "uri": ")" + data_uri(bin.bytes) + "\"}",
        view_json(0, p, count * 12) + ", " + view_json(0, n, count * 12) + ", " + view_json(0, t, count * 8) + ", " +
            view_json(0, g, count * 16) + ", " + view_json(0, i, grid.indices.size() * 4),
        accessor_json(0, 5126, count, "VEC3", false, R"(, "min": [0, 0, -1], "max": [2, 2, 1])") + ", " +
            accessor_json(1, 5126, count, "VEC3") + ", " + accessor_json(2, 5126, count, "VEC2") + ", " +
            accessor_json(3, 5126, count, "VEC4") + ", " + accessor_json(4, 5125, grid.indices.size(), "SCALAR"),
        R"({"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2, "TANGENT": 3}, "indices": 4})");
}

// The grid with EXT_meshopt_compression, as gltfpack writes it: compressed
// streams in buffer 0 (the GLB's BIN chunk), the views' nominal bytes in
// buffer 1, a fallback buffer without data. Positions float (ATTRIBUTES, no
// filter); normals BYTE normalized (OCTAHEDRAL, 4 bytes); uvs float
// (EXPONENTIAL); tangents SHORT normalized (OCTAHEDRAL, 8 bytes); indices u16
// (TRIANGLES, or INDICES when `index_sequence`). Returns {json, bin}.
struct GltfParts {
    std::string json;
    std::vector<std::uint8_t> bin;
};

inline GltfParts meshopt_grid_parts(const GridMesh& grid, bool index_sequence = false) {
    const std::size_t count = grid.positions.size();
    BinaryBuffer compressed;
    std::size_t fallback_size = 0;
    std::string views;
    const auto add_stream = [&](const void* data, std::size_t stride, std::size_t elements, const char* mode,
                                const char* filter) {
        std::vector<unsigned char> encoded;
        std::size_t size = 0;
        if (std::string(mode) == "ATTRIBUTES") {
            encoded.resize(meshopt_encodeVertexBufferBound(elements, stride));
            size = meshopt_encodeVertexBuffer(encoded.data(), encoded.size(), data, elements, stride);
        } else {
            std::vector<unsigned int> indices(elements);
            for (std::size_t k = 0; k < elements; ++k)
                indices[k] = stride == 2 ? static_cast<const std::uint16_t*>(data)[k] : static_cast<const std::uint32_t*>(data)[k];
            if (std::string(mode) == "TRIANGLES") {
                encoded.resize(meshopt_encodeIndexBufferBound(elements, count));
                size = meshopt_encodeIndexBuffer(encoded.data(), encoded.size(), indices.data(), elements);
            } else {
                encoded.resize(meshopt_encodeIndexSequenceBound(elements, count));
                size = meshopt_encodeIndexSequence(encoded.data(), encoded.size(), indices.data(), elements);
            }
        }
        const std::size_t offset = compressed.add(encoded.data(), size);
        std::string extension = R"({"buffer": 0, "byteOffset": )" + std::to_string(offset) + R"(, "byteLength": )" +
                                std::to_string(size) + R"(, "byteStride": )" + std::to_string(stride) +
                                R"(, "count": )" + std::to_string(elements) + R"(, "mode": ")" + mode + "\"";
        if (filter) extension += R"(, "filter": ")" + std::string(filter) + "\"";
        extension += "}";
        views += (views.empty() ? "" : ", ") +
                 view_json(1, fallback_size, elements * stride, std::string(mode) == "ATTRIBUTES" ? stride : 0, extension);
        fallback_size += (elements * stride + 3) / 4 * 4;
    };
    add_stream(grid.positions.data(), 12, count, "ATTRIBUTES", nullptr);
    std::vector<float> four(count * 4);
    for (std::size_t v = 0; v < count; ++v) std::memcpy(&four[v * 4], &grid.normals[v], 12), four[v * 4 + 3] = 0.0f;
    std::vector<std::int8_t> normals(count * 4);
    meshopt_encodeFilterOct(normals.data(), count, 4, 8, four.data());
    add_stream(normals.data(), 4, count, "ATTRIBUTES", "OCTAHEDRAL");
    std::vector<float> uvs(count * 2);
    std::memcpy(uvs.data(), grid.uvs.data(), count * 8);
    std::vector<std::uint32_t> exp_uvs(count * 2);
    meshopt_encodeFilterExp(exp_uvs.data(), count, 8, 15, uvs.data());
    add_stream(exp_uvs.data(), 8, count, "ATTRIBUTES", "EXPONENTIAL");
    std::memcpy(four.data(), grid.tangents.data(), count * 16);
    std::vector<std::int16_t> tangents(count * 4);
    meshopt_encodeFilterOct(tangents.data(), count, 8, 16, four.data());
    add_stream(tangents.data(), 8, count, "ATTRIBUTES", "OCTAHEDRAL");
    std::vector<std::uint16_t> indices(grid.indices.begin(), grid.indices.end());
    add_stream(indices.data(), 2, indices.size(), index_sequence ? "INDICES" : "TRIANGLES", nullptr);

    const std::string accessors =
        accessor_json(0, 5126, count, "VEC3", false, R"(, "min": [0, 0, -1], "max": [2, 2, 1])") + ", " +
        accessor_json(1, 5120, count, "VEC3", true) + ", " + accessor_json(2, 5126, count, "VEC2") + ", " +
        accessor_json(3, 5122, count, "VEC4", true) + ", " + accessor_json(4, 5123, indices.size(), "SCALAR");
    const std::string buffers = R"({"byteLength": )" + std::to_string(compressed.bytes.size()) + R"(}, {"byteLength": )" +
                                std::to_string(fallback_size) +
                                R"(, "extensions": {"EXT_meshopt_compression": {"fallback": true}}})";
    const std::string lists =
        R"("extensionsUsed": ["EXT_meshopt_compression", "KHR_mesh_quantization"], )"
        R"("extensionsRequired": ["EXT_meshopt_compression", "KHR_mesh_quantization"],)";
    return {one_primitive_gltf(lists, buffers, views, accessors,
                               R"({"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2, "TANGENT": 3}, "indices": 4})"),
            compressed.bytes};
}

inline std::vector<std::uint8_t> meshopt_grid_glb(const GridMesh& grid, bool index_sequence = false) {
    GltfParts parts = meshopt_grid_parts(grid, index_sequence);
    return make_glb(parts.json, parts.bin);
}

// The grid's Draco encoding (draco_test_encoder.hpp says how), and the unique
// ids of its POSITION, NORMAL, TEXCOORD_0 and TANGENT attributes.
using DracoGrid = DracoEncoded;

inline DracoGrid draco_grid(const GridMesh& grid, bool bool_tangents = false) {
    return encode_draco_triangles(&grid.positions[0].x, &grid.normals[0].x, &grid.uvs[0].x, &grid.tangents[0].x,
                                  grid.indices.data(), grid.indices.size(), bool_tangents);
}

// The grid as KHR_draco_mesh_compression writes it: accessors without buffer
// views (the counts the encoder was given), the Draco bytes in a buffer view.
inline GltfParts draco_grid_parts(const DracoGrid& draco, std::size_t vertex_count, std::size_t index_count) {
    const std::string extension = R"({"KHR_draco_mesh_compression": {"bufferView": 0, "attributes": {"POSITION": )" +
                                  std::to_string(draco.position_id) + R"(, "NORMAL": )" + std::to_string(draco.normal_id) +
                                  R"(, "TEXCOORD_0": )" + std::to_string(draco.uv_id) + R"(, "TANGENT": )" +
                                  std::to_string(draco.tangent_id) + "}}}";
    const std::string lists = R"("extensionsUsed": ["KHR_draco_mesh_compression"], )"
                              R"("extensionsRequired": ["KHR_draco_mesh_compression"],)";
    return {one_primitive_gltf(
                lists, R"({"byteLength": )" + std::to_string(draco.bytes.size()) + "}",
                view_json(0, 0, draco.bytes.size()),
                accessor_json(-1, 5126, vertex_count, "VEC3", false, R"(, "min": [0, 0, -1], "max": [2, 2, 1])") + ", " +
                    accessor_json(-1, 5126, vertex_count, "VEC3") + ", " + accessor_json(-1, 5126, vertex_count, "VEC2") +
                    ", " + accessor_json(-1, 5126, vertex_count, "VEC4") + ", " +
                    accessor_json(-1, 5125, index_count, "SCALAR"),
                R"({"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2, "TANGENT": 3}, "indices": 4, "extensions": )" +
                    extension + "}"),
            draco.bytes};
}

inline std::vector<std::uint8_t> draco_grid_glb(const GridMesh& grid) {
    const DracoGrid draco = draco_grid(grid);
    GltfParts parts = draco_grid_parts(draco, grid.positions.size(), grid.indices.size());
    return make_glb(parts.json, parts.bin);
}

inline std::string as_text(const std::vector<std::uint8_t>& bytes) { return std::string(bytes.begin(), bytes.end()); }

// The meshopt grid under KHR_meshopt_compression, the ratified name (gltfpack -ce khr):
// the same JSON with the extension renamed everywhere. `codec_version` sets the
// positions' ATTRIBUTES stream header (0xa0 | version; the encoder here writes 0).
inline std::vector<std::uint8_t> khr_meshopt_grid_glb(const GridMesh& grid, int codec_version = 0) {
    GltfParts parts = meshopt_grid_parts(grid);
    for (std::size_t at = parts.json.find("EXT_meshopt_compression"); at != std::string::npos;
         at = parts.json.find("EXT_meshopt_compression", at))
        parts.json.replace(at, 3, "KHR");
    parts.bin[0] = std::uint8_t(0xa0 | codec_version);  // the positions' stream starts buffer 0
    return make_glb(parts.json, parts.bin);
}

}  // namespace tessera::test
