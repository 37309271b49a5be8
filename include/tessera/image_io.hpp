// Writing rendered images. The format follows the file extension:
// .png  display-referred RGB, 8 bits per channel (after tonemapping and gamma);
// .exr  scene-linear HDR radiance, RGB half floats.
#pragma once

#include <filesystem>
#include <stdexcept>

#include "tessera/renderer.hpp"

namespace tessera {

class ImageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Writes to a temporary file beside `path` and renames it into place, so a
// failed or interrupted write never leaves a half-written image. Throws ImageError.
void write_image(const RenderedImage& image, const std::filesystem::path& path);

// True for the extensions write_image understands.
bool is_supported_image_path(const std::filesystem::path& path);

}  // namespace tessera
