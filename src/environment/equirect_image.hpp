// The environment's source: an equirectangular (latitude-longitude) HDR image,
// Radiance .hdr or OpenEXR, read as linear RGB floats through OpenImageIO's module.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <vector>

#include <glm/glm.hpp>

namespace tessera::environment {

// Loading or pre-computing an environment failed; the message names the file
// and what was expected.
class EnvironmentError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Sizes an environment image may have: 2:1 within [1.5, 2.5], sides up to 16384.
inline constexpr int kMaxEquirectWidth = 16384;

struct EquirectImage {
    int width = 0, height = 0;
    // Rows bottom-up, as the chapter's stbi_set_flip_vertically_on_load(true)
    // leaves them in the GL texture: row 0 is the image's last. RGB, >= 0, finite.
    std::vector<glm::vec3> rgb;

    // texture(equirectangularMap, uv): GL_LINEAR, GL_CLAMP_TO_EDGE.
    glm::vec3 sample(float u, float v) const;
};

// Reads `path`. Refuses (EnvironmentError) files that cannot be read as an
// image, that are not .hdr or .exr, or have a size no equirectangular image
// has; negative and non-finite samples become 0 (light cannot be negative).
EquirectImage load_equirect_image(const std::filesystem::path& path);
// The checks load_equirect_image makes before decoding: a .hdr or .exr name, an existing file.
void check_equirect_path(const std::filesystem::path& path);

}  // namespace tessera::environment
