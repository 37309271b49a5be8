// What a person looks at to see where a frame's time goes: a Chrome trace-event
// file (open it in Perfetto or chrome://tracing) and a heat map of the tiles' cost.
// Both read the timelines the renderer records with RenderSettings::profile.
#pragma once

#include <filesystem>
#include <span>
#include <string>

#include "tessera/renderer.hpp"

namespace tessera::profile {

// A recorded frame and when it began, in milliseconds from the start of the run.
struct TracedFrame {
    double start_ms = 0;
    FrameProfile profile;
};

// Writes the frames as one trace: a "frame" track with a span per frame and, inside
// it, one per pass; then one track per worker thread with a span per chunk and per tile
// (name, triangles, fragments, lights in its args), each tile holding its rasterize,
// shade and resolve steps. Timestamps are microseconds. Written to a temporary name and
// renamed; throws std::runtime_error naming the path when it cannot be written.
void write_chrome_trace(std::span<const TracedFrame> frames, const std::string& title,
                        const std::filesystem::path& path);

// What a tile's tint measures.
enum class HeatmapMetric {
    time,  // milliseconds per tile (rasterize + shade + resolve), the median over the frames
    work,  // fragments shaded × lights shaded per tile: the shading work, independent of timing
};
HeatmapMetric parse_heatmap_metric(const std::string& name);  // "time" | "work"; throws std::invalid_argument

// The frame in grey, each tile tinted by its cost on a colour ramp from 0 to
// heatmap_ramp_end, with a legend strip below it: the ramp and, where a font is found, its scale.
// The cost of each tile is the median over `frames` (all of one scene at one size).
// Returns the picture as an 8-bit display image, ready for tessera::write_image.
RenderedImage make_tile_heatmap(const RenderedImage& frame, std::span<const TracedFrame> frames,
                                HeatmapMetric metric);

// The tile cost where make_tile_heatmap's ramp ends (ms or fragment·lights): the busiest
// tile's work, or the 98th percentile of tile times (costlier tiles show at the ramp's end).
double heatmap_ramp_end(std::span<const TracedFrame> frames, HeatmapMetric metric);

}  // namespace tessera::profile
