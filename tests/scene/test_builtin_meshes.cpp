// Tests for src/scene/builtin_meshes.cpp: sizes, index ranges, normals and winding.
#include <cmath>
#include <cstddef>

#include <doctest/doctest.h>

#include "tessera/scene.hpp"

namespace {

using tessera::Mesh;

void check_indices_in_range(const Mesh& mesh) {
    REQUIRE(mesh.indices.size() % 3 == 0);
    for (const std::uint32_t index : mesh.indices) REQUIRE(index < mesh.positions.size());
}

void check_parallel_arrays(const Mesh& mesh) {
    REQUIRE(mesh.normals.size() == mesh.positions.size());
    REQUIRE(mesh.uvs.size() == mesh.positions.size());
}

void check_unit_normals(const Mesh& mesh, double tolerance) {
    for (const glm::vec3& n : mesh.normals) {
        CHECK(glm::length(n) == doctest::Approx(1.0).epsilon(tolerance));
    }
}

void check_uvs_in_unit_square(const Mesh& mesh) {
    for (const glm::vec2& uv : mesh.uvs) {
        CHECK(uv.x >= 0.0f);
        CHECK(uv.x <= 1.0f);
        CHECK(uv.y >= 0.0f);
        CHECK(uv.y <= 1.0f);
    }
}

// Counter-clockwise seen from outside: (b - a) × (c - a) points along every
// corner's normal, and for a convex solid centred on the origin, away from it.
void check_outward_ccw(const Mesh& mesh) {
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
        const std::uint32_t ia = mesh.indices[t], ib = mesh.indices[t + 1], ic = mesh.indices[t + 2];
        const glm::vec3 a = mesh.positions[ia], b = mesh.positions[ib], c = mesh.positions[ic];
        const glm::vec3 face = glm::cross(b - a, c - a);
        REQUIRE(glm::length(face) > 0.0f);
        CHECK(glm::dot(face, mesh.normals[ia]) > 0.0f);
        CHECK(glm::dot(face, mesh.normals[ib]) > 0.0f);
        CHECK(glm::dot(face, mesh.normals[ic]) > 0.0f);
    }
}

}  // namespace

TEST_CASE("sphere mesh is the reference's 64x64 UV sphere") {
    const Mesh mesh = tessera::make_sphere_mesh();
    CHECK(mesh.name == "sphere");
    REQUIRE(mesh.positions.size() == 65u * 65u);
    check_parallel_arrays(mesh);
    REQUIRE(mesh.indices.size() == 64u * 64u * 2u * 3u);
    check_indices_in_range(mesh);
    check_unit_normals(mesh, 1e-5);
    check_uvs_in_unit_square(mesh);

    SUBCASE("vertex (x, y) sits at index y*65 + x and follows the formula") {
        const double pi = 3.14159265359;
        for (const int y : {0, 1, 17, 32, 50, 64}) {
            for (const int x : {0, 3, 16, 40, 63, 64}) {
                const auto i = static_cast<std::size_t>(y * 65 + x);
                const double xs = x / 64.0, ys = y / 64.0;
                const glm::dvec3 expected{std::cos(2 * pi * xs) * std::sin(pi * ys), std::cos(pi * ys),
                                          std::sin(2 * pi * xs) * std::sin(pi * ys)};
                for (int k = 0; k < 3; ++k) {
                    CHECK(mesh.positions[i][k] == doctest::Approx(expected[k]).epsilon(1e-6));
                }
                CHECK(mesh.normals[i] == mesh.positions[i]);
                CHECK(mesh.uvs[i] == glm::vec2(static_cast<float>(xs), static_cast<float>(ys)));
            }
        }
        CHECK(mesh.positions[0] == glm::vec3(0.0f, 1.0f, 0.0f));  // north pole, exactly
    }

    SUBCASE("triangles follow the reference's index pattern, corners 1 and 2 swapped") {
        for (const int y : {0, 31, 63}) {
            for (const int x : {0, 5, 63}) {
                const auto quad = static_cast<std::size_t>(y * 64 + x) * 6;
                const auto i0 = static_cast<std::uint32_t>(y * 65 + x);
                const auto i1 = static_cast<std::uint32_t>((y + 1) * 65 + x);
                const auto i2 = i1 + 1, i3 = i0 + 1;
                CHECK(mesh.indices[quad + 0] == i0);
                CHECK(mesh.indices[quad + 1] == i2);
                CHECK(mesh.indices[quad + 2] == i1);
                CHECK(mesh.indices[quad + 3] == i0);
                CHECK(mesh.indices[quad + 4] == i3);
                CHECK(mesh.indices[quad + 5] == i2);
            }
        }
    }

    SUBCASE("winding is consistent: counter-clockwise from outside (the reference's is clockwise)") {
        int inward = 0, outward = 0, degenerate = 0;
        for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
            const glm::vec3 a = mesh.positions[mesh.indices[t]];
            const glm::vec3 b = mesh.positions[mesh.indices[t + 1]];
            const glm::vec3 c = mesh.positions[mesh.indices[t + 2]];
            const glm::vec3 face = glm::cross(b - a, c - a);
            if (glm::length(face) < 1e-7f) {
                ++degenerate;  // the fans at the poles have two corners on the pole
            } else if (glm::dot(face, a + b + c) < 0.0f) {
                ++inward;
            } else {
                ++outward;
            }
        }
        CHECK(inward == 0);
        CHECK(degenerate <= 2 * 64);
        CHECK(outward + degenerate == 64 * 64 * 2);
    }
}

TEST_CASE("plane mesh: 2x2 square in XZ at y = 0 facing +Y") {
    const Mesh mesh = tessera::make_plane_mesh();
    CHECK(mesh.name == "plane");
    REQUIRE(mesh.positions.size() == 4);
    check_parallel_arrays(mesh);
    REQUIRE(mesh.indices.size() == 6);
    check_indices_in_range(mesh);
    check_unit_normals(mesh, 1e-6);
    check_uvs_in_unit_square(mesh);
    check_outward_ccw(mesh);
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        CHECK(mesh.normals[i] == glm::vec3(0, 1, 0));
        CHECK(mesh.positions[i].y == 0.0f);
        CHECK(std::abs(mesh.positions[i].x) == 1.0f);
        CHECK(std::abs(mesh.positions[i].z) == 1.0f);
    }
}

TEST_CASE("cube mesh: 2x2x2, 24 vertices, flat outward normals, CCW from outside") {
    const Mesh mesh = tessera::make_cube_mesh();
    CHECK(mesh.name == "cube");
    REQUIRE(mesh.positions.size() == 24);
    check_parallel_arrays(mesh);
    REQUIRE(mesh.indices.size() == 36);
    check_indices_in_range(mesh);
    check_unit_normals(mesh, 1e-6);
    check_uvs_in_unit_square(mesh);
    check_outward_ccw(mesh);

    glm::vec3 normal_sum{0.0f};
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const glm::vec3 p = mesh.positions[i], n = mesh.normals[i];
        for (int k = 0; k < 3; ++k) CHECK(std::abs(p[k]) == 1.0f);
        CHECK(glm::dot(p, n) == 1.0f);  // on the face the normal points out of
        normal_sum += n;
    }
    CHECK(normal_sum == glm::vec3(0.0f));  // every face present, 4 vertices each
}
