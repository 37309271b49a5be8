// The reference shader (pbr_reference.cpp) over xsimd batches: one fragment per
// lane, lights in the inner loop. Compiled once per ISA (cmake/SimdTargets.cmake):
// TESSERA_SIMD_ARCH is the xsimd architecture, TESSERA_SIMD_SUFFIX names this
// copy's entry points (shade_fragments_avx2, ...). Everything else lives in an
// anonymous namespace so the three copies never meet at link time.
//
// Same terms as the reference; the differences are algebra and rounding, made
// so that a light costs few operations on the multiply-add pipes and a short
// chain of dependent ones (the light loop is bound by both):
//  - per-fragment terms (a², k, G(N·V), F0, diffuse albedo, N·V) are hoisted,
//    and so is the specular's per-fragment factor a²·G(N·V)/π;
//  - 1/distance is the hardware estimate refined by one Newton step
//    (inverse_sqrt_refined, ~2^-21 relative) instead of a square root and a
//    division;
//  - H is never normalized: with half = V + L, N·H = N·half/|half|, so
//    NDF = a²/(π·(N·H²·(a² − 1) + 1)²) = a²·|half|⁴/(π·(N·half²·(a² − 1) + |half|²)²),
//    N·half = N·V + N·L, and H·V = |half|/2 (V and L unit): the specular
//    fraction NDF·G/(4·N·V·N·L + 0.0001) takes one division, H·V one square root;
//  - F = F0 + (1 − F0)·w with w = (1 − H·V)⁵ is linear in w, and 1 − F = (1 − F0)(1 − w),
//    so a light's (k_D·albedo/π + specular)·radiance·N·L is, per channel,
//    diffuse·(1 − F0)·[E·(1 − w)] + F0·[E·spec] + (1 − F0)·[E·spec·w], E = radiance·N·L,
//    diffuse = albedo·(1 − metallic)/π: the kernel sums the bracketed terms
//    times the light's colour (LightTerms, Sums) and applies the per-fragment
//    factors once, after the lights;
//  - lights go two at a time (add_lights); 1-4 point lights alone, uncut (a
//    scene's few lights without ranges), take copies with the pairs unrolled
//    and the lights broadcast once per call; where every light is grey, the
//    uncut kernels sum one colour channel (shade_fragment_runs; same bits).
// Built without contraction (src/shade/CMakeLists.txt): every multiply-add that
// fuses is an explicit fma, so that a copy of the kernel inlined into another
// loop (plain runs, unrolled lights) fuses the same ones. Left to g++, the
// AVX-512 copy fused differently in the run loops than in shade_fragments
// (seen on real AVX-512 hardware: last-bit differences between the two paths).
// The explicit fmas are where g++ fused the AVX2 copy, so its bits are unchanged.
// The result stays within the tested bound of the reference
// (tests/shade/test_shade_kernels.cpp). The range test rounds exactly as the
// reference's, so every ISA cuts the same lanes, and a light adds the same bits
// to a lane whatever list it comes in (light culling gives the same image for
// any tile or cluster size).
#include <array>
#include <bit>
#include <cstdint>
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

// 1/sqrt(x): the hardware estimate (12 bits on SSE/AVX2; AVX-512's 14-bit one
// by intrinsic, since xsimd 8.1's rsqrt does not compile there) and one Newton
// step r·(3 − x·r²)/2, which squares the estimate's relative error (≤ 1.5·ε²).
// x = 0 gives NaN (where 1/sqrt gives inf: the reference's normalize(0) is NaN too).
Batch inverse_sqrt_refined(const Batch& x) {
#if defined(__AVX512F__)
    const Batch r = _mm512_rsqrt14_ps(x);
#else
    const Batch r = xsimd::rsqrt(x);
#endif
    return (r * Batch(0.5f)) * fnma(x * r, r, Batch(3.0f));
}

// A fragment batch's terms that do not depend on the light.
struct Surface {
    Vec3 world_pos, n, v;
    Batch n_dot_v_raw;     // N·V unclamped
    Batch a2_minus_1;      // a² − 1 of distribution_ggx
    Batch k, one_minus_k;  // geometry_schlick_ggx's k
    Batch four_n_dot_v;
    // The batch's shadow visibility planes (FragmentInputs::visibility from this
    // batch's first fragment), or null.
    const float* visibility = nullptr;
    std::size_t visibility_stride = 0;
};

// One light's share of a batch, per unit of light colour: E·(1 − w), E·spec' and
// E·spec'·w, E the radiance·N·L arriving, spec' = NDF·G/(4·N·V·N·L + 0.0001)
// without its per-fragment factor a²·G(N·V)/π, w the Fresnel weight (1 − H·V)⁵.
struct LightTerms {
    Batch diffuse, specular, specular_w;
};

// The light's terms: to_light points from the fragment towards it,
// inv_length = 1/|to_light| (the light's L = to_light·inv_length),
// attenuation the radiance arriving per unit of light colour.
[[gnu::always_inline]] inline LightTerms light_terms(const Surface& s, const Vec3& to_light, const Batch& inv_length,
                                                     const Batch& attenuation) {
    // half = V + L, not normalized: N·H = N·half/|half|. Formed as a vector
    // (not as |V|² + 2·V·L + |L|²) so that |half|² − N·half², which the GGX
    // term cancels down to, rounds like the reference's.
    const Vec3 half = {fma(to_light.x, inv_length, s.v.x), fma(to_light.y, inv_length, s.v.y),
                       fma(to_light.z, inv_length, s.v.z)};
    const Batch half_sq = dot(half, half);
    const Batch n_dot_to_light = dot(s.n, to_light);
    const Batch n_dot_l = max0(n_dot_to_light * inv_length);
    const Batch n_dot_half = max0(fma(n_dot_to_light, inv_length, s.n_dot_v_raw));

    // E·spec' = E·N·L·|half|⁴ / (ggx²·(N·L·(1 − k) + k)·(4·N·V·N·L + 0.0001)),
    // ggx = N·half²·(a² − 1) + |half|²: one division (a Newton-refined
    // reciprocal measured no faster: the divider takes ~2 multiply-add slots).
    const Batch ggx = fma(n_dot_half * n_dot_half, s.a2_minus_1, half_sq);
    const Batch g_l_denominator = fma(n_dot_l, s.one_minus_k, s.k);
    const Batch cook_torrance_denominator = fma(s.four_n_dot_v, n_dot_l, Batch(0.0001f));
    const Batch denominator = (ggx * ggx) * (g_l_denominator * cook_torrance_denominator);
    const Batch irradiance = attenuation * n_dot_l;  // E
    const Batch e_spec = ((irradiance * n_dot_l) * (half_sq * half_sq)) / denominator;

    // H·V = (V + L)·V/|half| = (1 + L·V)/|half| = |half|/2 for unit V and L;
    // w = x⁵, x = 1 − H·V clamped at 0 (H·V may round above 1), by
    // multiplication, as E·x·x⁴ to shorten the chain.
    const Batch x = max0(fnma(Batch(0.5f), xsimd::sqrt(half_sq), Batch(1.0f)));
    const Batch x2 = x * x;
    const Batch x4 = x2 * x2;
    return {fnma(irradiance * x, x4, irradiance), e_spec, (e_spec * x) * x4};
}

// The terms in the lanes of `reaches`, 0 elsewhere: in those lanes the bits of
// the unmasked terms, so that a light adds the same whether or not its cluster
// needed the lane test.
LightTerms masked(const LightTerms& t, const Mask& reaches) {
    return {xsimd::select(reaches, t.diffuse, Batch(0.0f)), xsimd::select(reaches, t.specular, Batch(0.0f)),
            xsimd::select(reaches, t.specular_w, Batch(0.0f))};
}

// Per channel, Σ over lights of colour × LightTerms.
struct Sums {
    Vec3 diffuse, specular, specular_w;
};

// sums += colour × terms by explicit fmas (fused where the ISA has FMA): left to
// the compiler, fusing would depend on the code around them, and a light would
// add different bits where a cluster needs the mask and where it does not.
// Adding zero terms leaves the sums' bits as they were.
template <class Colour>
[[gnu::always_inline]] inline void accumulate(Sums& sums, const LightTerms& t, const Colour& color_r,
                                              const Colour& color_g, const Colour& color_b) {
    const auto add_channel = [&](const Colour& color, Batch& diffuse, Batch& specular, Batch& specular_w) {
        const Batch c(color);
        diffuse = fma(c, t.diffuse, diffuse);
        specular = fma(c, t.specular, specular);
        specular_w = fma(c, t.specular_w, specular_w);
    };
    add_channel(color_r, sums.diffuse.x, sums.specular.x, sums.specular_w.x);
    add_channel(color_g, sums.diffuse.y, sums.specular.y, sums.specular_w.y);
    add_channel(color_b, sums.diffuse.z, sums.specular.z, sums.specular_w.z);
}

// Light k of the batch's list: light k itself, or (InRange) light index[k].
template <bool InRange, class Lights>
[[gnu::always_inline]] inline std::size_t light_id(const Lights& lights, std::size_t k) {
    if constexpr (InRange) return lights.index[k] & kLightIndexMask;
    else return k;
}

enum class LightKind { point, spot, directional };

// The vector from the batch's fragments to light j: towards its position, or
// (directional) against its direction.
template <LightKind Kind, class Lights>
[[gnu::always_inline]] inline Vec3 to_light(const Surface& s, const Lights& lights, std::size_t j) {
    if constexpr (Kind == LightKind::directional)
        return {Batch(-lights.dir_x[j]), Batch(-lights.dir_y[j]), Batch(-lights.dir_z[j])};
    else
        return Vec3{Batch(lights.pos_x[j]), Batch(lights.pos_y[j]), Batch(lights.pos_z[j])} - s.world_pos;
}

// Light j's terms, given to_light and (point, spot) its length² as the range test rounds it.
template <LightKind Kind, class Lights>
[[gnu::always_inline]] inline LightTerms terms_of(const Surface& s, const Lights& lights, std::size_t j,
                                                  const Vec3& to, const Batch& distance_sq) {
    if constexpr (Kind == LightKind::directional) {  // L = −direction, no attenuation
        return light_terms(s, to, Batch(1.0f), Batch(1.0f));
    } else {
        const Batch inv_distance = inverse_sqrt_refined(distance_sq);
        const Batch attenuation = inv_distance * inv_distance;  // radiance = color / distance²
        if constexpr (Kind == LightKind::point) {
            return light_terms(s, to, inv_distance, attenuation);
        } else {  // spot: a point light × cone factor
            // cos θ = direction · (light to fragment) = −(direction · L)
            const Vec3 direction{Batch(lights.dir_x[j]), Batch(lights.dir_y[j]), Batch(lights.dir_z[j])};
            const Batch cos_theta = -dot(direction, to) * inv_distance;
            const Batch cone = (cos_theta - Batch(lights.cos_outer[j])) * Batch(lights.inv_cone_width[j]);
            // clamp to [0, 1], NaN first so that it becomes 0
            const Batch cone_factor = xsimd::min(xsimd::max(cone, Batch(0.0f)), Batch(1.0f));
            return light_terms(s, to, inv_distance, attenuation * cone_factor);
        }
    }
}

// Which lanes list entry k (light j) reaches: every lane for a kReachesAll
// entry (its threshold is +inf), else those with distance² <= range².
[[gnu::always_inline]] inline Mask reaches(const LightArrays& lights, std::size_t k, std::size_t j,
                                           const Batch& distance_sq) {
    const bool all = lights.index[k] & kReachesAll;
    return distance_sq <= Batch(all ? INFINITY : lights.range_sq[j]);
}

// Whether every light of the list is grey (its three colour channels the same
// bits): each channel's sums then take the same operations on the same values,
// so the kernels sum the red channel alone and use it for all three.
template <class Lights>
inline constexpr bool grey_lights = false;

// Light j's terms times its shadow visibility, where it has a shadow map (the
// reference's visibility · reflected_radiance); the terms themselves otherwise.
// Fixed point-light lists (BroadcastPoints) are never shadowed.
template <class Lights>
[[gnu::always_inline]] inline LightTerms shadowed(const LightTerms& t, const Surface& s, const Lights& lights,
                                                  std::size_t j) {
    if constexpr (requires { lights.shadow_slot; }) {
        if (s.visibility != nullptr && lights.shadow_slot != nullptr && lights.shadow_slot[j] >= 0) {
            const Batch v = xsimd::load_unaligned(s.visibility + std::size_t(lights.shadow_slot[j]) * s.visibility_stride);
            return {t.diffuse * v, t.specular * v, t.specular_w * v};
        }
    }
    return t;
}

// sums += light j's colour × its terms (times its shadow visibility).
template <class Lights>
[[gnu::always_inline]] inline void add(Sums& sums, const Surface& s, const Lights& lights, std::size_t j,
                                       const LightTerms& unshadowed) {
    const LightTerms t = shadowed(unshadowed, s, lights, j);
    if constexpr (grey_lights<Lights>) {
        const Batch c(lights.color_r[j]);
        sums.diffuse.x = fma(c, t.diffuse, sums.diffuse.x);
        sums.specular.x = fma(c, t.specular, sums.specular.x);
        sums.specular_w.x = fma(c, t.specular_w, sums.specular_w.x);
    } else {
        accumulate(sums, t, lights.color_r[j], lights.color_g[j], lights.color_b[j]);
    }
}

// Lights k and k + 1 of the list, both of type Kind: their instructions are
// independent, so the core overlaps one light's long chain of dependent
// operations (1/distance, V + L, the GGX term, the division) with the other's
// rather than waiting for it. With InRange, each point or spot light counts
// only in the lanes within its range, unless its list entry says it reaches
// them all (kReachesAll).
template <bool InRange, LightKind Kind, class Lights>
[[gnu::always_inline]] inline void add_light_pair(Sums& sums, const Surface& s, const Lights& lights,
                                                  std::size_t k) {
    constexpr bool cut = InRange && Kind != LightKind::directional;
    const std::size_t j0 = light_id<InRange>(lights, k), j1 = light_id<InRange>(lights, k + 1);
    const Vec3 to0 = to_light<Kind>(s, lights, j0), to1 = to_light<Kind>(s, lights, j1);
    Batch distance_sq0(0.0f), distance_sq1(0.0f);
    if constexpr (Kind != LightKind::directional) {
        distance_sq0 = length_squared_unfused(to0);
        distance_sq1 = length_squared_unfused(to1);
    }
    if constexpr (cut) {
        const Mask reach0 = reaches(lights, k, j0, distance_sq0), reach1 = reaches(lights, k + 1, j1, distance_sq1);
        if (!xsimd::all(reach0 & reach1)) {  // some lane out of range of either
            if (!xsimd::any(reach0 | reach1)) return;
            const LightTerms t0 = masked(terms_of<Kind>(s, lights, j0, to0, distance_sq0), reach0);
            const LightTerms t1 = masked(terms_of<Kind>(s, lights, j1, to1, distance_sq1), reach1);
            add(sums, s, lights, j0, t0);
            add(sums, s, lights, j1, t1);
            return;
        }
    }
    const LightTerms t0 = terms_of<Kind>(s, lights, j0, to0, distance_sq0);
    const LightTerms t1 = terms_of<Kind>(s, lights, j1, to1, distance_sq1);
    add(sums, s, lights, j0, t0);
    add(sums, s, lights, j1, t1);
}

// Light k of the list alone, as add_light_pair.
template <bool InRange, LightKind Kind, class Lights>
[[gnu::always_inline]] inline void add_light(Sums& sums, const Surface& s, const Lights& lights, std::size_t k) {
    constexpr bool cut = InRange && Kind != LightKind::directional;
    const std::size_t j = light_id<InRange>(lights, k);
    const Vec3 to = to_light<Kind>(s, lights, j);
    Batch distance_sq(0.0f);
    if constexpr (Kind != LightKind::directional) distance_sq = length_squared_unfused(to);
    if constexpr (cut) {
        const Mask reach = reaches(lights, k, j, distance_sq);
        if (!xsimd::all(reach)) {
            if (xsimd::any(reach)) add(sums, s, lights, j, masked(terms_of<Kind>(s, lights, j, to, distance_sq), reach));
            return;
        }
    }
    add(sums, s, lights, j, terms_of<Kind>(s, lights, j, to, distance_sq));
}

// Adds the lights [begin, end) of one type group, two at a time.
template <bool InRange, LightKind Kind>
[[gnu::always_inline]] inline void add_lights(Sums& sums, const Surface& s, const LightArrays& lights,
                                              std::size_t begin, std::size_t end) {
    std::size_t k = begin;
    for (; k + 2 <= end; k += 2) add_light_pair<InRange, Kind>(sums, s, lights, k);
    if (k < end) add_light<InRange, Kind>(sums, s, lights, k);
}

// The list's lights, in its order. FixedPoints = 0: any list, its type groups
// and length read at run time. FixedPoints > 0: the list is that many point
// lights and nothing else, uncut (a scene's few lights without ranges, such as
// the reference's four): the pairs unroll, the loop and the empty groups'
// code vanish, and the compiler keeps more of the batch in registers. The same
// operations on the same lights in the same order either way, so the same bits.
template <bool InRange, std::size_t FixedPoints, class Lights>
[[gnu::always_inline]] inline void add_all_lights(Sums& sums, const Surface& s, const Lights& lights) {
    if constexpr (FixedPoints > 0) {
        static_assert(!InRange, "a fixed list is uncut");
        static_assert(FixedPoints <= 5, "two pairs at most, and one more");
        if constexpr (FixedPoints >= 2) add_light_pair<false, LightKind::point>(sums, s, lights, 0);
        if constexpr (FixedPoints >= 4) add_light_pair<false, LightKind::point>(sums, s, lights, 2);
        if constexpr (FixedPoints % 2 == 1) add_light<false, LightKind::point>(sums, s, lights, FixedPoints - 1);
    } else {
        add_lights<InRange, LightKind::point>(sums, s, lights, 0, lights.spot_begin);
        add_lights<InRange, LightKind::spot>(sums, s, lights, lights.spot_begin, lights.directional_begin);
        add_lights<InRange, LightKind::directional>(sums, s, lights, lights.directional_begin, lights.count);
    }
}

// A batch's material, per lane or the same in every lane.
struct MaterialBatch {
    Vec3 albedo;
    Batch metallic, roughness, ao;
};

MaterialBatch load_material(const FragmentInputs& in, std::size_t i) {
    return {load3(in.albedo_r, in.albedo_g, in.albedo_b, i), xsimd::load_unaligned(in.metallic + i),
            xsimd::load_unaligned(in.roughness + i), xsimd::load_unaligned(in.ao + i)};
}

// The batch of fragments i .. i + Batch::size of material m. InRange: each
// light is cut at its range, lane by lane (shade_pbr_within_range); otherwise
// every light reaches every lane (shade_pbr). Inlined into a loop over a run of
// one material, the terms of the material alone are worked out once per run
// (the compiler hoists them), with the same operations, so the same bits.
template <bool InRange, std::size_t FixedPoints = 0, class Lights = LightArrays>
[[gnu::always_inline]] inline void shade_batch_of(const FragmentInputs& in, std::size_t i, const MaterialBatch& m,
                                                  const Lights& lights, const Vec3& cam_pos,
                                                  const RadianceOutputs& out) {
    Surface s;
    s.world_pos = load3(in.world_x, in.world_y, in.world_z, i);
    if (in.visibility != nullptr) s.visibility = in.visibility + i, s.visibility_stride = in.visibility_stride;
    const Vec3& albedo = m.albedo;
    const Batch& metallic = m.metallic;
    const Batch& roughness = m.roughness;
    const Batch& ao = m.ao;

    // Per fragment, constant over the lights: exact 1/sqrt and divisions are cheap here.
    s.n = normalize(load3(in.normal_x, in.normal_y, in.normal_z, i));
    s.v = normalize(cam_pos - s.world_pos);
    const Batch f0_base(0.04f);  // mix(vec3(0.04), albedo, metallic)
    const Vec3 f0 = {fma(albedo.x - f0_base, metallic, f0_base), fma(albedo.y - f0_base, metallic, f0_base),
                     fma(albedo.z - f0_base, metallic, f0_base)};
    const Batch a = roughness * roughness;
    const Batch a2 = a * a;
    s.a2_minus_1 = a2 - Batch(1.0f);
    const Batch r = roughness + Batch(1.0f);
    s.k = (r * r) * Batch(1.0f / 8.0f);
    s.one_minus_k = Batch(1.0f) - s.k;
    s.n_dot_v_raw = dot(s.n, s.v);
    const Batch n_dot_v = max0(s.n_dot_v_raw);
    const Batch g_v = n_dot_v / fma(n_dot_v, s.one_minus_k, s.k);  // geometry_schlick_ggx(N·V)
    const Batch spec_numerator = a2 * g_v * Batch(1.0f / kPi);  // a²·G(N·V)/π: spec = spec_numerator·spec'

    s.four_n_dot_v = Batch(4.0f) * n_dot_v;

    // Zeros by member: the chained assignment of one Vec3 made g++ build the
    // zeros in 16-byte halves on the stack and reload them as whole vectors in
    // the run loop, a store-forwarding stall per batch.
    const Batch zero(0.0f);
    Sums sums{{zero, zero, zero}, {zero, zero, zero}, {zero, zero, zero}};
    add_all_lights<InRange, FixedPoints>(sums, s, lights);

    // Lo = diffuse·(1 − F0)·Σ E(1 − w) + F0·Σ E·spec + (1 − F0)·Σ E·spec·w, with
    // diffuse = albedo·(1 − metallic)/π (k_D·albedo/π = (1 − F)·diffuse, 1 − F = (1 − F0)(1 − w)).
    const Batch diffuse_scale = (Batch(1.0f) - metallic) * Batch(1.0f / kPi);
    const Batch ambient = Batch(0.03f) * ao;
    const auto radiance = [&](const Batch& albedo_c, const Batch& f0_c, const Batch& diffuse_sum,
                              const Batch& specular_sum, const Batch& specular_w_sum) {
        const Batch diffuse_and_w = fma(spec_numerator, specular_w_sum, (albedo_c * diffuse_scale) * diffuse_sum);
        const Batch lo = fma(f0_c * spec_numerator, specular_sum, (Batch(1.0f) - f0_c) * diffuse_and_w);
        return fma(albedo_c, ambient, lo);
    };
    if constexpr (grey_lights<Lights>) {  // green and blue summed as red
        sums.diffuse.y = sums.diffuse.z = sums.diffuse.x;
        sums.specular.y = sums.specular.z = sums.specular.x;
        sums.specular_w.y = sums.specular_w.z = sums.specular_w.x;
    }
    radiance(albedo.x, f0.x, sums.diffuse.x, sums.specular.x, sums.specular_w.x).store_unaligned(out.r + i);
    radiance(albedo.y, f0.y, sums.diffuse.y, sums.specular.y, sums.specular_w.y).store_unaligned(out.g + i);
    radiance(albedo.z, f0.z, sums.diffuse.z, sums.specular.z, sums.specular_w.z).store_unaligned(out.b + i);
}

// Each fragment its material from the material channels.
template <bool InRange, std::size_t FixedPoints = 0, class Lights = LightArrays>
void shade_batch(const FragmentInputs& in, std::size_t i, const Lights& lights, const Vec3& cam_pos,
                 const RadianceOutputs& out) {
    shade_batch_of<InRange, FixedPoints>(in, i, load_material(in, i), lights, cam_pos, out);
}

// Batches [begin, end) of fragments all of material `material`.
template <std::size_t FixedPoints, class Lights>
void shade_uniform_batches(const FragmentInputs& in, std::size_t begin, std::size_t end, const Material& material,
                           const Lights& lights, const Vec3& cam_pos, const RadianceOutputs& out) {
    const MaterialBatch m = {{Batch(material.albedo.r), Batch(material.albedo.g), Batch(material.albedo.b)},
                             Batch(material.metallic), Batch(material.roughness), Batch(material.ao)};
    for (std::size_t i = begin; i < end; i += Batch::size)
        shade_batch_of<false, FixedPoints>(in, i, m, lights, cam_pos, out);
}

// The FixedPoints point lights of a LightArrays, each value broadcast once per
// call rather than once per batch: the kernel reads them as memory operands.
// Grey: every light is grey (grey_lights), and only the red channel is kept.
template <std::size_t FixedPoints, bool Grey>
struct BroadcastPoints {
    static constexpr std::size_t count = FixedPoints;
    std::array<Batch, FixedPoints> pos_x, pos_y, pos_z, color_r, color_g, color_b;
    explicit BroadcastPoints(const LightArrays& lights) {
        for (std::size_t j = 0; j < FixedPoints; ++j) {
            pos_x[j] = Batch(lights.pos_x[j]), pos_y[j] = Batch(lights.pos_y[j]), pos_z[j] = Batch(lights.pos_z[j]);
            color_r[j] = Batch(lights.color_r[j]);
            if constexpr (!Grey) color_g[j] = Batch(lights.color_g[j]), color_b[j] = Batch(lights.color_b[j]);
        }
    }
};
template <std::size_t FixedPoints>
inline constexpr bool grey_lights<BroadcastPoints<FixedPoints, true>> = true;

// Any list whose lights are all grey.
struct GreyLightArrays : LightArrays {};
template <>
inline constexpr bool grey_lights<GreyLightArrays> = true;

// Whether every light's three colour channels have the same bits (true without lights).
bool all_grey(const LightArrays& lights) {
    const auto bits = [](float c) { return std::bit_cast<std::uint32_t>(c); };
    for (std::size_t j = 0; j < lights.count; ++j) {
        const std::uint32_t r = bits(lights.color_r[j]);
        if (bits(lights.color_g[j]) != r || bits(lights.color_b[j]) != r) return false;
    }
    return true;
}

// shade_fragment_runs over a light list as add_all_lights<false, FixedPoints> takes it.
template <std::size_t FixedPoints, bool Grey = false>
void shade_runs(const FragmentInputs& in, const MaterialRun* runs, std::size_t run_count,
                const LightArrays& light_arrays, const Vec3& cam, const RadianceOutputs& out) {
    const auto lights = [&] {
        if constexpr (FixedPoints > 0) return BroadcastPoints<FixedPoints, Grey>(light_arrays);
        else if constexpr (Grey) return GreyLightArrays{light_arrays};
        else return light_arrays;
    }();
    const std::size_t end = padded_count(in.count);
    std::size_t i = 0;
    for (std::size_t r = 0; r < run_count && i < end; ++r) {
        const MaterialRun& run = runs[r];
        // The run's last lane, the padding being the last run's; its batches
        // wholly inside it (from i, the first batch the runs before did not
        // shade), and then one it shares with the next run, if any.
        const std::size_t run_end = r + 1 == run_count ? end : run.end;
        const std::size_t inside_end = run_end / Batch::size * Batch::size;
        if (run.plain && i >= run.begin && i < inside_end) {
            shade_uniform_batches<FixedPoints>(in, i, inside_end, *run.material, lights, cam, out);
            i = inside_end;
        }
        for (; i < run_end; i += Batch::size) shade_batch<false, FixedPoints>(in, i, lights, cam, out);
    }
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

void TESSERA_SIMD_ENTRY(shade_fragment_runs)(const FragmentInputs& in, const MaterialRun* runs, std::size_t run_count,
                                             const LightArrays& lights, const glm::vec3& cam_pos,
                                             const RadianceOutputs& out) {
    const Vec3 cam = {Batch(cam_pos.x), Batch(cam_pos.y), Batch(cam_pos.z)};
    // A few point lights and nothing else (the reference's scene has four):
    // the list unrolled (add_all_lights). Any list whose lights are all grey
    // (grey_lights; the reference's are white): one channel of sums.
    const bool points_only = lights.index == nullptr && lights.spot_begin == lights.count &&
                             (in.visibility == nullptr || lights.shadow_slot == nullptr);
    const bool grey = all_grey(lights);
    switch (points_only ? lights.count : 0) {
        case 1: return grey ? shade_runs<1, true>(in, runs, run_count, lights, cam, out)
                            : shade_runs<1>(in, runs, run_count, lights, cam, out);
        case 2: return grey ? shade_runs<2, true>(in, runs, run_count, lights, cam, out)
                            : shade_runs<2>(in, runs, run_count, lights, cam, out);
        case 3: return grey ? shade_runs<3, true>(in, runs, run_count, lights, cam, out)
                            : shade_runs<3>(in, runs, run_count, lights, cam, out);
        case 4: return grey ? shade_runs<4, true>(in, runs, run_count, lights, cam, out)
                            : shade_runs<4>(in, runs, run_count, lights, cam, out);
        default: return grey ? shade_runs<0, true>(in, runs, run_count, lights, cam, out)
                             : shade_runs<0>(in, runs, run_count, lights, cam, out);
    }
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
