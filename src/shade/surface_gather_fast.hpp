// The gather the SIMD ISAs run: the same fragments, runs and bits as the
// reference gather (surface_gather.hpp), which `--isa scalar` runs, with less
// work per triangle and per fragment. Its loops are compiled once per ISA
// (surface_gather_simd.cpp, -ffp-contract=off: the reference's separate
// multiplies and adds, never fused), so they use the ISA's 3-operand forms and
// vectors; they take the triangles' corners from a concrete lookup
// (GatherCornerLookup) rather than a callable, which a per-ISA object cannot
// instantiate:
//  - a triangle is set up (looked up, 1/w and the corner differences worked
//    out) once per tile, in a per-tile table (TriangleTable), where the
//    reference does it at every change of triangle along a row — on the
//    spheres at 4K ~3.7 times per visible triangle;
//  - a plain triangle's set-up reads only its corners and its chunk's
//    material (the full TriangleCorners only beyond plain): at 720p, with
//    ~1.3 px triangles, there is a set-up per ~2 fragments;
//  - plain fragments (untextured, no vertex colours, not blended) get no
//    material channels: a run of them is marked plain (MaterialRun::plain),
//    and the kernels (shade_fragment_runs) take its material from the run;
//    FragmentBuffer::fill_plain_runs fills them where channels are read;
//  - a tile's covered pixels, their triangle ids and λ1 λ2 are packed into
//    lists without a branch per pixel (4 or, with AVX2, 8 pixels per compare);
//  - a one-sample tile's pixels hold positions in the tile's triangle list
//    (raster::TileBuffers::triangles): the positions its fragments show are
//    marked, numbered in the list's order (their entries) and set up, all
//    without a branch per fragment or a hash table;
//  - a fragment list (4× MSAA, blending) holds triangle ids: a hash table is
//    probed for a batch of fragments without a branch, then the batch's new
//    triangles are set up, then its fragments gathered: the probe's miss
//    (once per triangle of the tile) is no mispredicted branch;
//  - either way only the first of a row of fragments of one triangle (its
//    head) looks its entry up, so that a probe seldom waits for the store of
//    the one before;
//  - the perspective barycentrics of 4 (AVX2: 8) fragments as one vector;
//    WorldPos and Normal as 4-float vectors (AVX2: both in one 8-float
//    vector) transposed into the channels; the same IEEE operations per lane
//    and component as the reference's glm;
//  - the set-up, the run changes and the extras stay out of line, so the
//    per-fragment loop keeps its state in registers.
// Textured, vertex-coloured and blended fragments get the reference's scalar
// extras (detail::add_extras, which the reference gather calls too).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "raster/triangle_setup.hpp"
#include "shade/surface_gather.hpp"

namespace tessera::shade {

// A chunk of one object's triangles, as the gather sees it.
struct GatherChunk {
    const raster::RasterTriangle* triangles;  // by index in the chunk; `vertex` holds the corner references
    const geometry::ShadedVertex* clipped_vertices;  // the corners clipping made (references with kClippedVertexBit)
    const Material* material;  // the object's
    // Textured, vertex-coloured or blended: the gather needs the whole TriangleCorners.
    bool beyond_plain;
};

// The fast gather's lookup of a triangle by id = chunk << chunk_shift | index
// in the chunk: its corners and material from plain arrays, and through
// `full` (rarely: beyond-plain triangles only) its whole TriangleCorners.
struct GatherCornerLookup {
    const geometry::ShadedVertex* vertices;  // the frame's, by corner reference without kClippedVertexBit
    const GatherChunk* chunks;
    int chunk_shift;
    TriangleCorners (*full)(const void* context, std::uint32_t id);
    const void* context;

    const GatherChunk& chunk_of(std::uint32_t id) const { return chunks[id >> chunk_shift]; }
    const raster::RasterTriangle& triangle_of(std::uint32_t id) const {
        return chunk_of(id).triangles[id & ((std::uint32_t(1) << chunk_shift) - 1)];
    }
    const geometry::ShadedVertex& vertex(const GatherChunk& chunk, std::uint32_t ref) const {
        return (ref & geometry::kClippedVertexBit) ? chunk.clipped_vertices[ref & ~geometry::kClippedVertexBit]
                                                   : vertices[ref];
    }
    TriangleCorners corners(std::uint32_t id) const { return full(context, id); }
};

// gather_surface_points (surface_gather.hpp) with `isa`'s gather: the
// reference (with lookup.corners) for Isa::scalar, the fast one for the
// others; the same fragments, runs and bits either way.
std::size_t gather_surface_points(Isa isa, const raster::TileBuffers& tile, int width, int height,
                                  const GatherCornerLookup& lookup, FragmentBuffer& out, std::vector<MaterialRun>& runs);
// The same for a fragment list (4× MSAA, blending).
std::size_t gather_surface_points(Isa isa, const raster::TileFragments& fragments, const GatherCornerLookup& lookup,
                                  FragmentBuffer& out, std::vector<MaterialRun>& runs);

namespace detail {

// Out of line, built at baseline x86-64 (surface_gather_fast.cpp), for the
// per-ISA gathers' rare paths: a new material run, and a beyond-plain
// fragment's extras (as the reference: add_extras).
void push_run(std::vector<MaterialRun>& runs, const MaterialRun& run);
void add_gathered_extras(const GatheredTriangle& t, const GatheredTriangleExtras& e, int x, int y, float lambda1,
                         float lambda2, float b1, float b2, FragmentBuffer& out, std::size_t i);

}  // namespace detail

}  // namespace tessera::shade
