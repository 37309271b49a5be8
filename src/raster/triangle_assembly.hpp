// Triangle assembly: a run of one object's indexed triangles through clipping
// and triangle setup, into RasterTriangles ready to bin.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <utility>
#include <span>
#include <vector>

#include "geometry/clipper.hpp"
#include "geometry/shaded_vertex.hpp"
#include "geometry/viewport.hpp"
#include "raster/triangle_setup.hpp"
#include "simd/isa.hpp"

namespace tessera::raster {

// The vertex stage's output for the whole frame, indexed by vertex reference.
struct FrameVertices {
    std::span<const geometry::ShadedVertex> vertices;
    std::span<const std::uint32_t> outcodes;          // geometry::outcode() of each vertex
    std::span<const geometry::ScreenVertex> screen;   // its outcode is outcodes[i]; x, y, depth valid where that has no clip-plane bit
};

// An allocator whose resize() leaves new elements of plain types
// uninitialized: assembly grows the records by a batch's room, the setup
// kernel writes its records there in place, and the vector shrinks back to
// what was kept, with no zeroing and no copy of the records.
template <class T>
struct UninitializedAllocator : std::allocator<T> {
    template <class U>
    struct rebind {
        using other = UninitializedAllocator<U>;
    };
    UninitializedAllocator() = default;
    template <class U>
    UninitializedAllocator(const UninitializedAllocator<U>&) noexcept {}
    template <class U>
    void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};
using RasterTriangles = std::vector<RasterTriangle, UninitializedAllocator<RasterTriangle>>;

// Records assembly may hold beyond the triangles it keeps, while the setup
// kernel writes a batch in place: reserve this much more than the triangles
// expected, or the vector grows (and copies) on a chunk's last batch.
inline constexpr std::size_t kAssemblyRoom = 64;

struct AssembledTriangles {
    RasterTriangles triangles;                             // in submission order
    std::vector<geometry::ShadedVertex> clipped_vertices;  // corners made by clipping (kClippedVertexBit refs)
    std::vector<glm::vec4> clipped_colors;  // beside clipped_vertices, for meshes with vertex colours only
    std::vector<glm::vec2> clipped_uvs1;    // beside clipped_vertices, for meshes with a second uv set only
    void clear() { triangles.clear(), clipped_vertices.clear(), clipped_colors.clear(), clipped_uvs1.clear(); }
};

// Appends to `out` the triangles of `indices` (three per triangle, relative to
// `first_vertex`; an index >= vertex_count drops its triangle) that survive
// culling, clipping and setup, in order. With a SIMD ISA, the index check,
// the outcode test, culling and setup run a vector of triangles at a time
// (the same result as the scalar path's one by one); triangles that cross a
// clip plane (fans) or are large are merged in from the scalar code.
// samples: 1, or 4 for 4× MSAA. culling: which windings setup drops (clipping
// keeps a triangle's winding, so its pieces are culled alike). colors: the
// mesh's vertex colours (indexed like `indices`) or empty; a corner clipping
// makes gets its colour interpolated as its other attributes are. mirrored:
// the model matrix has a negative determinant (RasterTriangle::back_facing).
// uvs1: the mesh's second uv set (Mesh::uvs1) or empty, interpolated for
// clipping's corners as the colours are.
void assemble_triangles(simd::Isa isa, std::span<const std::uint32_t> indices, std::uint32_t first_vertex,
                        std::uint32_t vertex_count, const FrameVertices& frame,
                        const geometry::Viewport& viewport, const geometry::GuardBand& guard,
                        AssembledTriangles& out, int samples = 1, Culling culling = Culling::none,
                        std::span<const glm::vec4> colors = {}, bool mirrored = false,
                        std::span<const glm::vec2> uvs1 = {});

}  // namespace tessera::raster
