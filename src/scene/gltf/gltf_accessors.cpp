#include "scene/gltf/gltf_accessors.hpp"

#include <algorithm>
#include <cstring>

#include "scene/gltf/gltf_geometry.hpp"

namespace tessera::gltf {

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
        case TINYGLTF_TYPE_MAT2: return 4;
        case TINYGLTF_TYPE_MAT3: return 9;
        case TINYGLTF_TYPE_MAT4: return 16;
        default: return 0;
    }
}

namespace {

// Rows of a matrix type (its columns' length); 0 for scalars and vectors.
int matrix_rows(int type) {
    switch (type) {
        case TINYGLTF_TYPE_MAT2: return 2;
        case TINYGLTF_TYPE_MAT3: return 3;
        case TINYGLTF_TYPE_MAT4: return 4;
        default: return 0;
    }
}

std::size_t column_bytes(int rows, std::size_t size) { return (std::size_t(rows) * size + 3) / 4 * 4; }

template <typename T>
T load(const unsigned char* p) {
    T value;
    std::memcpy(&value, p, sizeof value);
    return value;
}

std::uint32_t load_index(const unsigned char* p, int component_type) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return load<std::uint8_t>(p);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return load<std::uint16_t>(p);
        default: return load<std::uint32_t>(p);
    }
}

}  // namespace

std::size_t element_size(int type, int component_type) {
    const std::size_t size = component_size(component_type);
    if (const int rows = matrix_rows(type)) return std::size_t(rows) * column_bytes(rows, size);
    return size * std::size_t(component_count(type));
}

std::size_t CheckedAccessor::component_offset(int c) const {
    const std::size_t size = component_size(component_type);
    if (const int rows = matrix_rows(type)) return std::size_t(c / rows) * column_bytes(rows, size) + std::size_t(c % rows) * size;
    return std::size_t(c) * size;
}

const unsigned char* AccessorReader::view_bytes(int view_index, std::size_t offset, std::size_t length,
                                                std::size_t stride, std::size_t count, const std::string& name,
                                                const char* part) const {
    if (view_index < 0 || std::size_t(view_index) >= model_.bufferViews.size())
        fail(source_, name + " uses bufferView " + std::to_string(view_index) + " but the file has " +
                          std::to_string(model_.bufferViews.size()));
    const tinygltf::BufferView& view = model_.bufferViews[std::size_t(view_index)];
    const std::string view_name = "bufferView " + std::to_string(view_index);
    if (view.buffer < 0 || std::size_t(view.buffer) >= model_.buffers.size())
        fail(source_, view_name + " (for " + name + ") uses buffer " + std::to_string(view.buffer) +
                          " but the file has " + std::to_string(model_.buffers.size()));
    const tinygltf::Buffer& buffer = model_.buffers[std::size_t(view.buffer)];

    // The view must lie inside the buffer, and the last element inside the view.
    std::size_t view_end = 0;
    if (__builtin_add_overflow(view.byteOffset, view.byteLength, &view_end) || view_end > buffer.data.size())
        fail(source_, view_name + " (for " + name + ") spans bytes " + std::to_string(view.byteOffset) + " + " +
                          std::to_string(view.byteLength) + ", past the end of buffer " +
                          std::to_string(view.buffer) + " (" + std::to_string(buffer.data.size()) + " bytes)");
    if (count == 0) return buffer.data.data() + view.byteOffset;
    std::size_t last_start = 0, end = 0;
    if (__builtin_mul_overflow(count - 1, stride, &last_start) || __builtin_add_overflow(last_start, offset, &last_start) ||
        __builtin_add_overflow(last_start, length, &end) || end > view.byteLength)
        fail(source_, name + " is out of range: " + std::to_string(count) + " " + part + " of " +
                          std::to_string(length) + " bytes every " + std::to_string(stride) + " from byteOffset " +
                          std::to_string(offset) + " do not fit " + view_name + " (" +
                          std::to_string(view.byteLength) + " bytes)");
    return buffer.data.data() + view.byteOffset + offset;
}

void AccessorReader::apply_sparse(const tinygltf::Accessor& accessor, const std::string& name,
                                  std::vector<unsigned char>& bytes, std::size_t element_bytes) const {
    const auto& sparse = accessor.sparse;
    if (sparse.count < 1 || std::size_t(sparse.count) > accessor.count)
        fail(source_, name + " has sparse.count " + std::to_string(sparse.count) + ", expected 1 to " +
                          std::to_string(accessor.count) + " (its count)");
    const int index_type = sparse.indices.componentType;
    if (index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        fail(source_, name + " has sparse indices of " + component_name(index_type) +
                          ", expected UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
    if (sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0)
        fail(source_, name + " has a negative sparse byteOffset");
    const auto count = std::size_t(sparse.count);
    const std::size_t index_size = component_size(index_type);
    const unsigned char* indices = view_bytes(sparse.indices.bufferView, std::size_t(sparse.indices.byteOffset),
                                              index_size, index_size, count, name + " sparse indices", "indices");
    const unsigned char* values = view_bytes(sparse.values.bufferView, std::size_t(sparse.values.byteOffset),
                                             element_bytes, element_bytes, count, name + " sparse values", "values");
    std::uint32_t previous = 0;
    for (std::size_t k = 0; k < count; ++k) {
        const std::uint32_t index = load_index(indices + k * index_size, index_type);
        if (index >= accessor.count)
            fail(source_, name + " sparse index " + std::to_string(index) + " at [" + std::to_string(k) +
                              "] is out of range; the accessor has " + std::to_string(accessor.count) + " elements");
        if (k > 0 && index <= previous)  // the spec's rule; it also keeps substitutions unambiguous
            fail(source_, name + " sparse indices do not strictly increase: " + std::to_string(index) + " at [" +
                              std::to_string(k) + "] follows " + std::to_string(previous));
        previous = index;
        std::memcpy(bytes.data() + std::size_t(index) * element_bytes, values + k * element_bytes, element_bytes);
    }
}

CheckedAccessor AccessorReader::check(int index, const std::string& what, const AccessorRule& rule) const {
    if (index < 0 || std::size_t(index) >= model_.accessors.size())
        fail(source_, what + " uses accessor " + std::to_string(index) + " but the file has " +
                          std::to_string(model_.accessors.size()) + " accessors");
    const tinygltf::Accessor& accessor = model_.accessors[std::size_t(index)];
    const std::string name = what + " (accessor " + std::to_string(index) + ")";
    if (accessor.type != rule.type)
        fail(source_, name + " is " + type_name(accessor.type) + ", expected " + type_name(rule.type));
    bool allowed = false;
    for (const int t : rule.component_types) allowed = allowed || accessor.componentType == t;
    std::string allowed_names;
    for (const int t : rule.component_types) allowed_names += (allowed_names.empty() ? "" : ", ") + component_name(t);
    const std::string note = rule.note.empty() ? "" : " (" + rule.note + ")";
    if (!allowed)
        fail(source_, name + " has components of " + component_name(accessor.componentType) + ", expected " +
                          allowed_names + note);
    const bool integer = accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT;
    if (rule.integer_needs_normalized && integer && !accessor.normalized)
        fail(source_, name + " holds " + component_name(accessor.componentType) +
                          " values that are not normalized; expected FLOAT or normalized integers" + note);
    if (rule.integer_must_not_be_normalized && integer && accessor.normalized)
        fail(source_, name + " holds normalized " + component_name(accessor.componentType) +
                          " values; expected plain integers");

    CheckedAccessor checked;
    checked.count = accessor.count;
    checked.type = accessor.type;
    checked.component_type = accessor.componentType;
    checked.components = component_count(accessor.type);
    checked.normalized = accessor.normalized;
    const std::size_t element_bytes = element_size(accessor.type, accessor.componentType);
    checked.stride = element_bytes;

    if (accessor.bufferView < 0) {  // all zeros, then the sparse substitutions if any
        if (accessor.count > kMaxImplicitElements)
            fail(source_, name + " has no bufferView and " + std::to_string(accessor.count) +
                              " elements; at most " + std::to_string(kMaxImplicitElements) +
                              " are read from an accessor without data");
        auto bytes = std::make_shared<std::vector<unsigned char>>(accessor.count * element_bytes, 0);
        if (accessor.sparse.isSparse) apply_sparse(accessor, name, *bytes, element_bytes);
        checked.first = bytes->data();
        checked.owned = std::move(bytes);
        return checked;
    }

    if (accessor.bufferView < 0 || std::size_t(accessor.bufferView) >= model_.bufferViews.size())
        fail(source_, name + " uses bufferView " + std::to_string(accessor.bufferView) + " but the file has " +
                          std::to_string(model_.bufferViews.size()));
    const tinygltf::BufferView& view = model_.bufferViews[std::size_t(accessor.bufferView)];
    if (view.byteStride != 0) {
        checked.stride = view.byteStride;
        if (checked.stride < element_bytes)
            fail(source_, "bufferView " + std::to_string(accessor.bufferView) + " (for " + name + ") has byteStride " +
                              std::to_string(view.byteStride) + ", less than the " + std::to_string(element_bytes) +
                              "-byte element");
    }
    checked.first = view_bytes(accessor.bufferView, accessor.byteOffset, element_bytes, checked.stride, accessor.count,
                               name, "elements");
    if (!accessor.sparse.isSparse) return checked;

    // Sparse over a buffer view: a packed copy of the base, then the substitutions.
    auto bytes = std::make_shared<std::vector<unsigned char>>(accessor.count * element_bytes);
    for (std::size_t i = 0; i < accessor.count; ++i)
        std::memcpy(bytes->data() + i * element_bytes, checked.element(i), element_bytes);
    apply_sparse(accessor, name, *bytes, element_bytes);
    checked.first = bytes->data();
    checked.stride = element_bytes;
    checked.owned = std::move(bytes);
    return checked;
}

float component(const CheckedAccessor& a, std::size_t i, int c) {
    const unsigned char* p = a.element(i) + a.component_offset(c);
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
    if (a.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT && a.components == N) {
        // The common case, one copy per element (positions of a million-triangle mesh).
        for (std::size_t i = 0; i < a.count; ++i) std::memcpy(&values[i], a.element(i), sizeof(float) * N);
        return values;
    }
    const int n = std::min(N, a.components);
    for (std::size_t i = 0; i < a.count; ++i)
        for (int c = 0; c < n; ++c) values[i][c] = component(a, i, c);
    return values;
}

template std::vector<glm::vec<2, float>> read_vectors<2>(const CheckedAccessor&);
template std::vector<glm::vec<3, float>> read_vectors<3>(const CheckedAccessor&);
template std::vector<glm::vec<4, float>> read_vectors<4>(const CheckedAccessor&);

std::vector<float> read_floats(const CheckedAccessor& a) {
    std::vector<float> values(a.count * std::size_t(a.components));
    for (std::size_t i = 0; i < a.count; ++i)
        for (int c = 0; c < a.components; ++c) values[i * std::size_t(a.components) + std::size_t(c)] = component(a, i, c);
    return values;
}

std::vector<std::uint32_t> read_uints(const CheckedAccessor& a) {
    std::vector<std::uint32_t> values(a.count * std::size_t(a.components));
    for (std::size_t i = 0; i < a.count; ++i) {
        for (int c = 0; c < a.components; ++c) {
            const unsigned char* p = a.element(i) + a.component_offset(c);
            std::uint32_t value = 0;
            switch (a.component_type) {
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: value = load<std::uint8_t>(p); break;
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: value = load<std::uint16_t>(p); break;
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: value = load<std::uint32_t>(p); break;
                default: {  // callers' rules exclude these; kept defined for any float
                    const float f = component(a, i, c);
                    value = f >= 0.0f && f < 4294967296.0f ? std::uint32_t(f) : 0;
                }
            }
            values[i * std::size_t(a.components) + std::size_t(c)] = value;
        }
    }
    return values;
}

}  // namespace tessera::gltf
