// Finds and opens the OpenImageIO module (oiio_module/oiio_module_abi.hpp) on
// first use: beside the running executable (/proc/self/exe), else in lib/tessera/ of an
// installed tree (bin/../lib/tessera), else where the build tree put it;
// TESSERA_OIIO_MODULE in the environment names it instead. Texture files that are neither PNG nor JPEG need it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "texture/oiio_module/oiio_module_abi.hpp"

namespace tessera::texture {

// The module's entry point, loaded once per process (thread-safe). Throws
// TextureError "<source>: reading this format needs OpenImageIO's module
// '<path>': <why>" when it is missing or broken.
TesseraReadImage oiio_module_reader(const std::string& source);
// The same module's float reader (environment maps), with the same errors.
TesseraReadFloatImage oiio_module_float_reader(const std::string& source);

// Where the module is looked for, first to last.
std::vector<std::filesystem::path> oiio_module_candidates();

}  // namespace tessera::texture
