#include "geometry/vertex_stage.hpp"

#include <cassert>

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

void transform_tangents(const Mesh& mesh, std::size_t first, const glm::mat4& model, std::span<glm::vec4> out) {
    assert(first + out.size() <= mesh.tangents.size());
    const glm::mat3 to_world(model);
    for (std::size_t i = 0; i < out.size(); ++i) {
        const glm::vec4& t = mesh.tangents[first + i];
        out[i] = glm::vec4(to_world * glm::vec3(t), t.w);
    }
}

}  // namespace tessera::geometry
