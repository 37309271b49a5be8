// Light culling: which lights can reach which fragments, so that shading loops
// over fewer of them. A light with a range (Light::range) adds nothing to a
// point farther than its range (shade_pbr_within_range); culling only skips
// lights that would add nothing, so the image is the same for any tile size,
// cluster size and thread count, and the same as shading every light cut at
// its range per fragment.
//
// Two levels, both known only after rasterization (the visible points):
//   tile:    the lights whose range sphere meets the box around the tile's
//            visible points (what the frame's lights are tested against once);
//   cluster: runs of kClusterFragments fragments in gather order (rows of the
//            tile: a 32-pixel tile's cluster is a 32×2 strip), each with the
//            tile's lights that meet the box around the cluster's points.
//            A strip's box is tight in depth as well as on screen, unlike a
//            tile's, which spans every depth the tile shows.
// The kernels then cut each light lane by lane and skip a light no lane of a
// SIMD batch is within range of.
#pragma once

#include <cstddef>

#include <glm/glm.hpp>

#include "shade/shade_kernels.hpp"

namespace tessera::shade {

// Bounds of a set of world-space points.
struct WorldBounds {
    glm::vec3 min{0.0f};
    glm::vec3 max{0.0f};
};

// The axis-aligned bounds of fragments' world positions; count > 0.
WorldBounds fragment_bounds(const FragmentInputs& in);

// The lights of `from` that may reach a point inside `bounds` (light_reaches),
// into `out`, type groups and order kept. Conservative to the last bit: the
// gap from the light to the box is computed per axis and squared and summed
// as distance_squared does, and rounding is monotonic, so the box's squared
// gap never exceeds any inside point's distance_squared; a light is dropped
// only when that gap exceeds its range². Lights without a range are kept.
// Alike, kReachesAll is set where the box's farthest point is within range
// (or the light has none), so that every point inside is.
void select_reaching(const ShadingLights& lights, const LightSelection& from, const WorldBounds& bounds,
                     LightSelection& out);

// Fragments per cluster: a multiple of every ISA's vector (kLanePadding), so
// that a cluster's padded batches never run into the next cluster.
inline constexpr std::size_t kClusterFragments = 64;
static_assert(kClusterFragments % kLanePadding == 0);

// A worker's selections, reserved once (reserve) so that culling allocates nothing per tile.
struct LightCullScratch {
    LightSelection tile, cluster;
    void reserve(std::size_t light_count);
};

// What culling left for a tile's fragments.
struct CulledWork {
    std::size_t tile_lights = 0;       // lights whose range meets the tile's visible points
    std::size_t fragment_lights = 0;   // Σ over clusters of fragments × the cluster's lights
};

// shade_fragments_in_range over every light, culled per tile and per cluster
// as above: out = shade_pbr_within_range(in[i], every light).
CulledWork shade_fragments_culled(Isa isa, const FragmentInputs& in, const ShadingLights& lights,
                                  LightCullScratch& scratch, const RadianceOutputs& out);

}  // namespace tessera::shade
