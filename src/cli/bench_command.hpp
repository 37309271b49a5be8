// tessera bench: renders one scene many times in one process and reports
// where a frame's time goes.
#pragma once

#include <string>

#include "cli/frame_options.hpp"
#include "tessera/renderer.hpp"

namespace tessera::cli {

struct BenchCommand {
    std::string scene_path;
    int frames = 30;
    int warmup = 3;
    int width = 0;  // 0: the scene's own
    int height = 0;
    int msaa = 0;  // 0: the scene's own
    bool cull_back_faces = false;  // every material single-sided, for racing llvmpipe with GL_CULL_FACE
    bool json = false;
    bool keep_radiance = false;  // like a render to PNG; --radiance adds the EXR's HDR image
    std::string trace_path;      // Chrome trace-event JSON of the timed frames, if set
    std::string heatmap_path;    // PNG of the tiles' cost over the last frame, if set
    std::string heatmap_metric = "time";  // time | work
    RenderSettings settings;
    LightingOptions lighting;
};

int run_bench(const BenchCommand& cmd);

}  // namespace tessera::cli
