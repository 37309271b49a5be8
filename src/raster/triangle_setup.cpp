#include "raster/triangle_setup.hpp"

#include <algorithm>

#include "raster/msaa/msaa.hpp"
#include "raster/raster_limits.hpp"

namespace tessera::raster {

namespace {

// Pixel i's centre is i·256 + 128 in fixed point. C++20's >> on a negative
// value is an arithmetic shift, i.e. floor division by 256.

// Smallest pixel index whose centre is >= v: ceil((v - 128) / 256).
std::int32_t first_centre_at_or_after(std::int32_t v) {
    return (v - kSubpixelScale / 2 + kSubpixelScale - 1) >> kSubpixelBits;
}

// Largest pixel index whose centre is <= v: floor((v - 128) / 256).
std::int32_t last_centre_at_or_before(std::int32_t v) { return (v - kSubpixelScale / 2) >> kSubpixelBits; }

// Tests every pixel centre in the triangle's box (meant for small boxes).
bool covers_a_centre(const RasterTriangle& t) {
    const std::int64_t px = std::int64_t(t.px_min) * kSubpixelScale + kSubpixelScale / 2;
    const std::int64_t py = std::int64_t(t.py_min) * kSubpixelScale + kSubpixelScale / 2;
    EdgeStepper e0(t.x[1], t.y[1], t.x[2], t.y[2], px, py), e1(t.x[2], t.y[2], t.x[0], t.y[0], px, py),
        e2(t.x[0], t.y[0], t.x[1], t.y[1], px, py);
    for (int y = t.py_min; y <= t.py_max; ++y) {
        std::int64_t w0 = e0.row, w1 = e1.row, w2 = e2.row;
        for (int x = t.px_min; x <= t.px_max; ++x) {
            if ((w0 | w1 | w2) >= 0) return true;
            w0 += e0.step_x, w1 += e1.step_x, w2 += e2.step_x;
        }
        e0.row += e0.step_y, e1.row += e1.step_y, e2.row += e2.step_y;
    }
    return false;
}

// The 4× samples lie 1/8 to 7/8 of a pixel from its top-left corner: the
// smallest pixel index with a sample at or after v, the largest with one at or before.
std::int32_t first_sample_at_or_after(std::int32_t v) {
    return (v - 7 * kSubpixelScale / 8 + kSubpixelScale - 1) >> kSubpixelBits;
}
std::int32_t last_sample_at_or_before(std::int32_t v) { return (v - kSubpixelScale / 8) >> kSubpixelBits; }

bool covers_a_sample(const RasterTriangle& t) {
    for (int y = t.py_min; y <= t.py_max; ++y)
        for (int x = t.px_min; x <= t.px_max; ++x)
            for (int s = 0; s < kMsaaSamples; ++s)
                if (covers_point(t, std::int64_t(x) * kSubpixelScale + kSubpixelScale / 2 + kSampleOffsetX[s],
                                 std::int64_t(y) * kSubpixelScale + kSubpixelScale / 2 + kSampleOffsetY[s]))
                    return true;
    return false;
}

}  // namespace

std::optional<RasterTriangle> setup_triangle(const Viewport& viewport, const std::array<ScreenVertex, 3>& corners,
                                             const std::array<std::uint32_t, 3>& vertex, int samples,
                                             Culling culling, bool mirrored) {
    RasterTriangle t;
    for (int i = 0; i < 3; ++i) {
        t.x[i] = corners[i].x;
        t.y[i] = corners[i].y;
        t.depth[i] = corners[i].depth;
        t.vertex[i] = vertex[i];
    }
    std::int64_t double_area = edge_function(t.x[0], t.y[0], t.x[1], t.y[1], t.x[2], t.y[2]);
    if (double_area == 0 || culled(culling, double_area)) return std::nullopt;
    // GL's front face turns counter-clockwise in window space: a negative area here.
    t.back_facing = (double_area < 0) == mirrored ? 1u : 0u;
    if (double_area < 0) {
        std::swap(t.x[1], t.x[2]);
        std::swap(t.y[1], t.y[2]);
        std::swap(t.depth[1], t.depth[2]);
        std::swap(t.vertex[1], t.vertex[2]);
        double_area = -double_area;
    }
    t.inv_area = 1.0f / float(double_area);
    const auto [min_x, max_x] = std::minmax({t.x[0], t.x[1], t.x[2]});
    const auto [min_y, max_y] = std::minmax({t.y[0], t.y[1], t.y[2]});
    const bool msaa = samples > 1;
    const auto first = msaa ? first_sample_at_or_after : first_centre_at_or_after;
    const auto last = msaa ? last_sample_at_or_before : last_centre_at_or_before;
    const std::int32_t px_min = std::max(first(min_x), 0);
    const std::int32_t px_max = std::min(last(max_x), viewport.width - 1);
    const std::int32_t py_min = std::max(first(min_y), 0);
    const std::int32_t py_max = std::min(last(max_y), viewport.height - 1);
    // Most triangles of a finely tessellated mesh fall between pixel centres:
    // those whose box holds no centre, and small ones that cover none of the
    // few centres in their box, go no further.
    if (px_min > px_max || py_min > py_max) return std::nullopt;
    t.px_min = std::int16_t(px_min), t.px_max = std::int16_t(px_max);
    t.py_min = std::int16_t(py_min), t.py_max = std::int16_t(py_max);
    if (px_max - px_min <= 1 && py_max - py_min <= 1 && !(msaa ? covers_a_sample(t) : covers_a_centre(t)))
        return std::nullopt;
    return t;
}

std::optional<RasterTriangle> setup_triangle(const Viewport& viewport, const std::array<glm::vec4, 3>& clip_pos,
                                             const std::array<std::uint32_t, 3>& vertex, int samples,
                                             Culling culling, bool mirrored) {
    return setup_triangle(viewport,
                          {geometry::to_screen(clip_pos[0], viewport), geometry::to_screen(clip_pos[1], viewport),
                           geometry::to_screen(clip_pos[2], viewport)},
                          vertex, samples, culling, mirrored);
}

}  // namespace tessera::raster
