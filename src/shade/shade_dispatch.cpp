// Run-time choice of the fragment kernels. Built at baseline x86-64: no batch
// types here, only the per-ISA entry points of shade_kernels_simd.cpp.
#include <stdexcept>
#include <string>
#include <vector>

#include "shade/pbr_reference.hpp"
#include "shade/shade_kernels.hpp"

namespace tessera::shade {

// Defined in shade_kernels_simd.cpp, once per ISA. light_arrays are pos_x,
// pos_y, pos_z, color_r, color_g, color_b, each light_count floats.
#define TESSERA_DECLARE_SIMD_ENTRIES(suffix)                                                                  \
    void shade_fragments_##suffix(const FragmentInputs& in, std::size_t light_count,                           \
                                  const float* const light_arrays[6], const glm::vec3& cam_pos,                \
                                  const RadianceOutputs& out);                                                 \
    void tonemap_gamma_##suffix(std::size_t count, float* r, float* g, float* b);
TESSERA_DECLARE_SIMD_ENTRIES(sse4)
TESSERA_DECLARE_SIMD_ENTRIES(avx2)
TESSERA_DECLARE_SIMD_ENTRIES(avx512)
#undef TESSERA_DECLARE_SIMD_ENTRIES

void ShadingLights::assign(const glm::vec3& camera_position, std::span<const Light> lights) {
    cam_pos = camera_position;
    for (std::vector<float>* column : {&pos_x, &pos_y, &pos_z, &color_r, &color_g, &color_b}) {
        column->clear();
        column->reserve(lights.size());
    }
    for (const Light& light : lights) {
        pos_x.push_back(light.position.x);
        pos_y.push_back(light.position.y);
        pos_z.push_back(light.position.z);
        color_r.push_back(light.color.r);
        color_g.push_back(light.color.g);
        color_b.push_back(light.color.b);
    }
}

namespace {

glm::vec3 load_vec3(const float* x, const float* y, const float* z, std::size_t i) { return {x[i], y[i], z[i]}; }

void shade_fragments_scalar(const FragmentInputs& in, const ShadingLights& lights, const RadianceOutputs& out) {
    // Rebuilt per call (once per tile batch, not per fragment): the SoA lights back to the reference's form.
    std::vector<Light> point_lights(lights.count());
    for (std::size_t j = 0; j < point_lights.size(); ++j) {
        point_lights[j].position = load_vec3(lights.pos_x.data(), lights.pos_y.data(), lights.pos_z.data(), j);
        point_lights[j].color = load_vec3(lights.color_r.data(), lights.color_g.data(), lights.color_b.data(), j);
    }
    for (std::size_t i = 0; i < in.count; ++i) {
        const Material material{.albedo = load_vec3(in.albedo_r, in.albedo_g, in.albedo_b, i), .metallic = in.metallic[i],
                                .roughness = in.roughness[i], .ao = in.ao[i]};
        const glm::vec3 radiance =
            shade_pbr(load_vec3(in.world_x, in.world_y, in.world_z, i),
                      load_vec3(in.normal_x, in.normal_y, in.normal_z, i), material, lights.cam_pos, point_lights);
        out.r[i] = radiance.r;
        out.g[i] = radiance.g;
        out.b[i] = radiance.b;
    }
}

void tonemap_gamma_scalar(std::size_t count, float* r, float* g, float* b) {
    for (std::size_t i = 0; i < count; ++i) {
        const glm::vec3 display = display_from_radiance({r[i], g[i], b[i]});
        r[i] = display.r;
        g[i] = display.g;
        b[i] = display.b;
    }
}

}  // namespace

void shade_fragments(Isa isa, const FragmentInputs& in, const ShadingLights& lights, const RadianceOutputs& out) {
    simd::require_supported(isa);
    const float* const light_arrays[6] = {lights.pos_x.data(),   lights.pos_y.data(),   lights.pos_z.data(),
                                          lights.color_r.data(), lights.color_g.data(), lights.color_b.data()};
    switch (isa) {
        case Isa::scalar: return shade_fragments_scalar(in, lights, out);
        case Isa::sse4: return shade_fragments_sse4(in, lights.count(), light_arrays, lights.cam_pos, out);
        case Isa::avx2: return shade_fragments_avx2(in, lights.count(), light_arrays, lights.cam_pos, out);
        case Isa::avx512: return shade_fragments_avx512(in, lights.count(), light_arrays, lights.cam_pos, out);
    }
}

void tonemap_gamma(Isa isa, std::size_t count, float* r, float* g, float* b) {
    simd::require_supported(isa);
    switch (isa) {
        case Isa::scalar: return tonemap_gamma_scalar(count, r, g, b);
        case Isa::sse4: return tonemap_gamma_sse4(count, r, g, b);
        case Isa::avx2: return tonemap_gamma_avx2(count, r, g, b);
        case Isa::avx512: return tonemap_gamma_avx512(count, r, g, b);
    }
}

}  // namespace tessera::shade
