// Points and lines drawn as 1-pixel squares and 1-pixel-wide parallelograms
// (src/geometry/line_expansion.hpp), checked pixel by pixel through the whole
// renderer under an orthographic camera where one world unit is one pixel.
#include <doctest/doctest.h>

#include <set>
#include <utility>

#include "geometry/line_expansion.hpp"
#include "tessera/renderer.hpp"

using namespace tessera;

namespace {

// 16×16 pixels, world x, y in [-8, 8] (y up), looking down -Z; one white
// directional light along -Z and a black background.
Scene pixel_grid_scene() {
    Scene scene;
    scene.width = scene.height = 16;
    scene.clear_color = glm::vec3(0.0f);
    scene.camera.position = {0, 0, 5};
    scene.camera.target = {0, 0, 0};
    scene.camera.projection = Projection::orthographic;
    scene.camera.x_magnification = scene.camera.y_magnification = 8.0f;
    scene.camera.near_plane = 0.0f;
    scene.camera.far_plane = 10.0f;
    Light light;
    light.type = LightType::directional;
    light.direction = {0, 0, -1};
    light.color = glm::vec3(3.0f);
    scene.lights.push_back(light);
    Material material;
    material.albedo = glm::vec3(0.8f);
    material.double_sided = false;  // drawn double-sided anyway
    scene.materials.push_back(material);
    return scene;
}

// (column, row from the top) of every pixel that is not the background.
std::set<std::pair<int, int>> covered(const RenderedImage& image) {
    std::set<std::pair<int, int>> pixels;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const std::uint8_t* p = &image.display[3 * (std::size_t(y) * std::size_t(image.width) + std::size_t(x))];
            if (p[0] || p[1] || p[2]) pixels.insert({x, y});
        }
    return pixels;
}

void add(Scene& scene, Topology topology, std::vector<glm::vec3> positions) {
    Mesh mesh;
    mesh.topology = topology;
    mesh.positions = std::move(positions);
    for (std::uint32_t i = 0; i < mesh.positions.size(); ++i) mesh.indices.push_back(i);
    scene.meshes.push_back(mesh);
    scene.objects.push_back(Object{std::uint32_t(scene.meshes.size() - 1), 0, glm::mat4(1.0f)});
}

}  // namespace

TEST_CASE("a point covers the one pixel whose centre is nearest, a line one pixel per step of its major axis") {
    SUBCASE("a point at window (8.3, 8.2) lights pixel (8, row 7 from the top)") {
        Scene scene = pixel_grid_scene();
        add(scene, Topology::points, {{0.3f, 0.2f, 0.0f}});
        Renderer renderer({.threads = 2});
        CHECK(covered(renderer.render(scene)) == std::set<std::pair<int, int>>{{8, 7}});
    }
    SUBCASE("an x-major line covers one pixel per column between its ends") {
        Scene scene = pixel_grid_scene();
        // Window x 2.7 → 12.6 at y 4.8: centres x = 3.5 .. 12.5 in the row whose centre is 4.5.
        add(scene, Topology::lines, {{-5.3f, -3.2f, 0.0f}, {4.6f, -3.2f, 0.0f}});
        std::set<std::pair<int, int>> expected;
        for (int x = 3; x <= 12; ++x) expected.insert({x, 16 - 1 - 4});
        Renderer renderer({.threads = 2});
        CHECK(covered(renderer.render(scene)) == expected);
    }
    SUBCASE("a diagonal y-major line covers one pixel per row, its column following the line") {
        Scene scene = pixel_grid_scene();
        // Window (10.2, 9.1) → (12.2, 14.6): rows with centres 9.5 .. 14.5.
        add(scene, Topology::lines, {{2.2f, 1.1f, 0.0f}, {4.2f, 6.6f, 0.0f}});
        Renderer renderer({.threads = 2});
        const auto pixels = covered(renderer.render(scene));
        CHECK(pixels.size() == 6);
        for (const auto& [x, row] : pixels) {
            const float y = float(16 - 1 - row) + 0.5f;
            const float line_x = 10.2f + (y - 9.1f) * 2.0f / 5.5f;
            CHECK(std::abs(float(x) + 0.5f - line_x) <= 0.5f);
        }
    }
    SUBCASE("scalar and SIMD, one and two threads draw the same pixels") {
        Scene scene = pixel_grid_scene();
        add(scene, Topology::lines, {{-7.0f, -7.0f, 0.0f}, {6.5f, 5.0f, 0.0f}, {-6.0f, 7.0f, 1.0f}, {7.0f, -6.0f, -1.0f}});
        add(scene, Topology::points, {{-2.5f, 3.5f, 0.0f}, {5.0f, -5.0f, 0.0f}});
        Renderer scalar({.threads = 1, .isa = "scalar"});
        Renderer simd({.threads = 2});
        CHECK(scalar.render(scene).display == simd.render(scene).display);
    }
}

TEST_CASE("lines are clipped at the near plane, points outside the view volume are dropped") {
    Scene scene = pixel_grid_scene();
    scene.camera.projection = Projection::perspective;
    scene.camera.near_plane = 0.5f;
    scene.camera.far_plane = 10.0f;
    Mesh line;
    line.topology = Topology::lines;
    line.positions = {{1, 0, 0}, {1, 0, 20}};  // past the camera and behind it
    line.indices = {0, 1};
    const Mesh triangles = geometry::expand_to_triangles(line, glm::mat4(1.0f), scene.camera, 16, 16);
    REQUIRE(triangles.indices.size() == 6);
    for (const glm::vec3& p : triangles.positions) CHECK(p.z <= 5.0f - 0.5f + 1e-4f);  // in front of the near plane
    Mesh point;
    point.topology = Topology::points;
    point.positions = {{0, 0, 6}, {0, 0, 0}};  // behind the camera, and in view
    point.indices = {0, 1};
    CHECK(geometry::expand_to_triangles(point, glm::mat4(1.0f), scene.camera, 16, 16).indices.size() == 6);
}
