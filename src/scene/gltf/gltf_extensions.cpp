#include "scene/gltf/gltf_extensions.hpp"

#include <algorithm>

#include "scene/gltf/gltf_geometry.hpp"

namespace tessera::gltf {

bool is_supported_extension(std::string_view name) {
    return std::find(std::begin(kSupportedExtensions), std::end(kSupportedExtensions), name) !=
           std::end(kSupportedExtensions);
}

void check_extensions(const tinygltf::Model& model, const std::string& source, std::vector<std::string>& warnings) {
    for (const std::string& name : model.extensionsRequired) {
        if (is_supported_extension(name)) continue;
        if (name == "KHR_texture_basisu")
            fail(source, "the file requires the extension 'KHR_texture_basisu', which is not supported (KTX2 images; "
                         "no Debian package transcodes Basis Universal): convert its images to PNG, e.g. with "
                         "KTX-Software's `ktx transcode --target rgba8 in.ktx2 rgba.ktx2` then `ktx extract rgba.ktx2 "
                         "out.png`, and point the textures at them");
        fail(source, "the file requires the extension '" + name + "', which is not supported");
    }
    std::vector<std::string> warned;
    for (const std::string& name : model.extensionsUsed) {
        if (is_supported_extension(name) || std::find(warned.begin(), warned.end(), name) != warned.end()) continue;
        warned.push_back(name);
        const bool shading = std::find(std::begin(kIgnoredShadingExtensions), std::end(kIgnoredShadingExtensions),
                                       name) != std::end(kIgnoredShadingExtensions);
        if (shading)
            warnings.push_back("extension '" + name + "' changes shading beyond the reference shader; it is ignored");
        else if (name == "KHR_texture_basisu")
            warnings.push_back("extension 'KHR_texture_basisu' (KTX2 images) is not supported; textures use their "
                               "PNG or JPEG fallback");
        else
            warnings.push_back("extension '" + name + "' is not supported and is ignored");
    }
}

}  // namespace tessera::gltf
