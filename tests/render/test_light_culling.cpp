// Per-tile light culling (RenderSettings::light_culling): exact where lights
// have no range, and within the documented tolerance of range = "auto"
// (kAutoRangeIrradiance) on the many-lights scene.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "tessera/renderer.hpp"
#include "test_paths.hpp"

using namespace tessera;

namespace {

struct Difference {
    int display_max = 0;                 // 8-bit steps
    std::size_t display_over_one = 0;    // channel values more than one step apart
    double radiance_max = 0.0;           // HDR, absolute
};

Difference difference(const RenderedImage& a, const RenderedImage& b) {
    Difference d;
    REQUIRE(a.display.size() == b.display.size());
    REQUIRE(a.radiance.size() == b.radiance.size());
    for (std::size_t i = 0; i < a.display.size(); ++i) {
        const int step = std::abs(int(a.display[i]) - int(b.display[i]));
        d.display_max = std::max(d.display_max, step);
        if (step > 1) ++d.display_over_one;
    }
    for (std::size_t i = 0; i < a.radiance.size(); ++i)
        d.radiance_max = std::max(d.radiance_max, double(std::abs(a.radiance[i] - b.radiance[i])));
    return d;
}

}  // namespace

TEST_CASE("light culling changes nothing, bit for bit, where no light has a range") {
    for (const char* name : {"spheres.toml", "shapes.toml"}) {
        CAPTURE(name);
        const Scene scene = load_scene_file(test::scene_path(name));
        Renderer culled({.threads = 2, .light_culling = true});
        Renderer unculled({.threads = 2, .light_culling = false});
        const RenderedImage& a = culled.render(scene);
        const RenderedImage& b = unculled.render(scene);
        CHECK(a.display == b.display);
        CHECK(a.radiance == b.radiance);
    }
}

TEST_CASE("light culling: ranges that reach every visible point change nothing") {
    Scene scene = load_scene_file(test::scene_path("spheres.toml"));
    for (Light& light : scene.lights) light.range = 1000.0f;
    Renderer culled({.threads = 2, .light_culling = true});
    Renderer unculled({.threads = 2, .light_culling = false});
    CHECK(culled.render(scene).radiance == unculled.render(scene).radiance);
}

TEST_CASE("light culling: short ranges do drop lights") {
    // Ranges far shorter than the distances to the spheres: culled, only ambient is left.
    Scene scene = load_scene_file(test::scene_path("spheres.toml"));
    for (Light& light : scene.lights) light.range = 1.0f;
    Renderer culled({.threads = 2, .light_culling = true});
    Renderer unculled({.threads = 2, .light_culling = false});
    const RenderedImage lit = unculled.render(scene);
    const RenderedImage& ambient_only = culled.render(scene);
    CHECK(difference(lit, ambient_only).display_max > 50);
    scene.lights.clear();
    CHECK(unculled.render(scene).radiance == ambient_only.radiance);
}

TEST_CASE("light culling with range = \"auto\" stays within its documented tolerance on many_lights.toml") {
    // The tolerance of kAutoRangeIrradiance (scene.hpp): at most 0.2% of the
    // 8-bit channel values more than one step from the unculled image (measured:
    // 0.1%). Single glints on the mirror-like spheres may differ by more.
    const Scene scene = load_scene_file(test::scene_path("many_lights.toml"));
    Renderer culled({.threads = 2, .light_culling = true});
    Renderer unculled({.threads = 2, .light_culling = false});
    const RenderedImage reference = unculled.render(scene);
    const RenderedImage& image = culled.render(scene);
    const Difference d = difference(image, reference);
    MESSAGE("culled vs unculled: display max ", d.display_max, "/255, ", d.display_over_one,
            " channel values more than 1/255 apart; HDR max ", d.radiance_max);
    CHECK(double(d.display_over_one) <= 0.002 * double(image.display.size()));
    // Culling did happen: otherwise this would test nothing.
    CHECK(image.radiance != reference.radiance);
}
