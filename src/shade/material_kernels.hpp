// The material pass's per-fragment math over batches (material_kernels_simd.cpp,
// one copy per ISA), and its scalar reference loops (material_maps.cpp).
#pragma once

#include <cstddef>

#include "simd/isa.hpp"
#include "tessera/scene.hpp"

namespace tessera::shade {

// A run of fragments whose normals a normal map perturbs. Every array holds
// padded_count(count) floats (simd/lane_padding.hpp).
struct NormalMapBatch {
    std::size_t count = 0;
    const float* map[3] = {};  // the sampled normal map, RGB in [0, 1]
    float scale = 1.0f;        // the material's normal scale, on x and y
    const float* dp_dx[3] = {};
    const float* dp_dy[3] = {};
    const float* duv_dx[2] = {};
    const float* duv_dy[2] = {};
    const float* tangent[4] = {};  // w = 0: none stored, derive the frame
    float* normal[3] = {};         // in: interpolated normals; out: the shading normals, unit length (only [0, count) written)
};

// In place, c = pow(c, 2.2) for the reference's albedo maps.
void pow_2_2(simd::Isa isa, std::size_t count, float* r, float* g, float* b);
// normal_from_map_* (material_maps.hpp) for every fragment of the batch.
void perturb_normals(simd::Isa isa, const NormalMapBatch& batch, DerivedTangentFrame frame);

}  // namespace tessera::shade
