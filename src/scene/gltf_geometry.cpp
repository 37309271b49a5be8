#include "scene/gltf_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

namespace tessera::gltf {

void fail(const std::string& source, const std::string& message) { throw SceneError(source + ": " + message); }

namespace {

std::string type_name(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return "SCALAR";
        case TINYGLTF_TYPE_VEC2: return "VEC2";
        case TINYGLTF_TYPE_VEC3: return "VEC3";
        case TINYGLTF_TYPE_VEC4: return "VEC4";
        case TINYGLTF_TYPE_MAT2: return "MAT2";
        case TINYGLTF_TYPE_MAT3: return "MAT3";
        case TINYGLTF_TYPE_MAT4: return "MAT4";
        default: return "type " + std::to_string(type);
    }
}

std::string component_name(int component_type) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
        case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
        default: return "component type " + std::to_string(component_type);
    }
}

// Bytes per component; 0 for a type glTF does not allow in accessors.
std::size_t component_size(int component_type) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        default: return 0;
    }
}

int component_count(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return 1;
        case TINYGLTF_TYPE_VEC2: return 2;
        case TINYGLTF_TYPE_VEC3: return 3;
        case TINYGLTF_TYPE_VEC4: return 4;
        default: return 0;
    }
}

// An accessor whose every element lies inside its buffer view and buffer.
struct CheckedAccessor {
    const unsigned char* first = nullptr;  // element 0
    std::size_t stride = 0;                // bytes from one element to the next
    std::size_t count = 0;
    int component_type = 0;
    int components = 0;
    bool normalized = false;

    const unsigned char* element(std::size_t i) const { return first + i * stride; }
};

// What an attribute may be stored as.
struct AccessorRule {
    int type;                                   // TINYGLTF_TYPE_*
    std::vector<int> component_types;           // allowed; the first is the float one where any is
    bool integer_needs_normalized = false;      // texture coordinates: u8/u16 must be normalized
};

class AccessorReader {
public:
    AccessorReader(const tinygltf::Model& model, const std::string& source) : model_(model), source_(source) {}

    CheckedAccessor check(int index, const std::string& what, const AccessorRule& rule) const {
        if (index < 0 || std::size_t(index) >= model_.accessors.size())
            fail(source_, what + " uses accessor " + std::to_string(index) + " but the file has " +
                              std::to_string(model_.accessors.size()) + " accessors");
        const tinygltf::Accessor& accessor = model_.accessors[std::size_t(index)];
        const std::string name = what + " (accessor " + std::to_string(index) + ")";
        if (accessor.sparse.isSparse) fail(source_, name + " is sparse; sparse accessors are not supported");
        if (accessor.type != rule.type)
            fail(source_, name + " is " + type_name(accessor.type) + ", expected " + type_name(rule.type));
        bool allowed = false;
        for (const int t : rule.component_types) allowed = allowed || accessor.componentType == t;
        std::string allowed_names;
        for (const int t : rule.component_types) allowed_names += (allowed_names.empty() ? "" : ", ") + component_name(t);
        if (!allowed)
            fail(source_, name + " has components of " + component_name(accessor.componentType) + ", expected " +
                              allowed_names);
        if (rule.integer_needs_normalized && accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT &&
            !accessor.normalized)
            fail(source_, name + " holds " + component_name(accessor.componentType) +
                              " values that are not normalized; expected FLOAT or normalized integers");

        CheckedAccessor checked;
        checked.count = accessor.count;
        checked.component_type = accessor.componentType;
        checked.components = component_count(accessor.type);
        checked.normalized = accessor.normalized;
        const std::size_t element_size = component_size(accessor.componentType) * std::size_t(checked.components);
        if (accessor.bufferView < 0) {
            if (accessor.count == 0) return checked;
            fail(source_, name + " has no bufferView (implicit zeros); not supported");
        }
        if (std::size_t(accessor.bufferView) >= model_.bufferViews.size())
            fail(source_, name + " uses bufferView " + std::to_string(accessor.bufferView) + " but the file has " +
                              std::to_string(model_.bufferViews.size()));
        const tinygltf::BufferView& view = model_.bufferViews[std::size_t(accessor.bufferView)];
        const std::string view_name = "bufferView " + std::to_string(accessor.bufferView);
        if (view.buffer < 0 || std::size_t(view.buffer) >= model_.buffers.size())
            fail(source_, view_name + " (for " + name + ") uses buffer " + std::to_string(view.buffer) +
                              " but the file has " + std::to_string(model_.buffers.size()));
        const tinygltf::Buffer& buffer = model_.buffers[std::size_t(view.buffer)];
        checked.stride = view.byteStride != 0 ? view.byteStride : element_size;
        if (checked.stride < element_size)
            fail(source_, view_name + " (for " + name + ") has byteStride " + std::to_string(view.byteStride) +
                              ", less than the " + std::to_string(element_size) + "-byte element");

        // The view must lie inside the buffer, and the last element inside the view.
        std::size_t view_end = 0;
        if (__builtin_add_overflow(view.byteOffset, view.byteLength, &view_end) || view_end > buffer.data.size())
            fail(source_, view_name + " (for " + name + ") spans bytes " + std::to_string(view.byteOffset) + " + " +
                              std::to_string(view.byteLength) + ", past the end of buffer " +
                              std::to_string(view.buffer) + " (" + std::to_string(buffer.data.size()) + " bytes)");
        if (accessor.count == 0) return checked;
        std::size_t last_start = 0, end = 0;
        if (__builtin_mul_overflow(accessor.count - 1, checked.stride, &last_start) ||
            __builtin_add_overflow(last_start, accessor.byteOffset, &last_start) ||
            __builtin_add_overflow(last_start, element_size, &end) || end > view.byteLength)
            fail(source_, name + " is out of range: " + std::to_string(accessor.count) + " elements of " +
                              std::to_string(element_size) + " bytes every " + std::to_string(checked.stride) +
                              " from byteOffset " + std::to_string(accessor.byteOffset) + " do not fit " + view_name +
                              " (" + std::to_string(view.byteLength) + " bytes)");
        checked.first = buffer.data.data() + view.byteOffset + accessor.byteOffset;
        return checked;
    }

private:
    const tinygltf::Model& model_;
    const std::string& source_;
};

template <typename T>
T load(const unsigned char* p) {
    T value;
    std::memcpy(&value, p, sizeof value);
    return value;
}

// Component c of element i as a float; normalized integers map to [0, 1] or [-1, 1] (glTF's rules).
float component(const CheckedAccessor& a, std::size_t i, int c) {
    const unsigned char* p = a.element(i) + std::size_t(c) * component_size(a.component_type);
    switch (a.component_type) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return load<float>(p);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return a.normalized ? load<std::uint8_t>(p) / 255.0f : load<std::uint8_t>(p);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return a.normalized ? load<std::uint16_t>(p) / 65535.0f : load<std::uint16_t>(p);
        case TINYGLTF_COMPONENT_TYPE_BYTE:
            return a.normalized ? std::max(load<std::int8_t>(p) / 127.0f, -1.0f) : load<std::int8_t>(p);
        case TINYGLTF_COMPONENT_TYPE_SHORT:
            return a.normalized ? std::max(load<std::int16_t>(p) / 32767.0f, -1.0f) : load<std::int16_t>(p);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return float(load<std::uint32_t>(p));
        default: return 0.0f;  // excluded by AccessorRule
    }
}

template <int N>
std::vector<glm::vec<N, float>> read_vectors(const CheckedAccessor& a) {
    std::vector<glm::vec<N, float>> values(a.count);
    if (a.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT) {
        // The common case, one copy per element (positions of a million-triangle mesh).
        for (std::size_t i = 0; i < a.count; ++i) std::memcpy(&values[i], a.element(i), sizeof(float) * N);
        return values;
    }
    for (std::size_t i = 0; i < a.count; ++i)
        for (int c = 0; c < N; ++c) values[i][c] = component(a, i, c);
    return values;
}

std::vector<std::uint32_t> read_indices(const CheckedAccessor& a) {
    std::vector<std::uint32_t> indices(a.count);
    for (std::size_t i = 0; i < a.count; ++i) {
        const unsigned char* p = a.element(i);
        switch (a.component_type) {
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: indices[i] = load<std::uint8_t>(p); break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: indices[i] = load<std::uint16_t>(p); break;
            default: indices[i] = load<std::uint32_t>(p); break;
        }
    }
    return indices;
}

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

// glTF's rule for a primitive without normals: flat shading. Each triangle gets
// its own three vertices carrying the face normal.
void make_flat_normals(Mesh& mesh) {
    const auto unweld = [&mesh](auto& attribute) {
        if (attribute.empty()) return;
        std::remove_reference_t<decltype(attribute)> split(mesh.indices.size());
        for (std::size_t i = 0; i < mesh.indices.size(); ++i) split[i] = attribute[mesh.indices[i]];
        attribute = std::move(split);
    };
    unweld(mesh.positions);
    unweld(mesh.uvs);
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
                             const std::string& source, const std::string& label, int texcoord_set) {
    PrimitiveMesh result;
    const int mode = primitive.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        if (mode < TINYGLTF_MODE_POINTS || mode > TINYGLTF_MODE_TRIANGLE_FAN)
            fail(source, label + " has mode " + std::to_string(mode) + "; glTF modes are 0..6");
        return result;  // points and lines: nothing to fill
    }
    result.is_surface = true;
    Mesh& mesh = result.mesh;
    mesh.name = label;
    const AccessorReader reader(model, source);
    const int position_accessor = attribute(primitive, "POSITION");
    if (position_accessor < 0) fail(source, label + " has no POSITION attribute");
    const AccessorRule float_vec3{TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT}};
    mesh.positions = read_vectors<3>(reader.check(position_accessor, label + " POSITION", float_vec3));
    const std::size_t vertex_count = mesh.positions.size();
    if (vertex_count > std::numeric_limits<std::uint32_t>::max())
        fail(source, label + " has " + std::to_string(vertex_count) + " vertices; at most 2^32 - 1 are supported");

    const auto check_count = [&](std::size_t count, const char* what) {
        if (count != vertex_count)
            fail(source, label + " " + what + " has " + std::to_string(count) + " elements for " +
                             std::to_string(vertex_count) + " positions");
    };
    if (const int n = attribute(primitive, "NORMAL"); n >= 0) {
        mesh.normals = read_vectors<3>(reader.check(n, label + " NORMAL", float_vec3));
        check_count(mesh.normals.size(), "NORMAL");
    }
    const std::string texcoord = "TEXCOORD_" + std::to_string(texcoord_set);
    if (const int uv = attribute(primitive, texcoord.c_str()); uv >= 0) {
        const AccessorRule rule{TINYGLTF_TYPE_VEC2,
                                {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                 TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                                true};
        mesh.uvs = read_vectors<2>(reader.check(uv, label + " " + texcoord, rule));
        check_count(mesh.uvs.size(), texcoord.c_str());
    }
    if (const int t = attribute(primitive, "TANGENT"); t >= 0) {
        mesh.tangents = read_vectors<4>(reader.check(t, label + " TANGENT", {TINYGLTF_TYPE_VEC4, {TINYGLTF_COMPONENT_TYPE_FLOAT}}));
        check_count(mesh.tangents.size(), "TANGENT");
    }
    if (const int c = attribute(primitive, "COLOR_0"); c >= 0) read_colors(model, reader, c, source, label, mesh);
    if (!mesh.colors.empty()) check_count(mesh.colors.size(), "COLOR_0");

    std::vector<std::uint32_t> vertices;  // in primitive order, before strips and fans become lists
    if (primitive.indices >= 0) {
        const AccessorRule rule{TINYGLTF_TYPE_SCALAR,
                                {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                 TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT}};
        vertices = read_indices(reader.check(primitive.indices, label + " indices", rule));
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
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (vertices.size() % 3 != 0)
            fail(source, label + " is TRIANGLES with " + std::to_string(vertices.size()) +
                             " vertices to draw, not a multiple of 3");
        mesh.indices = std::move(vertices);
    } else {
        mesh.indices = triangle_list(mode, vertices);
    }
    if (mesh.normals.empty()) make_flat_normals(mesh);
    return result;
}

}  // namespace tessera::gltf
