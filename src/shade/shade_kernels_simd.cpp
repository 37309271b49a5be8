// The reference shader (pbr_reference.cpp) over xsimd batches: one fragment per
// lane, lights in the inner loop. Compiled once per ISA (cmake/SimdTargets.cmake):
// TESSERA_SIMD_ARCH is the xsimd architecture, TESSERA_SIMD_SUFFIX names this
// copy's entry points (shade_fragments_avx2, ...). Everything else lives in an
// anonymous namespace so the three copies never meet at link time.
//
// Same terms, same names as the reference; the differences are algebra only:
// per-fragment terms (a², k, G(N·V), F0, diffuse albedo) are hoisted out of the
// light loop, the normalizations multiply by 1/sqrt, and the specular fraction
// NDF·G / (4·N·V·N·L + 0.0001) is evaluated with one division.
#include <cstddef>

#include "simd/kernel_prelude.hpp"

#include "shade/pbr_reference.hpp"
#include "shade/shade_kernels.hpp"

namespace tessera::shade {
namespace {

using Arch = TESSERA_SIMD_ARCH;
using Batch = xsimd::batch<float, Arch>;
static_assert(kLanePadding % Batch::size == 0, "padding must hold whole vectors");

struct Vec3 {
    Batch x, y, z;
};

Vec3 operator+(const Vec3& a, const Vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3 operator*(const Vec3& a, const Batch& s) { return {a.x * s, a.y * s, a.z * s}; }
Batch dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// 1/sqrt, not xsimd::rsqrt: that does not compile for AVX-512 in xsimd 8.1 and
// is only 12 bits on SSE/AVX2.
Batch inverse_length(const Vec3& a) { return Batch(1.0f) / xsimd::sqrt(dot(a, a)); }
Vec3 normalize(const Vec3& a) { return a * inverse_length(a); }

// max(x, 0) with x first: the hardware max returns the second operand for NaN,
// so a NaN dot product becomes 0 rather than spreading.
Batch max0(const Batch& x) { return xsimd::max(x, Batch(0.0f)); }

Vec3 load3(const float* x, const float* y, const float* z, std::size_t i) {
    return {xsimd::load_unaligned(x + i), xsimd::load_unaligned(y + i), xsimd::load_unaligned(z + i)};
}

// The GGX denominator's square root, n_dot_h²·(a² − 1) + 1; distribution_ggx is
// a2 / (π·denom²). The caller folds that division into the specular one.
Batch distribution_ggx_denom(const Batch& n_dot_h, const Batch& a2) {
    const Batch n_dot_h2 = n_dot_h * n_dot_h;
    return n_dot_h2 * (a2 - Batch(1.0f)) + Batch(1.0f);
}

// Schlick-GGX's denominator, n_dot_x·(1 − k) + k; geometry_schlick_ggx is n_dot_x / that.
Batch geometry_schlick_ggx_denom(const Batch& n_dot_x, const Batch& k) {
    return n_dot_x * (Batch(1.0f) - k) + k;
}

Batch geometry_schlick_ggx(const Batch& n_dot_x, const Batch& k) {
    return n_dot_x / geometry_schlick_ggx_denom(n_dot_x, k);
}

// (1 − cosθ)⁵ clamped to [0, 1], the Fresnel weight; pow(x, 5) by multiplication.
Batch fresnel_schlick_weight(const Batch& cos_theta) {
    const Batch x = xsimd::min(xsimd::max(Batch(1.0f) - cos_theta, Batch(0.0f)), Batch(1.0f));
    const Batch x2 = x * x;
    return x2 * x2 * x;
}

Batch fresnel_schlick(const Batch& weight, const Batch& f0) { return f0 + (Batch(1.0f) - f0) * weight; }

struct LightSoa {
    std::size_t count;
    const float* pos_x;
    const float* pos_y;
    const float* pos_z;
    const float* color_r;
    const float* color_g;
    const float* color_b;
};

void shade_batch(const FragmentInputs& in, std::size_t i, const LightSoa& lights, const Vec3& cam_pos,
                 const RadianceOutputs& out) {
    const Vec3 world_pos = load3(in.world_x, in.world_y, in.world_z, i);
    const Vec3 albedo = load3(in.albedo_r, in.albedo_g, in.albedo_b, i);
    const Batch metallic = xsimd::load_unaligned(in.metallic + i);
    const Batch roughness = xsimd::load_unaligned(in.roughness + i);
    const Batch ao = xsimd::load_unaligned(in.ao + i);

    const Vec3 n = normalize(load3(in.normal_x, in.normal_y, in.normal_z, i));
    const Vec3 v = normalize(cam_pos - world_pos);
    const Batch f0_base(0.04f);  // mix(vec3(0.04), albedo, metallic)
    const Vec3 f0 = {f0_base + (albedo.x - f0_base) * metallic, f0_base + (albedo.y - f0_base) * metallic,
                     f0_base + (albedo.z - f0_base) * metallic};

    // Per fragment, constant over the lights.
    const Batch a = roughness * roughness;
    const Batch a2 = a * a;
    const Batch r = roughness + Batch(1.0f);
    const Batch k = (r * r) * Batch(1.0f / 8.0f);
    const Batch n_dot_v = max0(dot(n, v));
    const Batch g_v = geometry_schlick_ggx(n_dot_v, k);
    const Batch spec_numerator = a2 * g_v * Batch(1.0f / kPi);  // the per-fragment part of NDF·G
    const Batch four_n_dot_v = Batch(4.0f) * n_dot_v;
    // k_D·albedo/π = (1 − F)·diffuse, k_D = (1 − F)·(1 − metallic)
    const Batch diffuse_scale = (Batch(1.0f) - metallic) * Batch(1.0f / kPi);
    const Vec3 diffuse = albedo * diffuse_scale;

    Vec3 lo = {Batch(0.0f), Batch(0.0f), Batch(0.0f)};
    for (std::size_t j = 0; j < lights.count; ++j) {
        const Vec3 to_light = Vec3{Batch(lights.pos_x[j]), Batch(lights.pos_y[j]), Batch(lights.pos_z[j])} - world_pos;
        const Batch inv_distance = inverse_length(to_light);
        const Vec3 l = to_light * inv_distance;
        const Vec3 half = v + l;
        const Batch inv_half_length = inverse_length(half);
        const Batch attenuation = inv_distance * inv_distance;  // radiance = color / distance²

        const Batch n_dot_l = max0(dot(n, l));
        const Batch n_dot_h = max0(dot(n, half) * inv_half_length);
        const Batch h_dot_v = max0(dot(half, v) * inv_half_length);

        // specular / F = NDF·G / (4·N·V·N·L + 0.0001)
        //   with NDF = a² / (π·denom²), G = G(N·V)·N·L / geometry_schlick_ggx_denom(N·L)
        const Batch ggx_denom = distribution_ggx_denom(n_dot_h, a2);
        const Batch spec_denominator = ggx_denom * ggx_denom * geometry_schlick_ggx_denom(n_dot_l, k) *
                                       (four_n_dot_v * n_dot_l + Batch(0.0001f));
        const Batch specular_scale = spec_numerator * n_dot_l / spec_denominator;

        const Batch fresnel_weight = fresnel_schlick_weight(h_dot_v);
        const Batch irradiance_scale = attenuation * n_dot_l;
        // lo += (k_D·albedo/π + specular) · radiance · N·L, per channel
        const auto add_channel = [&](Batch& lo_c, const Batch& f0_c, const Batch& diffuse_c, float color_c) {
            const Batch f = fresnel_schlick(fresnel_weight, f0_c);
            lo_c += ((Batch(1.0f) - f) * diffuse_c + specular_scale * f) * (irradiance_scale * Batch(color_c));
        };
        add_channel(lo.x, f0.x, diffuse.x, lights.color_r[j]);
        add_channel(lo.y, f0.y, diffuse.y, lights.color_g[j]);
        add_channel(lo.z, f0.z, diffuse.z, lights.color_b[j]);
    }

    const Batch ambient = Batch(0.03f) * ao;
    (albedo.x * ambient + lo.x).store_unaligned(out.r + i);
    (albedo.y * ambient + lo.y).store_unaligned(out.g + i);
    (albedo.z * ambient + lo.z).store_unaligned(out.b + i);
}

// Reinhard c / (c + 1), then c^(1/2.2) as exp(log(c)/2.2); c = 0 gives 0 (log would give -inf).
Batch display_from_radiance(const Batch& hdr) {
    const Batch c = hdr / (hdr + Batch(1.0f));
    const Batch encoded = xsimd::exp(xsimd::log(c) * Batch(1.0f / 2.2f));
    return xsimd::select(c > Batch(0.0f), encoded, Batch(0.0f));
}

}  // namespace

// Entry points, declared in shade_dispatch.cpp. The lights arrive as raw arrays,
// not ShadingLights, so no std::vector code is compiled here for a wider ISA
// and then shared (as an inline function) with the baseline callers.
void TESSERA_SIMD_ENTRY(shade_fragments)(const FragmentInputs& in, std::size_t light_count,
                                         const float* const light_arrays[6], const glm::vec3& cam_pos,
                                         const RadianceOutputs& out) {
    const LightSoa lights{light_count,     light_arrays[0], light_arrays[1], light_arrays[2],
                          light_arrays[3], light_arrays[4], light_arrays[5]};
    const Vec3 cam = {Batch(cam_pos.x), Batch(cam_pos.y), Batch(cam_pos.z)};
    const std::size_t end = padded_count(in.count);
    for (std::size_t i = 0; i < end; i += Batch::size) shade_batch(in, i, lights, cam, out);
}

void TESSERA_SIMD_ENTRY(tonemap_gamma)(std::size_t count, float* r, float* g, float* b) {
    const std::size_t end = padded_count(count);
    for (std::size_t i = 0; i < end; i += Batch::size) {
        display_from_radiance(xsimd::load_unaligned(r + i)).store_unaligned(r + i);
        display_from_radiance(xsimd::load_unaligned(g + i)).store_unaligned(g + i);
        display_from_radiance(xsimd::load_unaligned(b + i)).store_unaligned(b + i);
    }
}

}  // namespace tessera::shade
