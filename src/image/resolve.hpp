// Resolve: from shaded HDR radiance to the two images a frame produces.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

namespace tessera::image {

// 8-bit value of a display-referred channel, rounded to nearest as a UNORM8
// framebuffer stores it; out-of-range values clamp, NaN becomes 0.
inline std::uint8_t quantize_unorm8(float display) {
    const float c = display > 0.0f ? (display < 1.0f ? display : 1.0f) : 0.0f;
    return static_cast<std::uint8_t>(c * 255.0f + 0.5f);
}

// The scene-linear radiance that Reinhard + gamma map back onto a display
// colour (the tonemap's inverse), kept finite: the EXR's background.
glm::vec3 radiance_for_display(const glm::vec3& display);

}  // namespace tessera::image
