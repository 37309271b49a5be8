#include "cli/frame_options.hpp"

#include "tessera/scene.hpp"

namespace tessera::cli {

void add_frame_options(CLI::App* command, int& width, int& height, int& msaa, RenderSettings& settings) {
    command->add_option("--msaa", msaa, "Samples per pixel, 1 or 4 (overrides the scene's output.msaa)")
        ->check(CLI::IsMember({1, 4}));
    command->add_option("--width", width, "Override the scene's image width in pixels")
        ->check(CLI::Range(1, tessera::kMaxImageDimension));
    command->add_option("--height", height, "Override the scene's image height in pixels")
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
