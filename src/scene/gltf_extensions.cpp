#include "scene/gltf_extensions.hpp"

#include <algorithm>

#include "scene/gltf_geometry.hpp"

namespace tessera::gltf {

bool is_supported_extension(std::string_view name) {
    return std::find(std::begin(kSupportedExtensions), std::end(kSupportedExtensions), name) !=
           std::end(kSupportedExtensions);
}

void check_extensions(const tinygltf::Model& model, const std::string& source, std::vector<std::string>& warnings) {
    for (const std::string& name : model.extensionsRequired)
        if (!is_supported_extension(name))
            fail(source, "the file requires the extension '" + name + "', which is not supported");
    std::vector<std::string> warned;
    for (const std::string& name : model.extensionsUsed) {
        if (is_supported_extension(name) || std::find(warned.begin(), warned.end(), name) != warned.end()) continue;
        warned.push_back(name);
        warnings.push_back("extension '" + name + "' is not supported and is ignored");
    }
}

}  // namespace tessera::gltf
