// Where to look from and how to light a model nobody placed a camera or light
// for: a glTF file without cameras or KHR_lights_punctual lights. Everything is
// derived from the model's world-space bounding box, so it works at any scale.
#pragma once

#include <limits>
#include <vector>

#include <glm/glm.hpp>

#include "tessera/scene.hpp"

namespace tessera {

// A world-space axis-aligned box; empty (min > max) until a point is added.
struct Bounds {
    glm::vec3 min{std::numeric_limits<float>::infinity()};
    glm::vec3 max{-std::numeric_limits<float>::infinity()};

    bool empty() const { return !(min.x <= max.x && min.y <= max.y && min.z <= max.z); }
    void add(const glm::vec3& point);  // non-finite points are ignored
    void add(const Bounds& other);
    glm::vec3 center() const { return 0.5f * (min + max); }
    float radius() const { return 0.5f * glm::length(max - min); }  // of the enclosing sphere
    // The box of this box's eight corners moved by `transform`.
    Bounds transformed(const glm::mat4& transform) const;
};

// The world box of every object in `scene` (each mesh's box moved by its model matrix).
Bounds scene_bounds(const Scene& scene);

// A box this much thinner along an axis than along its longest is a flat model.
inline constexpr float kFlatExtentRatio = 0.1f;

// From where framing_camera looks at the box's centre (unit length): +Z (looking
// along -Z) for most models; for a model flat in Y (a floor, TwoSidedPlane)
// from above-front, 45° down, (0, 1, 1)/√2, which shows the flat face and that
// it lies flat; for a model flat in X (a wall facing ±X) from +X.
glm::vec3 framing_direction(const Bounds& bounds);

// A 45° camera on the framing_direction side of the box's centre, looking at it with
// +Y up, far enough that the bounding sphere fits the narrower field of view of
// an image of `aspect` = width / height; near and far planes enclose the sphere
// with a margin. An empty box gets Camera{}.
Camera framing_camera(const Bounds& bounds, float aspect);

// A far plane for a camera that has none (glTF's infinite projection): past the
// farthest point of the box, at least 100 × near.
float far_plane_covering(const Camera& camera, const Bounds& bounds);

// Four white point lights in front of the model, at the corners of a square
// around the camera (up/down, left/right by the box's radius, half way from
// the camera to the model), so every side the camera sees is lit. Each gives
// radiance 1.5 at the box's centre: color = 1.5 · d² for a light at distance d
// (Light::color is in radiance·distance² units). An empty box gets four lights
// around Camera{}'s view of the origin.
std::vector<Light> default_light_rig(const Camera& camera, const Bounds& bounds);

}  // namespace tessera
