// Compressed glTF geometry, decoded right after parsing into plain buffers,
// buffer views and accessors, so that everything after (gltf_accessors.hpp)
// reads ordinary glTF:
// - EXT_meshopt_compression (meshoptimizer's decoder): each compressed buffer
//   view (modes ATTRIBUTES, TRIANGLES, INDICES; filters NONE, OCTAHEDRAL,
//   QUATERNION, EXPONENTIAL) becomes a buffer view over its decoded bytes.
//   KHR_meshopt_compression likewise, with attribute codec version 1 and filter
//   COLOR decoded by meshopt_codec_v1.hpp (Debian's meshoptimizer 0.18 has neither).
//   Fallback buffers (marked `fallback`, or without a uri) are never read: the
//   bytes tinygltf parses have them replaced by a 3-byte placeholder first, and
//   a buffer view that reads one without being compressed is an error.
// - KHR_draco_mesh_compression (Google's Draco decoder): each TRIANGLES
//   primitive's Draco buffer view is decoded (primitives in parallel) and its
//   attributes (by the extension's ids) and faces become new accessors in the
//   types the primitive's accessors declare; indices are u32. Points and lines
//   are not decoded (they are not drawn).
// Every size, offset and count is checked first; what does not decode is a
// SceneError "source: ..." naming the buffer view or primitive.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <tiny_gltf.h>

namespace tessera::gltf {

// What tinygltf should parse instead of the file's bytes: its JSON with
// meshopt fallback buffers replaced (see above), and without the `indices` of
// Draco primitives (tinygltf 2.7 refuses indices accessors without a buffer
// view, which is how Draco files declare them; Draco's faces replace them).
struct ParseInput {
    std::vector<std::uint8_t> bytes;      // empty: parse the file's bytes as they are
    std::vector<int> fallback_buffers;    // indices of the buffers replaced
};

// `binary`: the bytes are a .glb. Does nothing (returns empty bytes) unless the
// JSON mentions EXT_meshopt_compression or KHR_draco_mesh_compression; bytes it
// cannot make sense of are left to tinygltf to refuse.
ParseInput prepare_for_tinygltf(std::span<const std::uint8_t> bytes, bool binary);

// Decodes every EXT_/KHR_meshopt_compression buffer view and KHR_draco_mesh_compression
// primitive of `model` in place (see above). `fallback_buffers` from prepare_for_tinygltf.
void decode_compressed_geometry(tinygltf::Model& model, const std::string& source,
                                const std::vector<int>& fallback_buffers);

}  // namespace tessera::gltf
