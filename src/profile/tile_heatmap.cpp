// Tile-cost heat maps: the frame in grey under a colour ramp of each tile's cost.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "profile/frame_profile_output.hpp"

namespace tessera::profile {

namespace {

double tile_cost(const ProfileSpan& tile, HeatmapMetric metric) {
    return metric == HeatmapMetric::time ? tile.end_ms - tile.start_ms : double(tile.fragment_lights);
}

// Per tile, the median cost over the frames (timings are noisy; work is the same every frame).
std::vector<double> median_tile_costs(std::span<const TracedFrame> frames, HeatmapMetric metric) {
    if (frames.empty()) throw std::invalid_argument("a heat map needs at least one recorded frame");
    const FrameProfile& first = frames.front().profile;
    const std::size_t tiles = std::size_t(first.tiles_x) * std::size_t(first.tiles_y);
    std::vector<std::vector<double>> samples(tiles);
    for (const TracedFrame& f : frames) {
        if (f.profile.tiles_x != first.tiles_x || f.profile.tiles_y != first.tiles_y)
            throw std::invalid_argument("the frames of a heat map must share one tile grid");
        for (const ProfileSpan& s : f.profile.spans)
            if (s.kind == ProfileSpan::Kind::tile) samples[std::size_t(s.index)].push_back(tile_cost(s, metric));
    }
    std::vector<double> costs(tiles, 0.0);
    for (std::size_t t = 0; t < tiles; ++t) {
        std::vector<double>& v = samples[t];
        if (v.empty()) continue;
        std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
        costs[t] = v[v.size() / 2];
    }
    return costs;
}

// OpenImageIO's text needs a font file; the legend keeps its ramp without one.
bool draw_label(OIIO::ImageBuf& image, int x, int y, const std::string& text, int size,
                OIIO::ImageBufAlgo::TextAlignX align) {
    const float white[3] = {1.0f, 1.0f, 1.0f};
    for (const char* font : {"", "DejaVuSans", "LiberationSans", "FreeSans"})
        if (OIIO::ImageBufAlgo::render_text(image, x, y, text, size, font, white, align)) return true;
    return false;
}

// Work ramps up to the busiest tile. Time ramps up to the 98th percentile: on a shared
// machine one pre-empted tile would otherwise take the whole ramp and leave the rest dark.
double ramp_end(std::vector<double> costs, HeatmapMetric metric) {
    if (costs.empty()) return 0.0;
    std::sort(costs.begin(), costs.end());
    const std::size_t at = metric == HeatmapMetric::time ? (costs.size() - 1) * 98 / 100 : costs.size() - 1;
    return costs[at];
}

std::string format_cost(double ramp_top, double largest, HeatmapMetric metric) {
    char text[96];
    if (metric == HeatmapMetric::work) std::snprintf(text, sizeof text, "%.0f fragment-lights per tile", ramp_top);
    else if (ramp_top < largest)
        std::snprintf(text, sizeof text, "%.3f ms per tile and more (max %.3f)", ramp_top, largest);
    else std::snprintf(text, sizeof text, "%.3f ms per tile", ramp_top);
    return text;
}

}  // namespace

HeatmapMetric parse_heatmap_metric(const std::string& name) {
    if (name == "time") return HeatmapMetric::time;
    if (name == "work") return HeatmapMetric::work;
    throw std::invalid_argument("unknown heat map metric '" + name + "' (expected time or work)");
}

double heatmap_ramp_end(std::span<const TracedFrame> frames, HeatmapMetric metric) {
    return ramp_end(median_tile_costs(frames, metric), metric);
}

RenderedImage make_tile_heatmap(const RenderedImage& frame, std::span<const TracedFrame> frames,
                                HeatmapMetric metric) {
    const std::vector<double> costs = median_tile_costs(frames, metric);
    const FrameProfile& grid = frames.front().profile;
    if (grid.width != frame.width || grid.height != frame.height)
        throw std::invalid_argument("the heat map's frame and its profile differ in size");
    const double largest = *std::max_element(costs.begin(), costs.end());
    const double ramp_top = std::max(ramp_end(costs, metric), 1e-12);
    const int width = frame.width, height = frame.height;
    const int legend = std::clamp(height / 8, 36, 96);  // strip below the picture: the ramp, then its scale
    const int ramp_rows = legend / 2;

    // One channel of normalized cost per pixel (tile cost over the picture, the ramp
    // 0 → 1 across the legend), coloured by OpenImageIO's perceptual "inferno" map.
    OIIO::ImageBuf level(OIIO::ImageSpec(width, height + legend, 1, OIIO::TypeDesc::FLOAT));
    for (int y = 0; y < height + legend; ++y) {
        for (int x = 0; x < width; ++x) {
            float v;
            if (y < height) {
                const int tile = (y / grid.tile_size) * grid.tiles_x + x / grid.tile_size;
                v = float(std::min(costs[std::size_t(tile)] / ramp_top, 1.0));
            } else if (y < height + ramp_rows) {
                v = width > 1 ? float(x) / float(width - 1) : 1.0f;
            } else {
                v = 0.0f;  // the ramp's dark end, under the labels
            }
            level.setpixel(x, y, &v, 1);
        }
    }
    OIIO::ImageBuf tint = OIIO::ImageBufAlgo::color_map(level, 0, "inferno");
    if (tint.has_error()) throw std::runtime_error("heat map colours: " + tint.geterror());

    // The picture shows through in grey, so that a person sees which object a hot tile holds.
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::uint8_t* rgb = &frame.display[3 * (std::size_t(y) * width + x)];
            const float grey = (0.2126f * rgb[0] + 0.7152f * rgb[1] + 0.0722f * rgb[2]) / 255.0f;
            float c[3];
            tint.getpixel(x, y, c, 3);
            for (float& channel : c) channel = 0.4f * grey + 0.6f * channel;
            tint.setpixel(x, y, c, 3);
        }
    }
    const int text_size = std::max(10, legend / 3);
    const int baseline = height + legend - legend / 8;
    using OIIO::ImageBufAlgo::TextAlignX;
    draw_label(tint, 4, baseline, "0", text_size, TextAlignX::Left) &&
        draw_label(tint, width - 4, baseline, format_cost(ramp_top, largest, metric), text_size, TextAlignX::Right);

    RenderedImage out;
    out.width = width;
    out.height = height + legend;
    out.display.resize(std::size_t(3) * out.width * out.height);
    tint.get_pixels(OIIO::ROI(0, out.width, 0, out.height, 0, 1, 0, 3), OIIO::TypeDesc::UINT8, out.display.data());
    return out;
}

}  // namespace tessera::profile
