#include <doctest/doctest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "image/resolve.hpp"
#include "tessera/renderer.hpp"

using namespace tessera;

namespace {

// A scene with one light, one material and the given triangles as one mesh.
Scene triangle_scene(std::vector<glm::vec3> positions) {
    Scene scene;
    scene.source = "test";
    scene.width = 96;
    scene.height = 64;
    scene.camera = {.position = {0, 1, 0}, .target = {0, 1, -1}, .up = {0, 1, 0}, .fov_y_degrees = 60, .near_plane = 0.1f, .far_plane = 50};
    scene.lights.push_back({{0, 5, 0}, {50, 50, 50}});
    scene.materials.push_back({});
    Mesh mesh;
    mesh.name = "triangles";
    mesh.positions = std::move(positions);
    mesh.normals.assign(mesh.positions.size(), glm::vec3(0, 1, 0));
    for (std::uint32_t i = 0; i < mesh.positions.size(); ++i) mesh.indices.push_back(i);
    scene.meshes.push_back(std::move(mesh));
    scene.objects.push_back({0, 0, glm::mat4(1.0f)});
    return scene;
}

int count_background(const Scene& scene, const RenderedImage& image) {
    const std::uint8_t clear = image::quantize_unorm8(scene.clear_color.r);
    int n = 0;
    for (std::size_t p = 0; p < image.display.size(); p += 3) n += image.display[p] == clear && image.display[p + 1] == clear;
    return n;
}

}  // namespace

TEST_CASE("a floor reaching behind the camera is clipped at the near plane and drawn below the horizon") {
    // One huge triangle at y = 0 with two corners in front of the eye and one far behind it.
    const Scene scene = triangle_scene({{-100, 0, -40}, {100, 0, -40}, {0, 0, 30}});
    Renderer renderer({.threads = 2});
    const RenderedImage& image = renderer.render(scene);
    CHECK(renderer.last_frame_stats().triangles_binned >= 2);  // clipped (near plane, then guard band) to a fan
    const std::uint8_t clear = image::quantize_unorm8(scene.clear_color.r);
    for (int x = 0; x < image.width; ++x) {
        CHECK(image.display[3 * x] == clear);                                            // top row: sky
        CHECK(image.display[3 * (std::size_t(image.height - 1) * image.width + x)] != clear);  // bottom row: floor
    }
    // Radiance stays finite everywhere (nothing from w <= 0 was drawn).
    for (float v : image.radiance) REQUIRE(std::isfinite(v));
}

TEST_CASE("a triangle wholly behind the camera draws nothing") {
    const Scene scene = triangle_scene({{-1, 0, 5}, {1, 0, 5}, {0, 2, 5}});
    Renderer renderer;
    const RenderedImage& image = renderer.render(scene);
    CHECK(renderer.last_frame_stats().triangles_binned == 0);
    CHECK(count_background(scene, image) == image.width * image.height);
}

TEST_CASE("triangles far outside the guard band are clipped, not overflowed") {
    // Corners a million units to the sides, in front of the camera.
    const Scene scene = triangle_scene({{-1e6f, -1e6f, -5}, {1e6f, -1e6f, -5}, {0, 1e6f, -5}});
    Renderer renderer;
    const RenderedImage& image = renderer.render(scene);
    CHECK(count_background(scene, image) == 0);  // it covers the whole view
}
