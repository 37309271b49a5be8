// The depth-only passes of shadow mapping (shade/shadow_maps.hpp): the scene
// drawn from a light, through the frame's own stages (the vertex stage,
// clipping, triangle setup, binning and the tile rasterizer), keeping the
// nearest depth per texel. Threaded like the frame (oneTBB, in the caller's
// arena), and like it the same bits for any thread count.
#pragma once

#include <cstdint>
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
    void render_depth(simd::Isa isa, const Scene& scene, const glm::mat4& view_projection, int size,
                      std::span<float> depth, const shade::ShadowMap* distances = nullptr);

    // Every shadowed light's map (Light::shadows), indexed like scene.lights
    // (null for lights without shadows); maps holds their storage.
    void render_maps(simd::Isa isa, const Scene& scene, std::vector<shade::ShadowMap>& maps,
                     std::vector<const shade::ShadowMap*>& by_light);

    std::uint64_t triangles_drawn() const { return triangles_drawn_; }

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
};

}  // namespace tessera::render
