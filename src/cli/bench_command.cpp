#include "cli/bench_command.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <system_error>
#include <vector>

#include <sys/resource.h>

#include "cli/frame_options.hpp"
#include "cli/output_paths.hpp"
#include "cli/usage.hpp"
#include "profile/frame_profile_output.hpp"
#include "scene/scene_validation.hpp"
#include "tessera/image_io.hpp"
#include "tessera/scene.hpp"

namespace tessera::cli {

namespace {

struct Summary {
    double median = 0, min = 0, max = 0;
};

// The process's peak resident memory so far, in MiB.
double peak_rss_mib() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return double(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

Summary summarize(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    const double median = n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
    return {median, values.front(), values.back()};
}

}  // namespace

int run_bench(const BenchCommand& cmd) {
    // Refused now, not after the timed frames.
    try {
        std::error_code ignored;
        if (!std::filesystem::is_directory(cmd.scene_path, ignored)) check_scene_file_extension(cmd.scene_path);
    } catch (const SceneError& e) {
        throw UsageError(e.what());
    }
    if (!cmd.trace_path.empty()) check_writable_file(cmd.trace_path, "the --trace file");
    if (!cmd.heatmap_path.empty()) check_writable_file(cmd.heatmap_path, "the --heatmap image");
    Scene scene = load_scene_file(cmd.scene_path);
    apply_lighting_options(cmd.lighting, cmd.scene_path, scene);
    if (cmd.width > 0) scene.width = cmd.width;
    if (cmd.height > 0) scene.height = cmd.height;
    if (cmd.msaa > 0) scene.msaa = cmd.msaa;
    if (cmd.cull_back_faces)
        for (Material& material : scene.materials) material.double_sided = false;
    RenderSettings settings = cmd.settings;
    settings.keep_radiance = cmd.keep_radiance;
    const bool profiling = !cmd.trace_path.empty() || !cmd.heatmap_path.empty();
    const profile::HeatmapMetric heatmap_metric = profile::parse_heatmap_metric(cmd.heatmap_metric);
    settings.profile = profiling;
    Renderer renderer(settings);
    for (int i = 0; i < cmd.warmup; ++i) renderer.render(scene);

    // Per-frame samples of each figure; medians are reported.
    struct Series {
        const char* name;
        double FrameStats::*field;
        std::vector<double> samples;
    };
    std::vector<Series> stages{{"vertex", &FrameStats::vertex_ms, {}},
                               {"clip_setup", &FrameStats::clip_setup_ms, {}},
                               {"binning", &FrameStats::binning_ms, {}},
                               {"rasterize", &FrameStats::rasterize_ms, {}},
                               {"shade", &FrameStats::shade_ms, {}},
                               {"resolve", &FrameStats::resolve_ms, {}},
                               {"triangles", &FrameStats::triangles_ms, {}},
                               {"tiles", &FrameStats::tiles_ms, {}},
                               {"shadows", &FrameStats::shadow_ms, {}}};
    std::vector<double> total;
    total.reserve(std::size_t(cmd.frames));
    std::vector<profile::TracedFrame> traced;  // with --trace/--heatmap: every timed frame's timeline
    if (profiling) traced.reserve(std::size_t(cmd.frames));
    const auto run_start = std::chrono::steady_clock::now();
    for (Series& stage : stages) stage.samples.reserve(std::size_t(cmd.frames));
    // Steady state allocates nothing: the peak after warm-up must not grow.
    const double rss_after_warmup = peak_rss_mib();
    for (int i = 0; i < cmd.frames; ++i) {
        const auto frame_start = std::chrono::steady_clock::now();
        renderer.render(scene);
        if (profiling)
            traced.push_back({std::chrono::duration<double, std::milli>(frame_start - run_start).count(),
                              renderer.last_frame_profile()});
        const FrameStats& s = renderer.last_frame_stats();
        total.push_back(s.total_ms);
        for (Series& stage : stages) stage.samples.push_back(s.*stage.field);
    }
    const double rss_peak = peak_rss_mib();
    if (!cmd.trace_path.empty()) profile::write_chrome_trace(traced, "tessera bench " + cmd.scene_path, cmd.trace_path);
    if (!cmd.heatmap_path.empty()) {
        const RenderedImage& last = renderer.render(scene);  // the picture under the tint (not timed)
        write_image(profile::make_tile_heatmap(last, traced, heatmap_metric), cmd.heatmap_path);
    }
    const FrameStats& s = renderer.last_frame_stats();  // counts are the same every frame
    const Summary frame = summarize(total);
    const double fragment_lights = double(std::max<std::uint64_t>(s.fragment_lights, 1));  // after light culling
    const double mfrag_per_s = double(s.fragments_shaded) / (frame.median * 1e3);
    // Shading time (interpolation included) per fragment and light shaded, on one thread.
    const auto shade_stage = std::find_if(stages.begin(), stages.end(),
                                          [](const Series& stage) { return stage.field == &FrameStats::shade_ms; });
    const double shade_median = summarize(shade_stage->samples).median;
    const double ns_per_fragment_light = shade_median * 1e6 * renderer.threads() / fragment_lights;

    if (cmd.json) {
        std::printf("{\"scene\": \"%s\", \"width\": %d, \"height\": %d, \"msaa\": %d, \"threads\": %d, \"isa\": \"%s\", "
                    "\"tile_size\": %d, \"frames\": %d, \"frame_ms_median\": %.3f, \"frame_ms_min\": %.3f, "
                    "\"frame_ms_max\": %.3f, \"stages_ms\": {",
                    cmd.scene_path.c_str(), scene.width, scene.height, scene.msaa, renderer.threads(),
                    renderer.isa_name().c_str(), cmd.settings.tile_size, cmd.frames, frame.median, frame.min, frame.max);
        for (std::size_t i = 0; i < stages.size(); ++i)
            std::printf("%s\"%s\": %.3f", i ? ", " : "", stages[i].name, summarize(stages[i].samples).median);
        std::printf("}, \"triangles\": %llu, \"triangles_binned\": %llu, \"fragments_rasterized\": %llu, "
                    "\"fragments_shaded\": %llu, \"lights\": %zu, \"fragment_lights\": %llu, \"mfragments_per_s\": %.2f, "
                    "\"ns_per_fragment_light\": %.3f, \"shadow_maps_drawn\": %u, \"shadow_maps_kept\": %u, "
                    "\"shadow_lookups_settled\": %llu, \"shadow_lookups_facing_away\": %llu, \"shadow_lookups_tapped\": %llu, "
                    "\"peak_rss_mib\": %.1f, \"rss_growth_mib\": %.1f}\n",
                    (unsigned long long)s.triangles_in, (unsigned long long)s.triangles_binned,
                    (unsigned long long)s.fragments_rasterized, (unsigned long long)s.fragments_shaded,
                    scene.lights.size(), (unsigned long long)s.fragment_lights, mfrag_per_s, ns_per_fragment_light, s.shadow_maps_drawn, s.shadow_maps_kept,
                    (unsigned long long)s.shadow_lookups_settled, (unsigned long long)s.shadow_lookups_facing_away,
                    (unsigned long long)s.shadow_lookups_tapped, rss_peak,
                    rss_peak - rss_after_warmup);
        return 0;
    }
    std::printf("%s: %dx%d, msaa %d, %d threads, %s kernels, tile %d, %d frames after %d warm-up\n",
                cmd.scene_path.c_str(), scene.width, scene.height, scene.msaa, renderer.threads(),
                renderer.isa_name().c_str(), cmd.settings.tile_size, cmd.frames, cmd.warmup);
    std::printf("frame        median %8.2f ms   min %8.2f   max %8.2f\n", frame.median, frame.min, frame.max);
    std::printf("stage medians (steps within the triangle and tile passes: busy time over all workers / threads):\n");
    for (const Series& stage : stages)
        std::printf("  %-12s %8.2f ms\n", stage.name, summarize(stage.samples).median);
    std::printf("triangles in %llu, binned %llu; fragments rasterized %llu, shaded %llu; %zu lights\n",
                (unsigned long long)s.triangles_in, (unsigned long long)s.triangles_binned,
                (unsigned long long)s.fragments_rasterized, (unsigned long long)s.fragments_shaded, scene.lights.size());
    std::printf("fragment-lights shaded %llu (%.1f lights per fragment after culling)\n",
                (unsigned long long)s.fragment_lights,
                double(s.fragment_lights) / double(std::max<std::uint64_t>(s.fragments_shaded, 1)));
    std::printf("%.1f Mfragments/s shaded; %.2f ns per fragment-light (shading step, one thread)\n", mfrag_per_s,
                ns_per_fragment_light);
    if (s.shadow_maps_drawn + s.shadow_maps_kept > 0)
        std::printf("shadow maps in the last frame: %u drawn, %u kept from the frame before "
                    "(TESSERA_NO_SHADOW_CACHE=1 draws them all)\n",
                    s.shadow_maps_drawn, s.shadow_maps_kept);
    if (const std::uint64_t lookups = s.shadow_lookups_settled + s.shadow_lookups_facing_away + s.shadow_lookups_tapped;
        lookups > 0)
        std::printf("point-light shadow lookups %llu: %.1f%% settled by the block summaries, %.1f%% facing away, "
                    "%.1f%% with every tap\n",
                    (unsigned long long)lookups, 100.0 * double(s.shadow_lookups_settled) / double(lookups),
                    100.0 * double(s.shadow_lookups_facing_away) / double(lookups),
                    100.0 * double(s.shadow_lookups_tapped) / double(lookups));
    std::printf("peak memory %.1f MiB; growth over the timed frames %.1f MiB\n", rss_peak, rss_peak - rss_after_warmup);
    if (!cmd.trace_path.empty())
        std::printf("trace of the %d timed frames: %s (open it in Perfetto or chrome://tracing)\n", cmd.frames,
                    cmd.trace_path.c_str());
    if (!cmd.heatmap_path.empty())
        std::printf("heat map of tile %s: %s (ramp from 0 to %g)\n",
                    heatmap_metric == profile::HeatmapMetric::time ? "time, ms" : "work, fragment-lights",
                    cmd.heatmap_path.c_str(), profile::heatmap_ramp_end(traced, heatmap_metric));
    return 0;
}

}  // namespace tessera::cli
