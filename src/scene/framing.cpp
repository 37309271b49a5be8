#include "scene/framing.hpp"

#include <algorithm>
#include <cmath>

namespace tessera {

void Bounds::add(const glm::vec3& point) {
    if (!(std::isfinite(point.x) && std::isfinite(point.y) && std::isfinite(point.z))) return;
    min = glm::min(min, point);
    max = glm::max(max, point);
}

void Bounds::add(const Bounds& other) {
    if (other.empty()) return;
    add(other.min);
    add(other.max);
}

Bounds Bounds::transformed(const glm::mat4& transform) const {
    Bounds result;
    if (empty()) return result;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 local{corner & 1 ? max.x : min.x, corner & 2 ? max.y : min.y, corner & 4 ? max.z : min.z};
        result.add(glm::vec3(transform * glm::vec4(local, 1.0f)));
    }
    return result;
}

Bounds scene_bounds(const Scene& scene) {
    std::vector<Bounds> mesh_bounds(scene.meshes.size());
    for (std::size_t m = 0; m < scene.meshes.size(); ++m)
        for (const glm::vec3& p : scene.meshes[m].positions) mesh_bounds[m].add(p);
    Bounds bounds;
    for (const Object& object : scene.objects)
        if (object.mesh < mesh_bounds.size()) bounds.add(mesh_bounds[object.mesh].transformed(object.model));
    return bounds;
}

glm::vec3 framing_direction(const Bounds& bounds) {
    if (bounds.empty()) return {0.0f, 0.0f, 1.0f};
    const glm::vec3 extent = bounds.max - bounds.min;
    const float largest = std::max({extent.x, extent.y, extent.z});
    const bool flat_y = extent.y <= kFlatExtentRatio * largest && extent.y <= extent.x && extent.y <= extent.z;
    const bool flat_x = extent.x <= kFlatExtentRatio * largest && extent.x < extent.y && extent.x <= extent.z;
    if (flat_y) return glm::normalize(glm::vec3(0.0f, 1.0f, 1.0f));  // above-front, 45° down
    if (flat_x) return {1.0f, 0.0f, 0.0f};
    return {0.0f, 0.0f, 1.0f};
}

Camera framing_camera(const Bounds& bounds, float aspect) {
    Camera camera;
    if (bounds.empty()) return camera;
    const glm::vec3 center = bounds.center();
    // A flat or point-like model still needs a non-zero distance.
    const float radius = std::max(bounds.radius(), 1e-3f * std::max(1.0f, glm::length(center)));
    const float half_fov_y = glm::radians(camera.fov_y_degrees) * 0.5f;
    // The narrower of the two half-angles decides: tall images need more distance.
    const float half_fov_x = std::atan(std::tan(half_fov_y) * (aspect > 0.0f ? aspect : 1.0f));
    const float distance = radius / std::sin(std::min(half_fov_y, half_fov_x));
    camera.position = center + distance * framing_direction(bounds);
    camera.target = center;
    camera.up = {0.0f, 1.0f, 0.0f};
    camera.near_plane = 0.5f * (distance - radius);
    camera.far_plane = 2.0f * (distance + radius);
    return camera;
}

float far_plane_covering(const Camera& camera, const Bounds& bounds) {
    float farthest = 0.0f;
    if (!bounds.empty()) {
        for (int corner = 0; corner < 8; ++corner) {
            const glm::vec3 p{corner & 1 ? bounds.max.x : bounds.min.x, corner & 2 ? bounds.max.y : bounds.min.y,
                              corner & 4 ? bounds.max.z : bounds.min.z};
            farthest = std::max(farthest, glm::length(p - camera.position));
        }
    }
    return std::max(1.5f * farthest, 100.0f * camera.near_plane);
}

std::vector<Light> default_light_rig(const Camera& camera, const Bounds& bounds) {
    const glm::vec3 center = bounds.empty() ? camera.target : bounds.center();
    const float radius = bounds.empty() ? 1.0f : std::max(bounds.radius(), 1e-3f);
    const glm::vec3 forward = glm::normalize(camera.target - camera.position);
    const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
    const glm::vec3 up = glm::cross(right, forward);
    const glm::vec3 middle = 0.5f * (camera.position + center);
    std::vector<Light> lights;
    for (const glm::vec2 corner : {glm::vec2{-1, 1}, glm::vec2{1, 1}, glm::vec2{-1, -1}, glm::vec2{1, -1}}) {
        Light light;
        light.position = middle + radius * (corner.x * right + corner.y * up);
        const float distance = glm::length(center - light.position);
        light.color = glm::vec3(1.5f * distance * distance);
        lights.push_back(light);
    }
    return lights;
}

}  // namespace tessera
