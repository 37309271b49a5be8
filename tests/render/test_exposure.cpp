// --exposure (Scene::exposure_ev): radiance × 2^EV before the tonemap; 0 changes nothing.
#include <doctest/doctest.h>

#include "tessera/renderer.hpp"

using namespace tessera;

TEST_CASE("exposure: EV 0 is bit-identical, EV 1 doubles every shaded radiance and brightens the display") {
    Scene scene = parse_scene("[output]\nwidth = 40\nheight = 30\n[camera]\nposition = [0, 0, 4]\ntarget = [0, 0, 0]\n"
                              "[[lights]]\nposition = [3, 3, 5]\ncolor = [40, 40, 40]\n[[objects]]\nmesh = \"sphere\"\n",
                              "exposure.toml");
    Renderer renderer;
    const RenderedImage plain = renderer.render(scene);
    scene.exposure_ev = 0.0f;
    CHECK(renderer.render(scene).display == plain.display);
    scene.exposure_ev = 1.0f;
    const RenderedImage brighter = renderer.render(scene);
    const std::size_t centre = 3 * (15 * 40 + 20);  // on the sphere
    CHECK(brighter.radiance[centre] == 2.0f * plain.radiance[centre]);
    CHECK(brighter.display[centre] > plain.display[centre]);
    CHECK(brighter.radiance[0] == plain.radiance[0]);  // the background is the clear colour either way
}
