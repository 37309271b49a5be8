// Draco mesh decoding behind a plain interface, in a shared library of its own
// (tessera_draco) that hides everything else: Debian's libdraco (shared or
// static) also carries a tinygltf of its own (Draco's glTF transcoder) whose
// symbols would take the place of libtinygltf's, with another class layout.
// tessera_draco links the static archive with every symbol hidden and exports
// only decode_draco_mesh. Used by gltf_compression.cpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#define TESSERA_DRACO_API __attribute__((visibility("default")))

namespace tessera::draco_codec {

// One attribute to extract: Draco's unique id, and the glTF component type
// (5120 BYTE ... 5126 FLOAT) and component count to convert its values to.
struct AttributeRequest {
    std::uint32_t unique_id = 0;
    int component_type = 0;
    int components = 0;
};

struct DecodedMesh {
    std::string error;          // empty when decoded; else what went wrong
    int failed_attribute = -1;  // with an error: the request it concerns, or -1 for the data as a whole
    std::size_t points = 0;     // vertices
    std::vector<std::uint32_t> indices;                  // 3 per triangle, each < points
    std::vector<std::vector<unsigned char>> attributes;  // per request: points × components values, packed
};

// Decodes a Draco mesh (not a point cloud) from `size` bytes; never throws for bad data.
TESSERA_DRACO_API DecodedMesh decode_draco_mesh(const unsigned char* data, std::size_t size,
                                                const std::vector<AttributeRequest>& requests);

}  // namespace tessera::draco_codec
