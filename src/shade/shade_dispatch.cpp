// Run-time choice of the fragment kernels. Built at baseline x86-64: no batch
// types here, only the per-ISA entry points of shade_kernels_simd.cpp.
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "shade/pbr_reference.hpp"
#include "shade/shade_kernels.hpp"

namespace tessera::shade {

// Defined in shade_kernels_simd.cpp, once per ISA.
#define TESSERA_DECLARE_SIMD_ENTRIES(suffix)                                                                  \
    void shade_fragments_##suffix(const FragmentInputs& in, const LightArrays& lights, const glm::vec3& cam_pos, \
                                  const RadianceOutputs& out);                                                 \
    void shade_fragments_in_range_##suffix(const FragmentInputs& in, const LightArrays& lights,                  \
                                           const glm::vec3& cam_pos, const RadianceOutputs& out);              \
    void shade_fragment_runs_##suffix(const FragmentInputs& in, const MaterialRun* runs, std::size_t run_count,     \
                                      const LightArrays& lights, const glm::vec3& cam_pos,                       \
                                      const RadianceOutputs& out);                                               \
    void tonemap_gamma_##suffix(std::size_t count, float* r, float* g, float* b);
TESSERA_DECLARE_SIMD_ENTRIES(sse4)
TESSERA_DECLARE_SIMD_ENTRIES(avx2)
TESSERA_DECLARE_SIMD_ENTRIES(avx512)
#undef TESSERA_DECLARE_SIMD_ENTRIES

namespace {

// Appends one light to the SoA columns (which must already hold its type group's predecessors).
void push_light(ShadingLights& soa, const Light& light) {
    soa.pos_x.push_back(light.position.x);
    soa.pos_y.push_back(light.position.y);
    soa.pos_z.push_back(light.position.z);
    soa.color_r.push_back(light.color.r);
    soa.color_g.push_back(light.color.g);
    soa.color_b.push_back(light.color.b);
    soa.dir_x.push_back(light.direction.x);
    soa.dir_y.push_back(light.direction.y);
    soa.dir_z.push_back(light.direction.z);
    // As spot_cone_factor works them out, so that the kernels use the same cosines.
    const float cos_inner = std::cos(glm::radians(light.inner_cone_degrees));
    const float cos_outer = std::cos(glm::radians(light.outer_cone_degrees));
    soa.cos_outer.push_back(cos_outer);
    soa.inv_cone_width.push_back(light.type == LightType::spot ? 1.0f / (cos_inner - cos_outer) : 0.0f);
    soa.range.push_back(light.type == LightType::directional ? 0.0f : light.range);
    soa.range_sq.push_back(soa.range.back() * soa.range.back());
    soa.records.push_back(light);
}

void clear_columns(ShadingLights& soa) {
    for (std::vector<float>* column : {&soa.pos_x, &soa.pos_y, &soa.pos_z, &soa.color_r, &soa.color_g, &soa.color_b,
                                       &soa.dir_x, &soa.dir_y, &soa.dir_z, &soa.cos_outer, &soa.inv_cone_width,
                                       &soa.range, &soa.range_sq})
        column->clear();
    soa.records.clear();
    soa.scene_index.clear();
    soa.shadow_slot.clear();
    soa.shadow_maps.clear();
    soa.spot_begin = soa.directional_begin = 0;
    soa.any_range = false;
}

}  // namespace

void ShadingLights::reserve(std::size_t capacity) {
    for (std::vector<float>* column : {&pos_x, &pos_y, &pos_z, &color_r, &color_g, &color_b, &dir_x, &dir_y, &dir_z,
                                       &cos_outer, &inv_cone_width, &range, &range_sq})
        column->reserve(capacity);
    records.reserve(capacity);
    scene_index.reserve(capacity);
    shadow_slot.reserve(capacity);
}

void ShadingLights::assign(const glm::vec3& camera_position, std::span<const Light> lights) {
    clear_columns(*this);
    reserve(lights.size());
    cam_pos = camera_position;
    for (const LightType type : {LightType::point, LightType::spot, LightType::directional}) {
        if (type == LightType::spot) spot_begin = count();
        if (type == LightType::directional) directional_begin = count();
        for (std::size_t i = 0; i < lights.size(); ++i)
            if (lights[i].type == type) push_light(*this, lights[i]), scene_index.push_back(std::uint32_t(i));
    }
    shadow_slot.assign(count(), -1);
    for (const float r : range) any_range = any_range || r > 0.0f;
    every.assign_all(*this);
}

void ShadingLights::assign_shadows(std::span<const ShadowMap* const> by_scene_light) {
    shadow_maps.clear();
    for (std::size_t j = 0; j < count(); ++j) {
        const ShadowMap* map = scene_index[j] < by_scene_light.size() ? by_scene_light[scene_index[j]] : nullptr;
        shadow_slot[j] = map != nullptr ? std::int32_t(shadow_maps.size()) : -1;
        if (map != nullptr) shadow_maps.push_back(map);
    }
}

void LightSelection::push(const ShadingLights& lights, std::uint32_t entry) {
    const std::uint32_t j = entry & kLightIndexMask;
    index.push_back(entry);
    x.push_back(lights.pos_x[j]), y.push_back(lights.pos_y[j]), z.push_back(lights.pos_z[j]);
    reach_sq.push_back(lights.range[j] > 0.0f ? lights.range_sq[j] : INFINITY);
}

void LightSelection::assign_all(const ShadingLights& lights) {
    for (auto* column : {&x, &y, &z, &reach_sq}) column->clear();
    index.clear();
    for (std::size_t j = 0; j < lights.count(); ++j)
        push(lights, std::uint32_t(j) | (lights.range[j] > 0.0f ? 0 : kReachesAll));
    spot_begin = lights.spot_begin;
    directional_begin = lights.directional_begin;
}

namespace {

glm::vec3 load_vec3(const float* x, const float* y, const float* z, std::size_t i) { return {x[i], y[i], z[i]}; }

// Light j's visibility of fragment i (1 without a shadow map).
float visibility_of(const FragmentInputs& in, const ShadingLights& lights, std::size_t j, std::size_t i) {
    if (in.visibility == nullptr || lights.shadow_slot[j] < 0) return 1.0f;
    return in.visibility[std::size_t(lights.shadow_slot[j]) * in.visibility_stride + i];
}

void shade_fragments_scalar(const FragmentInputs& in, const ShadingLights& lights, const RadianceOutputs& out) {
    std::vector<float> visibility(in.visibility != nullptr ? lights.count() : 0);
    for (std::size_t i = 0; i < in.count; ++i) {
        const Material material{.albedo = load_vec3(in.albedo_r, in.albedo_g, in.albedo_b, i), .metallic = in.metallic[i],
                                .roughness = in.roughness[i], .ao = in.ao[i]};
        for (std::size_t j = 0; j < visibility.size(); ++j) visibility[j] = visibility_of(in, lights, j, i);
        const glm::vec3 world_pos = load_vec3(in.world_x, in.world_y, in.world_z, i);
        const glm::vec3 normal = load_vec3(in.normal_x, in.normal_y, in.normal_z, i);
        const glm::vec3 radiance =
            in.visibility != nullptr ? shade_pbr(world_pos, normal, material, lights.cam_pos, lights.records, visibility)
                                     : shade_pbr(world_pos, normal, material, lights.cam_pos, lights.records);
        out.r[i] = radiance.r;
        out.g[i] = radiance.g;
        out.b[i] = radiance.b;
    }
}

void shade_fragments_in_range_scalar(const FragmentInputs& in, const ShadingLights& lights,
                                     const LightSelection& selection, const RadianceOutputs& out) {
    for (std::size_t i = 0; i < in.count; ++i) {
        const glm::vec3 world_pos = load_vec3(in.world_x, in.world_y, in.world_z, i);
        const Material material{.albedo = load_vec3(in.albedo_r, in.albedo_g, in.albedo_b, i), .metallic = in.metallic[i],
                                .roughness = in.roughness[i], .ao = in.ao[i]};
        // shade_pbr_within_range over the selected lights, without copying them out.
        const ShadingPoint p =
            shading_point(world_pos, load_vec3(in.normal_x, in.normal_y, in.normal_z, i), material, lights.cam_pos);
        glm::vec3 lo(0.0f);
        for (const std::uint32_t entry : selection.index) {
            const std::size_t j = entry & kLightIndexMask;
            const Light& light = lights.records[j];  // tested whatever kReachesAll says
            if (!light_reaches(light, world_pos)) continue;
            if (in.visibility != nullptr) lo += visibility_of(in, lights, j, i) * reflected_radiance(p, light);
            else lo += reflected_radiance(p, light);
        }
        const glm::vec3 radiance = ambient_radiance(material) + lo;
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

LightArrays light_arrays(const ShadingLights& lights) {
    return {lights.spot_begin,          lights.directional_begin, lights.count(),       lights.pos_x.data(),
            lights.pos_y.data(),        lights.pos_z.data(),      lights.color_r.data(), lights.color_g.data(),
            lights.color_b.data(),      lights.dir_x.data(),      lights.dir_y.data(),   lights.dir_z.data(),
            lights.cos_outer.data(),    lights.inv_cone_width.data(), lights.range.data(), lights.range_sq.data(),
            nullptr,                    lights.shadow_maps.empty() ? nullptr : lights.shadow_slot.data()};
}

}  // namespace

void shade_fragments(Isa isa, const FragmentInputs& in, const ShadingLights& lights, const RadianceOutputs& out) {
    simd::require_supported(isa);
    const LightArrays arrays = light_arrays(lights);
    switch (isa) {
        case Isa::scalar: return shade_fragments_scalar(in, lights, out);
        case Isa::sse4: return shade_fragments_sse4(in, arrays, lights.cam_pos, out);
        case Isa::avx2: return shade_fragments_avx2(in, arrays, lights.cam_pos, out);
        case Isa::avx512: return shade_fragments_avx512(in, arrays, lights.cam_pos, out);
    }
}

void shade_fragments_in_range(Isa isa, const FragmentInputs& in, const ShadingLights& lights,
                              const LightSelection& selection, const RadianceOutputs& out) {
    simd::require_supported(isa);
    LightArrays arrays = light_arrays(lights);
    arrays.spot_begin = selection.spot_begin, arrays.directional_begin = selection.directional_begin;
    arrays.count = selection.count(), arrays.index = selection.index.data();
    switch (isa) {
        case Isa::scalar: return shade_fragments_in_range_scalar(in, lights, selection, out);
        case Isa::sse4: return shade_fragments_in_range_sse4(in, arrays, lights.cam_pos, out);
        case Isa::avx2: return shade_fragments_in_range_avx2(in, arrays, lights.cam_pos, out);
        case Isa::avx512: return shade_fragments_in_range_avx512(in, arrays, lights.cam_pos, out);
    }
}

void shade_fragment_runs(Isa isa, const FragmentInputs& in, std::span<const MaterialRun> runs,
                         const ShadingLights& lights, const RadianceOutputs& out) {
    simd::require_supported(isa);
    if (isa == Isa::scalar || runs.empty()) return shade_fragments(isa, in, lights, out);
    const LightArrays arrays = light_arrays(lights);
    switch (isa) {
        case Isa::scalar: break;
        case Isa::sse4: return shade_fragment_runs_sse4(in, runs.data(), runs.size(), arrays, lights.cam_pos, out);
        case Isa::avx2: return shade_fragment_runs_avx2(in, runs.data(), runs.size(), arrays, lights.cam_pos, out);
        case Isa::avx512: return shade_fragment_runs_avx512(in, runs.data(), runs.size(), arrays, lights.cam_pos, out);
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
