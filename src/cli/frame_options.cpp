#include "cli/frame_options.hpp"

#include "cli/usage.hpp"
#include "tessera/scene.hpp"

namespace tessera::cli {

void add_frame_options(CLI::App* command, int& width, int& height, int& msaa, RenderSettings& settings) {
    // 0 (the scene's own) is no value a user can give: no "=0" in --help.
    no_default_shown(command->add_option("--msaa", msaa, "Samples per pixel, 1 or 4 (default: the scene's output.msaa)"))
        ->check(CLI::IsMember({1, 4}));
    no_default_shown(command->add_option("--width", width, "Image width in pixels (default: the scene's output.width)"))
        ->check(CLI::Range(1, tessera::kMaxImageDimension));
    no_default_shown(command->add_option("--height", height, "Image height in pixels (default: the scene's output.height)"))
        ->check(CLI::Range(1, tessera::kMaxImageDimension));
    command->add_option("--threads", settings.threads, "Worker threads (0 = one per hardware thread)")
        ->check(CLI::Range(0, 1024));
    command->add_option("--tile-size", settings.tile_size, "Screen tile side in pixels (power of two, 8-256)");
    command->add_option("--isa", settings.isa, "SIMD kernels: auto, scalar, sse4, avx2, avx512");
    command->add_flag_callback(
        "--no-light-culling", [&settings] { settings.light_culling = false; },
        "Ignore light ranges: shade every light at every pixel, as the reference shader does");
}

}  // namespace tessera::cli
