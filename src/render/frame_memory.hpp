// Everything a frame writes, kept from frame to frame so that a steady stream
// of frames allocates nothing (page faults are expensive on our machines).
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/shaded_vertex.hpp"
#include "raster/binning.hpp"
#include "raster/tile_rasterizer.hpp"
#include "raster/triangle_assembly.hpp"
#include "tessera/scene.hpp"

namespace tessera::render {

// The scene's triangles are cut into chunks of at most this many, each set up
// and binned on its own; chunk boundaries depend on the scene only.
inline constexpr std::uint32_t kChunkTriangles = 16384;
// A triangle id is (chunk << kChunkIdShift) | index in the chunk. Clipping
// turns one triangle into at most 7, so a chunk holds fewer than 2^17.
inline constexpr int kChunkIdShift = 17;
inline constexpr std::uint32_t kChunkIndexMask = (1u << kChunkIdShift) - 1;
inline constexpr std::uint32_t kMaxChunks = (raster::kNoTriangle >> kChunkIdShift);  // leaves kNoTriangle unused
static_assert(kChunkTriangles * 7 < (1u << kChunkIdShift));

// A run of one object's triangles and what assembly and binning made of them.
// Chunks are filled by different threads at once: each gets its own cache
// lines, or every push_back would bounce its neighbour's vector between cores.
struct alignas(128) Chunk {
    std::uint32_t object = 0;
    std::uint32_t first_triangle = 0;  // index into the mesh's triangles
    std::uint32_t triangle_count = 0;
    bool alpha_tested = false;  // the object's material is masked: fragments take the alpha test
    bool blended = false;       // the object's material blends: drawn in the blend pass, after the opaque ones
    const glm::vec4* colors = nullptr;  // the mesh's vertex colours (Mesh::colors), or null
    const glm::vec2* uvs1 = nullptr;    // the mesh's second uv set (Mesh::uvs1) where its material has maps, or null
    const Material* material = nullptr;  // the object's
    // The material has maps or blends, or the mesh has vertex colours: the
    // gather needs the whole shade::TriangleCorners, not just the corners.
    bool beyond_plain = false;
    raster::AssembledTriangles assembled;
    raster::ChunkBins bins;

    // A triangle corner's vertex: the frame's, or one this chunk's clipping made.
    const geometry::ShadedVertex& vertex(std::uint32_t ref, const std::vector<geometry::ShadedVertex>& frame) const {
        return (ref & geometry::kClippedVertexBit) ? assembled.clipped_vertices[ref & ~geometry::kClippedVertexBit]
                                                   : frame[ref];
    }
    // A corner's vertex colour (colors set); first_vertex: the object's first frame vertex.
    const glm::vec4& color(std::uint32_t ref, std::uint32_t first_vertex) const {
        return (ref & geometry::kClippedVertexBit) ? assembled.clipped_colors[ref & ~geometry::kClippedVertexBit]
                                                   : colors[ref - first_vertex];
    }
    // A corner's second uv (uvs1 set), as color().
    const glm::vec2& uv1(std::uint32_t ref, std::uint32_t first_vertex) const {
        return (ref & geometry::kClippedVertexBit) ? assembled.clipped_uvs1[ref & ~geometry::kClippedVertexBit]
                                                   : uvs1[ref - first_vertex];
    }
};

}  // namespace tessera::render
