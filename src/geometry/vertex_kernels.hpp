// The vertex stage's SIMD kernel (vertex_stage_simd.cpp), compiled once per ISA
// without FMA contraction: each lane computes exactly what the scalar path
// (shade_vertices, outcode, to_screen) computes for one vertex, in the same
// order of operations, so the two give bit-identical results.
#pragma once

#include <cstddef>
#include <cstdint>

namespace tessera::geometry {

// One run of a mesh's vertices, as plain data (per-ISA code calls no glm).
struct VertexRunInput {
    const float* positions;  // object space, 3 floats per vertex
    const float* normals;    // object space, 3 floats per vertex
    const float* uvs;        // 2 floats per vertex, or null for (0, 0)
    std::size_t count;
    const float* model;            // 4×4, column-major (glm's layout)
    const float* view_projection;  // 4×4, column-major
    const float* normal_matrix;    // 3×3, column-major
    float guard_x_ndc, guard_y_ndc;
    float width, height;  // viewport, pixels
};

// Where the run's results go: ShadedVertex seen as 12 floats (clip xyzw, world
// xyz, normal xyz, uv), its outcode, and its ScreenVertex seen as 4 int32 (x, y,
// then the bits of depth, and the outcode again). The screen vertex is written for every
// vertex but means something only where the outcode has no clip-plane bit
// and no kNotFinite.
struct VertexRunOutput {
    float* vertices;
    std::uint32_t* outcodes;
    std::int32_t* screen;
};

#define TESSERA_DECLARE_VERTEX_KERNEL(suffix) \
    void shade_vertex_run_##suffix(const VertexRunInput& in, const VertexRunOutput& out);
TESSERA_DECLARE_VERTEX_KERNEL(sse4)
TESSERA_DECLARE_VERTEX_KERNEL(avx2)
TESSERA_DECLARE_VERTEX_KERNEL(avx512)
#undef TESSERA_DECLARE_VERTEX_KERNEL

}  // namespace tessera::geometry
