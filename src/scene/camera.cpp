// Camera matrices with OpenGL conventions, as the reference demo builds them.
// GLM's defaults are exactly those (right-handed, clip z in [-w, w]); nothing
// here may define GLM_FORCE_DEPTH_ZERO_TO_ONE or GLM_FORCE_LEFT_HANDED.
#include <glm/gtc/matrix_transform.hpp>

#include "tessera/scene.hpp"

namespace tessera {

glm::mat4 view_matrix(const Camera& camera) {
    if (camera.explicit_matrices) return camera.explicit_view;
    return glm::lookAt(camera.position, camera.target, camera.up);
}

glm::mat4 projection_matrix(const Camera& camera, int width, int height) {
    if (camera.explicit_matrices) return camera.explicit_projection;
    if (camera.projection == Projection::orthographic) {
        glm::mat4 m(1.0f);  // column-major: m[column][row]
        m[0][0] = 1.0f / camera.x_magnification;
        m[1][1] = 1.0f / camera.y_magnification;
        m[2][2] = 2.0f / (camera.near_plane - camera.far_plane);
        m[3][2] = (camera.far_plane + camera.near_plane) / (camera.near_plane - camera.far_plane);
        return m;
    }
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    return glm::perspective(glm::radians(camera.fov_y_degrees), aspect, camera.near_plane,
                            camera.far_plane);
}

}  // namespace tessera
