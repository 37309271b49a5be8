// Vertex stage: the reference vertex shader over every object's mesh.
#pragma once

#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "geometry/clipper.hpp"
#include "geometry/shaded_vertex.hpp"
#include "geometry/viewport.hpp"
#include "simd/isa.hpp"
#include "tessera/scene.hpp"

namespace tessera::geometry {

// Inverse-transpose of the model's upper 3×3: keeps normals perpendicular
// under non-uniform scale (the reference's comment on mat3(model)).
glm::mat3 normal_matrix(const glm::mat4& model);

// Transforms the mesh's vertices [first, first + out.size()), placed by
// `model`, into `out`.
void shade_vertices(const Mesh& mesh, std::size_t first, const glm::mat4& model, const glm::mat4& view_projection,
                    std::span<ShadedVertex> out);

// Everything the frame keeps per vertex, for a run of vertices: the shaded
// vertex, its outcode, and its screen position (the outcode again, and x, y and
// depth set only where the outcode has no clip-plane bit and the vertex is
// finite: the only screen positions ever read).
struct VertexRun {
    std::span<ShadedVertex> vertices;
    std::uint32_t* outcodes;
    ScreenVertex* screen;
};

// The vertex stage for the mesh's vertices [first, first + out.vertices.size()):
// shade_vertices(), outcode() and to_screen(). `scalar` runs those plain
// functions; the SIMD ISAs give bit-identical results a vector of vertices at a time.
void run_vertex_stage(simd::Isa isa, const Mesh& mesh, std::size_t first, const glm::mat4& model,
                      const glm::mat4& view_projection, const GuardBand& guard, const Viewport& viewport,
                      const VertexRun& out);

// The mesh's tangents [first, first + out.size()) in world space: tangents
// follow the surface, so they take the model matrix itself (glTF's rule), not
// the normal matrix; w, the handedness, is kept, and flipped where the model
// matrix has a negative determinant (a mirror), so that B = cross(N, T)·w
// still points along the mapped surface's bitangent.
void transform_tangents(const Mesh& mesh, std::size_t first, const glm::mat4& model, std::span<glm::vec4> out);

}  // namespace tessera::geometry
