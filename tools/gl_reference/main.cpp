// tessera_gl_reference: renders a scene file with the OpenGL peer renderer (Mesa
// llvmpipe through EGL surfaceless) and times it, for comparing with `tessera bench`.
// llvmpipe's thread count comes from the environment: LP_NUM_THREADS.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "gl_renderer.hpp"
#include "tessera/image_io.hpp"
#include "tessera/scene.hpp"

namespace {

struct Options {
    std::string scene_path;
    std::string output;  // empty: no image
    int width = 0;       // 0: the scene's own
    int height = 0;
    int msaa = 0;        // 0: the scene's own
    bool cull_back_faces = false;  // every material single-sided (GL_CULL_FACE), as tessera bench's flag
    int frames = 30;
    int warmup = 3;
    bool json = false;
    tessera::gl_reference::IblOptions ibl;  // the defaults: Tessera's documented departures
    tessera::gl_reference::ShadowOptions shadows;  // the default: float depth maps, as Tessera's
};

struct Summary {
    double median = 0, min = 0, max = 0;
};

Summary summarize(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    const double median = n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
    return {median, values.front(), values.back()};
}

std::string json_escape(const std::string& s) {
    std::string out;
    for (const char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out;
}

int run(const Options& opt) {
    // PNG only: the reference shader yields display values, not the radiance an .exr holds.
    if (!opt.output.empty() && std::filesystem::path(opt.output).extension() != ".png")
        throw tessera::ImageError(opt.output + ": unsupported output format (expected .png)");
    tessera::Scene scene = tessera::load_scene_file(opt.scene_path);
    if (opt.width > 0) scene.width = opt.width;
    if (opt.height > 0) scene.height = opt.height;
    if (opt.msaa > 0) scene.msaa = opt.msaa;
    if (opt.cull_back_faces)
        for (tessera::Material& material : scene.materials) material.double_sided = false;

    tessera::gl_reference::GlReferenceRenderer renderer;
    renderer.set_ibl_options(opt.ibl);
    renderer.set_shadow_options(opt.shadows);
    if (!opt.output.empty()) tessera::write_image(renderer.render(scene), opt.output);

    const char* lp_env = std::getenv("LP_NUM_THREADS");
    const int lp_threads = lp_env ? std::atoi(lp_env) : -1;  // -1: unset, llvmpipe's default (one per CPU)
    if (opt.frames == 0) return 0;
    const Summary s = summarize(renderer.time_frames(scene, opt.frames, opt.warmup));
    if (opt.json) {
        std::printf(
            "{\"scene\": \"%s\", \"renderer\": \"%s\", \"gl_version\": \"%s\", \"width\": %d, \"height\": %d, "
            "\"msaa\": %d, \"lp_num_threads\": %s, \"frames\": %d, \"frame_ms_median\": %.3f, \"frame_ms_min\": %.3f, "
            "\"frame_ms_max\": %.3f}\n",
            json_escape(opt.scene_path).c_str(), json_escape(renderer.renderer_name()).c_str(),
            json_escape(renderer.version()).c_str(), scene.width, scene.height, scene.msaa,
            lp_threads < 0 ? "null" : std::to_string(lp_threads).c_str(), opt.frames, s.median,
            s.min, s.max);
        return 0;
    }
    std::printf("%s: %dx%d, msaa %d, %s, LP_NUM_THREADS=%s, %d frames after %d warm-up\n",
                opt.scene_path.c_str(), scene.width, scene.height, scene.msaa, renderer.renderer_name().c_str(),
                lp_threads < 0 ? "(unset)" : std::to_string(lp_threads).c_str(), opt.frames, opt.warmup);
    std::printf("frame      median %8.2f ms   min %8.2f   max %8.2f\n", s.median, s.min, s.max);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Renders a Tessera scene file with OpenGL 3.3 on Mesa llvmpipe (EGL surfaceless) and times it",
                 "tessera_gl_reference"};
    Options opt;
    app.add_option("scene", opt.scene_path, "Scene file (TOML)")->required();
    app.add_option("-o,--output", opt.output, "Write the rendered image (.png: display-referred 8-bit)");
    app.add_option("--width", opt.width, "Override the scene's image width in pixels")
        ->check(CLI::Range(1, tessera::kMaxImageDimension));
    app.add_option("--height", opt.height, "Override the scene's image height in pixels")
        ->check(CLI::Range(1, tessera::kMaxImageDimension));
    app.add_option("--msaa", opt.msaa, "Samples per pixel, 1 or 4 (overrides the scene's output.msaa)")
        ->check(CLI::IsMember({1, 4}));
    app.add_flag("--cull-back-faces", opt.cull_back_faces,
                 "Draw every material single-sided: back faces culled (GL_CULL_FACE), as Material::double_sided = false");
    app.add_option("--frames", opt.frames, "Frames to time (0: only render the image)")->check(CLI::Range(0, 100000));
    app.add_option("--warmup", opt.warmup, "Frames rendered before timing")->check(CLI::Range(0, 100000));
    app.add_flag("--json", opt.json, "Print one JSON object");
    app.add_flag("--ibl-half-float", opt.ibl.half_float_storage,
                 "Environment maps in the chapter's RGB16F/RG16F (default RGB32F/RG32F, as Tessera keeps them)");
    app.add_flag("--ibl-irradiance-lod-from-derivatives", opt.ibl.irradiance_lod_from_derivatives,
                 "The chapter's texture() in the irradiance convolution (default textureLod(..., 4.0), as Tessera)");
    app.add_flag("--shadow-chapter-depth-format", opt.shadows.chapter_depth_format,
                 "Shadow maps in the chapters' unsized GL_DEPTH_COMPONENT (default GL_DEPTH_COMPONENT32F, as Tessera's float)");
    app.footer("Threads: llvmpipe reads LP_NUM_THREADS from the environment. With 4x MSAA a timed frame\n"
               "includes the resolve blit (clear + draws + resolve + glFinish).");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }
    try {
        return run(opt);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tessera_gl_reference: error: %s\n", e.what());
        return 1;
    }
}
