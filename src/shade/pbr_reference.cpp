// The LearnOpenGL direct-lighting PBR fragment shader, line for line
// (docs/reference/pbr_lighting.md). Plain float math, no shortcuts: this is
// what the SIMD kernels are measured against.
#include "shade/pbr_reference.hpp"

#include <cmath>

namespace tessera::shade {

float distribution_ggx(const glm::vec3& n, const glm::vec3& h, float roughness) {
    const float a = roughness * roughness;
    const float a2 = a * a;
    const float n_dot_h = glm::max(glm::dot(n, h), 0.0f);
    const float n_dot_h2 = n_dot_h * n_dot_h;
    const float denom = (n_dot_h2 * (a2 - 1.0f) + 1.0f);
    return a2 / (kPi * denom * denom);
}

float geometry_schlick_ggx(float n_dot_v, float roughness) {
    const float r = (roughness + 1.0f);
    const float k = (r * r) / 8.0f;
    return n_dot_v / (n_dot_v * (1.0f - k) + k);
}

float geometry_smith(const glm::vec3& n, const glm::vec3& v, const glm::vec3& l, float roughness) {
    return geometry_schlick_ggx(glm::max(glm::dot(n, l), 0.0f), roughness) *
           geometry_schlick_ggx(glm::max(glm::dot(n, v), 0.0f), roughness);
}

glm::vec3 fresnel_schlick(float cos_theta, const glm::vec3& f0) {
    return f0 + (1.0f - f0) * std::pow(glm::clamp(1.0f - cos_theta, 0.0f, 1.0f), 5.0f);
}

float spot_cone_factor(const Light& light, const glm::vec3& light_to_fragment) {
    const float cos_theta = glm::dot(light.direction, light_to_fragment);
    const float cos_inner = std::cos(glm::radians(light.inner_cone_degrees));
    const float cos_outer = std::cos(glm::radians(light.outer_cone_degrees));
    return glm::clamp((cos_theta - cos_outer) / (cos_inner - cos_outer), 0.0f, 1.0f);
}

IncidentLight incident_light(const Light& light, const glm::vec3& world_pos) {
    if (light.type == LightType::directional) return {-light.direction, light.color};  // no attenuation
    // Point and spot: the GLSL's loop body.
    const glm::vec3 l = glm::normalize(light.position - world_pos);
    const float distance = glm::length(light.position - world_pos);
    const glm::vec3 radiance = light.color / (distance * distance);
    if (light.type == LightType::point) return {l, radiance};
    return {l, radiance * spot_cone_factor(light, -l)};
}

ShadingPoint shading_point(const glm::vec3& world_pos, const glm::vec3& normal, const Material& material,
                           const glm::vec3& cam_pos) {
    return {world_pos, glm::normalize(normal), glm::normalize(cam_pos - world_pos),
            glm::mix(glm::vec3(0.04f), material.albedo, material.metallic), material};
}

glm::vec3 reflected_radiance(const ShadingPoint& p, const Light& light) {
    const glm::vec3& albedo = p.material.albedo;
    const float metallic = p.material.metallic;
    const float roughness = p.material.roughness;
    const glm::vec3 &n = p.n, &v = p.v;
    const auto [l, radiance] = incident_light(light, p.world_pos);
    const glm::vec3 h = glm::normalize(v + l);

    const float ndf = distribution_ggx(n, h, roughness);
    const float g = geometry_smith(n, v, l, roughness);
    const glm::vec3 f = fresnel_schlick(glm::max(glm::dot(h, v), 0.0f), p.f0);

    const glm::vec3 k_d = (glm::vec3(1.0f) - f) * (1.0f - metallic);
    const glm::vec3 specular =
        ndf * g * f / (4.0f * glm::max(glm::dot(n, v), 0.0f) * glm::max(glm::dot(n, l), 0.0f) + 0.0001f);
    const float n_dot_l = glm::max(glm::dot(n, l), 0.0f);
    return (k_d * albedo / kPi + specular) * radiance * n_dot_l;
}

glm::vec3 ambient_radiance(const Material& material) { return glm::vec3(0.03f) * material.albedo * material.ao; }

glm::vec3 shade_pbr(const glm::vec3& world_pos, const glm::vec3& normal, const Material& material,
                    const glm::vec3& cam_pos, std::span<const Light> lights) {
    const ShadingPoint p = shading_point(world_pos, normal, material, cam_pos);
    glm::vec3 lo(0.0f);
    for (const Light& light : lights) lo += reflected_radiance(p, light);
    return ambient_radiance(material) + lo;
}

glm::vec3 shade_pbr(const glm::vec3& world_pos, const glm::vec3& normal, const Material& material,
                    const glm::vec3& cam_pos, std::span<const Light> lights, std::span<const float> visibility) {
    const ShadingPoint p = shading_point(world_pos, normal, material, cam_pos);
    glm::vec3 lo(0.0f);
    for (std::size_t k = 0; k < lights.size(); ++k) lo += visibility[k] * reflected_radiance(p, lights[k]);
    return ambient_radiance(material) + lo;
}

float distance_squared(const glm::vec3& a, const glm::vec3& b) {
    const glm::vec3 d = a - b;
    return (d.x * d.x + d.y * d.y) + d.z * d.z;
}

bool light_reaches(const Light& light, const glm::vec3& world_pos) {
    return light.type == LightType::directional || !(light.range > 0.0f) ||
           distance_squared(light.position, world_pos) <= light.range * light.range;
}

glm::vec3 shade_pbr_within_range(const glm::vec3& world_pos, const glm::vec3& normal, const Material& material,
                                 const glm::vec3& cam_pos, std::span<const Light> lights) {
    const ShadingPoint p = shading_point(world_pos, normal, material, cam_pos);
    glm::vec3 lo(0.0f);
    for (const Light& light : lights)
        if (light_reaches(light, world_pos)) lo += reflected_radiance(p, light);
    return ambient_radiance(material) + lo;
}

glm::vec3 tonemap_reinhard(const glm::vec3& hdr) { return hdr / (hdr + glm::vec3(1.0f)); }

glm::vec3 radiance_for_display(const glm::vec3& color) {
    glm::vec3 radiance;
    for (int c = 0; c < 3; ++c) {
        const float x = color[c] > 0.0f ? (color[c] < 1.0f ? color[c] : 1.0f) : 0.0f;  // NaN → 0
        const float encoded = x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
        const float tonemapped = std::pow(encoded, 2.2f);
        radiance[c] = tonemapped >= 1.0f ? 1e6f : tonemapped / (1.0f - tonemapped);
    }
    return radiance;
}

glm::vec3 gamma_encode(const glm::vec3& linear) {
    const float inv_gamma = 1.0f / 2.2f;
    return {std::pow(linear.r, inv_gamma), std::pow(linear.g, inv_gamma), std::pow(linear.b, inv_gamma)};
}

}  // namespace tessera::shade
