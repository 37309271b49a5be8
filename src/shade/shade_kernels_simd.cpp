// The reference shader (pbr_reference.cpp) over xsimd batches: one fragment per
// lane, lights in the inner loop. Compiled once per ISA (cmake/SimdTargets.cmake):
// TESSERA_SIMD_ARCH is the xsimd architecture, TESSERA_SIMD_SUFFIX names this
// copy's entry points (shade_fragments_avx2, ...). Everything else lives in an
// anonymous namespace so the three copies never meet at link time.
//
// Same terms, same names as the reference; the differences are algebra only:
// per-fragment terms (a², k, G(N·V), F0, diffuse albedo) are hoisted out of the
// light loop, the normalizations multiply by 1/sqrt, and the specular fraction
// NDF·G / (4·N·V·N·L + 0.0001) is evaluated with one division, and the spot
// cone divides by cos inner − cos outer as a multiply by its reciprocal
// (ShadingLights works it out once per frame).
#include <cstddef>

#include "simd/kernel_prelude.hpp"

#include "shade/pbr_reference.hpp"
#include "shade/shade_kernels.hpp"
#include "shade/vec3_batch.hpp"

namespace tessera::shade {
namespace {

static_assert(kLanePadding % Batch::size == 0, "padding must hold whole vectors");

// max(x, 0) with x first: the hardware max returns the second operand for NaN,
// so a NaN dot product becomes 0 rather than spreading.
Batch max0(const Batch& x) { return xsimd::max(x, Batch(0.0f)); }

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

// A fragment batch's terms that do not depend on the light.
struct Surface {
    Vec3 world_pos, n, v, f0, diffuse;
    Batch a2, k, spec_numerator, four_n_dot_v;
};

// lo += one light's reflected radiance: l is the unit direction towards the
// light, attenuation the radiance arriving per unit of light colour. Always
// inlined: a call would move the accumulators through memory in the hot loop.
// Accumulate(lo_c, a, b) adds one channel's term a·b: all lanes, or (InRange)
// the lanes the light reaches. As one explicit fma (fused where the ISA has
// FMA): left to the compiler, whether it fuses would depend on the code
// around it, and a light would add different bits where a cluster needs the
// lane mask and where it does not.
template <class Accumulate>
[[gnu::always_inline]] inline void add_light(Vec3& lo, const Surface& s, const Vec3& l, const Batch& attenuation, float color_r,
                      float color_g, float color_b, Accumulate&& accumulate) {
    const Vec3 half = s.v + l;
    const Batch inv_half_length = inverse_length(half);

    const Batch n_dot_l = max0(dot(s.n, l));
    const Batch n_dot_h = max0(dot(s.n, half) * inv_half_length);
    const Batch h_dot_v = max0(dot(half, s.v) * inv_half_length);

    // specular / F = NDF·G / (4·N·V·N·L + 0.0001)
    //   with NDF = a² / (π·denom²), G = G(N·V)·N·L / geometry_schlick_ggx_denom(N·L)
    const Batch ggx_denom = distribution_ggx_denom(n_dot_h, s.a2);
    const Batch spec_denominator = ggx_denom * ggx_denom * geometry_schlick_ggx_denom(n_dot_l, s.k) *
                                   (s.four_n_dot_v * n_dot_l + Batch(0.0001f));
    const Batch specular_scale = s.spec_numerator * n_dot_l / spec_denominator;

    const Batch fresnel_weight = fresnel_schlick_weight(h_dot_v);
    const Batch irradiance_scale = attenuation * n_dot_l;
    // lo += (k_D·albedo/π + specular) · radiance · N·L, per channel
    const auto add_channel = [&](Batch& lo_c, const Batch& f0_c, const Batch& diffuse_c, float color_c) {
        const Batch f = fresnel_schlick(fresnel_weight, f0_c);
        accumulate(lo_c, (Batch(1.0f) - f) * diffuse_c + specular_scale * f, irradiance_scale * Batch(color_c));
    };
    add_channel(lo.x, s.f0.x, s.diffuse.x, color_r);
    add_channel(lo.y, s.f0.y, s.diffuse.y, color_g);
    add_channel(lo.z, s.f0.z, s.diffuse.z, color_b);
}

// Light k of the batch's list: light k itself, or (InRange) light index[k].
template <bool InRange>
[[gnu::always_inline]] inline std::size_t light_id(const LightArrays& lights, std::size_t k) {
    if constexpr (InRange) return lights.index[k] & kLightIndexMask;
    else return k;
}

// InRange: each light is cut at its range, lane by lane (shade_pbr_within_range);
// otherwise every light reaches every lane (shade_pbr).
template <bool InRange>
void shade_batch(const FragmentInputs& in, std::size_t i, const LightArrays& lights, const Vec3& cam_pos,
                 const RadianceOutputs& out) {
    Surface s;
    s.world_pos = load3(in.world_x, in.world_y, in.world_z, i);
    const Vec3 albedo = load3(in.albedo_r, in.albedo_g, in.albedo_b, i);
    const Batch metallic = xsimd::load_unaligned(in.metallic + i);
    const Batch roughness = xsimd::load_unaligned(in.roughness + i);
    const Batch ao = xsimd::load_unaligned(in.ao + i);

    s.n = normalize(load3(in.normal_x, in.normal_y, in.normal_z, i));
    s.v = normalize(cam_pos - s.world_pos);
    const Batch f0_base(0.04f);  // mix(vec3(0.04), albedo, metallic)
    s.f0 = {f0_base + (albedo.x - f0_base) * metallic, f0_base + (albedo.y - f0_base) * metallic,
            f0_base + (albedo.z - f0_base) * metallic};

    // Per fragment, constant over the lights.
    const Batch a = roughness * roughness;
    s.a2 = a * a;
    const Batch r = roughness + Batch(1.0f);
    s.k = (r * r) * Batch(1.0f / 8.0f);
    const Batch n_dot_v = max0(dot(s.n, s.v));
    const Batch g_v = geometry_schlick_ggx(n_dot_v, s.k);
    s.spec_numerator = s.a2 * g_v * Batch(1.0f / kPi);  // the per-fragment part of NDF·G
    s.four_n_dot_v = Batch(4.0f) * n_dot_v;
    // k_D·albedo/π = (1 − F)·diffuse, k_D = (1 − F)·(1 − metallic)
    const Batch diffuse_scale = (Batch(1.0f) - metallic) * Batch(1.0f / kPi);
    s.diffuse = albedo * diffuse_scale;

    Vec3 lo = {Batch(0.0f), Batch(0.0f), Batch(0.0f)};
    const auto add_all = [](Batch& lo_c, const Batch& a, const Batch& b) { lo_c = xsimd::fma(a, b, lo_c); };
    // A point or spot light, light k of the list: 1/distance to it, and which
    // lanes it reaches: all (without InRange, or kReachesAll: no lane test),
    // or those within range (`masked`). Returns false where it reaches none:
    // the light is skipped, which adds the same as adding nothing per lane.
    Mask reaches(true);
    bool masked = false;
    Batch inv_distance;
    // The lane test rounds as the scalar distance_squared does; the shading
    // itself is the uncut kernel's, so that a light adds the same bits to a lane
    // whether or not its cluster needed the test.
    const auto reach = [&](std::size_t k, std::size_t j, const Vec3& to_light) {
        if constexpr (InRange) {
            masked = !(lights.index[k] & kReachesAll);
            if (masked) {
                reaches = length_squared_unfused(to_light) <= Batch(lights.range_sq[j]);
                if (!xsimd::any(reaches)) return false;
            }
        }
        inv_distance = inverse_length(to_light);
        return true;
    };
    const auto add_masked = [&](Batch& lo_c, const Batch& a, const Batch& b) {
        lo_c = xsimd::select(reaches, xsimd::fma(a, b, lo_c), lo_c);
    };
    // add_light with the accumulation `reach` chose (two inlined copies: no mask in the common case).
    const auto add_reached_light = [&](const Vec3& l, const Batch& attenuation, std::size_t j) {
        if (InRange && masked)
            add_light(lo, s, l, attenuation, lights.color_r[j], lights.color_g[j], lights.color_b[j], add_masked);
        else
            add_light(lo, s, l, attenuation, lights.color_r[j], lights.color_g[j], lights.color_b[j], add_all);
    };

    // One loop per light type: the type is uniform over a light, so it costs no lane math.
    for (std::size_t k = 0; k < lights.spot_begin; ++k) {  // point: radiance = color / distance²
        const std::size_t j = light_id<InRange>(lights, k);
        const Vec3 to_light =
            Vec3{Batch(lights.pos_x[j]), Batch(lights.pos_y[j]), Batch(lights.pos_z[j])} - s.world_pos;
        if (!reach(k, j, to_light)) continue;
        add_reached_light(to_light * inv_distance, inv_distance * inv_distance, j);
    }
    for (std::size_t k = lights.spot_begin; k < lights.directional_begin; ++k) {  // spot: a point light × cone factor
        const std::size_t j = light_id<InRange>(lights, k);
        const Vec3 to_light =
            Vec3{Batch(lights.pos_x[j]), Batch(lights.pos_y[j]), Batch(lights.pos_z[j])} - s.world_pos;
        if (!reach(k, j, to_light)) continue;
        const Vec3 l = to_light * inv_distance;
        // cos θ = direction · (light to fragment) = −(direction · L)
        const Batch cos_theta = -dot(Vec3{Batch(lights.dir_x[j]), Batch(lights.dir_y[j]), Batch(lights.dir_z[j])}, l);
        const Batch cone = (cos_theta - Batch(lights.cos_outer[j])) * Batch(lights.inv_cone_width[j]);
        // clamp to [0, 1], NaN first so that it becomes 0
        const Batch cone_factor = xsimd::min(xsimd::max(cone, Batch(0.0f)), Batch(1.0f));
        add_reached_light(l, inv_distance * inv_distance * cone_factor, j);
    }
    for (std::size_t k = lights.directional_begin; k < lights.count; ++k) {  // directional: L = −direction, no attenuation
        const std::size_t j = light_id<InRange>(lights, k);
        const Vec3 l = {Batch(-lights.dir_x[j]), Batch(-lights.dir_y[j]), Batch(-lights.dir_z[j])};
        add_light(lo, s, l, Batch(1.0f), lights.color_r[j], lights.color_g[j], lights.color_b[j], add_all);
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

// Entry points, declared in shade_dispatch.cpp.
void TESSERA_SIMD_ENTRY(shade_fragments)(const FragmentInputs& in, const LightArrays& lights, const glm::vec3& cam_pos,
                                         const RadianceOutputs& out) {
    const Vec3 cam = {Batch(cam_pos.x), Batch(cam_pos.y), Batch(cam_pos.z)};
    const std::size_t end = padded_count(in.count);
    for (std::size_t i = 0; i < end; i += Batch::size) shade_batch<false>(in, i, lights, cam, out);
}

void TESSERA_SIMD_ENTRY(shade_fragments_in_range)(const FragmentInputs& in, const LightArrays& lights,
                                                  const glm::vec3& cam_pos, const RadianceOutputs& out) {
    const Vec3 cam = {Batch(cam_pos.x), Batch(cam_pos.y), Batch(cam_pos.z)};
    const std::size_t end = padded_count(in.count);
    for (std::size_t i = 0; i < end; i += Batch::size) shade_batch<true>(in, i, lights, cam, out);
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
