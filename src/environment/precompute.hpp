// LearnOpenGL's IBL pre-computation (chapters "Diffuse irradiance" and
// "Specular IBL", docs/reference/ibl_lighting.md), on the CPU: each output
// texel is what the chapter's fragment shader computes for it, with its sizes
// and sample counts. Texels are computed in parallel (oneTBB), each by one
// thread in a fixed order, so the result has the same bits on any thread count.
#pragma once

#include <memory>

#include "environment/cube_map.hpp"
#include "environment/equirect_image.hpp"
#include "simd/isa.hpp"

namespace tessera::environment {

inline constexpr float kPi = 3.14159265359f;          // the GLSL's PI
inline constexpr int kEnvironmentCubeSize = 512;      // envCubemap, RGB16F, mipmapped
inline constexpr int kIrradianceSize = 32;            // irradianceMap
inline constexpr int kPrefilterSize = 128;            // prefilterMap
inline constexpr int kPrefilterLevels = 5;            // maxMipLevels; roughness = mip / 4
inline constexpr int kBrdfLutSize = 512;              // brdfLUTTexture, RG16F
inline constexpr unsigned kSampleCount = 1024;        // SAMPLE_COUNT of prefilter.fs and brdf.fs
inline constexpr float kSampleDelta = 0.025f;         // sampleDelta of irradiance_convolution.fs
inline constexpr float kMaxReflectionLod = 4.0f;      // MAX_REFLECTION_LOD of pbr.fs
// The level of envCubemap the convolution's texture() reads. GL picks it from
// the screen-space derivatives of sampleVec; to first order one irradiance
// texel spans 512/32 = 16 environment texels, log2 16 = 4 (the reference page says more).
inline constexpr float kIrradianceLod = 4.0f;

// What a scene's environment lighting samples.
struct EnvironmentMaps {
    CubeMap background;   // envCubemap level 0 (background.fs reads textureLod(..., 0))
    CubeMap irradiance;   // kIrradianceSize, one level
    CubeMap prefiltered;  // kPrefilterSize, kPrefilterLevels levels
    std::shared_ptr<const BrdfLut> brdf;
};

// equirectangular_to_cubemap.fs into a cube of `size` with its full mip chain (glGenerateMipmap).
CubeMap equirect_to_cubemap(const EquirectImage& image, int size);
// The three sample loops below run the chapter's code as plain C++ with
// `isa` scalar (the reference, slow), else its SIMD kernels
// (precompute_kernels.hpp), which give the same bits.
// irradiance_convolution.fs over `environment` (mipmapped), into a cube of `size`.
CubeMap convolve_irradiance(const CubeMap& environment, int size, simd::Isa isa = simd::best_supported_isa());
// prefilter.fs: level m of the result at roughness m / (levels − 1).
CubeMap prefilter_specular(const CubeMap& environment, int size, int levels, simd::Isa isa = simd::best_supported_isa());
// brdf.fs: texel (x, y) at N·V = (x + ½)/size, roughness = (y + ½)/size.
BrdfLut integrate_brdf(int size, simd::Isa isa = simd::best_supported_isa());

// The chapter's helpers, shared with the tests.
float radical_inverse_vdc(unsigned bits);
glm::vec2 hammersley(unsigned i, unsigned n);
// ImportanceSampleGGX in two steps: the tangent-space H (which depends only on
// Xi and roughness), then the chapter's tangent frame around N.
glm::vec3 ggx_sample_tangent(const glm::vec2& xi, float roughness);
glm::vec3 sample_to_world(const glm::vec3& h, const glm::vec3& n);
glm::vec3 importance_sample_ggx(const glm::vec2& xi, const glm::vec3& n, float roughness);

// Every map for one image, the BRDF table being `brdf`.
EnvironmentMaps precompute_environment(const EquirectImage& image, std::shared_ptr<const BrdfLut> brdf,
                                       simd::Isa isa = simd::best_supported_isa());

}  // namespace tessera::environment
