// What the llvmpipe cross-checks share: comparing Tessera's image with the OpenGL peer's
// (tools/gl_reference) pixel by pixel, silhouettes from the peer's object ids, and the one
// OpenGL context of the test executable.
#pragma once

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "gl_renderer.hpp"
#include "tessera/image_io.hpp"
#include "tessera/renderer.hpp"
#include "test_paths.hpp"

namespace tessera::crosscheck {

// On display values (8-bit steps).
constexpr int kChannelTolerance = 2;  // a pixel agrees if every channel is within 2/255
constexpr int kSilhouetteRadius = 2;  // pixels (Chebyshev distance)

// A pixel is "on a silhouette" when, within kSilhouetteRadius pixels, the OpenGL render
// shows a different object or the background (its object-id buffer: same geometry and
// depth test). That covers outlines against the background, objects in front of
// objects, and where two objects intersect (the ball resting on the floor).
struct Agreement {
    std::size_t pixels = 0;
    std::size_t agreeing = 0;         // every channel within kChannelTolerance
    std::size_t within_one = 0;       // every channel within 1/255
    std::size_t exact = 0;            // identical
    std::size_t disagreeing = 0;
    std::size_t on_silhouette = 0;    // disagreeing and on a silhouette
    int max_difference = 0;           // 8-bit steps, any channel, any pixel
    int max_interior_difference = 0;  // the same, over pixels not on a silhouette
    int max_x = 0, max_y = 0;         // where max_difference is

    double agreeing_fraction() const { return double(agreeing) / double(pixels); }
    double within_one_fraction() const { return double(within_one) / double(pixels); }
    double exact_fraction() const { return double(exact) / double(pixels); }
    double silhouette_fraction() const { return disagreeing ? double(on_silhouette) / double(disagreeing) : 1.0; }
};

inline bool on_silhouette(const std::vector<std::uint32_t>& ids, int width, int height, int x, int y) {
    const std::uint32_t id = ids[std::size_t(y) * std::size_t(width) + std::size_t(x)];
    for (int ny = std::max(0, y - kSilhouetteRadius); ny <= std::min(height - 1, y + kSilhouetteRadius); ++ny)
        for (int nx = std::max(0, x - kSilhouetteRadius); nx <= std::min(width - 1, x + kSilhouetteRadius); ++nx)
            if (ids[std::size_t(ny) * std::size_t(width) + std::size_t(nx)] != id) return true;
    return false;
}

// The largest of a pixel's three 8-bit channel differences between two images.
inline int max_channel_difference(const RenderedImage& a, const RenderedImage& b, std::size_t pixel) {
    int diff = 0;
    for (std::size_t c = 0; c < 3; ++c)
        diff = std::max(diff, std::abs(int(a.display[pixel * 3 + c]) - int(b.display[pixel * 3 + c])));
    return diff;
}

inline Agreement measure(const RenderedImage& tessera_image, const RenderedImage& gl_image,
                  const std::vector<std::uint32_t>& gl_ids) {
    Agreement a;
    const int w = gl_image.width, h = gl_image.height;
    a.pixels = std::size_t(w) * std::size_t(h);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const int diff =
                max_channel_difference(tessera_image, gl_image, std::size_t(y) * std::size_t(w) + std::size_t(x));
            if (diff == 0) ++a.exact;
            if (diff <= 1) ++a.within_one;
            if (diff > a.max_difference) {
                a.max_difference = diff;
                a.max_x = x;
                a.max_y = y;
            }
            if (diff <= kChannelTolerance) {
                ++a.agreeing;
                continue;
            }
            ++a.disagreeing;
            if (on_silhouette(gl_ids, w, h, x, y))
                ++a.on_silhouette;
            else
                a.max_interior_difference = std::max(a.max_interior_difference, diff);
        }
    }
    return a;
}

inline std::string describe(const Agreement& a) {
    return std::to_string(100.0 * a.agreeing_fraction()) + "% of pixels within " + std::to_string(kChannelTolerance) +
           "/255 (" + std::to_string(100.0 * a.exact_fraction()) + "% identical, " +
           std::to_string(100.0 * a.within_one_fraction()) + "% within 1/255); " +
           std::to_string(a.disagreeing) + " pixels further off, " + std::to_string(a.on_silhouette) +
           " of them on a silhouette (" + std::to_string(100.0 * a.silhouette_fraction()) + "%); max difference " +
           std::to_string(a.max_difference) + "/255 at (" + std::to_string(a.max_x) + ", " + std::to_string(a.max_y) +
           "), max off-silhouette " + std::to_string(a.max_interior_difference) + "/255";
}

// Both images and their difference (x16, so small differences show) for a look by eye.
inline std::string write_failure_images(const RenderedImage& tessera_image, const RenderedImage& gl_image,
                                 const std::string& name) {
    const std::filesystem::path dir = tessera::test::binary_dir() / "crosscheck_failures";
    std::filesystem::create_directories(dir);
    RenderedImage diff;
    diff.width = gl_image.width;
    diff.height = gl_image.height;
    diff.display.resize(gl_image.display.size());
    for (std::size_t i = 0; i < diff.display.size(); ++i)
        diff.display[i] = std::uint8_t(
            std::min(255, 16 * std::abs(int(tessera_image.display[i]) - int(gl_image.display[i]))));
    write_image(tessera_image, dir / (name + ".tessera.png"));
    write_image(gl_image, dir / (name + ".llvmpipe.png"));
    write_image(diff, dir / (name + ".diff.png"));
    return (dir / (name + ".{tessera,llvmpipe,diff}.png")).string();
}

// One OpenGL context for the whole executable, or null with why it could not be made.
inline gl_reference::GlReferenceRenderer* shared_gl_renderer(std::string& error) {
    static std::unique_ptr<gl_reference::GlReferenceRenderer> renderer;
    static std::string failure;
    if (!renderer && failure.empty()) {
        try {
            renderer = std::make_unique<gl_reference::GlReferenceRenderer>();
        } catch (const std::exception& e) {
            failure = e.what();
        }
    }
    error = failure;
    return renderer.get();
}

// The direct-light cross-checks do not skip: the test command installs Mesa, so a missing EGL
// driver is a failure, reported with its reason.
inline gl_reference::GlReferenceRenderer& gl_renderer() {
    std::string error;
    gl_reference::GlReferenceRenderer* renderer = shared_gl_renderer(error);
    if (!renderer) FAIL("cannot create the OpenGL reference context: " << error);
    return *renderer;
}

// The IBL cross-checks skip (ctest reports Skipped) where no EGL device/driver makes a context,
// or where it is not llvmpipe (their bounds are llvmpipe's: its asin, its mip generation).
inline gl_reference::GlReferenceRenderer* gl_renderer_or_skip() {
    std::string error;
    gl_reference::GlReferenceRenderer* renderer = shared_gl_renderer(error);
    if (!renderer) {
        std::printf("TESSERA_TEST_SKIPPED: no OpenGL reference context: %s\n", error.c_str());
    } else if (renderer->renderer_name().find("llvmpipe") == std::string::npos) {
        std::printf("TESSERA_TEST_SKIPPED: the OpenGL reference context is %s, not llvmpipe\n",
                    renderer->renderer_name().c_str());
        return nullptr;
    }
    return renderer;
}

}  // namespace tessera::crosscheck
