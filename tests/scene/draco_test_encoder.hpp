// Draco encoding for the tests' small models, in a shared library of its own
// for the reason src/scene/gltf/draco_codec.hpp gives (libdraco carries a tinygltf).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#define TESSERA_DRACO_TEST_API __attribute__((visibility("default")))

namespace tessera::test {

// A triangle list encoded with positions 14 bits, normals 10, uvs 12 and
// tangents (a generic 4-component attribute) not quantized; with the unique ids
// of those four attributes. Empty bytes if Draco refused. bool_tangents: the
// generic attribute is of Draco's bool type instead, its bytes 93, 1, 0, 200 at
// every corner (what no glTF accessor holds).
struct DracoEncoded {
    std::vector<std::uint8_t> bytes;
    int position_id = 0, normal_id = 0, uv_id = 0, tangent_id = 0;
};

TESSERA_DRACO_TEST_API DracoEncoded encode_draco_triangles(const float* positions, const float* normals, const float* uvs,
                                                          const float* tangents, const std::uint32_t* indices,
                                                          std::size_t index_count, bool bool_tangents = false);

}  // namespace tessera::test
