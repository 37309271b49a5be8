// PNG output through libpng: 8-bit RGB, display-referred (sRGB-encoded).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace tessera {

// Writes width·height RGB8 pixels (rows top first) to `path`. Returns why it
// failed, or "" on success. Not atomic: write_image writes a temporary file.
std::string write_png_rgb8(const std::uint8_t* rgb, int width, int height, const std::filesystem::path& path);

}  // namespace tessera
