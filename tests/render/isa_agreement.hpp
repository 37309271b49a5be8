// Every SIMD ISA against a reference image: each ISA this CPU runs renders the scene (the
// others are skipped, saying so), and its 8-bit display values must lie within max_steps of
// the reference's everywhere. `settings` gives the rest (threads, tile size); its isa is replaced.
#pragma once

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <stdexcept>

#include "tessera/renderer.hpp"
#include "tessera/scene.hpp"

namespace tessera::test {

inline void check_every_isa_within(const Scene& scene, const RenderedImage& reference, int max_steps,
                                   RenderSettings settings = {}) {
    for (const char* isa : {"sse4", "avx2", "avx512"}) {
        CAPTURE(isa);
        std::optional<Renderer> renderer;
        settings.isa = isa;
        try {
            renderer.emplace(settings);
        } catch (const std::invalid_argument& e) {
            MESSAGE("skipped: " << e.what());
            continue;
        }
        const RenderedImage& image = renderer->render(scene);
        REQUIRE(image.display.size() == reference.display.size());
        int worst = 0;
        for (std::size_t i = 0; i < image.display.size(); ++i)
            worst = std::max(worst, std::abs(int(image.display[i]) - int(reference.display[i])));
        CHECK(worst <= max_steps);
    }
}

}  // namespace tessera::test
