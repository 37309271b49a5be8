#include "raster/triangle_assembly.hpp"

#include <algorithm>
#include <bit>

#include "raster/raster_kernels.hpp"
#include "simd/prefetch.hpp"

namespace tessera::raster {

namespace {

static_assert(sizeof(geometry::ScreenVertex) == 4 * sizeof(std::int32_t), "the setup kernels read it as 4 int32");

// What one triangle's assembly needs besides the triangle.
struct AssemblyContext {
    std::span<const std::uint32_t> indices;
    std::uint32_t first_vertex;
    const FrameVertices& frame;
    geometry::Viewport viewport;
    const geometry::GuardBand& guard;
    AssembledTriangles& out;
    int samples;
    Culling culling;
    bool mirrored;
    std::span<const glm::vec4> colors;
    std::span<const glm::vec2> uvs1;

    // The corners' vertex references of triangle t (its indices in range).
    std::array<std::uint32_t, 3> refs(std::size_t t) const {
        return {first_vertex + indices[3 * t], first_vertex + indices[3 * t + 1], first_vertex + indices[3 * t + 2]};
    }

    // A triangle inside the guard band and the near and far planes.
    void set_up(const std::array<std::uint32_t, 3>& ref) const {
        const auto set_up = setup_triangle(
            viewport, {frame.screen[ref[0]], frame.screen[ref[1]], frame.screen[ref[2]]}, ref, samples, culling, mirrored);
        if (set_up) out.triangles.push_back(*set_up);
    }

    // A triangle crossing the clip planes in `planes`: clipped into a fan.
    void clip(std::size_t t, const std::array<std::uint32_t, 3>& ref, std::uint32_t planes) const {
        geometry::ClippedPolygon polygon;
        geometry::clip_triangle(frame.vertices[ref[0]], frame.vertices[ref[1]], frame.vertices[ref[2]], planes, guard,
                                polygon);
        // Every new corner gets a reference into the clipped vertices.
        std::array<std::uint32_t, geometry::ClippedPolygon::kMaxCorners> corner_ref;
        for (int i = 0; i < polygon.count; ++i) {
            if (polygon.source[i] >= 0) {
                corner_ref[i] = ref[polygon.source[i]];
            } else {
                corner_ref[i] = geometry::kClippedVertexBit | std::uint32_t(out.clipped_vertices.size());
                out.clipped_vertices.push_back(polygon.corners[i]);
                const glm::vec3& w = polygon.weights[i];
                if (!colors.empty())
                    out.clipped_colors.push_back(w.x * colors[indices[3 * t]] + w.y * colors[indices[3 * t + 1]] +
                                                 w.z * colors[indices[3 * t + 2]]);
                if (!uvs1.empty())
                    out.clipped_uvs1.push_back(w.x * uvs1[indices[3 * t]] + w.y * uvs1[indices[3 * t + 1]] +
                                               w.z * uvs1[indices[3 * t + 2]]);
            }
        }
        for (int i = 1; i + 1 < polygon.count; ++i) {  // a fan around corner 0
            const auto set_up = setup_triangle(
                viewport, {polygon.corners[0].clip_pos, polygon.corners[i].clip_pos, polygon.corners[i + 1].clip_pos},
                {corner_ref[0], corner_ref[i], corner_ref[i + 1]}, samples, culling, mirrored);
            if (set_up) out.triangles.push_back(*set_up);
        }
    }

    std::uint32_t clip_planes(const std::array<std::uint32_t, 3>& ref) const {
        return (frame.outcodes[ref[0]] | frame.outcodes[ref[1]] | frame.outcodes[ref[2]]) & geometry::kClipPlaneBits;
    }
};

// The reference: one triangle at a time.
void assemble_one_by_one(const AssemblyContext& c, std::uint32_t vertex_count) {
    for (std::size_t t = 0; t < c.indices.size() / 3; ++t) {
        if (c.indices[3 * t] >= vertex_count || c.indices[3 * t + 1] >= vertex_count ||
            c.indices[3 * t + 2] >= vertex_count)
            continue;
        const std::array<std::uint32_t, 3> ref = c.refs(t);
        const std::uint32_t oc0 = c.frame.outcodes[ref[0]], oc1 = c.frame.outcodes[ref[1]],
                            oc2 = c.frame.outcodes[ref[2]];
        const geometry::ClipResult kind = geometry::classify_triangle(oc0, oc1, oc2);
        if (kind == geometry::ClipResult::accepted) c.set_up(ref);
        if (kind == geometry::ClipResult::clipped) c.clip(t, ref, (oc0 | oc1 | oc2) & geometry::kClipPlaneBits);
    }
}

// The ISA's kernel a batch of triangles at a time; what it leaves to the scalar
// code (clipping, large triangles) is merged back in submission order.
void assemble_in_batches(simd::Isa isa, const AssemblyContext& c, std::uint32_t vertex_count) {
    const std::size_t triangle_count = c.indices.size() / 3;
    if (vertex_count == 0 || triangle_count == 0) return;  // every index is out of range
    SetupBatchInput in;
    in.outcodes = c.frame.outcodes.data();
    in.screen = reinterpret_cast<const std::int32_t*>(c.frame.screen.data());
    in.first_vertex = std::int32_t(c.first_vertex);
    in.vertex_count = std::int32_t(vertex_count);
    in.width = c.viewport.width, in.height = c.viewport.height;
    in.samples = c.samples;
    in.culling = c.culling;
    in.mirrored = c.mirrored;
    static_assert(kAssemblyRoom >= kSetupBatch);
    SetupBatchOutput batch;
    std::array<RasterTriangle, kSetupBatch> aside;  // a batch's records while the scalar code's are merged in
    std::array<std::uint32_t, 3 * kSetupBatch> tail;  // the last, partial batch, padded with index 0
    RasterTriangles& triangles = c.out.triangles;
    std::size_t prefetched = 0;  // records before it were prefetched
    for (std::size_t first = 0; first < triangle_count; first += kSetupBatch) {
        in.count = int(std::min<std::size_t>(kSetupBatch, triangle_count - first));
        in.indices = c.indices.data() + 3 * first;
        if (in.count < kSetupBatch) {  // the kernel reads whole vectors of triangles
            tail.fill(0);
            std::copy_n(in.indices, 3 * in.count, tail.begin());
            in.indices = tail.data();
        }
        // The kernel writes its records straight after the ones kept so far.
        const std::size_t kept_before = triangles.size();
        // The records (a line each) of the next batches, asked for ahead of
        // their stores (simd/prefetch.hpp): in a frame on several threads the
        // other core read them last frame.
        const std::size_t ahead_end = std::min(triangles.capacity(), kept_before + 2 * std::size_t(kSetupBatch));
        for (prefetched = std::max(prefetched, kept_before + kSetupBatch); prefetched < ahead_end; ++prefetched)
            simd::prefetch_for_write(triangles.data() + prefetched);
        triangles.resize(kept_before + kSetupBatch);  // uninitialized (UninitializedAllocator)
        batch.records = triangles.data() + kept_before;
        switch (isa) {
            case simd::Isa::sse4: setup_batch_sse4(in, batch); break;
            case simd::Isa::avx2: setup_batch_avx2(in, batch); break;
            case simd::Isa::avx512: setup_batch_avx512(in, batch); break;
            case simd::Isa::scalar: triangles.resize(kept_before); return;  // not reached: the caller runs the scalar path
        }
        const int kept = std::popcount(batch.kept);
        const std::uint64_t one_by_one = batch.scalar | batch.clipped;
        if (one_by_one == 0) {
            triangles.resize(kept_before + std::size_t(kept));
            continue;
        }
        // Rare (clipping, large triangles): the records go aside and come back in order.
        std::copy_n(triangles.data() + kept_before, kept, aside.begin());
        triangles.resize(kept_before);
        int record = 0;
        for (std::uint64_t bits = batch.kept | one_by_one; bits != 0; bits &= bits - 1) {
            const int i = std::countr_zero(bits);
            const std::uint64_t bit = std::uint64_t(1) << i;
            if (batch.kept & bit) {
                triangles.push_back(aside[std::size_t(record++)]);
                continue;
            }
            const std::array<std::uint32_t, 3> ref = c.refs(first + std::size_t(i));
            if (batch.scalar & bit) c.set_up(ref);
            else c.clip(first + std::size_t(i), ref, c.clip_planes(ref));
        }
    }
}

}  // namespace

void assemble_triangles(simd::Isa isa, std::span<const std::uint32_t> indices, std::uint32_t first_vertex,
                        std::uint32_t vertex_count, const FrameVertices& frame,
                        const geometry::Viewport& viewport, const geometry::GuardBand& guard,
                        AssembledTriangles& out, int samples, Culling culling, std::span<const glm::vec4> colors,
                        bool mirrored, std::span<const glm::vec2> uvs1) {
    const AssemblyContext context{indices, first_vertex, frame, viewport, guard, out,
                                  samples, culling, mirrored, colors, uvs1};
    if (isa == simd::Isa::scalar) assemble_one_by_one(context, vertex_count);
    else assemble_in_batches(isa, context, vertex_count);
}

}  // namespace tessera::raster
