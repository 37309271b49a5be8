// Cube-map addressing and seamless filtering (src/environment/cube_map.cpp).
#include <cmath>
#include <random>

#include <doctest/doctest.h>

#include "environment/cube_map.hpp"

using namespace tessera::environment;

namespace {

// A smooth function of direction, written into every texel of a cube.
glm::vec3 smooth(const glm::vec3& d) {
    const glm::vec3 n = glm::normalize(d);
    return {1.0f + n.x, 1.0f + 0.5f * n.y, 2.0f + n.z * n.x};
}

CubeMap smooth_cube(int size, int levels = 1) {
    CubeMap cube(size, levels);
    for (int f = 0; f < kCubeFaces; ++f)
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x)
                cube.texel(0, f, x, y) = smooth(face_direction(f, (x + 0.5f) / size, (y + 0.5f) / size));
    cube.fill_borders(0);
    cube.generate_mipmaps();
    return cube;
}

}  // namespace

TEST_CASE("cube map: face_coords inverts face_direction on every face (GL's major-axis table)") {
    std::mt19937 random(7);
    std::uniform_real_distribution<float> unit(0.001f, 0.999f);
    for (int f = 0; f < kCubeFaces; ++f)
        for (int i = 0; i < 100; ++i) {
            const float s = unit(random), t = unit(random);
            const FaceCoords c = face_coords(face_direction(f, s, t) * 3.0f);
            CHECK(c.face == f);
            CHECK(c.s == doctest::Approx(s).epsilon(1e-5));
            CHECK(c.t == doctest::Approx(t).epsilon(1e-5));
        }
    // The GL table's orientation, one case per face: +X's s runs along −z, +Y's t along +z.
    CHECK(face_coords({1.0f, 0.0f, -0.5f}).s > 0.5f);
    CHECK(face_coords({0.0f, 1.0f, 0.5f}).t > 0.5f);
    CHECK(face_coords({0.0f, -0.5f, -1.0f}).t > 0.5f);
}

TEST_CASE("cube map: bilinear taps are seamless across face edges and corners") {
    const CubeMap cube = smooth_cube(16);
    // Along each edge, a tap just on either side sees nearly the same value (a
    // tap that clamped at its own face would jump by ~half a texel's change).
    const float step = 1e-4f;
    for (const glm::vec3 edge : {glm::vec3(1, 1, 0.3f), glm::vec3(1, -0.2f, 1), glm::vec3(-1, 0.4f, -1), glm::vec3(0.1f, -1, -1)}) {
        glm::vec3 a = edge, b = edge;
        // Nudge across the edge between the two largest components.
        const int i = std::fabs(edge.x) == 1 ? 0 : 1, j = std::fabs(edge.z) == 1 ? 2 : 1;
        a[i] += step * (edge[i] > 0 ? 1 : -1), b[j] += step * (edge[j] > 0 ? 1 : -1);
        const glm::vec3 va = cube.sample_bilinear(a, 0), vb = cube.sample_bilinear(b, 0);
        CHECK(va.x == doctest::Approx(vb.x).epsilon(1e-3));
        CHECK(va.z == doctest::Approx(vb.z).epsilon(1e-3));
        // ...and close to the function itself (bilinear error only).
        CHECK(va.x == doctest::Approx(smooth(edge).x).epsilon(0.02));
    }
    const glm::vec3 corner = cube.sample_bilinear({1, 1, 1}, 0);
    CHECK(corner.x == doctest::Approx(smooth({1, 1, 1}).x).epsilon(0.03));
}

TEST_CASE("cube map: mip levels are box means, trilinear blends two levels") {
    const CubeMap cube = smooth_cube(8, 4);
    CHECK(cube.size(1) == 4);
    CHECK(cube.size(3) == 1);
    const glm::vec3 mean = (cube.texel(0, 2, 0, 0) + cube.texel(0, 2, 1, 0) + cube.texel(0, 2, 0, 1) + cube.texel(0, 2, 1, 1)) * 0.25f;
    CHECK(cube.texel(1, 2, 0, 0).x == doctest::Approx(mean.x));
    const glm::vec3 d(0.3f, 1.0f, -0.2f);
    const glm::vec3 a = cube.sample_bilinear(d, 1), b = cube.sample_bilinear(d, 2);
    const glm::vec3 half = cube.sample_trilinear(d, 1.5f);
    CHECK(half.y == doctest::Approx(0.5f * (a.y + b.y)));
    CHECK(cube.sample_trilinear(d, -3.0f).x == cube.sample_bilinear(d, 0).x);  // clamped to the base
    CHECK(cube.sample_trilinear(d, 9.0f).x == doctest::Approx(cube.sample_bilinear(d, 3).x));
}

TEST_CASE("BRDF table: GL_LINEAR with GL_CLAMP_TO_EDGE") {
    BrdfLut lut(4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) lut.texel(x, y) = {float(x), float(10 * y)};
    CHECK(lut.sample(0.375f, 0.125f).x == doctest::Approx(1.0f));  // texel centres (1.5/4, 0.5/4)
    CHECK(lut.sample(0.5f, 0.125f).x == doctest::Approx(1.5f));
    CHECK(lut.sample(0.0f, 0.0f).x == 0.0f);  // clamped
    CHECK(lut.sample(1.0f, 1.0f).y == 30.0f);
}
