#include "scene/model_cache.hpp"

#include <system_error>

namespace tessera {

std::shared_ptr<const GltfContent> ModelCache::load(const std::filesystem::path& path, bool allow_external_uris) {
    std::error_code error;
    std::filesystem::path key = std::filesystem::weakly_canonical(path, error);
    if (error) key = path.lexically_normal();
    GltfReadOptions options;
    options.allow_external_uris = options.allow_external_uris || allow_external_uris;
    if (options.allow_external_uris) key += "\n(external URIs allowed)";
    // Held during the import: a second scene asking for the same file waits for
    // it instead of importing it again.
    const std::lock_guard lock(mutex_);
    if (const auto found = models_.find(key.string()); found != models_.end()) return found->second;
    auto content = std::make_shared<const GltfContent>(import_gltf_file(path, options));
    ++imports_;
    models_.emplace(key.string(), content);
    return content;
}

std::size_t ModelCache::imports() const {
    const std::lock_guard lock(mutex_);
    return imports_;
}

void ModelCache::clear() {
    const std::lock_guard lock(mutex_);
    models_.clear();
}

}  // namespace tessera
