// The reference fragment shader in plain scalar C++: the LearnOpenGL direct
// lighting PBR shader of docs/reference/pbr_lighting.md, term for term and
// with the same names, so it can be checked by eye against the GLSL. The SIMD
// kernels (shade_kernels.hpp) are tested against it.
#pragma once

#include <span>

#include <glm/glm.hpp>

#include "tessera/scene.hpp"

namespace tessera::shade {

inline constexpr float kPi = 3.14159265359f;  // the GLSL's PI

// GGX / Trowbridge-Reitz normal distribution; alpha = roughness².
float distribution_ggx(const glm::vec3& n, const glm::vec3& h, float roughness);
// Schlick-GGX with k = (roughness + 1)² / 8 (direct lighting).
float geometry_schlick_ggx(float n_dot_v, float roughness);
float geometry_smith(const glm::vec3& n, const glm::vec3& v, const glm::vec3& l, float roughness);
glm::vec3 fresnel_schlick(float cos_theta, const glm::vec3& f0);

// The reference's spot falloff, clamp((cos θ − cos outer)/(cos inner − cos outer), 0, 1),
// θ being the angle between the light's direction and light_to_fragment (unit).
float spot_cone_factor(const Light& light, const glm::vec3& light_to_fragment);

// What one light sends to world_pos: l, the unit direction towards the light
// (the GLSL's L), and the radiance arriving along it.
struct IncidentLight {
    glm::vec3 l;
    glm::vec3 radiance;
};
IncidentLight incident_light(const Light& light, const glm::vec3& world_pos);

// Scene-linear HDR radiance leaving world_pos towards cam_pos (the GLSL's `color`
// before tonemapping), every light shaded whatever its range. normal need not be unit length: it is normalized here, as the GLSL does.
glm::vec3 shade_pbr(const glm::vec3& world_pos, const glm::vec3& normal, const Material& material,
                    const glm::vec3& cam_pos, std::span<const Light> lights);

// shade_pbr with shadows: light k's share of Lo times visibility[k], 1 − the
// shadow chapters' `shadow` (shadow_maps.hpp), as their
// ambient + (1.0 − shadow) · (diffuse + specular).
glm::vec3 shade_pbr(const glm::vec3& world_pos, const glm::vec3& normal, const Material& material,
                    const glm::vec3& cam_pos, std::span<const Light> lights, std::span<const float> visibility);

// |a − b|² as (dx² + dy²) + dz² in float, the order the SIMD kernels use too
// (without fused multiply-adds), so that every path draws a range's edge alike.
float distance_squared(const glm::vec3& a, const glm::vec3& b);
// Whether `light` lights world_pos at all: no range (Light::range = 0, and
// directional lights), or distance_squared(position, world_pos) <= range².
bool light_reaches(const Light& light, const glm::vec3& world_pos);
// shade_pbr with ranges: a light adds nothing to a point past its range (the
// renderer with light culling on). The same bits as shade_pbr over the lights
// that reach world_pos.
glm::vec3 shade_pbr_within_range(const glm::vec3& world_pos, const glm::vec3& normal, const Material& material,
                                 const glm::vec3& cam_pos, std::span<const Light> lights);

// shade_pbr's pieces: what does not depend on the light, one light's
// reflected radiance (the GLSL's loop body), and the ambient term.
struct ShadingPoint {
    glm::vec3 world_pos, n, v, f0;  // n, v unit
    const Material& material;
};
ShadingPoint shading_point(const glm::vec3& world_pos, const glm::vec3& normal, const Material& material,
                           const glm::vec3& cam_pos);
glm::vec3 reflected_radiance(const ShadingPoint& p, const Light& light);
glm::vec3 ambient_radiance(const Material& material);

// Reinhard c / (c + 1), then gamma c^(1/2.2): display-referred, in [0, 1].
glm::vec3 tonemap_reinhard(const glm::vec3& hdr);
glm::vec3 gamma_encode(const glm::vec3& linear);
inline glm::vec3 display_from_radiance(const glm::vec3& hdr) { return gamma_encode(tonemap_reinhard(hdr)); }

// An unlit material's radiance (KHR_materials_unlit): the radiance that
// display_from_radiance turns into the sRGB encoding of `color` (linear, each
// clamped to [0, 1]), so the base colour is the displayed colour, as glTF
// viewers show unlit materials (no tone curve on them). Inverts both steps:
// L = sRGB_encode(c)^2.2, radiance = L/(1 − L); c = 1 gives 1e6 (displays as 255).
glm::vec3 radiance_for_display(const glm::vec3& color);

}  // namespace tessera::shade
