// Scenes built in code, as a program using the library would: the frame
// survives degenerate and extreme geometry, bad triangles are dropped (the
// image equals the one without them), and validate_scene refuses meshes the
// pipeline cannot read.
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include <doctest/doctest.h>

#include "scene/scene_validation.hpp"
#include "tessera/renderer.hpp"
#include "test_paths.hpp"

using namespace tessera;

namespace {

using Tri = std::array<glm::vec3, 3>;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// A 64×64 view of the z = 0 plane from z = 3, one light and one material.
Scene base_scene() {
    Scene scene;
    scene.source = "test scene";
    scene.width = 64;
    scene.height = 64;
    scene.camera.position = {0.0f, 0.0f, 3.0f};
    scene.camera.target = {0.0f, 0.0f, 0.0f};
    scene.lights.push_back({{1.0f, 2.0f, 4.0f}, {30.0f, 30.0f, 30.0f}});
    scene.materials.push_back(Material{.albedo = {0.8f, 0.3f, 0.2f}, .metallic = 0.2f, .roughness = 0.4f, .ao = 1.0f});
    return scene;
}

// One triangle per entry of `corners` (three positions each), normals +Z.
Mesh triangles(const std::vector<std::array<glm::vec3, 3>>& corners) {
    Mesh mesh;
    mesh.name = "test mesh";
    for (const auto& triangle : corners) {
        for (const glm::vec3& p : triangle) {
            mesh.indices.push_back(std::uint32_t(mesh.positions.size()));
            mesh.positions.push_back(p);
            mesh.normals.push_back({0.0f, 0.0f, 1.0f});
        }
    }
    return mesh;
}

Scene scene_with(Mesh mesh) {
    Scene scene = base_scene();
    scene.meshes.push_back(std::move(mesh));
    scene.objects.push_back(Object{});
    return scene;
}

const std::array<glm::vec3, 3> kGood{glm::vec3{-1.0f, -1.0f, 0.0f}, glm::vec3{1.0f, -1.0f, 0.0f},
                                     glm::vec3{0.0f, 1.0f, 0.0f}};

struct Frame {
    RenderedImage image;
    FrameStats stats;
};

Frame render(const Scene& scene) {
    validate_scene(scene);
    Renderer renderer({.threads = 2});
    Frame frame{renderer.render(scene), renderer.last_frame_stats()};
    REQUIRE(frame.image.width == scene.width);
    REQUIRE(frame.image.height == scene.height);
    REQUIRE(frame.image.display.size() == std::size_t(3) * scene.width * scene.height);
    return frame;
}

bool all_finite(const std::vector<float>& values) {
    for (float v : values)
        if (!std::isfinite(v)) return false;
    return true;
}

}  // namespace

TEST_CASE("bad triangles are dropped and the rest of the frame is unchanged") {
    const Frame reference = render(scene_with(triangles({kGood})));
    REQUIRE(reference.stats.fragments_shaded > 100);
    REQUIRE(all_finite(reference.image.radiance));

    struct Case {
        const char* name;
        std::array<glm::vec3, 3> bad;
    };
    const glm::vec3 a{-0.5f, 0.2f, 0.5f}, b{0.7f, -0.4f, 0.5f};
    const Case cases[] = {
        {"zero area: one point three times", Tri{a, a, a}},
        {"zero area: collinear corners", Tri{a, b, 0.5f * (a + b)}},
        {"NaN position", Tri{a, b, glm::vec3{kNaN, 0.0f, 0.5f}}},
        {"all positions NaN", Tri{glm::vec3(kNaN), glm::vec3(kNaN), glm::vec3(kNaN)}},
        {"+infinite position", Tri{a, b, glm::vec3{0.0f, kInf, 0.5f}}},
        {"-infinite position", Tri{a, glm::vec3{-kInf, 0.0f, 0.0f}, b}},
        {"far outside the guard band, in front of the camera", Tri{glm::vec3{1e6f, 0, 0}, glm::vec3{1e6f + 1, 0, 0}, glm::vec3{1e6f, 1, 0}}},
        {"huge coordinates, all off to one side", Tri{glm::vec3{1e30f, 1e30f, 0}, glm::vec3{2e30f, 1e30f, 0}, glm::vec3{1e30f, 2e30f, 0}}},
        {"huge and finite but overflowing in clip space", Tri{glm::vec3{3e38f, 0, 0}, glm::vec3{0, 3e38f, 0}, glm::vec3{0, 0, 3e38f}}},
        {"behind the camera", Tri{glm::vec3{-1, -1, 10}, glm::vec3{1, -1, 10}, glm::vec3{0, 1, 10}}},
        {"beyond the far plane", Tri{glm::vec3{-1, -1, -200}, glm::vec3{1, -1, -200}, glm::vec3{0, 1, -200}}},
    };
    for (const Case& c : cases) {
        CAPTURE(c.name);
        // The bad triangle is drawn first and in front of the good one, so it would show if kept.
        const Frame frame = render(scene_with(triangles({c.bad, kGood})));
        CHECK(frame.image.display == reference.image.display);
        CHECK(frame.image.radiance == reference.image.radiance);
        CHECK(frame.stats.triangles_in == 2);
        CHECK(frame.stats.fragments_shaded == reference.stats.fragments_shaded);
    }
}

TEST_CASE("extreme but valid triangles render with finite output") {
    const glm::vec3 a{-0.5f, 0.2f, 0.5f}, b{0.7f, -0.4f, 0.5f};
    const std::array<glm::vec3, 3> cases[] = {
        // Slivers: long and thinner than a subpixel step, or with one tiny edge.
        {glm::vec3{-2, 0, 0}, glm::vec3{2, 1e-6f, 0}, glm::vec3{2, 0, 0}},
        {glm::vec3{-2, -2, 0}, glm::vec3{2, 2, 0}, glm::vec3{2.0001f, 2, 0}},
        // One corner far outside the guard band (clipped), the others on screen.
        {a, b, glm::vec3{1e30f, 0, 0}},
        {a, b, glm::vec3{0, -1e30f, 0.5f}},
        {a, b, glm::vec3{1e7f, 1e7f, 0}},
        // Crossing the camera plane and the near plane.
        {glm::vec3{-1, -1, 10}, glm::vec3{1, -1, -1}, glm::vec3{0, 1, -1}},
        // Huge coordinates on every corner, spanning the view.
        {glm::vec3{1e30f, 1e30f, 0}, glm::vec3{-1e30f, 1e30f, 0}, glm::vec3{1e30f, -1e30f, -1e30f}},
        // Covering the whole screen many times over.
        {glm::vec3{-1e4f, -1e4f, 0}, glm::vec3{1e4f, -1e4f, 0}, glm::vec3{0, 1e4f, 0}},
    };
    for (const auto& corners : cases) {
        CAPTURE(corners[0].x);
        CAPTURE(corners[2].x);
        const Frame frame = render(scene_with(triangles({corners, kGood})));
        CHECK(all_finite(frame.image.radiance));
        CHECK(frame.stats.fragments_shaded <= std::uint64_t(64 * 64));
    }
}

Scene nan_normal_scene() {
    Mesh mesh = triangles({Tri{glm::vec3{-0.3f, -0.3f, 0.5f}, glm::vec3{0.3f, -0.3f, 0.5f}, glm::vec3{0, 0.3f, 0.5f}},
                           kGood});
    mesh.normals[0] = glm::vec3(kNaN);
    mesh.normals[1] = {kInf, 0.0f, 0.0f};
    return scene_with(mesh);
}

TEST_CASE("a triangle with NaN normals does not break the frame") {
    const Scene scene = nan_normal_scene();
    const Frame reference = render(scene_with(triangles({kGood})));
    for (const char* isa : {"scalar", "auto"}) {
        CAPTURE(std::string(isa));
        Renderer renderer({.threads = 2, .isa = isa});
        const RenderedImage& image = renderer.render(scene);
        REQUIRE(image.display.size() == reference.image.display.size());
        // Only the bad triangle's pixels may differ from the picture without it.
        std::size_t differing = 0;
        for (std::size_t i = 0; i < image.display.size(); i += 3)
            differing += image.display[i] != reference.image.display[i];
        CHECK(differing < 64 * 64 / 4);
    }
}

// The vertex stage marks a vertex with a NaN or infinite normal as not finite,
// so its triangle is dropped before any shading path could turn it into NaN.
TEST_CASE("a triangle with NaN normals shades to finite radiance in every shading path") {
    const Scene scene = nan_normal_scene();
    for (const char* isa : {"auto", "scalar"}) {
        CAPTURE(std::string(isa));
        Renderer renderer({.threads = 2, .isa = isa});
        CHECK(all_finite(renderer.render(scene).radiance));
    }
}

TEST_CASE("empty and enclosing scenes render") {
    SUBCASE("no objects: the clear colour everywhere") {
        Scene scene = base_scene();
        scene.clear_color = {0.2f, 0.4f, 0.6f};
        const Frame frame = render(scene);
        CHECK(frame.stats.fragments_shaded == 0);
        for (std::size_t i = 0; i < frame.image.display.size(); i += 3) {
            CHECK(frame.image.display[i] == 51);
            CHECK(frame.image.display[i + 1] == 102);
            CHECK(frame.image.display[i + 2] == 153);
        }
        CHECK(all_finite(frame.image.radiance));
    }
    SUBCASE("no lights: ambient only, darker than lit but not the clear colour") {
        Scene scene = scene_with(triangles({kGood}));
        const Frame lit = render(scene);
        scene.lights.clear();
        const Frame dark = render(scene);
        CHECK(dark.stats.fragments_shaded == lit.stats.fragments_shaded);
        CHECK(all_finite(dark.image.radiance));
        const std::size_t centre = 3 * (32 * 64 + 32);
        CHECK(dark.image.radiance[centre] > 0.0f);
        CHECK(dark.image.radiance[centre] < lit.image.radiance[centre]);
    }
    SUBCASE("the camera inside a sphere sees its inside everywhere") {
        Scene scene = base_scene();
        scene.camera.position = {0.0f, 0.0f, 0.5f};
        scene.meshes.push_back(make_sphere_mesh());
        scene.objects.push_back(Object{0, 0, glm::mat4(4.0f)});
        scene.objects[0].model[3][3] = 1.0f;  // uniform scale 4
        const Frame frame = render(scene);
        CHECK(frame.stats.fragments_shaded == 64 * 64);
        CHECK(all_finite(frame.image.radiance));
    }
    SUBCASE("the camera on a sphere's surface") {
        Scene scene = base_scene();
        scene.camera.position = {0.0f, 0.0f, 1.0f};
        scene.meshes.push_back(make_sphere_mesh());
        scene.objects.push_back(Object{});
        CHECK(all_finite(render(scene).image.radiance));
    }
}

TEST_CASE("validate_scene refuses what the pipeline cannot read, naming the mesh") {
    const auto error_of = [](const Scene& scene) -> std::string {
        try {
            validate_scene(scene);
        } catch (const SceneError& e) {
            return e.what();
        }
        return "(accepted)";
    };
    const Scene good = scene_with(triangles({kGood}));
    CHECK(error_of(good) == "(accepted)");

    Scene scene = good;
    scene.meshes[0].indices[1] = 3;
    CHECK(error_of(scene) == "test scene: mesh 'test mesh' (meshes[0]): index 3 at indices[1] (triangle 0) is out "
                             "of range; the mesh has 3 vertices");
    scene = good;
    scene.meshes[0].indices[0] = 0xFFFFFFFFu;
    CHECK(doctest::String(error_of(scene).c_str()) == doctest::Contains("index 4294967295 at indices[0]"));
    scene = good;
    scene.meshes[0].indices.pop_back();
    CHECK(doctest::String(error_of(scene).c_str()) == doctest::Contains("has 2 indices, not a multiple of 3"));
    scene = good;
    scene.meshes[0].normals.pop_back();
    CHECK(doctest::String(error_of(scene).c_str()) == doctest::Contains("has 2 normals for 3 positions"));
    scene = good;
    scene.meshes[0].uvs.resize(1);
    CHECK(doctest::String(error_of(scene).c_str()) == doctest::Contains("has 1 uvs for 3 positions"));
    scene = good;
    scene.objects[0].mesh = 1;
    CHECK(doctest::String(error_of(scene).c_str()) == doctest::Contains("objects[0] uses mesh 1 but the scene has 1"));
    scene = good;
    scene.objects[0].material = 5;
    CHECK(doctest::String(error_of(scene).c_str()) == doctest::Contains("objects[0] uses material 5"));
    scene = good;
    scene.objects[0].model[3][0] = kNaN;
    CHECK(doctest::String(error_of(scene).c_str()) == doctest::Contains("non-finite model matrix"));
    scene = good;
    scene.width = scene.height = kMaxImageDimension;
    CHECK(doctest::String(error_of(scene).c_str()) == doctest::Contains("268435456 pixels; at most 134217728"));
    scene.height = kMaxImageDimension / 2;
    CHECK(error_of(scene) == "(accepted)");
    scene.width = 0;
    CHECK(doctest::String(error_of(scene).c_str()) == doctest::Contains("outside 1..16384"));
    scene = good;
    scene.camera.target = scene.camera.position;
    CHECK(doctest::String(error_of(scene).c_str()) == doctest::Contains("target must differ"));
    scene = good;
    scene.camera.up = {0.0f, 0.0f, -2.0f};
    CHECK(doctest::String(error_of(scene).c_str()) == doctest::Contains("not parallel"));
    scene = good;
    scene.camera.fov_y_degrees = 180.0f;
    CHECK(doctest::String(error_of(scene).c_str()) == doctest::Contains("fov_y must be in (0, 180)"));
    scene = good;
    scene.camera.near_plane = 0.0f;
    CHECK(doctest::String(error_of(scene).c_str()) == doctest::Contains("0 < near < far"));
    scene = good;
    scene.lights[0].color.y = kNaN;
    CHECK(doctest::String(error_of(scene).c_str()) == doctest::Contains("lights[0]"));
    scene = good;
    scene.materials[0].roughness = 1.5f;
    CHECK(doctest::String(error_of(scene).c_str()) == doctest::Contains("materials[0]"));

    // Non-finite vertices are the renderer's to drop, not errors.
    scene = good;
    scene.meshes[0].positions[0].x = kNaN;
    scene.meshes[0].normals[1].y = kInf;
    CHECK(error_of(scene) == "(accepted)");
    // Every bundled scene passes.
    for (const char* name : {"spheres.toml", "shapes.toml"})
        CHECK(error_of(load_scene_file(test::scene_path(name))) == "(accepted)");
}

TEST_CASE("the renderer itself refuses what it would index out of bounds, and drops out-of-range indices") {
    Scene scene = scene_with(triangles({kGood}));
    SUBCASE("an index past the mesh's vertices drops just that triangle") {
        const Frame reference = render(scene);
        Mesh& mesh = scene.meshes[0];
        mesh.indices.insert(mesh.indices.end(), {0, 1, 1000000});
        Renderer renderer;  // straight to the renderer: validate_scene would refuse this scene
        CHECK(renderer.render(scene).display == reference.image.display);
    }
    SUBCASE("a missing mesh, fewer normals than positions, or too many pixels are refused") {
        Scene bad = scene;
        bad.objects[0].mesh = 7;
        CHECK_THROWS_AS(Renderer().render(bad), std::invalid_argument);
        bad = scene;
        bad.meshes[0].normals.pop_back();
        CHECK_THROWS_AS(Renderer().render(bad), std::invalid_argument);
        bad = scene;
        bad.width = bad.height = kMaxImageDimension;
        CHECK_THROWS_WITH_AS(Renderer().render(bad), doctest::Contains("pixels"), std::invalid_argument);
    }
}
