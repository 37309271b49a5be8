// tessera: the command line. Parses arguments, runs the pipeline, and turns
// every error into one line on stderr and a non-zero exit status.
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include <unistd.h>

#include "batch/batch_render.hpp"
#include "batch/frames.hpp"
#include "batch/shard.hpp"
#include "cli/frame_options.hpp"
#include "cli/load_stats.hpp"
#include "cli/cli_docs.hpp"
#include "cli/output_paths.hpp"
#include "cli/usage.hpp"
#include "cli/tools_exec.hpp"
#include "io/memory_budget.hpp"
#include "scene/gltf/gltf_import.hpp"
#include "scene/model_cache.hpp"
#include "scene/scene_validation.hpp"
#include "tessera/animation.hpp"
#include "tessera/image_io.hpp"
#include "tessera/renderer.hpp"
#include "tessera/scene.hpp"

namespace {

struct RenderCommand {
    std::vector<std::string> scene_paths;
    std::vector<std::string> outputs;  // may hold {scene} and {frame} (src/batch/frames.hpp)
    tessera::cli::LightingOptions lighting;
    int width = 0;                     // 0: the scene's own
    int height = 0;
    int msaa = 0;                      // 0: the scene's own
    std::string camera;                // --camera NAME|INDEX of a glTF file; empty: its first
    std::optional<std::string> time;   // --time SECONDS: glTF models' animations sampled then
    std::string animation;             // --animation NAME|INDEX of a glTF file; empty: its first
    bool stats = false;
    std::vector<std::string> aov_lists;  // each "depth,normal,..." as given to --aov
    tessera::RenderSettings settings;
    // Batch rendering (src/batch/): frame ranges, shards, resuming, records.
    std::optional<std::string> frames;  // --frames 0-239:2; unset = each scene as loaded (frame 0); "" is refused
    std::optional<std::string> shard;   // --shard I/N
    std::optional<int> shard_count;     // --shard-count N (Kubernetes Indexed Jobs)
    bool skip_existing = false;
    std::string log_path;
    bool serial_writes = false;
    std::string max_memory;             // --max-memory SIZE; "" = io::default_memory_budget()
    bool allow_external_uris = false;   // --allow-external-uris
};

bool is_exr_path(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".exr";
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

// --time SECONDS as a number; anything else is refused here, NaN and
// negative times by set_scene_time.
double parse_seconds(const std::string& text) {
    char* end = nullptr;
    const double seconds = text.empty() ? 0.0 : std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size())
        throw std::invalid_argument("--time '" + text + "': expected a number of seconds");
    return seconds;
}

// --time and --animation (glTF animations, docs/cli.md); --frames on
// a glTF file alone plays its animation at 24 fps.
void pose_for_render(const RenderCommand& cmd, const std::string& scene_path, tessera::Scene& scene) {
    const bool gltf = tessera::is_gltf_path(scene_path);
    if (!cmd.animation.empty() && !gltf)
        throw tessera::SceneError(scene_path + ": --animation selects a glTF file's animation; in a TOML scene "
                                  "each [[models]] entry chooses its own with 'animation'");
    if (cmd.time) {
        tessera::set_scene_time(scene, parse_seconds(*cmd.time), cmd.animation);
    } else if (cmd.frames && gltf) {
        tessera::play_gltf_animation(scene, cmd.animation);
    } else if (!cmd.animation.empty()) {
        throw tessera::SceneError(scene_path + ": --animation chooses what --time or --frames plays; give one of them");
    }
}

// A scene file with the command line's size overrides; the batch validates each frame.
// Models come from `models`; after loading the last scene they are dropped (the scene
// holds what it uses), so its frames do not pay for them.
tessera::Scene load_for_render(const RenderCommand& cmd, const std::string& scene_path, tessera::ModelCache& models) {
    const tessera::cli::LoadCounters before = tessera::cli::read_load_counters();
    const auto start = std::chrono::steady_clock::now();
    tessera::Scene scene = tessera::load_scene_file(scene_path, models, cmd.camera);
    if (scene_path == cmd.scene_paths.back()) models.clear();
    pose_for_render(cmd, scene_path, scene);
    tessera::cli::apply_lighting_options(cmd.lighting, scene_path, scene);
    if (cmd.stats)
        tessera::cli::print_load_stats(before, tessera::cli::read_load_counters(),
                                       tessera::cli::milliseconds_since(start));
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
    return scene;
}

// Every folder -o names (with {scene} and {frame} expanded), created where
// missing, and checked to take new files: before the first frame renders.
void prepare_output_folders(const tessera::batch::BatchJob& job) {
    std::set<std::string> folders;
    const std::vector<int> frames = job.frames ? *job.frames : std::vector<int>{0};
    for (const std::string& pattern : job.outputs)
        for (const std::string& scene : job.scene_paths)
            for (const int frame : frames) {
                const std::string path = tessera::batch::expand_output_pattern(
                    pattern, std::filesystem::path(scene).stem().string(), frame);
                const std::string folder = std::filesystem::path(path).parent_path().string();
                if (folders.insert(folder).second) {  // each folder made and tried once
                    tessera::cli::create_parent_folders(path, "the output image");
                    tessera::cli::check_writable_file(path, "the output image");
                } else {
                    tessera::cli::check_not_folder(path, "the output image");
                }
            }
}

// The job as the command line describes it; anything wrong with it is a usage
// error (exit 2), found before any scene is loaded.
tessera::batch::BatchJob make_job(const RenderCommand& cmd) {
    using tessera::cli::UsageError;
    if (cmd.time && cmd.frames)
        throw UsageError("--time renders one moment and --frames a range of them; give one of the two");
    for (const std::string& scene : cmd.scene_paths) {
        std::error_code ignored;
        if (std::filesystem::is_directory(scene, ignored)) continue;  // "cannot open scene file", as the loader says
        try {
            tessera::check_scene_file_extension(scene);
        } catch (const tessera::SceneError& e) {
            throw UsageError(e.what());
        }
    }
    tessera::batch::BatchJob job;
    job.scene_paths = cmd.scene_paths;
    job.outputs = cmd.outputs;
    try {
        if (cmd.frames) job.frames = tessera::batch::parse_frame_ranges(*cmd.frames);
        job.shard = tessera::batch::choose_shard(cmd.shard, cmd.shard_count, tessera::batch::process_environment());
        tessera::batch::check_job(job);
    } catch (const std::exception& e) {  // a bad --frames, --shard or -o
        throw UsageError(e.what());
    }
    if (!cmd.aov_lists.empty() && std::none_of(cmd.outputs.begin(), cmd.outputs.end(), is_exr_path))
        throw UsageError("--aov needs an .exr output: PNG holds only the display image");
    prepare_output_folders(job);
    if (!cmd.log_path.empty()) tessera::cli::check_writable_file(cmd.log_path, "the --log file", true);
    return job;
}

// One failing scene does not stop the others; the exit status says whether any failed.
int run_render(const RenderCommand& cmd) {
    if (!cmd.max_memory.empty()) tessera::io::set_memory_budget(tessera::io::parse_byte_size(cmd.max_memory));
    tessera::set_external_uris_allowed(cmd.allow_external_uris);
    tessera::batch::BatchJob job = make_job(cmd);
    job.skip_existing = cmd.skip_existing;
    job.log_path = cmd.log_path;
    job.write_behind = !cmd.serial_writes;
    if (job.frames || job.shard.sharded())
        job.progress = isatty(fileno(stdout)) ? tessera::batch::ProgressDisplay::terminal
                                              : tessera::batch::ProgressDisplay::lines;
    tessera::ModelCache models;  // a model several scenes place is loaded once
    job.load_scene = [&cmd, &models](const std::string& path) { return load_for_render(cmd, path, models); };
    if (cmd.stats) job.after_frame = print_stats, job.after_write = tessera::cli::print_write_stats;

    tessera::RenderSettings settings = cmd.settings;
    // The HDR radiance image costs memory bandwidth: keep it only for EXR output.
    settings.keep_radiance = std::any_of(cmd.outputs.begin(), cmd.outputs.end(), is_exr_path);
    std::optional<tessera::Renderer> renderer;  // one renderer: its frame memory is reused from frame to frame
    try {
        for (const std::string& list : cmd.aov_lists) tessera::parse_aov_list(list, settings.aovs);
        renderer.emplace(settings);
    } catch (const std::invalid_argument& e) {  // an unknown --aov, --isa or a bad --tile-size
        throw tessera::cli::UsageError(e.what());
    }
    const tessera::batch::BatchResult result = tessera::batch::run_batch(job, *renderer, stdout, stderr);
    const std::vector<std::string>& failed = result.failed_scenes;
    if (job.skip_existing && result.frames_skipped > 0)
        std::printf("skipped %d frames already written; rendered %d\n", result.frames_skipped, result.frames_rendered);
    if (cmd.scene_paths.size() > 1) {
        const std::size_t attempted = std::size_t(result.scenes_with_work);
        const std::size_t rendered = attempted - failed.size();
        std::string summary = "rendered " + std::to_string(rendered) + " of " + std::to_string(attempted) + " scenes";
        for (std::size_t i = 0; i < failed.size(); ++i) summary += (i == 0 ? "; failed: " : ", ") + failed[i];
        std::fprintf(failed.empty() ? stdout : stderr, "%s%s\n", failed.empty() ? "" : "tessera: error: ",
                     summary.c_str());
    }
    return failed.empty() ? 0 : 1;
}

// Batch rendering: frame ranges of animated scenes, sharding, resuming (docs/batch.md).
void add_batch_options(CLI::App* command, RenderCommand& render) {
    command->add_option("--frames", render.frames,
                        "Frames of each scene's [animation] (or of a glTF file's animation, at 24 fps) to render: A-B[:STEP] (inclusive), comma-separated; "
                        "-o must then contain {frame} or {frame:0N}. Without it: frame 0");
    command->add_option("--shard", render.shard,
                        "Render only part I of N (1-based) of the frames and scenes; default: from "
                        "SLURM_ARRAY_TASK_ID/_MIN/_COUNT/_STEP, or JOB_COMPLETION_INDEX with --shard-count");
    command->add_option("--shard-count", render.shard_count, "The number of parts, N, for JOB_COMPLETION_INDEX");
    command->add_flag("--skip-existing", render.skip_existing,
                      "Do not render frames whose every output file exists (resume a pre-empted task)");
    command->add_option("--log", render.log_path,
                        "Append one JSON record per rendered frame to this file (scene, frame, file, ms, triangles, "
                        "fragments, ...)");
    command->add_flag("--serial-writes", render.serial_writes,
                      "Write each frame before rendering the next (by default the next frame renders while the "
                      "previous one is encoded: same files, one more image in memory)");
}

// Hostile input (docs/robustness.md): the memory budget and where glTF URIs may point.
void add_input_limit_options(CLI::App* command, RenderCommand& render) {
    command->add_option("--max-memory", render.max_memory,
                        "Memory budget for what one input may decode to (textures, a glTF model's meshes), e.g. 4G "
                        "or 512M, checked before allocating; default: half of physical memory, or "
                        "TESSERA_MAX_MEMORY");
    command->add_flag("--allow-external-uris", render.allow_external_uris,
                      "Let glTF buffer and image URIs name files outside the model's folder (absolute paths, ../, "
                      "symbolic links out); refused by default");
}

}  // namespace

int main(int argc, char** argv) {
    // `tessera check|bench|contact-sheet ...` run as they always did, in tessera-tools.
    if (argc > 1 && tessera::cli::is_tool_command(argv[1])) return tessera::cli::exec_tools(argc, argv);
    CLI::App app{"Tessera: a multithreaded SIMD CPU rasterizer with a PBR fragment stage", "tessera"};
    app.set_version_flag("--version", "tessera " TESSERA_VERSION);
    app.require_subcommand(1);
    app.option_defaults()->always_capture_default();  // every --help shows the defaults

    RenderCommand render;
    CLI::App* render_app = app.add_subcommand("render", "Render scene files to one or more images each");
    render_app->add_option("scene", render.scene_paths,
                           "Scene files: .toml scenes, or .gltf/.glb models rendered on their own (their camera "
                           "and lights); one failing does not stop the others")
        ->required();
    render_app->add_option("-o,--output", render.outputs,
                           "Output image; .png is display-referred 8-bit, .exr is scene-linear HDR (repeatable: one "
                           "render, several files); {scene} stands for the scene file's stem and is required "
                           "with several scenes; missing folders are created")
        ->required();
    render_app->add_option("--aov", render.aov_lists,
                           "Add surface data to every .exr output, a comma-separated list of depth, normal, albedo, "
                           "roughness, metallic, position, object_id, material_id, shadow (channels Z, N.XYZ, albedo.RGB, "
                           "roughness, metallic, P.XYZ, object_id, material_id: uint, 0 = background; shadow: mean light visibility)")
        ->allow_extra_args(false);  // one list per --aov: a scene file after it stays a scene
    tessera::cli::add_frame_options(render_app, render.width, render.height, render.msaa, render.settings);
    tessera::cli::add_lighting_options(render_app, render.lighting);
    render_app->add_flag("--stats", render.stats, "Print triangle and fragment counts and time per stage");
    add_batch_options(render_app, render);
    add_input_limit_options(render_app, render);
    render_app->add_option("--camera", render.camera,
                           "For glTF files: the camera to render from, by name or by index in the file's cameras "
                           "(default: the first perspective camera in the node tree)");
    render_app->add_option("--time", render.time,
                           "Pose glTF models at this many seconds into their animation (skins, morph weights, "
                           "nodes); default: their rest pose");
    render_app->add_option("--animation", render.animation,
                           "For glTF files: the animation --time or --frames plays, by name or index (default: the "
                           "first); --frames on a glTF file renders its animation at 24 fps");

    // Image analysis lives in tessera-tools beside this binary (it links
    // OpenImageIO, which renders do not need): main() execs it for these.
    for (const tessera::cli::ToolCommand& tool : tessera::cli::tool_commands())
        app.add_subcommand(tool.name, tool.description)->allow_extras()->prefix_command();

    tessera::cli::hide_empty_defaults(app);
    // Hidden: the bash completion and the man page, made from this definition at build time (cli_docs.hpp).
    if (argc > 1 && tessera::cli::is_docs_request(argv[1])) return tessera::cli::print_docs(app, argc, argv);

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return tessera::cli::report_parse_error(app, e, argc, argv);
    }
    try {
        if (*render_app) return run_render(render);
        for (const tessera::cli::ToolCommand& tool : tessera::cli::tool_commands())
            if (*app.get_subcommand(tool.name)) return tessera::cli::exec_tools(argc, argv);
    } catch (const tessera::cli::UsageError& e) {
        tessera::cli::print_error(e.what());
        return tessera::cli::kUsageExit;
    } catch (const std::exception& e) {
        tessera::cli::print_error(tessera::io::error_sentence(e));
        return 1;
    }
    return 1;
}
