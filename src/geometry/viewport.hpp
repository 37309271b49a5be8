// Viewport transform with OpenGL conventions, snapped to the rasterizer's
// fixed point: image space, x right and y down (row 0 is the top of the
// picture), pixel (i, j) centred at (i + 0.5, j + 0.5), depth z_ndc·0.5 + 0.5.
#pragma once

#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

namespace tessera::geometry {

// Screen positions are snapped to 1/256 pixel (24.8 fixed point).
inline constexpr int kSubpixelBits = 8;
inline constexpr std::int32_t kSubpixelScale = 1 << kSubpixelBits;

struct Viewport {
    int width = 0;
    int height = 0;
};

// A vertex on screen. x, y and depth are only meaningful for a vertex inside
// the near plane and the guard band (its outcode has no clip-plane bit).
struct ScreenVertex {
    std::int32_t x, y;      // 24.8 fixed point, image space
    float depth;            // window depth in [0, 1]
    std::uint32_t outcode;  // geometry::outcode() (clipper.hpp), beside the position:
                            // triangle setup reads one 16-byte record per corner
};

// The outcode is left 0: the vertex stage sets it.
inline ScreenVertex to_screen(const glm::vec4& clip_pos, const Viewport& viewport) {
    const float inv_w = 1.0f / clip_pos.w;
    const float x = (clip_pos.x * inv_w * 0.5f + 0.5f) * float(viewport.width);
    const float y = (0.5f - clip_pos.y * inv_w * 0.5f) * float(viewport.height);
    // lrintf rounds to nearest even; with -fno-math-errno it is one instruction.
    return {static_cast<std::int32_t>(std::lrintf(x * float(kSubpixelScale))),
            static_cast<std::int32_t>(std::lrintf(y * float(kSubpixelScale))), clip_pos.z * inv_w * 0.5f + 0.5f, 0};
}

}  // namespace tessera::geometry
