// tessera: the command line. Parses arguments, runs the pipeline, and turns
// every error into one line on stderr and a non-zero exit status.
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/bench_command.hpp"
#include "cli/load_stats.hpp"
#include "scene/model_cache.hpp"
#include "scene/scene_validation.hpp"
#include "tessera/image_io.hpp"
#include "tessera/renderer.hpp"
#include "tessera/scene.hpp"

namespace {

constexpr std::string_view kScenePlaceholder = "{scene}";

struct RenderCommand {
    std::vector<std::string> scene_paths;
    std::vector<std::string> outputs;  // may hold {scene}, replaced by each scene file's stem
    int width = 0;                     // 0: the scene's own
    int height = 0;
    int msaa = 0;                      // 0: the scene's own
    bool stats = false;
    std::vector<std::string> aov_lists;  // each "depth,normal,..." as given to --aov
    tessera::RenderSettings settings;
};

// `pattern` with every {scene} replaced by the scene file's stem.
std::string output_path_for(std::string pattern, const std::string& scene_path) {
    const std::string stem = std::filesystem::path(scene_path).stem().string();
    for (std::size_t at = pattern.find(kScenePlaceholder); at != std::string::npos;
         at = pattern.find(kScenePlaceholder, at + stem.size())) {
        pattern.replace(at, kScenePlaceholder.size(), stem);
    }
    return pattern;
}

bool is_exr_path(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".exr";
}

// Mistakes in the command itself, found before any scene is rendered.
void check_render_command(const RenderCommand& cmd) {
    for (const std::string& out : cmd.outputs)
        if (!tessera::is_supported_image_path(out))
            throw tessera::ImageError(out + ": unsupported output format (expected .png or .exr)");
    if (!cmd.aov_lists.empty() && std::none_of(cmd.outputs.begin(), cmd.outputs.end(), is_exr_path))
        throw std::invalid_argument("--aov needs an .exr output: PNG holds only the display image");
    if (cmd.scene_paths.size() < 2) return;
    for (const std::string& out : cmd.outputs) {
        if (out.find(kScenePlaceholder) == std::string::npos)
            throw std::invalid_argument("with several scenes every -o must contain {scene} (the scene file's stem), "
                                        "got '" + out + "'");
    }
    std::set<std::string> stems;
    for (const std::string& path : cmd.scene_paths) {
        const std::string stem = std::filesystem::path(path).stem().string();
        if (!stems.insert(stem).second)
            throw std::invalid_argument("two scene files have the stem '" + stem +
                                        "': their outputs would overwrite each other");
    }
}

void print_stats(const tessera::Renderer& renderer, const tessera::RenderedImage& image) {
    const tessera::FrameStats& s = renderer.last_frame_stats();
    std::printf("%dx%d, %d threads, %s kernels: %.2f ms (vertex %.2f, triangles %.2f, tiles %.2f)\n", image.width,
                image.height, renderer.threads(), renderer.isa_name().c_str(), s.total_ms, s.vertex_ms, s.triangles_ms,
                s.tiles_ms);
    std::printf("triangles in %llu, binned %llu; fragments rasterized %llu, shaded %llu\n",
                (unsigned long long)s.triangles_in, (unsigned long long)s.triangles_binned,
                (unsigned long long)s.fragments_rasterized, (unsigned long long)s.fragments_shaded);
}

// Renders one scene to every output; throws on the first error before the
// render, and after it tries every output and throws if any write failed.
// Models come from `models`; after loading the last scene they are dropped
// (the scene holds what it uses), so its frame does not pay for them.
void render_scene(const RenderCommand& cmd, const std::string& scene_path, tessera::Renderer& renderer,
                  tessera::ModelCache& models, bool last_scene) {
    const tessera::cli::LoadCounters counters_before = tessera::cli::read_load_counters();
    tessera::cli::SceneWallTimes wall;
    auto start = std::chrono::steady_clock::now();
    tessera::Scene scene = tessera::load_scene_file(scene_path, models);
    if (last_scene) models.clear();
    wall.load_ms = tessera::cli::milliseconds_since(start);
    if (cmd.width > 0) scene.width = cmd.width;
    if (cmd.height > 0) scene.height = cmd.height;
    if (cmd.msaa > 0) scene.msaa = cmd.msaa;
    if ((cmd.width > 0 || cmd.height > 0) &&
        static_cast<long long>(scene.width) * scene.height > tessera::kMaxImagePixels) {
        throw std::invalid_argument(scene_path + ": image size " + std::to_string(scene.width) + "x" +
                                    std::to_string(scene.height) + " (after --width/--height) is " +
                                    std::to_string(static_cast<long long>(scene.width) * scene.height) +
                                    " pixels; at most " + std::to_string(tessera::kMaxImagePixels) + " are allowed");
    }
    tessera::validate_scene(scene);  // the renderer trusts its input

    start = std::chrono::steady_clock::now();
    const tessera::RenderedImage& image = renderer.render(scene);  // once, whatever the number of outputs
    wall.render_ms = tessera::cli::milliseconds_since(start);
    start = std::chrono::steady_clock::now();
    std::string pending_error;
    for (const std::string& pattern : cmd.outputs) {
        try {
            tessera::write_image(image, output_path_for(pattern, scene_path));
        } catch (const std::exception& e) {
            if (!pending_error.empty()) std::fprintf(stderr, "tessera: error: %s\n", pending_error.c_str());
            pending_error = e.what();
        }
    }
    wall.encode_ms = tessera::cli::milliseconds_since(start);
    if (!pending_error.empty()) throw tessera::ImageError(pending_error);
    if (cmd.stats) {
        print_stats(renderer, image);
        tessera::cli::print_load_stats(counters_before, tessera::cli::read_load_counters(), wall);
    }
}

// One failing scene does not stop the others; the exit status says whether any failed.
int run_render(const RenderCommand& cmd) {
    check_render_command(cmd);
    tessera::RenderSettings settings = cmd.settings;
    // The HDR radiance image costs memory bandwidth: keep it only for EXR output.
    settings.keep_radiance = std::any_of(cmd.outputs.begin(), cmd.outputs.end(), is_exr_path);
    for (const std::string& list : cmd.aov_lists) tessera::parse_aov_list(list, settings.aovs);
    tessera::Renderer renderer(settings);  // one renderer: its frame memory is reused from scene to scene
    tessera::ModelCache models;            // a model several scenes place is loaded once
    std::vector<std::string> failed;
    for (const std::string& scene_path : cmd.scene_paths) {
        try {
            render_scene(cmd, scene_path, renderer, models, &scene_path == &cmd.scene_paths.back());
        } catch (const std::exception& e) {
            std::fprintf(stderr, "tessera: error: %s\n", e.what());
            failed.push_back(scene_path);
        }
    }
    if (cmd.scene_paths.size() > 1) {
        const std::size_t rendered = cmd.scene_paths.size() - failed.size();
        std::string summary = "rendered " + std::to_string(rendered) + " of " +
                              std::to_string(cmd.scene_paths.size()) + " scenes";
        for (std::size_t i = 0; i < failed.size(); ++i) summary += (i == 0 ? "; failed: " : ", ") + failed[i];
        std::fprintf(failed.empty() ? stdout : stderr, "%s%s\n", failed.empty() ? "" : "tessera: error: ",
                     summary.c_str());
    }
    return failed.empty() ? 0 : 1;
}

// The options render and bench share: output size and how the renderer runs.
void add_frame_options(CLI::App* command, int& width, int& height, int& msaa, tessera::RenderSettings& settings) {
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
        "Shade every light in every tile, ranges or not (to compare with the culled image)");
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Tessera: a multithreaded SIMD CPU rasterizer with a PBR fragment stage", "tessera"};
    app.set_version_flag("--version", "tessera " TESSERA_VERSION);
    app.require_subcommand(1);

    RenderCommand render;
    CLI::App* render_app = app.add_subcommand("render", "Render scene files to one or more images each");
    render_app->add_option("scene", render.scene_paths, "Scene files (TOML); one failing does not stop the others")
        ->required();
    render_app->add_option("-o,--output", render.outputs,
                           "Output image; .png is display-referred 8-bit, .exr is scene-linear HDR (repeatable: one "
                           "render, several files); {scene} stands for the scene file's stem and is required "
                           "with several scenes")
        ->required();
    render_app->add_option("--aov", render.aov_lists,
                           "Add surface data to every .exr output, a comma-separated list of depth, normal, albedo, "
                           "roughness, metallic, position (channels Z, N.XYZ, albedo.RGB, roughness, metallic, P.XYZ)")
        ->allow_extra_args(false);  // one list per --aov: a scene file after it stays a scene
    add_frame_options(render_app, render.width, render.height, render.msaa, render.settings);
    render_app->add_flag("--stats", render.stats, "Print triangle and fragment counts and time per stage");

    tessera::cli::BenchCommand bench;
    CLI::App* bench_app = app.add_subcommand("bench", "Render a scene many times and report time per stage");
    bench_app->add_option("scene", bench.scene_path, "Scene file (TOML)")->required();
    bench_app->add_option("--frames", bench.frames, "Frames to time")->check(CLI::Range(1, 100000));
    bench_app->add_option("--warmup", bench.warmup, "Frames rendered before timing")->check(CLI::Range(0, 100000));
    add_frame_options(bench_app, bench.width, bench.height, bench.msaa, bench.settings);
    bench_app->add_flag("--json", bench.json, "Print one JSON object");
    bench_app->add_flag("--radiance", bench.keep_radiance, "Also keep the HDR radiance image, as a render to EXR does");
    bench_app->add_option("--trace", bench.trace_path,
                          "Write the timed frames as a Chrome trace-event JSON file (Perfetto, chrome://tracing): "
                          "a track per worker, a span per pass, chunk and tile");
    bench_app->add_option("--heatmap", bench.heatmap_path,
                          "Write a PNG of the frame with each tile tinted by its cost");
    bench_app->add_option("--heatmap-metric", bench.heatmap_metric,
                          "What the heat map shows: time (ms per tile, median of the timed frames) or work "
                          "(fragments x lights per tile)")
        ->check(CLI::IsMember({"time", "work"}));

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
