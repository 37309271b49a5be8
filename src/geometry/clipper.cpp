#include "geometry/clipper.hpp"

#include <cmath>

namespace tessera::geometry {

std::uint32_t outcode(const glm::vec4& p, const GuardBand& guard) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || !std::isfinite(p.w)) return kNotFinite;
    std::uint32_t code = 0;
    if (p.z < -p.w) code |= kOutsideNear;
    if (p.z > p.w) code |= kOutsideFar;
    if (p.x > guard.x_ndc * p.w) code |= kOutsideGuardRight;
    if (p.x < -guard.x_ndc * p.w) code |= kOutsideGuardLeft;
    if (p.y > guard.y_ndc * p.w) code |= kOutsideGuardTop;
    if (p.y < -guard.y_ndc * p.w) code |= kOutsideGuardBottom;
    if (p.x > p.w) code |= kOutsideViewRight;
    if (p.x < -p.w) code |= kOutsideViewLeft;
    if (p.y > p.w) code |= kOutsideViewTop;
    if (p.y < -p.w) code |= kOutsideViewBottom;
    return code;
}

std::uint32_t outcode(const ShadedVertex& vertex, const GuardBand& guard) {
    const glm::vec3& n = vertex.normal;
    if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) return kNotFinite;
    return outcode(vertex.clip_pos, guard);
}

namespace {

// Signed distance to a clip plane: >= 0 inside.
float plane_distance(int plane, const glm::vec4& p, const GuardBand& guard) {
    switch (plane) {
        case 0: return p.w + p.z;                  // near
        case 1: return p.w - p.z;                  // far
        case 2: return guard.x_ndc * p.w - p.x;   // guard right
        case 3: return guard.x_ndc * p.w + p.x;   // guard left
        case 4: return guard.y_ndc * p.w - p.y;   // guard top
        default: return guard.y_ndc * p.w + p.y;  // guard bottom
    }
}

ShadedVertex lerp(const ShadedVertex& a, const ShadedVertex& b, float t) {
    return {a.clip_pos + t * (b.clip_pos - a.clip_pos), a.world_pos + t * (b.world_pos - a.world_pos),
            a.normal + t * (b.normal - a.normal), a.uv + t * (b.uv - a.uv)};
}

}  // namespace

// Sutherland-Hodgman, one plane at a time, ping-ponging between two polygons.
void clip_triangle(const ShadedVertex& a, const ShadedVertex& b, const ShadedVertex& c, std::uint32_t planes,
                   const GuardBand& guard, ClippedPolygon& out) {
    ClippedPolygon scratch;
    ClippedPolygon* src = &out;
    ClippedPolygon* dst = &scratch;
    src->corners[0] = a, src->corners[1] = b, src->corners[2] = c;
    src->source[0] = 0, src->source[1] = 1, src->source[2] = 2;
    src->weights[0] = {1, 0, 0}, src->weights[1] = {0, 1, 0}, src->weights[2] = {0, 0, 1};
    src->count = 3;
    for (int plane = 0; plane < 6 && src->count > 0; ++plane) {
        if (!(planes & (1u << plane))) continue;
        dst->count = 0;
        for (int i = 0; i < src->count; ++i) {
            const int j = (i + 1) % src->count;
            const ShadedVertex& p = src->corners[i];
            const ShadedVertex& q = src->corners[j];
            const float dp = plane_distance(plane, p.clip_pos, guard);
            const float dq = plane_distance(plane, q.clip_pos, guard);
            if (dp >= 0.0f) {
                dst->corners[dst->count] = p;
                dst->weights[dst->count] = src->weights[i];
                dst->source[dst->count++] = src->source[i];
            }
            if ((dp >= 0.0f) != (dq >= 0.0f)) {
                // Interpolate from the inside corner, so an edge gives the same
                // new vertex whichever triangle it belongs to.
                const bool p_inside = dp >= 0.0f;
                const float t = p_inside ? dp / (dp - dq) : dq / (dq - dp);
                dst->corners[dst->count] = p_inside ? lerp(p, q, t) : lerp(q, p, t);
                const glm::vec3 &wp = src->weights[i], &wq = src->weights[j];
                dst->weights[dst->count] = p_inside ? wp + t * (wq - wp) : wq + t * (wp - wq);
                dst->source[dst->count++] = -1;
            }
        }
        std::swap(src, dst);
    }
    if (src != &out) out = *src;
}

}  // namespace tessera::geometry
