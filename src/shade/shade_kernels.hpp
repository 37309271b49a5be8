// The vectorized fragment stage: the reference shader (pbr_reference.hpp) over
// batches of fragments in structure-of-arrays layout, compiled once per
// instruction set (SSE4.2, AVX2+FMA, AVX-512) and chosen at run time.
#pragma once

#include <cstddef>
#include <span>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "simd/isa.hpp"
#include "simd/lane_padding.hpp"
#include "tessera/scene.hpp"

namespace tessera::shade {

using simd::kLanePadding;  // arrays hold whole vectors past `count`
using simd::padded_count;

// Fragments to shade, one array per scalar input. All pointers address at
// least padded_count(count) floats.
struct FragmentInputs {
    std::size_t count = 0;
    const float* world_x = nullptr;  // world-space position
    const float* world_y = nullptr;
    const float* world_z = nullptr;
    const float* normal_x = nullptr;  // world-space normal, any length > 0 (normalized by the shader)
    const float* normal_y = nullptr;
    const float* normal_z = nullptr;
    const float* albedo_r = nullptr;  // material, as in tessera::Material
    const float* albedo_g = nullptr;
    const float* albedo_b = nullptr;
    const float* metallic = nullptr;
    const float* roughness = nullptr;
    const float* ao = nullptr;
};

// Scene-linear HDR radiance out, one array per channel, padded as above.
struct RadianceOutputs {
    float* r = nullptr;
    float* g = nullptr;
    float* b = nullptr;
};

// Point lights and camera in SoA form, built once per frame.
struct ShadingLights {
    glm::vec3 cam_pos{0.0f};
    std::vector<float> pos_x, pos_y, pos_z;    // world space
    std::vector<float> color_r, color_g, color_b;
    std::size_t count() const { return pos_x.size(); }
    void assign(const glm::vec3& camera_position, std::span<const Light> lights);
};

// Which code runs the kernels. `scalar` calls the reference shader per fragment.
using simd::Isa;
using simd::isa_name;
using simd::isa_supported;
using simd::best_supported_isa;

// HDR radiance of every fragment: out = shade_pbr(in[i]) for i < in.count.
void shade_fragments(Isa isa, const FragmentInputs& in, const ShadingLights& lights, const RadianceOutputs& out);

// In place, over `count` (padded) values per channel: Reinhard then gamma 1/2.2,
// the display values PNG output quantizes.
void tonemap_gamma(Isa isa, std::size_t count, float* r, float* g, float* b);

}  // namespace tessera::shade
