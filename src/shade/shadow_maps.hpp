// Shadow mapping, after LearnOpenGL's "Shadow Mapping" chapter (3.1.3,
// shadow_mapping.fs: a directional light's 2D depth map, 3×3 PCF and the
// slope-scaled bias max(0.05·(1 − N·L), 0.005)) and its "Point Shadows" chapter
// (3.2.2, point_shadows.fs: a cube of linear distances / far_plane, the 20
// gridSamplingDisk offsets, diskRadius = (1 + viewDistance / far_plane) / 25,
// bias 0.15). A light's visibility (1 − the chapters' `shadow`) multiplies its
// direct contribution to Lo (pbr_reference.hpp shade_pbr).
//
// The maps follow GL's sampling exactly: nearest texel, a 2D map clamped to a
// border of depth 1 (GL_CLAMP_TO_BORDER), a cube clamped to each face's edge;
// the texel of coordinate t ∈ [0, 1] is floor(t · size) (GL's rows from the
// bottom; the maps store row 0 at the top, as the rasterizer draws them).
//
// What the chapters leave to their demo scene, and Tessera decides:
//  - directional: an orthographic light camera looking along the light's
//    direction, fitted to the part of the scene's bounds the camera sees (the
//    frustum up to the farthest scene point), deep enough to hold every caster;
//    the map keeps window depth, as the chapter's (linear for an orthographic
//    projection), and the bias is in those units;
//  - spot: a perspective light camera along its direction, its field of view
//    the outer cone (plus two texels), far plane at the range or the farthest
//    scene point; the map keeps distance / far_plane as the point chapter's
//    cube does, filtered and biased as the directional map (bias in those units);
//  - point: the chapter's six 90° faces (GL cube order +X −X +Y −Y +Z −Z and its
//    lookAt up vectors), far plane at the range or the farthest scene point.
//    The chapter's far_plane (25) is also the scale of its disk, (1 +
//    viewDistance / far_plane) / 25: there it is the light's reach in the
//    demo room. Tessera's reach is the light's range, else auto_light_range of
//    its colour (where it falls to kAutoRangeIrradiance): a projection fitted
//    to a small scene would make the disk several times the chapter's, wider
//    than the 0.15 bias, and the floor under the light would shadow itself;
//  - near planes at far / 1000 (the chapters' 1.0 for a 25-unit far plane
//    would hide casters nearer than that).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "shade/shade_kernels.hpp"
#include "tessera/scene.hpp"

namespace tessera::shade {

// The world-space box around every object's vertices (as placed). empty: no vertex.
struct SceneBounds {
    glm::vec3 min{0.0f}, max{0.0f};
    bool empty = true;
};
SceneBounds scene_bounds(const Scene& scene);
// Whether Renderer draws `object` into shadow maps: every object but blended ones
// (a masked material casts where its alpha test keeps the surface).
bool casts_shadow(const Scene& scene, const Object& object);

enum class ShadowMapKind : std::uint8_t {
    planar_depth,     // directional: window depth of an orthographic view
    planar_distance,  // spot: distance / far_plane through a perspective view
    cube_distance,    // point: six perspective faces, distance / far_plane
};

struct ShadowMap {
    ShadowMapKind kind = ShadowMapKind::planar_depth;
    int size = 0;           // texels per side
    int filter_radius = 1;  // Light::shadow_filter_radius
    int faces = 1;          // 6 for a cube
    // World → the light camera's clip space, per face (the chapters'
    // lightSpaceMatrix, shadowTransforms).
    std::array<glm::mat4, 6> view_projection{};
    glm::vec3 position{0.0f};     // spot and point: the light's (lightPos)
    glm::vec3 to_light{0.0f};     // directional: −direction (the chapter's lightDir)
    float near_plane = 0.0f, far_plane = 1.0f;
    float disk_far_plane = 1.0f;  // point: the far_plane of the chapter's diskRadius (the light's reach)
    float tan_half_fov = 1.0f;    // of the perspective faces
    // faces × size² texels, face after face, row 0 of each at the top; 1 = nothing drawn.
    std::vector<float> depth;
    // Cube maps: the least and greatest texel of each window of kShadowWindow²
    // blocks of kShadowBlock² texels (summarize_cube_blocks), for the SIMD lookups to
    // settle a fragment whose 20 taps all fall in one window without taking
    // them. Empty: none (the taps are always taken). Stale if depth changes
    // without summarize_cube_blocks after it.
    std::vector<float> block_min, block_max;
    int blocks_per_side = 0;

    float texel(int face, int column, int row) const {
        return depth[(std::size_t(face) * size + std::size_t(row)) * size + std::size_t(column)];
    }
};

// The side of the blocks that ShadowMap::block_min and block_max summarize,
// and of their windows in blocks: 12 texels, wider than the point chapter's
// disk of 20 taps spans on a 1024² face 15 units from its light (7 texels).
inline constexpr int kShadowBlock = 4;
inline constexpr int kShadowWindow = 3;
// ShadowMap::blocks_per_side of a cube of `size` texels a side (its summaries
// take 2 × 6 × that² floats).
inline int summary_blocks_per_side(int size) { return (std::max(size, 0) + kShadowBlock - 1) / kShadowBlock; }

// Fills a cube map's block_min, block_max and blocks_per_side from its depth:
// window (bx, by) of a face covers blocks bx .. bx + kShadowWindow − 1 and
// by .. by + kShadowWindow − 1 (those that exist), rows as depth stores them.
// A window holding a NaN texel gets (−inf, +inf), which settles nothing.
// Other kinds of map: left empty.
void summarize_cube_blocks(ShadowMap& map);
// The same in the steps the depth pass takes, tile by tile while the texels
// are in cache: prepare_cube_summaries sizes the arrays (empty for other kinds
// of map); summarize_cube_rect summarizes the blocks of a face's texel rect
// [x0, x1) × [y0, y1), x0 and y0 multiples of kShadowBlock, x1 and y1 too or
// the map's side, once its texels are final; finish_cube_summaries, after
// every block, widens them into windows.
void prepare_cube_summaries(ShadowMap& map);
void summarize_cube_rect(ShadowMap& map, int face, int x0, int y0, int x1, int y1);
void finish_cube_summaries(ShadowMap& map);

// The light camera(s) for `light` in `scene` (bounds: scene_bounds(scene)), and
// the map's size; depth is sized (its values left as they were) for the depth pass to fill.
void plan_shadow_map(const Scene& scene, const SceneBounds& bounds, const Light& light, ShadowMap& map);

// What a distance map (spot, point) stores at texel (column, row) of a face
// where the depth pass left window depth d < 1: distance / far_plane, the
// distance from the light to that surface through the texel's centre (what
// the point chapter's depth shader writes as gl_FragDepth). The nearest
// surface along the ray is the same either way (view depth and distance grow
// together), so the depth pass's LESS test picks it.
float distance_from_window_depth(const ShadowMap& map, float d, int column, int row);

// The chapters' visibility, 1 − ShadowCalculation, in [0, 1], of a point at
// world_pos with shading normal `normal` (any length) seen from cam_pos.
float shadow_visibility(const ShadowMap& map, const glm::vec3& world_pos, const glm::vec3& normal,
                        const glm::vec3& cam_pos);

// How the cube lookups of shadow_visibility_planes went, in fragments × lights
// (for tests and benchmarks).
struct CubeLookupStats {
    std::size_t settled = 0;      // by the block summaries: the taps' result, without taking them
    std::size_t facing_away = 0;  // not looked up: the light's share of Lo is 0 whatever the visibility
    std::size_t tapped = 0;       // every tap taken
    CubeLookupStats& operator+=(const CubeLookupStats& o) {
        settled += o.settled, facing_away += o.facing_away, tapped += o.tapped;
        return *this;
    }
};

// shadow_visibility of in's fragments for every shadowed light of `lights`:
// slot s's (ShadingLights::shadow_maps[s]) at planes[s · stride + i], for
// i < padded_count(in.count) (1 in the padding). stride >= padded_count(in.count).
// With a SIMD ISA, cube maps are looked up a vector of fragments at a time
// (shadow_kernels_simd.cpp: the same operations, so the same bits; 2D maps
// take the scalar code for every ISA), settling what the block summaries
// can without the taps. every_visibility false: where a fragment faces away
// from a point light (its share of Lo is 0 whatever the visibility), the
// plane may hold any value in [0, 1] instead (the shadow AOV asks for true).
CubeLookupStats shadow_visibility_planes(Isa isa, const FragmentInputs& in, const ShadingLights& lights, float* planes,
                                         std::size_t stride, bool every_visibility = true);

// What the cube kernels read of a cube map (plain values: no std::vector in per-ISA code).
struct CubeMapView {
    const float* depth;
    int size, filter_radius;
    float position_x, position_y, position_z, far_plane, disk_far_plane;
    const float* block_min;  // null: no summaries
    const float* block_max;
    int blocks_per_side;
};

// The fragments the cube kernels look up: positions, normals (null: none
// skipped as facing away), and room for kCubeLookupLists lists of
// pending_capacity >= count indices each (one per face, and one more).
inline constexpr std::size_t kCubeLookupLists = 7;
struct CubeLookupInputs {
    const float* x;
    const float* y;
    const float* z;
    const float* normal_x;
    const float* normal_y;
    const float* normal_z;
    std::size_t count;
    glm::vec3 view_pos;
    std::uint32_t* pending;
    std::size_t pending_capacity;
};

// The 20 offsets of the point chapter's gridSamplingDisk.
extern const std::array<glm::vec3, 20> kGridSamplingDisk;

}  // namespace tessera::shade
