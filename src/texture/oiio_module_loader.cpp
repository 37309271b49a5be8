#include "texture/oiio_module_loader.hpp"

#include <cstdlib>
#include <mutex>
#include <system_error>
#include <vector>

#include <dlfcn.h>

#include "texture/texture.hpp"

namespace tessera::texture {

std::vector<std::filesystem::path> oiio_module_candidates() {
    std::vector<std::filesystem::path> candidates;
    // An explicit choice (packagers, tests) is the only candidate.
    if (const char* chosen = std::getenv("TESSERA_OIIO_MODULE"); chosen && *chosen) return {chosen};
    std::error_code error;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
    if (!error) {
        candidates.push_back(exe.parent_path() / kTesseraOiioModuleFile);
#ifdef TESSERA_HELPERS_FROM_BIN
        // An installed tree: bin/tessera -> lib/tessera/ (a relative path: the tree may be moved).
        candidates.push_back((exe.parent_path() / TESSERA_HELPERS_FROM_BIN / kTesseraOiioModuleFile).lexically_normal());
#endif
    }
#ifdef TESSERA_OIIO_MODULE_BUILD_PATH
    // Test programs live elsewhere in the build tree than the module.
    const std::filesystem::path built = TESSERA_OIIO_MODULE_BUILD_PATH;
    if (candidates.empty() || candidates.front() != built) candidates.push_back(built);
#endif
    return candidates;
}

namespace {

// The module's entry points, loaded once per process (thread-safe).
struct OiioModule {
    TesseraReadImage read_image = nullptr;
    TesseraReadFloatImage read_float_image = nullptr;
    std::string failure;
};

const OiioModule& oiio_module() {
    static const OiioModule loaded = [] {
        OiioModule m;
        const std::vector<std::filesystem::path> candidates = oiio_module_candidates();
        std::string tried;
        for (const std::filesystem::path& path : candidates) {
            std::error_code error;
            if (!std::filesystem::exists(path, error)) {
                tried += (tried.empty() ? "" : ", ") + path.string();
                continue;
            }
            // RTLD_LOCAL: OpenImageIO's symbols stay out of the program's namespace.
            void* module = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
            if (!module) {
                m.failure = "OpenImageIO's module '" + path.string() + "' does not load: " + dlerror();
                return m;
            }
            m.read_image = reinterpret_cast<TesseraReadImage>(dlsym(module, kTesseraOiioModuleEntry));
            m.read_float_image = reinterpret_cast<TesseraReadFloatImage>(dlsym(module, kTesseraOiioModuleFloatEntry));
            if (!m.read_image || !m.read_float_image)
                m.failure = "OpenImageIO's module '" + path.string() + "' has no " + kTesseraOiioModuleEntry + " or " +
                            kTesseraOiioModuleFloatEntry;
            return m;  // never closed: it may be used again, and closing OpenImageIO is not safe
        }
        m.failure = "reading this format needs OpenImageIO's module " + std::string(kTesseraOiioModuleFile) +
                    ", which is not installed (looked for " + tried + ")";
        return m;
    }();
    return loaded;
}

}  // namespace

TesseraReadImage oiio_module_reader(const std::string& source) {
    const OiioModule& m = oiio_module();
    if (!m.read_image) throw TextureError(source + ": " + m.failure);
    return m.read_image;
}

TesseraReadFloatImage oiio_module_float_reader(const std::string& source) {
    const OiioModule& m = oiio_module();
    if (!m.read_float_image) throw TextureError(source + ": " + m.failure);
    return m.read_float_image;
}

}  // namespace tessera::texture
