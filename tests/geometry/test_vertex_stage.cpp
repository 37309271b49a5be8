#include <doctest/doctest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "geometry/vertex_stage.hpp"

using namespace tessera;

TEST_CASE("the normal matrix keeps normals perpendicular under non-uniform scale") {
    const glm::mat4 model = glm::scale(glm::mat4(1.0f), glm::vec3(4.0f, 1.0f, 1.0f));
    // A surface through (1,0,0) and (0,1,0): tangent (-1,1,0), normal (1,1,0).
    const glm::vec3 tangent_world = glm::vec3(model * glm::vec4(-1, 1, 0, 0));
    const glm::vec3 normal_world = geometry::normal_matrix(model) * glm::vec3(1, 1, 0);
    CHECK(glm::dot(tangent_world, normal_world) == doctest::Approx(0.0f));
    // mat3(model) alone would not be perpendicular.
    CHECK(glm::dot(tangent_world, glm::mat3(model) * glm::vec3(1, 1, 0)) != doctest::Approx(0.0f));
}

TEST_CASE("shade_vertices computes WorldPos, clip position and normal as the reference vertex shader") {
    Mesh mesh;
    mesh.positions = {{1, 2, 3}};
    mesh.normals = {{0, 0, 1}};
    mesh.uvs = {{0.25f, 0.75f}};
    const glm::mat4 model = glm::translate(glm::mat4(1.0f), glm::vec3(10, 0, 0));
    const glm::mat4 view_projection = glm::perspective(glm::radians(45.0f), 1.0f, 0.1f, 100.0f);
    geometry::ShadedVertex out;
    geometry::shade_vertices(mesh, 0, model, view_projection, {&out, 1});
    CHECK(out.world_pos.x == doctest::Approx(11.0f));
    CHECK(out.world_pos.y == doctest::Approx(2.0f));
    const glm::vec4 expected = view_projection * glm::vec4(11, 2, 3, 1);
    for (int i = 0; i < 4; ++i) CHECK(out.clip_pos[i] == doctest::Approx(expected[i]));
    CHECK(out.normal.z == doctest::Approx(1.0f));
    CHECK(out.uv.x == 0.25f);
}
