#include "raster/triangle_assembly.hpp"

#include "raster/raster_kernels.hpp"

namespace tessera::raster {

namespace {

static_assert(sizeof(geometry::ScreenVertex) == 4 * sizeof(std::int32_t), "the setup kernels read it as 4 int32");

// Accepted triangles waiting for the setup kernel, kept in submission order.
class SetupQueue {
public:
    SetupQueue(simd::Isa isa, const FrameVertices& frame, const geometry::Viewport& viewport, AssembledTriangles& out,
               int samples, Culling culling)
        : isa_(isa), frame_(frame), viewport_(viewport), out_(out), samples_(samples), culling_(culling) {
        in_.screen = reinterpret_cast<const std::int32_t*>(frame.screen.data());
        in_.count = 0;
        in_.width = viewport.width;
        in_.height = viewport.height;
    }

    void push(const std::array<std::uint32_t, 3>& ref) {
        if (isa_ == simd::Isa::scalar || samples_ != 1) return set_up_one(ref);
        for (int k = 0; k < 3; ++k) in_.ref[k][in_.count] = std::int32_t(ref[k]);
        if (++in_.count == kSetupBatch) flush();
    }

    // Sets up what is queued; called before anything else is appended, to keep the order.
    void flush() {
        if (in_.count == 0) return;
        for (int i = in_.count; i < kSetupBatch; ++i)
            for (int k = 0; k < 3; ++k) in_.ref[k][i] = in_.ref[k][0];  // spare lanes: any valid vertex
        switch (isa_) {
            case simd::Isa::sse4: setup_batch_sse4(in_, verdicts_); break;
            case simd::Isa::avx2: setup_batch_avx2(in_, verdicts_); break;
            case simd::Isa::avx512: setup_batch_avx512(in_, verdicts_); break;
            case simd::Isa::scalar: break;
        }
        for (int i = 0; i < in_.count; ++i) {
            std::array<std::uint32_t, 3> ref{std::uint32_t(in_.ref[0][i]), std::uint32_t(in_.ref[1][i]),
                                             std::uint32_t(in_.ref[2][i])};
            if (verdicts_.verdict[i] == kSetupScalar) set_up_one(ref);
            if (verdicts_.verdict[i] != kSetupKept) continue;
            // Kept means a non-zero area, negative where swapped: the scalar setup's culling test.
            if (culled(culling_, verdicts_.swapped[i] ? -1 : 1)) continue;
            if (verdicts_.swapped[i]) std::swap(ref[1], ref[2]);
            RasterTriangle& t = out_.triangles.emplace_back();
            for (int k = 0; k < 3; ++k) {
                const geometry::ScreenVertex& v = frame_.screen[ref[k]];
                t.x[k] = v.x, t.y[k] = v.y, t.depth[k] = v.depth, t.vertex[k] = ref[k];
            }
            t.inv_area = 1.0f / float(verdicts_.double_area[i]);  // as setup_triangle() computes it
            t.px_min = std::int16_t(verdicts_.px_min[i]), t.px_max = std::int16_t(verdicts_.px_max[i]);
            t.py_min = std::int16_t(verdicts_.py_min[i]), t.py_max = std::int16_t(verdicts_.py_max[i]);
        }
        in_.count = 0;
    }

private:
    void set_up_one(const std::array<std::uint32_t, 3>& ref) {
        const auto set_up = setup_triangle(
            viewport_, {frame_.screen[ref[0]], frame_.screen[ref[1]], frame_.screen[ref[2]]}, ref, samples_, culling_);
        if (set_up) out_.triangles.push_back(*set_up);
    }

    simd::Isa isa_;
    const FrameVertices& frame_;
    geometry::Viewport viewport_;
    AssembledTriangles& out_;
    int samples_;
    Culling culling_;
    SetupBatchInput in_;
    SetupBatchOutput verdicts_;
};

}  // namespace

void assemble_triangles(simd::Isa isa, std::span<const std::uint32_t> indices, std::uint32_t first_vertex,
                        std::uint32_t vertex_count, const FrameVertices& frame,
                        const geometry::Viewport& viewport, const geometry::GuardBand& guard,
                        AssembledTriangles& out, int samples, Culling culling, std::span<const glm::vec4> colors) {
    SetupQueue queue(isa, frame, viewport, out, samples, culling);
    geometry::ClippedPolygon polygon;
    for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
        if (indices[t] >= vertex_count || indices[t + 1] >= vertex_count || indices[t + 2] >= vertex_count) continue;
        const std::array<std::uint32_t, 3> ref{first_vertex + indices[t], first_vertex + indices[t + 1],
                                               first_vertex + indices[t + 2]};
        const std::uint32_t oc0 = frame.outcodes[ref[0]], oc1 = frame.outcodes[ref[1]], oc2 = frame.outcodes[ref[2]];
        const geometry::ClipResult kind = geometry::classify_triangle(oc0, oc1, oc2);
        if (kind == geometry::ClipResult::rejected) continue;
        if (kind == geometry::ClipResult::accepted) {
            queue.push(ref);
            continue;
        }
        queue.flush();
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
                if (!colors.empty()) {
                    const glm::vec3& w = polygon.weights[i];
                    out.clipped_colors.push_back(w.x * colors[indices[t]] + w.y * colors[indices[t + 1]] +
                                                 w.z * colors[indices[t + 2]]);
                }
            }
        }
        for (int i = 1; i + 1 < polygon.count; ++i) {  // a fan around corner 0
            const auto set_up = setup_triangle(
                viewport, {polygon.corners[0].clip_pos, polygon.corners[i].clip_pos, polygon.corners[i + 1].clip_pos},
                {corner_ref[0], corner_ref[i], corner_ref[i + 1]}, samples, culling);
            if (set_up) out.triangles.push_back(*set_up);
        }
    }
    queue.flush();
}

}  // namespace tessera::raster
