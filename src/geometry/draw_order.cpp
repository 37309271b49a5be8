#include "geometry/draw_order.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tessera::geometry {

float object_view_depth(const Scene& scene, const Object& object) {
    const Mesh& mesh = scene.meshes[object.mesh];
    glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
    for (const glm::vec3& p : mesh.positions) {
        if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))) continue;  // dropped when drawn too
        lo = glm::min(lo, p), hi = glm::max(hi, p);
    }
    if (!(lo.x <= hi.x)) return 0.0f;
    const glm::vec4 centre = view_matrix(scene.camera) * object.model * glm::vec4((lo + hi) * 0.5f, 1.0f);
    return std::isfinite(centre.z) ? -centre.z : 0.0f;
}

std::vector<std::uint32_t> blended_objects_back_to_front(const Scene& scene) {
    std::vector<std::uint32_t> order;
    std::vector<float> depth(scene.objects.size(), 0.0f);
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        const Object& object = scene.objects[o];
        if (scene.materials[object.material].alpha_mode != AlphaMode::blend) continue;
        order.push_back(std::uint32_t(o));
        depth[o] = object_view_depth(scene, object);
    }
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return depth[a] > depth[b]; });
    return order;
}

}  // namespace tessera::geometry
