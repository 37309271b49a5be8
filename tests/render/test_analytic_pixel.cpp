#include <doctest/doctest.h>

#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>

#include "shade/pbr_reference.hpp"
#include "tessera/renderer.hpp"
#include "test_paths.hpp"

using namespace tessera;

// For a sphere of the demo grid, the pixel its centre projects into should show
// what the reference shader gives at the exact sphere surface seen through that
// pixel's centre: the mesh, rasterizer, interpolation and SIMD shader together
// must stay within 1/255 of the analytic answer.
TEST_CASE("the pixel at a sphere's centre matches the scalar shader at the exact surface point") {
    const Scene scene = load_scene_file(test::scene_path("spheres.toml"));
    Renderer renderer;
    const RenderedImage& image = renderer.render(scene);
    const glm::mat4 view = view_matrix(scene.camera);
    const glm::mat4 projection = projection_matrix(scene.camera, scene.width, scene.height);
    const glm::mat4 inverse_view_projection = glm::inverse(projection * view);

    for (std::size_t o = 0; o < scene.objects.size(); o += 4) {  // every 4th sphere: all rows and columns
        CAPTURE(o);
        const Object& sphere = scene.objects[o];
        const glm::vec3 centre = glm::vec3(sphere.model[3]);
        // The pixel containing the projected centre (image row 0 at the top).
        const glm::vec4 clip = projection * view * glm::vec4(centre, 1);
        const float sx = (clip.x / clip.w * 0.5f + 0.5f) * scene.width;
        const float sy = (0.5f - clip.y / clip.w * 0.5f) * scene.height;
        const int px = int(sx), py = int(sy);
        // The ray from the eye through that pixel's centre, hitting the unit sphere.
        const float ndc_x = (px + 0.5f) / scene.width * 2 - 1, ndc_y = 1 - (py + 0.5f) / scene.height * 2;
        const glm::vec4 far_point = inverse_view_projection * glm::vec4(ndc_x, ndc_y, 1, 1);
        const glm::vec3 origin = scene.camera.position;
        const glm::vec3 dir = glm::normalize(glm::vec3(far_point) / far_point.w - origin);
        const glm::vec3 oc = origin - centre;
        const float b = glm::dot(oc, dir), c = glm::dot(oc, oc) - 1.0f;
        REQUIRE(b * b - c > 0);
        const glm::vec3 hit = origin + (-b - std::sqrt(b * b - c)) * dir;
        const glm::vec3 normal = hit - centre;  // unit sphere: the exact normal

        const glm::vec3 expected = shade::display_from_radiance(shade::shade_pbr(
            hit, normal, scene.materials[sphere.material], scene.camera.position, scene.lights));
        const std::size_t i = 3 * (std::size_t(py) * scene.width + px);
        const glm::vec3 rendered_hdr{image.radiance[i], image.radiance[i + 1], image.radiance[i + 2]};
        const glm::vec3 rendered = shade::display_from_radiance(rendered_hdr);
        for (int ch = 0; ch < 3; ++ch) {
            CHECK(std::abs(rendered[ch] - expected[ch]) <= 1.0f / 255.0f);
            CHECK(std::abs(float(image.display[i + ch]) - expected[ch] * 255.0f) <= 1.0f);
        }
    }
}
