// Homogeneous clipping. Triangles are clipped against the near and far planes
// and against a guard band far outside the viewport, so that the rasterizer's
// fixed-point coordinates never overflow; triangles merely crossing the
// viewport's sides are not clipped (the rasterizer scissors them for free).
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "geometry/shaded_vertex.hpp"

namespace tessera::geometry {

// How far outside the viewport, in pixels, a vertex may lie before its
// triangle is clipped. With kMaxImageDimension this bounds every screen
// coordinate by 32768 px, which the raster stage's fixed point relies on.
inline constexpr float kGuardBandPixels = 16384.0f;

// Outcode bits: which planes a clip-space vertex lies outside of.
enum OutcodeBits : std::uint32_t {
    kOutsideNear = 1u << 0,   // z < -w
    kOutsideFar = 1u << 1,    // z > w
    kOutsideGuardRight = 1u << 2,
    kOutsideGuardLeft = 1u << 3,
    kOutsideGuardTop = 1u << 4,
    kOutsideGuardBottom = 1u << 5,
    kOutsideViewRight = 1u << 6,  // x > w: cannot be seen, but needs no clipping
    kOutsideViewLeft = 1u << 7,
    kOutsideViewTop = 1u << 8,
    kOutsideViewBottom = 1u << 9,
    kNotFinite = 1u << 10,  // NaN or infinity anywhere in the position (or the normal)
};
inline constexpr std::uint32_t kClipPlaneBits = 0x3Fu;  // the planes that really clip

// Guard band as a bound on |x/w| and |y/w|, for a viewport of width × height.
struct GuardBand {
    float x_ndc;
    float y_ndc;
    GuardBand(int width, int height)
        : x_ndc(1.0f + 2.0f * kGuardBandPixels / float(width)), y_ndc(1.0f + 2.0f * kGuardBandPixels / float(height)) {}
};

std::uint32_t outcode(const glm::vec4& clip_pos, const GuardBand& guard);
// The same for a shaded vertex: a NaN or infinite normal (or position) makes
// it kNotFinite, so its triangles are dropped rather than shaded into NaN.
std::uint32_t outcode(const ShadedVertex& vertex, const GuardBand& guard);

enum class ClipResult { rejected, accepted, clipped };

// What to do with a triangle given its corners' outcodes.
inline ClipResult classify_triangle(std::uint32_t oc0, std::uint32_t oc1, std::uint32_t oc2) {
    if ((oc0 | oc1 | oc2) & kNotFinite) return ClipResult::rejected;
    if (oc0 & oc1 & oc2) return ClipResult::rejected;  // all outside one plane
    if (((oc0 | oc1 | oc2) & kClipPlaneBits) == 0) return ClipResult::accepted;
    return ClipResult::clipped;
}

// A convex polygon produced by clipping one triangle: at most 3 + 6 corners.
struct ClippedPolygon {
    static constexpr int kMaxCorners = 9;
    std::array<ShadedVertex, kMaxCorners> corners;
    // Which input corner each output corner is (0..2), or -1 for a new vertex.
    std::array<int, kMaxCorners> source;
    // Each corner as weights of the input corners a, b, c (interpolated as the
    // attributes are): what attributes kept outside ShadedVertex (vertex colours) need.
    std::array<glm::vec3, kMaxCorners> weights;
    int count = 0;
};

// Clips triangle (a, b, c) against the planes in `planes` (a mask of
// kClipPlaneBits). Every attribute is interpolated linearly in clip space,
// which is what keeps the later perspective-correct interpolation right.
void clip_triangle(const ShadedVertex& a, const ShadedVertex& b, const ShadedVertex& c, std::uint32_t planes,
                   const GuardBand& guard, ClippedPolygon& out);

}  // namespace tessera::geometry
