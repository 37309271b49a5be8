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

TesseraReadImage oiio_module_reader(const std::string& source) {
    static std::once_flag once;
    static TesseraReadImage reader = nullptr;
    static std::string failure;
    std::call_once(once, [] {
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
                failure = "OpenImageIO's module '" + path.string() + "' does not load: " + dlerror();
                return;
            }
            reader = reinterpret_cast<TesseraReadImage>(dlsym(module, kTesseraOiioModuleEntry));
            if (!reader) failure = "OpenImageIO's module '" + path.string() + "' has no " + kTesseraOiioModuleEntry;
            return;  // never closed: it may be used again, and closing OpenImageIO is not safe
        }
        failure = "reading this format needs OpenImageIO's module " + std::string(kTesseraOiioModuleFile) +
                  ", which is not installed (looked for " + tried + ")";
    });
    if (!reader) throw TextureError(source + ": " + failure);
    return reader;
}

}  // namespace tessera::texture
