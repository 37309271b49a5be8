// The pre-computation's inner loops over xsimd batches (precompute_simd.cpp,
// compiled once per ISA), one output texel a lane: each lane runs the
// reference loop of precompute.cpp over every sample, in the same order and
// with the same operations, so a lane's sums have the reference's bits.
// What depends only on the texel (its direction and frame) or only on the
// sample (Hammersley point, tangent-space H, mip level) is worked out by
// precompute.cpp with the reference's code and handed over in plain arrays.
// Lane arrays are padded to simd::padded_count; `first` and `count` are
// multiples of 16.
#pragma once

#include <cstddef>

#include "simd/isa.hpp"

namespace tessera::environment {

// One level of a CubeMap's RGB texel array (CubeMap::data()).
struct CubeLevelArrays {
    const float* texels = nullptr;
    float size = 0;    // the face side
    float offset = 0;  // the level's first texel (exact: every index < 2^24)
};

// irradiance_convolution.fs: lane i sums tap(sample)·cos θ·sin θ over the samples.
struct IrradianceKernelInput {
    const float *nx, *ny, *nz;     // per texel: N
    const float *rx, *ry, *rz;     // right = cross(up, N), not normalized
    const float *ux, *uy, *uz;     // up = cross(N, right)
    const float *sx, *sy, *sz;     // per sample: the tangent-space direction
    const float *cos_theta, *sin_theta;
    std::size_t samples;
    CubeLevelArrays level;         // the environment level every tap reads
};
struct SumOutputs {
    float *r, *g, *b, *weight;     // weight: prefilter only
};

// prefilter.fs: lane i sums tap(L, lod)·N·L and N·L over the samples with N·L > 0.
struct PrefilterKernelInput {
    const float *nx, *ny, *nz;     // per texel: N = V = R
    const float *tx, *ty, *tz;     // the sample frame's tangent
    const float *bx, *by, *bz;     // and bitangent
    const float *hx, *hy, *hz;     // per sample: tangent-space H
    const int* level0;             // trilinear: levels level0 and level0 + 1
    const float* level_fraction;   // and the weight of the second
    std::size_t samples;
    const float* texels;           // the environment, every level
    const float* level_size;       // per level: face side
    const float* level_offset;     // per level: first texel
};

// brdf.fs over one row (a roughness): lane x integrates at N·V = n_dot_v[x].
struct BrdfKernelInput {
    const float *n_dot_v, *vx, *vy, *vz;  // per texel of the row: N·V and V
    const float *hx, *hy, *hz;            // per sample: H (N = +Z)
    std::size_t samples;
    float roughness;
};

void irradiance_sums(simd::Isa isa, const IrradianceKernelInput& in, std::size_t first, std::size_t count,
                     const SumOutputs& out);
void prefilter_sums(simd::Isa isa, const PrefilterKernelInput& in, std::size_t first, std::size_t count,
                    const SumOutputs& out);
// out_a, out_b: the row's A and B before the division by the sample count.
void brdf_sums(simd::Isa isa, const BrdfKernelInput& in, std::size_t count, float* out_a, float* out_b);

}  // namespace tessera::environment
