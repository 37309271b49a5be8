// Tessera against an independent implementation of the same specification: OpenGL 3.3
// on Mesa llvmpipe running the reference GLSL (tools/gl_reference). Two rasterizers
// with different arithmetic will never agree bit for bit; what must hold is that the
// shading agrees to within rounding everywhere, and that the pixels that differ more
// are where coverage decides (silhouettes, where one object meets another or the
// background), because there a sub-pixel difference in edge placement flips a pixel.
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
#include "tessera/scene.hpp"
#include "test_paths.hpp"

using namespace tessera;

namespace {

// The agreement required, on display values (8-bit steps).
constexpr int kChannelTolerance = 2;                // a pixel agrees if every channel is within 2/255
constexpr double kMinAgreeingFraction = 0.995;      // of all pixels
constexpr int kSilhouetteRadius = 2;                // pixels (Chebyshev distance)
constexpr double kMinSilhouetteFraction = 0.90;     // of the pixels that disagree

// A pixel is "on a silhouette" when, within kSilhouetteRadius pixels, the OpenGL render
// shows a different object or the background (its object-id buffer: same geometry and
// depth test). That covers outlines against the background, objects in front of
// objects, and where two objects intersect (the ball resting on the floor).
// Decision: at least kMinSilhouetteFraction of the disagreeing pixels must be on a
// silhouette; the rest (interior pixels) may differ only by rounding in the shading,
// bounded by kMaxInteriorDifference.
constexpr int kMaxInteriorDifference = 4;

struct Agreement {
    std::size_t pixels = 0;
    std::size_t agreeing = 0;         // every channel within kChannelTolerance
    std::size_t exact = 0;            // identical
    std::size_t disagreeing = 0;
    std::size_t on_silhouette = 0;    // disagreeing and on a silhouette
    int max_difference = 0;           // 8-bit steps, any channel, any pixel
    int max_interior_difference = 0;  // the same, over pixels not on a silhouette
    int max_x = 0, max_y = 0;         // where max_difference is

    double agreeing_fraction() const { return double(agreeing) / double(pixels); }
    double silhouette_fraction() const { return disagreeing ? double(on_silhouette) / double(disagreeing) : 1.0; }
};

bool on_silhouette(const std::vector<std::uint32_t>& ids, int width, int height, int x, int y) {
    const std::uint32_t id = ids[std::size_t(y) * std::size_t(width) + std::size_t(x)];
    for (int ny = std::max(0, y - kSilhouetteRadius); ny <= std::min(height - 1, y + kSilhouetteRadius); ++ny)
        for (int nx = std::max(0, x - kSilhouetteRadius); nx <= std::min(width - 1, x + kSilhouetteRadius); ++nx)
            if (ids[std::size_t(ny) * std::size_t(width) + std::size_t(nx)] != id) return true;
    return false;
}

Agreement measure(const RenderedImage& tessera_image, const RenderedImage& gl_image,
                  const std::vector<std::uint32_t>& gl_ids) {
    Agreement a;
    const int w = gl_image.width, h = gl_image.height;
    a.pixels = std::size_t(w) * std::size_t(h);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const std::size_t p = (std::size_t(y) * std::size_t(w) + std::size_t(x)) * 3;
            int diff = 0;
            for (int c = 0; c < 3; ++c)
                diff = std::max(diff, std::abs(int(tessera_image.display[p + std::size_t(c)]) -
                                               int(gl_image.display[p + std::size_t(c)])));
            if (diff == 0) ++a.exact;
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

// Both images and their difference (x16, so small differences show) for a look by eye.
std::string write_failure_images(const RenderedImage& tessera_image, const RenderedImage& gl_image,
                                 const std::string& name) {
    const std::filesystem::path dir = std::filesystem::path(TESSERA_BINARY_DIR) / "crosscheck_failures";
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

// One OpenGL context for the whole executable. No skipping: the test command installs
// Mesa, so a missing EGL driver is a failure, reported with its reason.
gl_reference::GlReferenceRenderer& gl_renderer() {
    static std::unique_ptr<gl_reference::GlReferenceRenderer> renderer;
    if (!renderer) {
        try {
            renderer = std::make_unique<gl_reference::GlReferenceRenderer>();
        } catch (const std::exception& e) {
            FAIL("cannot create the OpenGL reference context: " << std::string(e.what()));
        }
    }
    return *renderer;
}

void check_scene_agrees(const char* scene_file) {
    const Scene scene = load_scene_file(test::scene_path(scene_file));
    const std::string name = std::filesystem::path(scene_file).stem().string();

    gl_reference::GlReferenceRenderer* gl = &gl_renderer();
    const RenderedImage gl_image = gl->render(scene);
    const std::vector<std::uint32_t> gl_ids = gl->render_object_ids(scene);

    Renderer renderer;  // default settings, as `tessera render` uses
    const RenderedImage tessera_image = renderer.render(scene);
    REQUIRE(tessera_image.width == gl_image.width);
    REQUIRE(tessera_image.height == gl_image.height);

    const Agreement a = measure(tessera_image, gl_image, gl_ids);
    const std::string summary =
        name + " vs " + gl->renderer_name() + ": " + std::to_string(100.0 * a.agreeing_fraction()) +
        "% of pixels within " + std::to_string(kChannelTolerance) + "/255 (" +
        std::to_string(100.0 * double(a.exact) / double(a.pixels)) + "% identical); " +
        std::to_string(a.disagreeing) + " pixels further off, " + std::to_string(a.on_silhouette) +
        " of them on a silhouette (" + std::to_string(100.0 * a.silhouette_fraction()) + "%); max difference " +
        std::to_string(a.max_difference) + "/255 at (" + std::to_string(a.max_x) + ", " + std::to_string(a.max_y) +
        "), max off-silhouette " + std::to_string(a.max_interior_difference) + "/255";
    MESSAGE(summary);

    const bool passed = a.agreeing_fraction() >= kMinAgreeingFraction &&
                        a.silhouette_fraction() >= kMinSilhouetteFraction &&
                        a.max_interior_difference <= kMaxInteriorDifference;
    if (!passed) {
        const std::string images = write_failure_images(tessera_image, gl_image, name);
        FAIL_CHECK(summary << "; images: " << images);
    }
    CHECK(a.agreeing_fraction() >= kMinAgreeingFraction);
    CHECK(a.silhouette_fraction() >= kMinSilhouetteFraction);
    CHECK(a.max_interior_difference <= kMaxInteriorDifference);
}

}  // namespace

TEST_CASE("crosscheck: the OpenGL reference context is llvmpipe with a core profile of 3.3 or newer") {
    const gl_reference::GlReferenceRenderer& gl = gl_renderer();
    MESSAGE("GL_RENDERER " << gl.renderer_name() << ", GL_VERSION " << gl.version());
    CHECK(gl.renderer_name().find("llvmpipe") != std::string::npos);
    // Mesa answers a 3.3 core request with its newest core version ("4.5 (Core Profile) Mesa ...").
    int major = 0, minor = 0;
    REQUIRE(std::sscanf(gl.version().c_str(), "%d.%d", &major, &minor) == 2);
    CHECK(major * 10 + minor >= 33);
    CHECK(gl.version().find("Core Profile") != std::string::npos);
}

TEST_CASE("crosscheck: spheres.toml agrees with OpenGL on llvmpipe") { check_scene_agrees("spheres.toml"); }

TEST_CASE("crosscheck: shapes.toml agrees with OpenGL on llvmpipe") { check_scene_agrees("shapes.toml"); }

TEST_CASE("crosscheck: a scene without lights renders ambient only in both") {
    Scene scene = load_scene_file(test::scene_path("shapes.toml"));
    scene.lights.clear();
    gl_reference::GlReferenceRenderer* gl = &gl_renderer();
    const RenderedImage gl_image = gl->render(scene);
    Renderer renderer;
    const RenderedImage& tessera_image = renderer.render(scene);
    const Agreement a = measure(tessera_image, gl_image, gl->render_object_ids(scene));
    MESSAGE("no lights: " << 100.0 * a.agreeing_fraction() << "% within 2/255, max " << a.max_difference << "/255");
    CHECK(a.agreeing_fraction() >= kMinAgreeingFraction);
    CHECK(a.max_interior_difference <= kMaxInteriorDifference);
}
