#include "scene/gltf/gltf_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "scene/gltf/gltf_accessors.hpp"

namespace tessera::gltf {

void fail(const std::string& source, const std::string& message) { throw SceneError(source + ": " + message); }

namespace {

// Strips and fans as triangle lists, keeping glTF's winding (spec §3.7.2.1).
std::vector<std::uint32_t> triangle_list(int mode, const std::vector<std::uint32_t>& v) {
    std::vector<std::uint32_t> list;
    if (v.size() < 3) return list;
    list.reserve(3 * (v.size() - 2));
    for (std::size_t i = 0; i + 2 < v.size(); ++i) {
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            const std::size_t odd = i % 2;
            list.insert(list.end(), {v[i], v[i + 1 + odd], v[i + 2 - odd]});
        } else {  // fan
            list.insert(list.end(), {v[i + 1], v[i + 2], v[0]});
        }
    }
    return list;
}

// Loops and strips as line lists (spec §3.7.2.1): a strip joins each vertex to
// the next, a loop also the last to the first.
std::vector<std::uint32_t> line_list(int mode, const std::vector<std::uint32_t>& v) {
    if (mode == TINYGLTF_MODE_LINE) return v;
    std::vector<std::uint32_t> list;
    if (v.size() < 2) return list;
    for (std::size_t i = 0; i + 1 < v.size(); ++i) list.insert(list.end(), {v[i], v[i + 1]});
    if (mode == TINYGLTF_MODE_LINE_LOOP) list.insert(list.end(), {v.back(), v.front()});
    return list;
}

// glTF's rule for a primitive without normals: flat shading. Each triangle gets
// its own three vertices carrying the face normal. `sources` gets the vertex
// each new one copies.
void make_flat_normals(Mesh& mesh, std::vector<std::uint32_t>& sources) {
    sources = mesh.indices;
    const auto unweld = [&mesh](auto& attribute) {
        if (attribute.empty()) return;
        std::remove_reference_t<decltype(attribute)> split(mesh.indices.size());
        for (std::size_t i = 0; i < mesh.indices.size(); ++i) split[i] = attribute[mesh.indices[i]];
        attribute = std::move(split);
    };
    unweld(mesh.positions);
    unweld(mesh.uvs);
    unweld(mesh.uvs1);
    unweld(mesh.tangents);
    unweld(mesh.colors);
    mesh.normals.resize(mesh.positions.size());
    for (std::size_t t = 0; t + 2 < mesh.positions.size(); t += 3) {
        const glm::vec3 n = glm::cross(mesh.positions[t + 1] - mesh.positions[t], mesh.positions[t + 2] - mesh.positions[t]);
        const float length = glm::length(n);
        // A degenerate triangle covers no pixel; any unit normal will do.
        const glm::vec3 unit = length > 0.0f && std::isfinite(length) ? n / length : glm::vec3(0.0f, 0.0f, 1.0f);
        mesh.normals[t] = mesh.normals[t + 1] = mesh.normals[t + 2] = unit;
    }
    for (std::size_t i = 0; i < mesh.indices.size(); ++i) mesh.indices[i] = std::uint32_t(i);
}

int attribute(const tinygltf::Primitive& primitive, const char* name) {
    const auto found = primitive.attributes.find(name);
    return found == primitive.attributes.end() ? -1 : found->second;
}

// What each attribute may be stored as: glTF's base types, and with
// KHR_mesh_quantization (when the file lists it in extensionsUsed) the
// extension's table: positions and uvs in any 8/16-bit integers, normalized or
// not; normals and tangents in normalized signed ones.
struct AttributeRules {
    AccessorRule position, normal, tangent, texcoord;
};

AttributeRules attribute_rules(const tinygltf::Model& model) {
    constexpr int f32 = TINYGLTF_COMPONENT_TYPE_FLOAT, i8 = TINYGLTF_COMPONENT_TYPE_BYTE,
                  u8 = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, i16 = TINYGLTF_COMPONENT_TYPE_SHORT,
                  u16 = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    const bool quantized = std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(),
                                     "KHR_mesh_quantization") != model.extensionsUsed.end();
    if (quantized)
        return {{TINYGLTF_TYPE_VEC3, {f32, i8, u8, i16, u16}},
                {TINYGLTF_TYPE_VEC3, {f32, i8, i16}, true},
                {TINYGLTF_TYPE_VEC4, {f32, i8, i16}, true},
                {TINYGLTF_TYPE_VEC2, {f32, i8, u8, i16, u16}}};
    const std::string note = "other types need KHR_mesh_quantization in extensionsUsed";
    return {{TINYGLTF_TYPE_VEC3, {f32}, false, false, note},
            {TINYGLTF_TYPE_VEC3, {f32}, false, false, note},
            {TINYGLTF_TYPE_VEC4, {f32}, false, false, note},
            {TINYGLTF_TYPE_VEC2, {f32, u8, u16}, true, false, note}};
}

// COLOR_0: VEC3 (alpha 1) or VEC4 of FLOAT or normalized UNSIGNED_BYTE / UNSIGNED_SHORT,
// read through the same checked accessor readers as every attribute. Floats are
// clamped to [0, 1] (an exporter's 1.0000001 should not refuse a model); NaN and
// infinities are refused.
void read_colors(const tinygltf::Model& model, const AccessorReader& reader, int accessor, const std::string& source,
                 const std::string& label, Mesh& mesh) {
    const std::string what = label + " COLOR_0";
    int type = TINYGLTF_TYPE_VEC4;
    if (accessor >= 0 && std::size_t(accessor) < model.accessors.size()) {
        type = model.accessors[std::size_t(accessor)].type;
        if (type != TINYGLTF_TYPE_VEC3 && type != TINYGLTF_TYPE_VEC4)
            fail(source, what + " (accessor " + std::to_string(accessor) + ") is " + type_name(type) +
                             ", expected VEC3 or VEC4");
    }
    const AccessorRule rule{type,
                            {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                             TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                            true};
    const CheckedAccessor checked = reader.check(accessor, what, rule);
    if (type == TINYGLTF_TYPE_VEC3) {
        const std::vector<glm::vec3> rgb = read_vectors<3>(checked);
        mesh.colors.resize(rgb.size());
        for (std::size_t i = 0; i < rgb.size(); ++i) mesh.colors[i] = glm::vec4(rgb[i], 1.0f);
    } else {
        mesh.colors = read_vectors<4>(checked);
    }
    for (std::size_t i = 0; i < mesh.colors.size(); ++i) {
        glm::vec4& color = mesh.colors[i];
        for (int k = 0; k < 4; ++k) {
            if (!std::isfinite(color[k]))
                fail(source, what + " (accessor " + std::to_string(accessor) + ") element " + std::to_string(i) +
                                 " is not finite; expected colours in [0, 1]");
            color[k] = std::clamp(color[k], 0.0f, 1.0f);
        }
    }
}

}  // namespace

PrimitiveMesh read_primitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                             const std::string& source, const std::string& label, int texcoord_set,
                             int second_texcoord_set) {
    PrimitiveMesh result;
    const int mode = primitive.mode;
    if (mode < TINYGLTF_MODE_POINTS || mode > TINYGLTF_MODE_TRIANGLE_FAN)
        fail(source, label + " has mode " + std::to_string(mode) + "; glTF modes are 0..6");
    result.is_surface = true;
    Mesh& mesh = result.mesh;
    mesh.name = label;
    mesh.topology = mode == TINYGLTF_MODE_POINTS ? Topology::points
                    : mode <= TINYGLTF_MODE_LINE_STRIP ? Topology::lines
                                                       : Topology::triangles;
    const AccessorReader reader(model, source);
    const int position_accessor = attribute(primitive, "POSITION");
    if (position_accessor < 0) fail(source, label + " has no POSITION attribute");
    const AttributeRules rules = attribute_rules(model);
    mesh.positions = read_vectors<3>(reader.check(position_accessor, label + " POSITION", rules.position));
    const std::size_t vertex_count = mesh.positions.size();
    if (vertex_count > std::numeric_limits<std::uint32_t>::max())
        fail(source, label + " has " + std::to_string(vertex_count) + " vertices; at most 2^32 - 1 are supported");

    const auto check_count = [&](std::size_t count, const char* what) {
        if (count != vertex_count)
            fail(source, label + " " + what + " has " + std::to_string(count) + " elements for " +
                             std::to_string(vertex_count) + " positions");
    };
    if (const int n = attribute(primitive, "NORMAL"); n >= 0) {
        mesh.normals = read_vectors<3>(reader.check(n, label + " NORMAL", rules.normal));
        check_count(mesh.normals.size(), "NORMAL");
    }
    const auto read_uvs = [&](int set, std::vector<glm::vec2>& uvs) {
        const std::string texcoord = "TEXCOORD_" + std::to_string(set);
        if (const int uv = attribute(primitive, texcoord.c_str()); uv >= 0) {
            uvs = read_vectors<2>(reader.check(uv, label + " " + texcoord, rules.texcoord));
            check_count(uvs.size(), texcoord.c_str());
        }
    };
    read_uvs(texcoord_set, mesh.uvs);
    if (second_texcoord_set >= 0) read_uvs(second_texcoord_set, mesh.uvs1);
    if (const int t = attribute(primitive, "TANGENT"); t >= 0) {
        mesh.tangents = read_vectors<4>(reader.check(t, label + " TANGENT", rules.tangent));
        check_count(mesh.tangents.size(), "TANGENT");
    }
    if (const int c = attribute(primitive, "COLOR_0"); c >= 0) read_colors(model, reader, c, source, label, mesh);
    if (!mesh.colors.empty()) check_count(mesh.colors.size(), "COLOR_0");

    std::vector<std::uint32_t> vertices;  // in primitive order, before strips and fans become lists
    if (primitive.indices >= 0) {
        const AccessorRule rule{TINYGLTF_TYPE_SCALAR,
                                {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                 TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT}};
        vertices = read_uints(reader.check(primitive.indices, label + " indices", rule));
        for (std::size_t i = 0; i < vertices.size(); ++i) {
            if (vertices[i] >= vertex_count)
                fail(source, label + " indices (accessor " + std::to_string(primitive.indices) + "): index " +
                                 std::to_string(vertices[i]) + " at [" + std::to_string(i) + "] is out of range; " +
                                 "the primitive has " + std::to_string(vertex_count) + " vertices");
        }
    } else {
        vertices.resize(vertex_count);
        for (std::size_t i = 0; i < vertex_count; ++i) vertices[i] = std::uint32_t(i);
    }
    if (mode == TINYGLTF_MODE_POINTS) {
        mesh.indices = std::move(vertices);
        return result;  // no NORMAL: lit facing the camera (Mesh::normals)
    }
    if (mesh.topology == Topology::lines) {
        // LINES with an odd vertex count (the validator's MESH_PRIMITIVE_INCOMPATIBLE_MODE):
        // not drawn, counted in GltfContent::skipped_primitives.
        if (mode == TINYGLTF_MODE_LINE && vertices.size() % 2 != 0) {
            result.is_surface = false;
            return result;
        }
        mesh.indices = line_list(mode, vertices);
        return result;
    }
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (vertices.size() % 3 != 0)
            fail(source, label + " is TRIANGLES with " + std::to_string(vertices.size()) +
                             " vertices to draw, not a multiple of 3");
        mesh.indices = std::move(vertices);
    } else {
        mesh.indices = triangle_list(mode, vertices);
    }
    if (mesh.normals.empty()) make_flat_normals(mesh, result.vertex_sources);
    return result;
}

std::vector<float> read_accessor_floats(const tinygltf::Model& model, int index, const std::string& source,
                                        const std::string& what, int type, std::initializer_list<int> component_types,
                                        bool integers_need_normalized) {
    return read_floats(AccessorReader(model, source)
                           .check(index, what, AccessorRule{type, component_types, integers_need_normalized}));
}

}  // namespace tessera::gltf
