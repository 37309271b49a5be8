#include <doctest/doctest.h>

#include "tessera/renderer.hpp"
#include "test_paths.hpp"

using namespace tessera;

namespace {

// One lit triangle that covers the whole 24×16 image (and stays inside the
// guard band, so it is not clipped into a fan with edges across the image).
Scene covering_triangle_scene() {
    Scene scene;
    scene.width = 24, scene.height = 16;
    scene.camera.position = {0, 0, 3};
    Mesh mesh;
    mesh.name = "big";
    mesh.positions = {{-4, -4, 0}, {12, -4, 0}, {-4, 12, 0}};
    mesh.normals = {{0, 0, 1}, {0.3f, 0, 1}, {0, 0.3f, 1}};
    mesh.indices = {0, 1, 2};
    scene.meshes.push_back(mesh);
    scene.materials.push_back(Material{});
    scene.objects.push_back(Object{});
    scene.lights.push_back(Light{});
    scene.lights.back().position = {1, 2, 3};
    scene.lights.back().color = {20, 20, 20};
    return scene;
}

}  // namespace

TEST_CASE("4x MSAA: an image whose every pixel is inside one triangle is the no-MSAA image, bit for bit") {
    Scene scene = covering_triangle_scene();
    RenderSettings settings;
    parse_aov_list("depth,normal,position", settings.aovs);
    Renderer renderer(settings);
    const RenderedImage one = renderer.render(scene);
    scene.msaa = 4;
    const RenderedImage& four = renderer.render(scene);
    CHECK(four.display == one.display);
    CHECK(four.radiance == one.radiance);
    // AOVs take sample 0's fragment: here the pixel's one fragment, shaded at its centre.
    REQUIRE(one.aov.position.size() == 3u * 24 * 16);
    CHECK(four.aov.depth == one.aov.depth);
    CHECK(four.aov.normal == one.aov.normal);
    CHECK(four.aov.position == one.aov.position);
    CHECK(one.display[0] != 25);  // really covered: not the clear colour (0.1 → 26 or 25)
}

TEST_CASE("4x MSAA smooths edges: spheres differ from the one-sample image only near edges, by mixing") {
    Scene scene = load_scene_file(test::scene_path("spheres_msaa.toml"));
    REQUIRE(scene.msaa == 4);
    Renderer renderer({.threads = 2});
    const RenderedImage four = renderer.render(scene);
    scene.msaa = 1;
    const RenderedImage& one = renderer.render(scene);
    std::size_t changed = 0, between = 0;
    for (std::size_t i = 0; i < one.display.size(); ++i) {
        if (one.display[i] == four.display[i]) continue;
        ++changed;
        // An edge pixel mixes the surface with the background (0.1 → 26): its
        // value lies between a neighbour's surface value and the clear colour.
        const int lo = std::min<int>(one.display[i], 26), hi = std::max<int>(one.display[i], 26);
        const int v = four.display[i];
        const int left = i >= 3 ? one.display[i - 3] : v, right = i + 3 < one.display.size() ? one.display[i + 3] : v;
        between += (v >= std::min({lo, left, right}) && v <= std::max({hi, left, right}));
    }
    CHECK(changed > 1000);                       // the 49 spheres' outlines
    CHECK(changed < one.display.size() / 10);    // not the interiors
    CHECK(double(between) >= 0.9 * double(changed));
}
