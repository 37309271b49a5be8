#include "raster/triangle_assembly.hpp"

namespace tessera::raster {

void assemble_triangles(std::span<const std::uint32_t> indices, std::uint32_t first_vertex, std::uint32_t material,
                        const FrameVertices& frame, const geometry::Viewport& viewport,
                        const geometry::GuardBand& guard, AssembledTriangles& out) {
    geometry::ClippedPolygon polygon;
    for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
        const std::array<std::uint32_t, 3> ref{first_vertex + indices[t], first_vertex + indices[t + 1],
                                               first_vertex + indices[t + 2]};
        const std::uint32_t oc0 = frame.outcodes[ref[0]], oc1 = frame.outcodes[ref[1]], oc2 = frame.outcodes[ref[2]];
        const geometry::ClipResult kind = geometry::classify_triangle(oc0, oc1, oc2);
        if (kind == geometry::ClipResult::rejected) continue;
        if (kind == geometry::ClipResult::accepted) {
            const auto set_up =
                setup_triangle(viewport, {frame.screen[ref[0]], frame.screen[ref[1]], frame.screen[ref[2]]}, ref, material);
            if (set_up) out.triangles.push_back(*set_up);
            continue;
        }
        geometry::clip_triangle(frame.vertices[ref[0]], frame.vertices[ref[1]], frame.vertices[ref[2]],
                                (oc0 | oc1 | oc2) & geometry::kClipPlaneBits, guard, polygon);
        // Every new corner gets a reference into the clipped vertices.
        std::array<std::uint32_t, geometry::ClippedPolygon::kMaxCorners> corner_ref;
        for (int i = 0; i < polygon.count; ++i) {
            if (polygon.source[i] >= 0) {
                corner_ref[i] = ref[polygon.source[i]];
            } else {
                corner_ref[i] = geometry::kClippedVertexBit | std::uint32_t(out.clipped_vertices.size());
                out.clipped_vertices.push_back(polygon.corners[i]);
            }
        }
        for (int i = 1; i + 1 < polygon.count; ++i) {  // a fan around corner 0
            const auto set_up = setup_triangle(
                viewport, {polygon.corners[0].clip_pos, polygon.corners[i].clip_pos, polygon.corners[i + 1].clip_pos},
                {corner_ref[0], corner_ref[i], corner_ref[i + 1]}, material);
            if (set_up) out.triangles.push_back(*set_up);
        }
    }
}

}  // namespace tessera::raster
