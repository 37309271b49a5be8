// Writing rendered images. The format follows the file extension:
// .png  display-referred RGB, 8 bits per channel (after tonemapping and gamma);
//       AOVs are not written to PNG.
// .exr  one multi-channel file: scene-linear HDR radiance as R G B (half), then
//       each AOV plane the image has (RenderedImage::aov; values, spaces and
//       background values documented at AovPlanes), named by the OpenEXR and
//       OpenImageIO conventions:
//         depth      Z                               float (OpenImageIO reads it as ImageSpec::z_channel)
//         normal     N.X N.Y N.Z                     float, world space, unit length
//         albedo     albedo.R albedo.G albedo.B      half
//         roughness  roughness                       half
//         metallic   metallic                        half
//         position   P.X P.Y P.Z                     float, world space
//         object_id  object_id                       uint, 0 = background (AovPlanes::object_id)
//         material_id material_id                    uint, 0 = background
//         shadow      shadow                         half, mean light visibility, 1 = background
//       OpenEXR keeps channels sorted by name; look them up by name when reading.
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
