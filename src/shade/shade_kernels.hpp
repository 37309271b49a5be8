// The vectorized fragment stage: the reference shader (pbr_reference.hpp) over
// batches of fragments in structure-of-arrays layout, compiled once per
// instruction set (SSE4.2, AVX2+FMA, AVX-512) and chosen at run time.
#pragma once

#include <cstddef>
#include <cstdint>
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
    // Shadows (shadow_maps.hpp): light j's visibility of fragment i is
    // visibility[slot · visibility_stride + i], slot = ShadingLights::shadow_slot[j],
    // for the lights that have a slot; null where no light casts shadows.
    const float* visibility = nullptr;
    std::size_t visibility_stride = 0;
    std::size_t visibility_planes = 0;  // how many (ShadingLights::shadowed_count)
};

// Fragments [begin, end) of a FragmentBuffer (surface_gather.hpp) that share one material.
struct MaterialRun {
    std::uint32_t begin = 0, end = 0;
    const Material* material = nullptr;
    bool textured = false;  // the material has maps: texture coordinates and derivatives were gathered
    // Every fragment is plain (no maps, no vertex colours, not blended): its
    // material is *material, whatever the material channels hold.
    bool plain = false;
};

// Scene-linear HDR radiance out, one array per channel, padded as above.
struct RadianceOutputs {
    float* r = nullptr;
    float* g = nullptr;
    float* b = nullptr;
};

struct ShadingLights;
struct ShadowMap;

// Some of a ShadingLights' lights: indices into it, in its type-group order,
// and where the spots and directionals begin among them (light culling). An
// entry is a light's index, with kReachesAll set where the light is known to
// reach every fragment shaded with the selection (it has no range, or they all
// lie within it): the kernels then skip the per-lane range test.
inline constexpr std::uint32_t kReachesAll = 1u << 31;
inline constexpr std::uint32_t kLightIndexMask = kReachesAll - 1;
struct LightSelection {
    std::vector<std::uint32_t> index;
    std::size_t spot_begin = 0, directional_begin = 0;
    // The selected lights' positions and range², +inf where unlimited, beside
    // `index`: what culling tests a selection with, packed so that the test
    // vectorizes. `verdict` is select_reaching's scratch.
    std::vector<float> x, y, z, reach_sq;
    std::vector<std::uint32_t> verdict;

    std::size_t count() const { return index.size(); }
    // Every light of `lights` (kReachesAll where it has no range).
    void assign_all(const ShadingLights& lights);
    // Appends light j of `lights`, entry = j with or without kReachesAll.
    void push(const ShadingLights& lights, std::uint32_t entry);
};

// The lights and camera in SoA form, built once per frame, grouped by type so
// that the kernels branch per group, never per lane or per light: points
// [0, spot_begin), spots [spot_begin, directional_begin), directionals
// [directional_begin, count()), each group in scene order.
struct ShadingLights {
    glm::vec3 cam_pos{0.0f};
    std::size_t spot_begin = 0;
    std::size_t directional_begin = 0;
    std::vector<float> pos_x, pos_y, pos_z;    // world space; point and spot
    std::vector<float> color_r, color_g, color_b;
    std::vector<float> dir_x, dir_y, dir_z;    // where the light travels, unit; spot and directional
    // Spot cone, worked out once: factor = clamp((cos θ − cos_outer)·inv_cone_width, 0, 1),
    // inv_cone_width = 1/(cos inner − cos outer).
    std::vector<float> cos_outer, inv_cone_width;
    std::vector<float> range;                  // Light::range; 0 = never culled
    std::vector<float> range_sq;               // range·range (float), the edge shade_fragments_in_range cuts at
    std::vector<Light> records;                // the same lights as given, for the scalar path
    bool any_range = false;                    // whether culling could drop any light at all
    LightSelection every;                      // every light, where light culling starts
    std::vector<std::uint32_t> scene_index;    // each light's index in the scene's list
    // Shadows: per light, its slot among the shadowed lights (FragmentInputs::visibility)
    // or -1; per slot, its map.
    std::vector<std::int32_t> shadow_slot;
    std::vector<const ShadowMap*> shadow_maps;

    std::size_t count() const { return pos_x.size(); }
    std::size_t shadowed_count() const { return shadow_maps.size(); }
    // Every light of `lights`, in type groups, none shadowed.
    void assign(const glm::vec3& camera_position, std::span<const Light> lights);
    // The maps of the scene's lights (by_scene_light[scene index], null: no
    // shadow), after assign.
    void assign_shadows(std::span<const ShadowMap* const> by_scene_light);
    // Room for `capacity` lights, so that later assigns and culls up to that count allocate nothing.
    void reserve(std::size_t capacity);
};

// The raw arrays of ShadingLights, as the per-ISA kernels take them (no
// std::vector code is compiled for a wider ISA and shared with baseline callers).
// With `index`, the kernels shade lights index[0 .. count) (the group bounds
// counting in it) and cut each at its range; without, lights 0 .. count, uncut.
struct LightArrays {
    std::size_t spot_begin, directional_begin, count;
    const float *pos_x, *pos_y, *pos_z, *color_r, *color_g, *color_b, *dir_x, *dir_y, *dir_z, *cos_outer,
        *inv_cone_width, *range, *range_sq;
    const std::uint32_t* index;
    const std::int32_t* shadow_slot = nullptr;  // ShadingLights::shadow_slot; null when no light is shadowed
};

// Which code runs the kernels. `scalar` calls the reference shader per fragment.
using simd::Isa;
using simd::isa_name;
using simd::isa_supported;
using simd::best_supported_isa;

// HDR radiance of every fragment: out = shade_pbr(in[i]) for i < in.count.
void shade_fragments(Isa isa, const FragmentInputs& in, const ShadingLights& lights, const RadianceOutputs& out);
// The same over the selected lights, each cut at its range per fragment:
// out = shade_pbr_within_range(in[i], selected lights). Lights left out of
// `selection` must reach none of the fragments (light_culling.hpp makes such
// selections), so that the result is the same for any such selection.
void shade_fragments_in_range(Isa isa, const FragmentInputs& in, const ShadingLights& lights,
                              const LightSelection& selection, const RadianceOutputs& out);

// shade_fragments over fragments in runs of one material, `runs` covering
// [0, in.count) in order: a SIMD batch wholly inside a plain run (the padding
// past in.count counting as the last run's) takes the run's material, any
// other batch the fragments' material channels, which must hold their material
// there (FragmentBuffer::fill_plain_run_edges); `--isa scalar` reads the channels
// of every fragment (FragmentBuffer::fill_plain_runs). The same bits as
// shade_fragments with every channel filled.
void shade_fragment_runs(Isa isa, const FragmentInputs& in, std::span<const MaterialRun> runs,
                         const ShadingLights& lights, const RadianceOutputs& out);

// In place, over `count` (padded) values per channel: Reinhard then gamma 1/2.2,
// the display values PNG output quantizes.
void tonemap_gamma(Isa isa, std::size_t count, float* r, float* g, float* b);

}  // namespace tessera::shade
