#include "geometry/vertex_stage.hpp"

#include <cassert>
#include <cstddef>

#include <glm/gtc/type_ptr.hpp>

#include "geometry/vertex_kernels.hpp"

namespace tessera::geometry {

glm::mat3 normal_matrix(const glm::mat4& model) { return glm::transpose(glm::inverse(glm::mat3(model))); }

void shade_vertices(const Mesh& mesh, std::size_t first, const glm::mat4& model, const glm::mat4& view_projection,
                    std::span<ShadedVertex> out) {
    assert(first + out.size() <= mesh.positions.size());
    const glm::mat3 to_world_normal = normal_matrix(model);
    const bool has_uvs = mesh.uvs.size() == mesh.positions.size();
    for (std::size_t i = 0; i < out.size(); ++i) {
        const std::size_t v = first + i;
        const glm::vec3 world = glm::vec3(model * glm::vec4(mesh.positions[v], 1.0f));
        out[i].world_pos = world;
        out[i].clip_pos = view_projection * glm::vec4(world, 1.0f);
        out[i].normal = to_world_normal * mesh.normals[v];
        out[i].uv = has_uvs ? mesh.uvs[v] : glm::vec2(0.0f);
    }
}

void run_vertex_stage(simd::Isa isa, const Mesh& mesh, std::size_t first, const glm::mat4& model,
                      const glm::mat4& view_projection, const GuardBand& guard, const Viewport& viewport,
                      const VertexRun& out) {
    if (out.vertices.empty()) return;
    if (isa == simd::Isa::scalar) {
        shade_vertices(mesh, first, model, view_projection, out.vertices);
        for (std::size_t i = 0; i < out.vertices.size(); ++i) {
            out.outcodes[i] = outcode(out.vertices[i], guard);
            if (!(out.outcodes[i] & (kClipPlaneBits | kNotFinite)))
                out.screen[i] = to_screen(out.vertices[i].clip_pos, viewport);
            out.screen[i].outcode = out.outcodes[i];
        }
        return;
    }
    static_assert(sizeof(ShadedVertex) == 12 * sizeof(float) && offsetof(ShadedVertex, world_pos) == 4 * sizeof(float) &&
                      offsetof(ShadedVertex, normal) == 7 * sizeof(float) &&
                      offsetof(ShadedVertex, uv) == 10 * sizeof(float),
                  "the vertex kernels write ShadedVertex as 12 floats");
    static_assert(sizeof(ScreenVertex) == 4 * sizeof(std::int32_t), "the vertex kernels write ScreenVertex as 4 int32");
    assert(first + out.vertices.size() <= mesh.positions.size() && mesh.normals.size() == mesh.positions.size());
    const glm::mat3 to_world_normal = normal_matrix(model);
    const VertexRunInput in{glm::value_ptr(mesh.positions[first]),
                            glm::value_ptr(mesh.normals[first]),
                            mesh.uvs.size() == mesh.positions.size() ? glm::value_ptr(mesh.uvs[first]) : nullptr,
                            out.vertices.size(),
                            glm::value_ptr(model),
                            glm::value_ptr(view_projection),
                            glm::value_ptr(to_world_normal),
                            guard.x_ndc,
                            guard.y_ndc,
                            float(viewport.width),
                            float(viewport.height)};
    const VertexRunOutput kernel_out{reinterpret_cast<float*>(out.vertices.data()), out.outcodes,
                                     reinterpret_cast<std::int32_t*>(out.screen)};
    switch (isa) {
        case simd::Isa::sse4: return shade_vertex_run_sse4(in, kernel_out);
        case simd::Isa::avx2: return shade_vertex_run_avx2(in, kernel_out);
        case simd::Isa::avx512: return shade_vertex_run_avx512(in, kernel_out);
        case simd::Isa::scalar: break;
    }
}

void transform_tangents(const Mesh& mesh, std::size_t first, const glm::mat4& model, std::span<glm::vec4> out) {
    assert(first + out.size() <= mesh.tangents.size());
    const glm::mat3 to_world(model);
    // A mirroring transform turns cross(N, T) around (the normal matrix keeps N
    // outward, T follows the surface): the handedness flips with it.
    const float handedness = glm::determinant(to_world) < 0.0f ? -1.0f : 1.0f;
    for (std::size_t i = 0; i < out.size(); ++i) {
        const glm::vec4& t = mesh.tangents[first + i];
        out[i] = glm::vec4(to_world * glm::vec3(t), t.w * handedness);
    }
}

}  // namespace tessera::geometry
