// tessera: the command line. Parses arguments, runs the pipeline, and turns
// every error into one line on stderr and a non-zero exit status.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/bench_command.hpp"
#include "tessera/image_io.hpp"
#include "tessera/renderer.hpp"
#include "tessera/scene.hpp"

namespace {

struct RenderCommand {
    std::string scene_path;
    std::vector<std::string> outputs;
    int width = 0;   // 0: the scene's own
    int height = 0;
    bool stats = false;
    tessera::RenderSettings settings;
};

int run_render(const RenderCommand& cmd) {
    for (const std::string& out : cmd.outputs)
        if (!tessera::is_supported_image_path(out))
            throw tessera::ImageError(out + ": unsupported output format (expected .png or .exr)");

    tessera::Scene scene = tessera::load_scene_file(cmd.scene_path);
    if (cmd.width > 0) scene.width = cmd.width;
    if (cmd.height > 0) scene.height = cmd.height;

    tessera::Renderer renderer(cmd.settings);
    const tessera::RenderedImage& image = renderer.render(scene);  // once, whatever the number of outputs
    for (const std::string& out : cmd.outputs) tessera::write_image(image, out);

    if (cmd.stats) {
        const tessera::FrameStats& s = renderer.last_frame_stats();
        std::printf("%dx%d, %d threads, %s kernels: %.2f ms (vertex %.2f, clip+setup %.2f, binning %.2f, tiles %.2f)\n",
                    image.width, image.height, renderer.threads(), renderer.isa_name().c_str(), s.total_ms, s.vertex_ms,
                    s.clip_setup_ms, s.binning_ms, s.tiles_ms);
        std::printf("triangles in %llu, binned %llu; fragments rasterized %llu, shaded %llu\n",
                    (unsigned long long)s.triangles_in, (unsigned long long)s.triangles_binned,
                    (unsigned long long)s.fragments_rasterized, (unsigned long long)s.fragments_shaded);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Tessera: a multithreaded SIMD CPU rasterizer with a PBR fragment stage", "tessera"};
    app.set_version_flag("--version", "tessera " TESSERA_VERSION);
    app.require_subcommand(1);

    RenderCommand render;
    CLI::App* render_app = app.add_subcommand("render", "Render a scene file to one or more images");
    render_app->add_option("scene", render.scene_path, "Scene file (TOML)")->required();
    render_app->add_option("-o,--output", render.outputs,
                           "Output image; .png is display-referred 8-bit, .exr is scene-linear HDR (repeatable: one "
                           "render, several files)")
        ->required();
    render_app->add_option("--width", render.width, "Override the scene's image width in pixels")
        ->check(CLI::Range(1, tessera::kMaxImageDimension));
    render_app->add_option("--height", render.height, "Override the scene's image height in pixels")
        ->check(CLI::Range(1, tessera::kMaxImageDimension));
    render_app->add_option("--threads", render.settings.threads, "Worker threads (0 = one per hardware thread)")
        ->check(CLI::Range(0, 1024));
    render_app->add_option("--tile-size", render.settings.tile_size, "Screen tile side in pixels (power of two, 8-256)");
    render_app->add_option("--isa", render.settings.isa, "Shading kernels: auto, scalar, sse4, avx2, avx512");
    render_app->add_flag("--stats", render.stats, "Print triangle and fragment counts and time per stage");

    tessera::cli::BenchCommand bench;
    CLI::App* bench_app = app.add_subcommand("bench", "Render a scene many times and report time per stage");
    bench_app->add_option("scene", bench.scene_path, "Scene file (TOML)")->required();
    bench_app->add_option("--frames", bench.frames, "Frames to time")->check(CLI::Range(1, 100000));
    bench_app->add_option("--warmup", bench.warmup, "Frames rendered before timing")->check(CLI::Range(0, 100000));
    bench_app->add_option("--width", bench.width, "Override the scene's image width")
        ->check(CLI::Range(1, tessera::kMaxImageDimension));
    bench_app->add_option("--height", bench.height, "Override the scene's image height")
        ->check(CLI::Range(1, tessera::kMaxImageDimension));
    bench_app->add_option("--threads", bench.settings.threads, "Worker threads (0 = one per hardware thread)")
        ->check(CLI::Range(0, 1024));
    bench_app->add_option("--tile-size", bench.settings.tile_size, "Screen tile side in pixels");
    bench_app->add_option("--isa", bench.settings.isa, "Shading kernels: auto, scalar, sse4, avx2, avx512");
    bench_app->add_flag("--json", bench.json, "Print one JSON object");

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }
    try {
        if (*render_app) return run_render(render);
        if (*bench_app) return tessera::cli::run_bench(bench);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tessera: error: %s\n", e.what());
        return 1;
    }
    return 1;
}
