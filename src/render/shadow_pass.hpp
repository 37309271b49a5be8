// The depth-only passes of shadow mapping (shade/shadow_maps.hpp): the scene
// drawn from a light, through the frame's own stages (the vertex stage,
// clipping, triangle setup, binning and the tile rasterizer), keeping the
// nearest depth per texel. Threaded like the frame (oneTBB, in the caller's
// arena), and like it the same bits for any thread count.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>
#include <tbb/enumerable_thread_specific.h>

#include "geometry/shaded_vertex.hpp"
#include "raster/binning.hpp"
#include "raster/tile_rasterizer.hpp"
#include "render/frame_memory.hpp"
#include "shade/surface_gather.hpp"
#include "shade/shadow_maps.hpp"
#include "simd/isa.hpp"
#include "tessera/scene.hpp"

namespace tessera::render {

// Memory kept from frame to frame, as the frame's.
class ShadowPass {
public:
    // Per frame, before any map: the casters' bounds (shade::casts_shadow).
    void prepare(const Scene& scene);
    const shade::SceneBounds& bounds() const { return bounds_; }

    // Window depths of the scene's casters seen through view_projection,
    // nearest per texel (LESS), into `depth`: size × size texels, row 0 at the
    // top, 1 where nothing was drawn. Every triangle is drawn, front or back
    // facing (the chapter's depth pass culls nothing); a masked material's
    // fragments take its alpha test (shade/alpha_mask.hpp), as in the frame. With `distances`, each
    // covered texel is stored as shade::distance_from_window_depth(*distances, ...).
    // With `summaries` (a cube map prepared by shade::prepare_cube_summaries,
    // `depth` its face `face`), each tile's blocks are summarized once written.
    void render_depth(simd::Isa isa, const Scene& scene, const glm::mat4& view_projection, int size,
                      std::span<float> depth, const shade::ShadowMap* distances = nullptr,
                      shade::ShadowMap* summaries = nullptr, int face = 0);

    // Every shadowed light's map (Light::shadows), indexed like scene.lights
    // (null for lights without shadows); maps holds their storage. A map whose
    // inputs are those it was last drawn from in `maps` (its light camera, the
    // casters' meshes, placements and alpha tests: a still scene, or a camera
    // moving around point and spot lights) is kept as it is, not drawn again:
    // the same bits, as the depth pass gives the same bits for the same input.
    // TESSERA_NO_SHADOW_CACHE=1 in the environment draws every map every frame.
    void render_maps(simd::Isa isa, const Scene& scene, std::vector<shade::ShadowMap>& maps,
                     std::vector<const shade::ShadowMap*>& by_light);

    std::uint64_t triangles_drawn() const { return triangles_drawn_; }
    // Of the last render_maps: the maps drawn, and those kept from the frame before.
    int maps_drawn() const { return maps_drawn_; }
    int maps_kept() const { return maps_kept_; }

private:
    shade::TriangleCorners corners_of(const Chunk& chunk, const raster::RasterTriangle& t) const;
    shade::SceneBounds bounds_;
    std::vector<shade::SceneBounds> object_bounds_;  // per object; empty: casts no shadow
    std::vector<std::uint32_t> objects_;             // the current view's casters
    std::vector<geometry::ShadedVertex> vertices_;
    std::vector<std::uint32_t> outcodes_;
    std::vector<geometry::ScreenVertex> screen_;
    std::vector<std::uint32_t> first_vertex_;  // per entry of objects_
    std::vector<Chunk> chunks_;
    std::vector<std::uint32_t> chunk_entry_;   // per chunk, its entry in objects_
    std::size_t chunk_count_ = 0;
    raster::TileGrid grid_;
    raster::TileBinIndex tile_bins_;
    tbb::enumerable_thread_specific<raster::TileBuffers> tiles_;
    std::uint64_t triangles_drawn_ = 0;

    // What the maps were drawn from (render_maps): a hash of every caster's
    // input, and per slot of `maps` the hash of that and its light camera, with
    // the storage it was drawn into (another vector's maps are not ours). The
    // textures masked casters read are held, so that a new texture cannot
    // take a freed one's address and pass for it.
    std::uint64_t casters_key(const Scene& scene);
    std::vector<std::uint8_t> mesh_use_;  // per mesh: drawn, and read by an alpha test
    std::vector<std::uint64_t> mesh_keys_;
    std::vector<std::uint64_t> map_keys_;
    std::vector<const float*> map_storage_;
    std::vector<std::shared_ptr<const texture::Texture>> held_textures_, next_textures_;
    int maps_drawn_ = 0, maps_kept_ = 0;
};

}  // namespace tessera::render
