// Per-tile light culling (RenderSettings::light_culling): exact where lights
// have no range, and within the documented tolerance of range = "auto"
// (kAutoRangeIrradiance) on the many-lights scene.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <utility>

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
    // The scalar path shades exactly the reference's terms either way. The
    // SIMD kernels add such lights as the uncut kernels do (kReachesAll: no
    // lane test), but they are another instantiation, and where the compiler
    // fuses a multiply-add may differ between them in the last bits, which
    // the GGX peak magnifies (tests/shade/test_shade_kernels.cpp bounds it).
    Scene scene = load_scene_file(test::scene_path("spheres.toml"));
    scene.width = 320, scene.height = 180;
    for (Light& light : scene.lights) light.range = 1000.0f;
    Renderer culled_scalar({.threads = 2, .isa = "scalar", .light_culling = true});
    Renderer unculled_scalar({.threads = 2, .isa = "scalar", .light_culling = false});
    CHECK(culled_scalar.render(scene).radiance == unculled_scalar.render(scene).radiance);
    Renderer culled({.threads = 2, .light_culling = true});
    Renderer unculled({.threads = 2, .light_culling = false});
    const RenderedImage reference = unculled.render(scene);
    const RenderedImage& image = culled.render(scene);
    CHECK(difference(image, reference).display_max <= 1);
    double worst_relative = 0.0;
    for (std::size_t i = 0; i < image.radiance.size(); ++i)
        worst_relative = std::max(worst_relative, double(std::abs(image.radiance[i] - reference.radiance[i])) /
                                                      std::max(1e-3, double(std::abs(reference.radiance[i]))));
    CHECK(worst_relative <= 2e-3);  // measured 5e-4, at a glint
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

TEST_CASE("light culling: the image is the same for every tile size and thread count") {
    // A light adds nothing past its range, per pixel, and culling skips only
    // lights that add nothing: tiles and clusters do not show.
    Scene scene = load_scene_file(test::scene_path("many_lights.toml"));
    scene.width = 480, scene.height = 270;
    Renderer reference_renderer({.threads = 1, .tile_size = 32});
    const RenderedImage reference = reference_renderer.render(scene);
    for (const auto& [threads, tile_size] : {std::pair{2, 8}, std::pair{3, 16}, std::pair{2, 64}, std::pair{1, 128}}) {
        CAPTURE(threads);
        CAPTURE(tile_size);
        Renderer renderer({.threads = threads, .tile_size = tile_size});
        const RenderedImage& image = renderer.render(scene);
        CHECK(image.radiance == reference.radiance);
        CHECK(image.display == reference.display);
    }
}
