#include <doctest/doctest.h>

#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>

#include "raster_test_util.hpp"

using namespace tessera;

namespace {

constexpr int kSize = 64;

struct Ray {
    glm::vec3 origin, direction;
};

// The view-space ray through pixel (i, j)'s centre for a symmetric perspective
// with vertical field of view fov_y and a square viewport.
Ray view_ray(int i, int j, float fov_y) {
    const float t = std::tan(fov_y / 2);
    const float ndc_x = (i + 0.5f) / kSize * 2 - 1, ndc_y = 1 - (j + 0.5f) / kSize * 2;
    return {{0, 0, 0}, {ndc_x * t, ndc_y * t, -1}};
}

}  // namespace

TEST_CASE("interpolation is perspective-correct: barycentrics match the ray-triangle intersection") {
    // A triangle receding in depth: corners at very different w.
    const glm::vec3 p0{-3, -3, -2}, p1{6, -2, -12}, p2{-1, 5, -6};
    const float fov = glm::radians(90.0f);
    const glm::mat4 projection = glm::perspective(fov, 1.0f, 0.1f, 100.0f);
    const auto t = raster::setup_triangle({kSize, kSize},
                                          {projection * glm::vec4(p0, 1), projection * glm::vec4(p1, 1),
                                           projection * glm::vec4(p2, 1)},
                                          {0, 1, 2});
    REQUIRE(t);
    raster::TileBuffers buffers;
    buffers.reset(kSize);
    raster::RasterCounters counters;
    raster::rasterize_triangle(*t, 7, {0, 0, kSize, kSize}, buffers, counters);
    REQUIRE(counters.fragments > 200);

    // Which input corner each set-up corner is (setup may swap 1 and 2).
    const glm::vec3 corner[3] = {p0, t->vertex[1] == 1 ? p1 : p2, t->vertex[1] == 1 ? p2 : p1};
    std::array<float, 3> inv_w;  // 1 / clip w of the set-up corners
    for (int k = 0; k < 3; ++k) inv_w[k] = 1.0f / (projection * glm::vec4(corner[k], 1)).w;
    const glm::vec3 normal = glm::cross(corner[1] - corner[0], corner[2] - corner[0]);
    double worst_perspective = 0, worst_linear = 0, worst_depth = 0;
    for (int j = 0; j < kSize; ++j)
        for (int i = 0; i < kSize; ++i) {
            const std::size_t p = std::size_t(j) * kSize + i;
            if (!buffers.covered(p)) continue;
            CHECK(buffers.triangle[p] == 7);
            // Analytic: intersect the pixel's ray with the triangle's plane, then
            // express the hit point in the corners' barycentric coordinates.
            const Ray ray = view_ray(i, j, fov);
            const float s = glm::dot(corner[0] - ray.origin, normal) / glm::dot(ray.direction, normal);
            const glm::vec3 hit = ray.origin + s * ray.direction;
            const float area = glm::dot(glm::cross(corner[1] - corner[0], corner[2] - corner[0]), normal);
            const float exact_b1 = glm::dot(glm::cross(hit - corner[0], corner[2] - corner[0]), normal) / area;
            const float exact_b2 = glm::dot(glm::cross(corner[1] - corner[0], hit - corner[0]), normal) / area;
            const auto [b1, b2] = raster::perspective_barycentrics(inv_w, buffers.lambda1[p], buffers.lambda2[p]);
            worst_perspective = std::max({worst_perspective, double(std::abs(b1 - exact_b1)), double(std::abs(b2 - exact_b2))});
            worst_linear = std::max(worst_linear, double(std::abs(buffers.lambda1[p] - exact_b1)));
            // Window depth of the hit point: z_ndc · 0.5 + 0.5.
            const glm::vec4 clip = projection * glm::vec4(hit, 1);
            worst_depth = std::max(worst_depth, double(std::abs(buffers.depth[p] - (clip.z / clip.w * 0.5f + 0.5f))));
        }
    // Snapping corners to 1/256 pixel moves the triangle by ~1e-4 of its size.
    CHECK(worst_perspective < 2e-3);
    CHECK(worst_depth < 1e-5);
    // Screen-space (affine) barycentrics are far off here: the test can tell them apart.
    CHECK(worst_linear > 0.05);
}

TEST_CASE("depth test LESS: the nearer triangle wins in either order, the first of equal depths wins") {
    const auto near_tri = test::screen_triangle({4, 4}, {60, 8}, {10, 60}, kSize, 0.25f);
    const auto far_tri = test::screen_triangle({2, 30}, {62, 2}, {62, 62}, kSize, 0.75f);
    REQUIRE(near_tri);
    REQUIRE(far_tri);
    for (bool near_first : {true, false}) {
        raster::TileBuffers buffers;
        buffers.reset(kSize);
        raster::RasterCounters counters;
        const raster::TileRect all{0, 0, kSize, kSize};
        if (near_first) raster::rasterize_triangle(*near_tri, 1, all, buffers, counters);
        raster::rasterize_triangle(*far_tri, 2, all, buffers, counters);
        if (!near_first) raster::rasterize_triangle(*near_tri, 1, all, buffers, counters);
        const auto near_cov = test::coverage(near_tri, kSize), far_cov = test::coverage(far_tri, kSize);
        int overlap = 0;
        for (std::size_t p = 0; p < near_cov.size(); ++p) {
            if (near_cov[p] && far_cov[p]) ++overlap;
            if (near_cov[p]) CHECK(buffers.triangle[p] == 1);
            else if (far_cov[p]) CHECK(buffers.triangle[p] == 2);
        }
        CHECK(overlap > 300);
    }
    // Equal depth: LESS keeps the first triangle drawn.
    raster::TileBuffers buffers;
    buffers.reset(kSize);
    raster::RasterCounters counters;
    const auto same_depth = test::screen_triangle({2, 30}, {62, 2}, {62, 62}, kSize, 0.25f);
    raster::rasterize_triangle(*near_tri, 1, {0, 0, kSize, kSize}, buffers, counters);
    raster::rasterize_triangle(*same_depth, 2, {0, 0, kSize, kSize}, buffers, counters);
    CHECK(buffers.triangle[30 * kSize + 30] == 1);
}
