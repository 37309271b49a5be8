// What tinygltf would not check, or not survive, looked at before it parses a file.
#pragma once

#include <cstdint>
#include <span>
#include <string>

namespace tessera::gltf {

// Refuses (SceneError naming `source`): a GLB of another version than 2; JSON nested so deep
// that a recursive parser would overflow the stack (io::kMaxJsonDepth; the GLB's JSON chunk
// alike); negative byteOffset, byteLength or byteStride (tinygltf reads them unsigned and keeps
// 0 for a negative number); morph weights that are not all numbers (tinygltf drops such an array
// without a word). A document that is not JSON at all is left to tinygltf's own message.
void check_json_before_parsing(std::span<const std::uint8_t> bytes, bool binary, const std::string& source);

}  // namespace tessera::gltf
