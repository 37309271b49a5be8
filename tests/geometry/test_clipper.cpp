#include <doctest/doctest.h>

#include <limits>

#include "geometry/clipper.hpp"

using namespace tessera::geometry;

namespace {

ShadedVertex vertex_at(glm::vec4 clip, glm::vec3 world) { return {clip, world, glm::vec3(0, 0, 1), glm::vec2(0)}; }

const GuardBand kGuard(640, 480);

}  // namespace

TEST_CASE("a triangle straddling the near plane is cut at z = -w, attributes following") {
    // One corner behind the near plane (z < -w), two in front.
    const ShadedVertex a = vertex_at({0, 0, -3, 1}, {0, 0, 0});
    const ShadedVertex b = vertex_at({1, 0, 0, 2}, {1, 0, 0});
    const ShadedVertex c = vertex_at({0, 1, 0, 2}, {0, 1, 0});
    const std::uint32_t oa = outcode(a.clip_pos, kGuard), ob = outcode(b.clip_pos, kGuard), oc = outcode(c.clip_pos, kGuard);
    CHECK(((oa) & kOutsideNear) != 0);
    CHECK(((ob) & kOutsideNear) == 0);
    REQUIRE(classify_triangle(oa, ob, oc) == ClipResult::clipped);

    ClippedPolygon polygon;
    clip_triangle(a, b, c, (oa | ob | oc) & kClipPlaneBits, kGuard, polygon);
    REQUIRE(polygon.count == 4);  // the corner behind is replaced by two on the plane
    int new_corners = 0;
    for (int i = 0; i < polygon.count; ++i) {
        const ShadedVertex& v = polygon.corners[i];
        CHECK(v.clip_pos.z + v.clip_pos.w >= -1e-6f);
        CHECK(v.clip_pos.w > 0.0f);
        if (polygon.source[i] < 0) {
            ++new_corners;
            CHECK(v.clip_pos.z + v.clip_pos.w == doctest::Approx(0.0f).epsilon(1e-6));
        } else {
            CHECK(polygon.source[i] != 0);  // corner a is gone
        }
    }
    CHECK(new_corners == 2);
    // Edge a->b crosses the plane halfway (distances z + w of -2 and +2), and
    // every attribute moves by the same fraction as the clip position.
    bool found_ab = false;
    for (int i = 0; i < polygon.count; ++i)
        if (polygon.source[i] < 0 && polygon.corners[i].world_pos.y == doctest::Approx(0.0f)) {
            found_ab = true;
            CHECK(polygon.corners[i].world_pos.x == doctest::Approx(0.5f));
            CHECK(polygon.corners[i].clip_pos.w == doctest::Approx(1.5f));
        }
    CHECK(found_ab);
}

TEST_CASE("a triangle wholly behind the camera is rejected without clipping") {
    // Behind the eye w < 0 with z > -w... for a perspective matrix z = a·z_eye + b and w = -z_eye,
    // so points behind the eye have w < 0 and lie outside the near plane (z < -w).
    const glm::vec4 p0{0, 0, -5, -1}, p1{1, 0, -5, -1}, p2{0, 1, -6, -2};
    const std::uint32_t o0 = outcode(p0, kGuard), o1 = outcode(p1, kGuard), o2 = outcode(p2, kGuard);
    CHECK(((o0) & kOutsideNear) != 0);
    CHECK(((o1) & kOutsideNear) != 0);
    CHECK(((o2) & kOutsideNear) != 0);
    CHECK(classify_triangle(o0, o1, o2) == ClipResult::rejected);
}

TEST_CASE("triangles inside the guard band need no clipping even when they leave the viewport") {
    const glm::vec4 p0{-3, 0, 0, 1}, p1{3, 0, 0, 1}, p2{0, 3, 0, 1};  // wider than the viewport
    const std::uint32_t o0 = outcode(p0, kGuard), o1 = outcode(p1, kGuard), o2 = outcode(p2, kGuard);
    CHECK(classify_triangle(o0, o1, o2) == ClipResult::accepted);
    // Beyond the guard band it must be clipped.
    const glm::vec4 far_right{kGuard.x_ndc * 2.0f, 0, 0, 1};
    CHECK(classify_triangle(o0, outcode(far_right, kGuard), o2) == ClipResult::clipped);
}

TEST_CASE("triangles wholly outside one side of the viewport are culled") {
    const glm::vec4 p0{2, 0, 0, 1}, p1{3, 0, 0, 1}, p2{2, 1, 0, 1};
    CHECK(classify_triangle(outcode(p0, kGuard), outcode(p1, kGuard), outcode(p2, kGuard)) == ClipResult::rejected);
}

TEST_CASE("a vertex with NaN drops its triangle") {
    const glm::vec4 bad{std::numeric_limits<float>::quiet_NaN(), 0, 0, 1};
    const glm::vec4 good{0, 0, 0, 1};
    CHECK(outcode(bad, kGuard) == kNotFinite);
    CHECK(classify_triangle(outcode(bad, kGuard), outcode(good, kGuard), outcode(good, kGuard)) == ClipResult::rejected);
}

TEST_CASE("clipping against the far plane and the guard band together keeps every corner inside both") {
    const ShadedVertex a = vertex_at({0, 0, 0, 1}, {0, 0, 0});
    const ShadedVertex b = vertex_at({kGuard.x_ndc * 40.0f, 0, 0, 10}, {1, 0, 0});  // beyond the guard band
    const ShadedVertex c = vertex_at({0, 1, 30, 10}, {0, 1, 0});                      // beyond the far plane
    const std::uint32_t planes =
        (outcode(a.clip_pos, kGuard) | outcode(b.clip_pos, kGuard) | outcode(c.clip_pos, kGuard)) & kClipPlaneBits;
    CHECK(planes == (kOutsideFar | kOutsideGuardRight));
    ClippedPolygon polygon;
    clip_triangle(a, b, c, planes, kGuard, polygon);
    REQUIRE(polygon.count >= 3);
    for (int i = 0; i < polygon.count; ++i) {
        const glm::vec4& p = polygon.corners[i].clip_pos;
        CHECK(p.z <= p.w * (1 + 1e-6f));
        CHECK(p.x <= kGuard.x_ndc * p.w * (1 + 1e-6f));
    }
}

TEST_CASE("clipped corners carry their weights of the input corners, for attributes kept outside the vertex") {
    // Both near and guard-band clipping, so corners are made from corners already made.
    const ShadedVertex a = vertex_at({0, 0, -3, 1}, {0, 0, 0});
    const ShadedVertex b = vertex_at({1e6f, 0, 0, 2}, {4, 0, 1});
    const ShadedVertex c = vertex_at({0, 1, 0, 2}, {0, 2, 3});
    const std::uint32_t planes =
        (outcode(a.clip_pos, kGuard) | outcode(b.clip_pos, kGuard) | outcode(c.clip_pos, kGuard)) & kClipPlaneBits;
    REQUIRE((planes & kOutsideNear) != 0);
    REQUIRE((planes & kOutsideGuardRight) != 0);
    ClippedPolygon polygon;
    clip_triangle(a, b, c, planes, kGuard, polygon);
    REQUIRE(polygon.count >= 4);
    for (int i = 0; i < polygon.count; ++i) {
        CAPTURE(i);
        const glm::vec3& w = polygon.weights[i];
        CHECK(w.x + w.y + w.z == doctest::Approx(1.0f).epsilon(1e-6));
        const glm::vec3 world = w.x * a.world_pos + w.y * b.world_pos + w.z * c.world_pos;
        for (int k = 0; k < 3; ++k) CHECK(world[k] == doctest::Approx(polygon.corners[i].world_pos[k]).epsilon(1e-5));
        if (polygon.source[i] >= 0) CHECK(w[polygon.source[i]] == 1.0f);
    }
}
