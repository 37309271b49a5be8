// Triangle setup: viewport transform, snapping to fixed point, orientation,
// and the pixel box whose centres the triangle can cover.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "geometry/viewport.hpp"
#include "tessera/scene.hpp"

namespace tessera::raster {

// A triangle ready to rasterize, in image space: x right, y down, row 0 at
// the top of the picture, pixel (i, j) centred at (i + 0.5, j + 0.5).
// One cache line: setup writes hundreds of thousands of these a frame and the
// tiles read them back, so their size is memory traffic. What only visible
// pixels need is looked up then: 1/w from the corners' vertices, the
// material from the object the triangle belongs to.
struct alignas(64) RasterTriangle {
    std::array<std::int32_t, 3> x, y;     // corner positions, 24.8 fixed point
    std::int16_t px_min, px_max, py_min, py_max;  // inclusive pixel box, clamped to the image (< 16384)
    float inv_area;                       // 1 / double area, where double area = edge function of corner 2 against edge 0→1 > 0
    std::array<float, 3> depth;           // window depth z_ndc·0.5 + 0.5, in [0, 1]
    std::array<std::uint32_t, 3> vertex;  // the corners' vertex references (see ShadedVertex)
    // 1: the triangle shows its back (clockwise on screen in GL's window space, or
    // counter-clockwise under a mirroring model matrix), so a double-sided material
    // flips its normal there (glTF §3.9.5: gl_FrontFacing false). 0: its front.
    std::uint32_t back_facing;
};
static_assert(sizeof(RasterTriangle) == 64);
static_assert(kMaxImageDimension <= 32767, "pixel boxes are int16");

using geometry::ScreenVertex;
using geometry::Viewport;

// Face culling by winding in image space (x right, y down), before corners
// are reordered: a triangle whose double area (edge function of corner 2
// against edge 0→1) has the named sign is dropped. GL's default front face
// turns counter-clockwise on screen; with image y pointing down its double
// area is negative, so culling GL's back faces drops positive areas.
enum class Culling : std::uint8_t { none, drop_positive_area, drop_negative_area };

inline bool culled(Culling culling, std::int64_t double_area) {
    return (culling == Culling::drop_positive_area && double_area > 0) ||
           (culling == Culling::drop_negative_area && double_area < 0);
}

// Makes a RasterTriangle of three screen vertices, or nothing when the
// triangle has no area, is culled, or covers no pixel centre. Corners 1 and 2 are swapped where needed
// so that the edge functions are positive inside (clockwise as seen on screen).
// With samples = 4 (raster/msaa/msaa.hpp) the test and the pixel box are about the
// pixels' sample positions instead of their centres. mirrored: the object's
// model matrix has a negative determinant, which swaps front and back
// (RasterTriangle::back_facing).
std::optional<RasterTriangle> setup_triangle(const Viewport& viewport, const std::array<ScreenVertex, 3>& corners,
                                             const std::array<std::uint32_t, 3>& vertex, int samples = 1,
                                             Culling culling = Culling::none, bool mirrored = false);
// The same from clip positions (each inside the near plane and the guard band).
std::optional<RasterTriangle> setup_triangle(const Viewport& viewport, const std::array<glm::vec4, 3>& clip_pos,
                                             const std::array<std::uint32_t, 3>& vertex, int samples = 1,
                                             Culling culling = Culling::none, bool mirrored = false);

// Edge function of the edge a→b at point p, all in fixed point: twice the
// signed area of (a, b, p), positive when p lies inside a set-up triangle.
inline std::int64_t edge_function(std::int64_t ax, std::int64_t ay, std::int64_t bx, std::int64_t by, std::int64_t px,
                                  std::int64_t py) {
    return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
}

// One edge a→b of a set-up triangle, stepped over pixel centres from a
// starting centre. The top-left rule is a bias: a centre exactly on an edge
// belongs to the triangle only when the edge is a top edge (horizontal,
// interior below) or a left edge (interior to its right), so edges of
// neither kind test E - 1 >= 0 instead of E >= 0.
struct EdgeStepper {
    std::int64_t row;     // biased E at the current row's first pixel centre
    std::int64_t step_x;  // change of E for one pixel right
    std::int64_t step_y;  // change of E for one pixel down
    std::int64_t bias;    // 0 or -1

    // (px, py): the starting pixel centre in fixed point.
    EdgeStepper(std::int32_t ax, std::int32_t ay, std::int32_t bx, std::int32_t by, std::int64_t px, std::int64_t py) {
        const std::int64_t dx = std::int64_t(bx) - ax;
        const std::int64_t dy = std::int64_t(by) - ay;
        const bool top_left = dy < 0 || (dy == 0 && dx > 0);
        bias = top_left ? 0 : -1;
        row = edge_function(ax, ay, bx, by, px, py) + bias;
        step_x = -dy * geometry::kSubpixelScale;
        step_y = dx * geometry::kSubpixelScale;
    }
};

}  // namespace tessera::raster
