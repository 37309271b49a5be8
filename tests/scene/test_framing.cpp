// Default framing (src/scene/framing.hpp): the view direction follows the
// model's shape so that a flat model is seen from its flat side.
#include <doctest/doctest.h>

#include "scene/framing.hpp"

using namespace tessera;

namespace {

Bounds box(const glm::vec3& min, const glm::vec3& max) {
    Bounds b;
    b.add(min), b.add(max);
    return b;
}

bool near(const glm::vec3& a, const glm::vec3& b) { return glm::length(a - b) <= 1e-5f; }

// Whether the box's eight corners all land inside the camera's image.
bool frames_box(const Camera& camera, const Bounds& bounds, float aspect) {
    const glm::mat4 clip_from_world = glm::mat4(projection_matrix(camera, int(100 * aspect), 100)) * view_matrix(camera);
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p{corner & 1 ? bounds.max.x : bounds.min.x, corner & 2 ? bounds.max.y : bounds.min.y,
                          corner & 4 ? bounds.max.z : bounds.min.z};
        const glm::vec4 clip = clip_from_world * glm::vec4(p, 1.0f);
        if (!(clip.w > 0.0f) || std::abs(clip.x) > clip.w || std::abs(clip.y) > clip.w || std::abs(clip.z) > clip.w)
            return false;
    }
    return true;
}

}  // namespace

TEST_CASE("framing looks along -Z at a solid model and from above-front at a flat horizontal one") {
    // A cube and a box flat in Z keep the old view along -Z.
    CHECK(near(framing_direction(box({-1, -1, -1}, {1, 1, 1})), {0, 0, 1}));
    CHECK(near(framing_direction(box({-1, -1, 0}, {1, 1, 0})), {0, 0, 1}));
    // TwoSidedPlane's box: 2 × 0 × 2 in XZ. Looking along -Z would see it edge on.
    const Bounds floor = box({-1, 0, -1}, {1, 0, 1});
    CHECK(near(framing_direction(floor), glm::normalize(glm::vec3(0, 1, 1))));
    // Thin, not quite flat: 5% of the longest side.
    CHECK(near(framing_direction(box({-1, 0, -1}, {1, 0.1f, 1})), glm::normalize(glm::vec3(0, 1, 1))));
    // 20% is a slab, not a floor.
    CHECK(near(framing_direction(box({-1, 0, -1}, {1, 0.4f, 1})), {0, 0, 1}));
    // A wall facing ±X is seen from +X.
    CHECK(near(framing_direction(box({0, -1, -1}, {0, 1, 1})), {1, 0, 0}));

    const Camera camera = framing_camera(floor, 16.0f / 9.0f);
    CHECK(near(glm::normalize(camera.position - camera.target), glm::normalize(glm::vec3(0, 1, 1))));
    CHECK(frames_box(camera, floor, 16.0f / 9.0f));
    // The plane covers a real part of the image (not an edge-on line): its far and near
    // edges are well apart vertically.
    const glm::mat4 clip_from_world = projection_matrix(camera, 160, 90) * view_matrix(camera);
    const glm::vec4 near_edge = clip_from_world * glm::vec4(0, 0, 1, 1), far_edge = clip_from_world * glm::vec4(0, 0, -1, 1);
    CHECK(near_edge.y / near_edge.w - far_edge.y / far_edge.w < -0.5f);
}
