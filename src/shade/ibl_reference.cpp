// The IBL ambient term of pbr.fs, line for line; the samplers are
// environment/cube_map.cpp's (GL's seamless bilinear and trilinear filtering).
#include "shade/ibl_reference.hpp"

#include <cmath>

namespace tessera::shade {

IblLighting ibl_lighting(const EnvironmentLight& environment) {
    const float radians = glm::radians(environment.rotation_degrees);
    return {environment.maps.get(), environment.intensity, std::cos(radians), std::sin(radians)};
}

glm::vec3 environment_direction(const IblLighting& ibl, const glm::vec3& d) {
    return {ibl.cos_rotation * d.x - ibl.sin_rotation * d.z, d.y, ibl.sin_rotation * d.x + ibl.cos_rotation * d.z};
}

glm::vec3 fresnel_schlick_roughness(float cos_theta, const glm::vec3& f0, float roughness) {
    const float x = glm::clamp(1.0f - cos_theta, 0.0f, 1.0f);
    const float x2 = x * x;
    const float w = x2 * x2 * x;  // pow(x, 5.0)
    return f0 + (glm::max(glm::vec3(1.0f - roughness), f0) - f0) * w;
}

glm::vec3 ambient_radiance_ibl(const ShadingPoint& p, const IblLighting& ibl) {
    const environment::EnvironmentMaps& maps = *ibl.maps;
    const glm::vec3 &n = p.n, &v = p.v;
    const float metallic = p.material.metallic, roughness = p.material.roughness;
    const float n_dot_v = glm::max(glm::dot(n, v), 0.0f);
    const glm::vec3 r = -v - 2.0f * glm::dot(n, -v) * n;  // reflect(-V, N)

    const glm::vec3 f = fresnel_schlick_roughness(n_dot_v, p.f0, roughness);
    const glm::vec3 k_s = f;
    const glm::vec3 k_d = (1.0f - k_s) * (1.0f - metallic);

    const glm::vec3 irradiance = maps.irradiance.sample_bilinear(environment_direction(ibl, n), 0) * ibl.intensity;
    const glm::vec3 diffuse = irradiance * p.material.albedo;

    const glm::vec3 prefiltered_color =
        maps.prefiltered.sample_trilinear(environment_direction(ibl, r), roughness * environment::kMaxReflectionLod) *
        ibl.intensity;
    const glm::vec2 brdf = maps.brdf->sample(n_dot_v, roughness);
    const glm::vec3 specular = prefiltered_color * (f * brdf.x + brdf.y);

    return (k_d * diffuse + specular) * p.material.ao;
}

glm::vec3 shade_pbr_ibl(const glm::vec3& world_pos, const glm::vec3& normal, const Material& material,
                        const glm::vec3& cam_pos, std::span<const Light> lights, const IblLighting& ibl) {
    const ShadingPoint p = shading_point(world_pos, normal, material, cam_pos);
    glm::vec3 lo(0.0f);
    for (const Light& light : lights) lo += reflected_radiance(p, light);
    return ambient_radiance_ibl(p, ibl) + lo;
}

glm::vec3 environment_background(const IblLighting& ibl, const glm::vec3& d) {
    return ibl.maps->background.sample_bilinear(environment_direction(ibl, d), 0) * ibl.intensity;
}

glm::vec3 background_ray(const BackgroundRays& rays, float column) {
    const float ndc_x = 2.0f * (column + 0.5f) / rays.width - 1.0f;
    return rays.forward + rays.right * ndc_x + rays.up * rays.ndc_y;
}

}  // namespace tessera::shade
