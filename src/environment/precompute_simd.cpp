// The pre-computation's sample loops (precompute.cpp's reference loops) over
// xsimd batches, one output texel a lane, compiled once per ISA without
// contraction: each lane performs its texel's reference operations in the
// reference's order, so the maps have the reference's bits
// (tests/environment/test_precompute.cpp). A lane whose sample the reference
// skips (N·L ≤ 0) keeps its sums by a select, as the reference's `if` does.
#include <cstddef>

#include "simd/kernel_prelude.hpp"

#include "environment/cube_map_simd.hpp"
#include "environment/precompute_kernels.hpp"

namespace tessera::environment {
namespace {

using namespace cube_simd;

void irradiance_batch(const IrradianceKernelInput& in, std::size_t i, const SumOutputs& out) {
    const V3 n = load3(in.nx, in.ny, in.nz, i), right = load3(in.rx, in.ry, in.rz, i), up = load3(in.ux, in.uy, in.uz, i);
    const Batch size(in.level.size), offset(in.level.offset);
    V3 irradiance{Batch(0.0f), Batch(0.0f), Batch(0.0f)};
    for (std::size_t s = 0; s < in.samples; ++s) {
        // tangent.x·right + tangent.y·up + tangent.z·N, as glm evaluates it.
        const V3 sample_vec = (right * Batch(in.sx[s]) + up * Batch(in.sy[s])) + n * Batch(in.sz[s]);
        const V3 tap = sample_bilinear(in.level.texels, face_coords(sample_vec), size, offset);
        irradiance = irradiance + (tap * Batch(in.cos_theta[s])) * Batch(in.sin_theta[s]);
    }
    irradiance.x.store_unaligned(out.r + i), irradiance.y.store_unaligned(out.g + i), irradiance.z.store_unaligned(out.b + i);
}

void prefilter_batch(const PrefilterKernelInput& in, std::size_t i, const SumOutputs& out) {
    const V3 n = load3(in.nx, in.ny, in.nz, i);
    const V3 tangent = load3(in.tx, in.ty, in.tz, i), bitangent = load3(in.bx, in.by, in.bz, i);
    const Batch zero(0.0f);
    V3 prefiltered{zero, zero, zero};
    Batch total_weight = zero;
    for (std::size_t s = 0; s < in.samples; ++s) {
        const V3 h = normalize((tangent * Batch(in.hx[s]) + bitangent * Batch(in.hy[s])) + n * Batch(in.hz[s]));
        const V3 l = normalize(h * (Batch(2.0f) * dot(n, h)) - n);  // V = N
        const Batch n_dot_l = gmax(dot(n, l), zero);
        const Mask lit = n_dot_l > zero;
        if (xsimd::none(lit)) continue;
        // CubeMap::sample_trilinear, the level and weight being the sample's.
        const Face c = face_coords(l);
        const int l0 = in.level0[s];
        const V3 a = sample_bilinear(in.texels, c, Batch(in.level_size[l0]), Batch(in.level_offset[l0]));
        const V3 b = sample_bilinear(in.texels, c, Batch(in.level_size[l0 + 1]), Batch(in.level_offset[l0 + 1]));
        const V3 term = (a + (b - a) * Batch(in.level_fraction[s])) * n_dot_l;
        prefiltered.x = xsimd::select(lit, prefiltered.x + term.x, prefiltered.x);
        prefiltered.y = xsimd::select(lit, prefiltered.y + term.y, prefiltered.y);
        prefiltered.z = xsimd::select(lit, prefiltered.z + term.z, prefiltered.z);
        total_weight = xsimd::select(lit, total_weight + n_dot_l, total_weight);
    }
    prefiltered.x.store_unaligned(out.r + i), prefiltered.y.store_unaligned(out.g + i);
    prefiltered.z.store_unaligned(out.b + i), total_weight.store_unaligned(out.weight + i);
}

void brdf_batch(const BrdfKernelInput& in, std::size_t x, float* out_a, float* out_b) {
    const V3 v = load3(in.vx, in.vy, in.vz, x);
    const Batch n_dot_v = xsimd::load_unaligned(in.n_dot_v + x);
    const Batch zero(0.0f), one(1.0f);
    // geometry_schlick_ggx_ibl: k = roughness² / 2, n·v / (n·v·(1 − k) + k).
    const float k = (in.roughness * in.roughness) / 2.0f;
    const Batch k_batch(k), one_minus_k(1.0f - k);
    const auto schlick_ggx = [&](const Batch& cos) { return cos / (cos * one_minus_k + k_batch); };
    const Batch g_view = schlick_ggx(gmax(v.z, zero));  // the same every sample
    Batch a = zero, b = zero;
    for (std::size_t s = 0; s < in.samples; ++s) {
        const V3 h{Batch(in.hx[s]), Batch(in.hy[s]), Batch(in.hz[s])};
        const Batch v_dot_h_raw = dot(v, h);
        const V3 l = normalize(h * (Batch(2.0f) * v_dot_h_raw) - v);
        const Batch n_dot_l = gmax(l.z, zero);
        const float n_dot_h = in.hz[s] < 0.0f ? 0.0f : in.hz[s];  // glm::max(h.z, 0)
        const Batch v_dot_h = gmax(v_dot_h_raw, zero);
        const Mask lit = n_dot_l > zero;
        const Batch g = g_view * schlick_ggx(n_dot_l);
        const Batch g_vis = (g * v_dot_h) / (Batch(n_dot_h) * n_dot_v);
        const Batch one_minus = one - v_dot_h;
        const Batch one_minus2 = one_minus * one_minus;
        const Batch fc = one_minus2 * one_minus2 * one_minus;  // pow(1 − V·H, 5)
        a = xsimd::select(lit, a + (one - fc) * g_vis, a);
        b = xsimd::select(lit, b + fc * g_vis, b);
    }
    a.store_unaligned(out_a + x), b.store_unaligned(out_b + x);
}

}  // namespace

void TESSERA_SIMD_ENTRY(irradiance_sums)(const IrradianceKernelInput& in, std::size_t first, std::size_t count,
                                         const SumOutputs& out) {
    for (std::size_t i = first; i < first + count; i += Batch::size) irradiance_batch(in, i, out);
}

void TESSERA_SIMD_ENTRY(prefilter_sums)(const PrefilterKernelInput& in, std::size_t first, std::size_t count,
                                        const SumOutputs& out) {
    for (std::size_t i = first; i < first + count; i += Batch::size) prefilter_batch(in, i, out);
}

void TESSERA_SIMD_ENTRY(brdf_sums)(const BrdfKernelInput& in, std::size_t count, float* out_a, float* out_b) {
    for (std::size_t x = 0; x < count; x += Batch::size) brdf_batch(in, x, out_a, out_b);
}

}  // namespace tessera::environment
