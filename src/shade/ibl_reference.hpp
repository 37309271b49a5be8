// Image-based lighting, LearnOpenGL's "Specular IBL" pbr.fs (docs/reference/ibl_lighting.md):
// the ambient term (kD·irradiance·albedo + prefiltered·(F·A + B))·ao that takes the
// place of the reference's 0.03·albedo·ao when a scene has an environment. The
// scalar reference; ibl_kernels_simd.cpp repeats it operation for operation (the
// same bits, tests/shade/test_ibl.cpp).
#pragma once

#include <cstddef>

#include <glm/glm.hpp>

#include "environment/precompute.hpp"
#include "shade/pbr_reference.hpp"
#include "shade/shade_kernels.hpp"

namespace tessera::shade {

// A scene's environment as the shader uses it.
struct IblLighting {
    const environment::EnvironmentMaps* maps = nullptr;
    float intensity = 1.0f;
    // rotation_degrees about +Y: a world direction d is looked up at
    // (c·d.x − s·d.z, d.y, s·d.x + c·d.z), c = cos, s = sin of the angle.
    float cos_rotation = 1.0f, sin_rotation = 0.0f;
};
IblLighting ibl_lighting(const EnvironmentLight& environment);

// Where the environment's images hold what arrives from world direction d.
glm::vec3 environment_direction(const IblLighting& ibl, const glm::vec3& d);

// F0 + (max(1 − roughness, F0) − F0)·(1 − cos θ)⁵, the power as x²·x²·x.
glm::vec3 fresnel_schlick_roughness(float cos_theta, const glm::vec3& f0, float roughness);

// The ambient term at a shading point (pbr.fs after the light loop).
glm::vec3 ambient_radiance_ibl(const ShadingPoint& p, const IblLighting& ibl);

// shade_pbr with the IBL ambient: ambient + Lo.
glm::vec3 shade_pbr_ibl(const glm::vec3& world_pos, const glm::vec3& normal, const Material& material,
                        const glm::vec3& cam_pos, std::span<const Light> lights, const IblLighting& ibl);

// What background.fs shows along world direction d: envCubemap at level 0,
// times the intensity (HDR; tonemapped like the surfaces).
glm::vec3 environment_background(const IblLighting& ibl, const glm::vec3& d);

// out[i] += ambient_radiance_ibl(fragment i) for i < in.count, over the
// fragments' material channels (all filled); `isa` scalar runs the reference.
void add_ibl_ambient(Isa isa, const FragmentInputs& in, const glm::vec3& cam_pos, const IblLighting& ibl,
                     const RadianceOutputs& out);

// out[i] = environment_background(ibl, (x[i], y[i], z[i])) · scale for i < count
// (arrays padded to padded_count(count)); every ISA gives the scalar bits.
void sample_environment_background(Isa isa, std::size_t count, const float* x, const float* y, const float* z,
                                   const IblLighting& ibl, float scale, const RadianceOutputs& out);

// The view rays of one image row, as background.vs makes them: through pixel
// column x (its centre), forward + right·ndc_x + up·ndc_y with
// ndc_x = 2·(x + ½)/width − 1 (right and up scaled to the image's half extent).
struct BackgroundRays {
    glm::vec3 forward, right, up;
    float width, ndc_y;
};
glm::vec3 background_ray(const BackgroundRays& rays, float column);
// sample_environment_background along background_ray(rays, column[i]) for i <
// count (column: pixel x as float, padded to padded_count(count)).
void sample_environment_background_row(Isa isa, std::size_t count, const float* column, const BackgroundRays& rays,
                                       const IblLighting& ibl, float scale, const RadianceOutputs& out);

// The maps' raw arrays, as the per-ISA kernels take them (plain data only).
struct CubeArrays {
    const float* texels = nullptr;  // RGB, CubeMap::data()
    std::size_t float_count = 0;    // 3 · CubeMap::data().size()
    int levels = 0;
    float size[8] = {};    // per level: the face side
    float offset[8] = {};  // per level: the first texel's index (exact in float: < 2^24)
};
struct IblArrays {
    CubeArrays irradiance, prefiltered;
    const float* brdf = nullptr;  // RG, BrdfLut::data()
    float brdf_size = 0;
    float intensity, cos_rotation, sin_rotation;
};

}  // namespace tessera::shade
