// Reading glTF accessors: the one place that turns an accessor into numbers.
// Every accessor is checked (type, component type, its bytes inside its buffer
// view and buffer) before a byte is read; accessors without a bufferView are
// zeros (spec §3.6.2.2) and sparse accessors get their substitutions (§3.6.2.3),
// both checked too. Compressed geometry (Draco, meshopt) is decoded into plain
// buffer views before this runs (gltf_compression.hpp), so readers need not
// know about it. Used by the importer's geometry and anything else that reads
// accessors (skins, morph targets, animation samplers).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

namespace tessera::gltf {

// Names for messages: "VEC3", "UNSIGNED_SHORT".
std::string type_name(int type);
std::string component_name(int component_type);
// Bytes per component; 0 for a type glTF does not allow in accessors.
std::size_t component_size(int component_type);
// Components per element: SCALAR 1 ... VEC4 4, MAT2 4, MAT3 9, MAT4 16; 0 for others.
int component_count(int type);

// An accessor whose every element can be read: either in place in its buffer
// view, or (implicit zeros, sparse substitutions) in bytes it owns.
struct CheckedAccessor {
    const unsigned char* first = nullptr;  // element 0
    std::size_t stride = 0;                // bytes from one element to the next
    std::size_t count = 0;
    int type = 0;                          // TINYGLTF_TYPE_*
    int component_type = 0;                // TINYGLTF_COMPONENT_TYPE_*
    int components = 0;                    // per element (MAT4: 16)
    bool normalized = false;
    std::shared_ptr<const std::vector<unsigned char>> owned;  // what `first` points into, when not the file's buffer

    const unsigned char* element(std::size_t i) const { return first + i * stride; }
    // Byte offset of component c inside an element: matrix columns of 1- and
    // 2-byte components start on 4-byte boundaries (spec §3.6.2.4).
    std::size_t component_offset(int c) const;
};

// Bytes of one element, with the column padding of small matrices.
std::size_t element_size(int type, int component_type);

// What an accessor may be stored as.
struct AccessorRule {
    int type = 0;                           // TINYGLTF_TYPE_*
    std::vector<int> component_types = {};  // allowed; the first is the float one where any is
    bool integer_needs_normalized = false;  // integer types must be normalized (e.g. NORMAL as BYTE)
    bool integer_must_not_be_normalized = false;  // integers are counts or indices (JOINTS_n)
    std::string note = {};  // appended to a component type error, e.g. which extension allows more
};

// An accessor without a bufferView (zeros) may have at most this many elements:
// its size is not backed by any bytes of the file, so a few bytes of JSON could
// otherwise ask for gigabytes.
inline constexpr std::size_t kMaxImplicitElements = std::size_t(1) << 24;

class AccessorReader {
public:
    // `source` names the file in messages; both must outlive the reader.
    AccessorReader(const tinygltf::Model& model, const std::string& source) : model_(model), source_(source) {}

    // `what` names the use in messages, e.g. "meshes[0] primitives[1] NORMAL".
    // Throws SceneError "source: what (accessor N) ..." when the accessor breaks
    // the rule or its bytes (or its sparse indices and values) lie outside its
    // buffer views and buffers.
    CheckedAccessor check(int index, const std::string& what, const AccessorRule& rule) const;

private:
    const unsigned char* view_bytes(int view_index, std::size_t offset, std::size_t length, std::size_t stride,
                                    std::size_t count, const std::string& name, const char* part) const;
    void apply_sparse(const tinygltf::Accessor& accessor, const std::string& name, std::vector<unsigned char>& bytes,
                      std::size_t element_bytes) const;

    const tinygltf::Model& model_;
    const std::string& source_;
};

// Component c of element i as a float; normalized integers map to [0, 1] or
// [-1, 1] (glTF's rules: max(c / 127, -1) for BYTE), others convert as is.
float component(const CheckedAccessor& a, std::size_t i, int c);

// Every element as a vector of N floats (N = the accessor's components).
template <int N>
std::vector<glm::vec<N, float>> read_vectors(const CheckedAccessor& a);
// Every component of every element, element after element (a MAT4 is 16 floats, column-major).
std::vector<float> read_floats(const CheckedAccessor& a);
// Every component as an unsigned integer (indices, JOINTS_n): for integer types only.
std::vector<std::uint32_t> read_uints(const CheckedAccessor& a);

extern template std::vector<glm::vec<2, float>> read_vectors<2>(const CheckedAccessor&);
extern template std::vector<glm::vec<3, float>> read_vectors<3>(const CheckedAccessor&);
extern template std::vector<glm::vec<4, float>> read_vectors<4>(const CheckedAccessor&);

}  // namespace tessera::gltf
