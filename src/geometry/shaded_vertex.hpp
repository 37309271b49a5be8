// What the vertex stage hands on: one vertex after the reference vertex shader.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

namespace tessera::geometry {

struct ShadedVertex {
    glm::vec4 clip_pos;   // gl_Position: projection · view · world
    glm::vec3 world_pos;  // the shader's WorldPos
    glm::vec3 normal;     // world space (normal matrix applied), not normalized
    glm::vec2 uv;         // the shader's TexCoords
};

// A triangle corner refers either to the frame's vertex array or, with this bit
// set, to the vertices its chunk created while clipping.
inline constexpr std::uint32_t kClippedVertexBit = 0x8000'0000u;

}  // namespace tessera::geometry
