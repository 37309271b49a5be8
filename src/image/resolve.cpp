#include "image/resolve.hpp"

#include <algorithm>
#include <cmath>

namespace tessera::image {

glm::vec3 radiance_for_display(const glm::vec3& display) {
    glm::vec3 radiance;
    for (int c = 0; c < 3; ++c) {
        const float linear = std::pow(std::clamp(display[c], 0.0f, 1.0f), 2.2f);  // undo gamma
        // Undo Reinhard x/(x+1); white would need infinity, so stop at half's largest value.
        radiance[c] = linear < 1.0f ? std::min(linear / (1.0f - linear), 65504.0f) : 65504.0f;
    }
    return radiance;
}

}  // namespace tessera::image
