#include "cli/bench_command.hpp"

#include <algorithm>
#include <cstdio>
#include <vector>

#include "tessera/scene.hpp"

namespace tessera::cli {

namespace {

struct Summary {
    double median = 0, min = 0, max = 0;
};

Summary summarize(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    const double median = n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
    return {median, values.front(), values.back()};
}

}  // namespace

int run_bench(const BenchCommand& cmd) {
    Scene scene = load_scene_file(cmd.scene_path);
    if (cmd.width > 0) scene.width = cmd.width;
    if (cmd.height > 0) scene.height = cmd.height;
    Renderer renderer(cmd.settings);
    for (int i = 0; i < cmd.warmup; ++i) renderer.render(scene);

    std::vector<double> total, vertex, setup, tiles;
    for (int i = 0; i < cmd.frames; ++i) {
        renderer.render(scene);
        const FrameStats& s = renderer.last_frame_stats();
        total.push_back(s.total_ms);
        vertex.push_back(s.vertex_ms);
        setup.push_back(s.setup_and_binning_ms);
        tiles.push_back(s.tiles_ms);
    }
    const FrameStats& s = renderer.last_frame_stats();  // counts are the same every frame
    const Summary frame = summarize(total);
    const double v = summarize(vertex).median, sb = summarize(setup).median, t = summarize(tiles).median;
    const double mfrag_per_s = double(s.fragments_shaded) / (frame.median * 1e3);
    const double light_count = double(std::max<std::size_t>(scene.lights.size(), 1));
    // Wall-clock tile time over shaded fragment·lights: an upper bound on the shading cost.
    const double ns_per_fragment_light = t * 1e6 / (double(std::max<std::uint64_t>(s.fragments_shaded, 1)) * light_count);

    if (cmd.json) {
        std::printf(
            "{\"scene\": \"%s\", \"width\": %d, \"height\": %d, \"threads\": %d, \"isa\": \"%s\", "
            "\"tile_size\": %d, \"frames\": %d, \"frame_ms_median\": %.3f, \"frame_ms_min\": %.3f, "
            "\"frame_ms_max\": %.3f, \"stages_ms\": {\"vertex\": %.3f, \"setup_and_binning\": %.3f, \"tiles\": %.3f}, "
            "\"triangles\": %llu, \"triangles_binned\": %llu, \"fragments_rasterized\": %llu, "
            "\"fragments_shaded\": %llu, \"lights\": %zu, \"mfragments_per_s\": %.2f, "
            "\"ns_per_fragment_light\": %.3f}\n",
            cmd.scene_path.c_str(), scene.width, scene.height, renderer.threads(), renderer.isa_name().c_str(),
            cmd.settings.tile_size, cmd.frames, frame.median, frame.min, frame.max, v, sb, t,
            (unsigned long long)s.triangles_in, (unsigned long long)s.triangles_binned,
            (unsigned long long)s.fragments_rasterized, (unsigned long long)s.fragments_shaded, scene.lights.size(),
            mfrag_per_s, ns_per_fragment_light);
        return 0;
    }
    std::printf("%s: %dx%d, %d threads, %s kernels, tile %d, %d frames after %d warm-up\n", cmd.scene_path.c_str(),
                scene.width, scene.height, renderer.threads(), renderer.isa_name().c_str(), cmd.settings.tile_size,
                cmd.frames, cmd.warmup);
    std::printf("frame      median %8.2f ms   min %8.2f   max %8.2f\n", frame.median, frame.min, frame.max);
    std::printf("  vertex             %8.2f ms (median)\n", v);
    std::printf("  setup + binning    %8.2f ms\n", sb);
    std::printf("  tiles              %8.2f ms (rasterize, shade, resolve)\n", t);
    std::printf("triangles in %llu, binned %llu; fragments rasterized %llu, shaded %llu\n",
                (unsigned long long)s.triangles_in, (unsigned long long)s.triangles_binned,
                (unsigned long long)s.fragments_rasterized, (unsigned long long)s.fragments_shaded);
    std::printf("%.1f Mfragments/s; %.2f ns per fragment-light (tile time / shaded fragment-lights)\n", mfrag_per_s,
                ns_per_fragment_light);
    return 0;
}

}  // namespace tessera::cli
