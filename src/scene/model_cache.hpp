// glTF models loaded once per process: `tessera render A.toml B.toml` (or a
// check over many scenes) that places the same model in several scenes reads,
// decodes and mip-maps its file once. Scenes share the model's textures (they
// are shared_ptr) and copy its meshes, materials and objects.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "scene/gltf/gltf_import.hpp"

namespace tessera {

class ModelCache {
public:
    // The content of a .gltf or .glb file: imported (import_gltf_file) on the
    // first call for that file, the same object on every later call. Files are
    // told apart by their canonical path. Throws what import_gltf_file throws;
    // a file that failed is not remembered (the next call tries again).
    // Safe to call from several threads (one import at a time).
    // allow_external_uris: a scene's [[models]] key (GltfReadOptions); a file is
    // cached once per setting.
    std::shared_ptr<const GltfContent> load(const std::filesystem::path& path, bool allow_external_uris = false);

    // Files imported so far; a call answered from the cache does not count.
    std::size_t imports() const;
    // Forgets every model: their memory goes once no scene shares it. The CLI
    // does this before rendering its last scene.
    void clear();

private:
    mutable std::mutex mutex_;
    std::map<std::string, std::shared_ptr<const GltfContent>> models_;  // canonical path -> content
    std::size_t imports_ = 0;
};

// load_scene_file (tessera/scene.hpp) taking glTF models from `models`: each model file is
// imported once however many scenes loaded through it use it.
Scene load_scene_file(const std::filesystem::path& path, ModelCache& models, const std::string& gltf_camera = "");

}  // namespace tessera
