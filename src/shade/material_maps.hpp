// The textured variant's material inputs (docs/reference/pbr_lighting.md, "Textured
// variant"): between gathering a tile's fragments and shading them, every
// textured run of fragments has its factors replaced by factor × texture, its
// normals perturbed by the normal map, and its emission set. Sampling and the
// per-fragment math run over whole runs with the ISA's kernels; the scalar
// functions below are the reference they are tested against.
#pragma once

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "shade/surface_gather.hpp"
#include "simd/isa.hpp"
#include "tessera/scene.hpp"

namespace tessera::shade {

// The shading normal from a tangent-space normal-map value `tangent_normal`
// (texel·2 − 1, x and y already scaled by the material's normal scale).
// normal: the interpolated normal, any length; dp_dx, dp_dy, duv_dx, duv_dy:
// dFdx/dFdy of WorldPos and TexCoords. Where the frame is degenerate (no uv
// change across the pixel) the interpolated normal is kept, normalized.
glm::vec3 normal_from_map_learnopengl(const glm::vec3& tangent_normal, const glm::vec3& normal, const glm::vec3& dp_dx,
                                      const glm::vec3& dp_dy, const glm::vec2& duv_dx, const glm::vec2& duv_dy);
glm::vec3 normal_from_map_gltf(const glm::vec3& tangent_normal, const glm::vec3& normal, const glm::vec3& dp_dx,
                               const glm::vec3& dp_dy, const glm::vec2& duv_dx, const glm::vec2& duv_dy);
// With a stored tangent (xyz, handedness w = ±1): glTF's B = cross(N, T)·w.
glm::vec3 normal_from_map_tangent(const glm::vec3& tangent_normal, const glm::vec3& normal, const glm::vec4& tangent);

// A worker's scratch for the material pass, reserved once.
struct MaterialScratch {
    std::vector<float> lod, r, g, b, a;
    void reserve(std::size_t max_fragments);
};

// For every textured run: samples the material's maps at the gathered
// texture coordinates (trilinear, level of detail from the derivatives) and
// overwrites the fragments' albedo, metallic, roughness, ao and normal with
// the textured values, and their emission channels. Untextured runs are left
// as gathered.
void apply_material_maps(simd::Isa isa, std::span<const std::shared_ptr<const texture::Texture>> textures,
                         std::span<const MaterialRun> runs, FragmentBuffer& fragments, MaterialScratch& scratch);

// After shading: adds each emitting run's emission (factor × map, or the
// factor alone) to its shaded radiance.
void add_emission(std::span<const MaterialRun> runs, FragmentBuffer& fragments);

}  // namespace tessera::shade
