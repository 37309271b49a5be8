// Reading a scene file's [animation] table (format: docs/scene-format.md).
#pragma once

#include <memory>
#include <string>

#include <toml++/toml.h>

#include "tessera/animation.hpp"

namespace tessera {

// Reads a scene file's [animation] table (format: docs/scene-format.md;
// implemented in animation_file.cpp). `root` is the whole document, `scene` what was read from it so far
// (the [[objects]] and [[lights]] the tracks refer to, by index); an object
// whose colour is animated gets its own copy of its material. Throws
// SceneError "file:line:column: message".
std::shared_ptr<const Animation> read_animation(const toml::table& root, const std::string& source, Scene& scene);

}  // namespace tessera
