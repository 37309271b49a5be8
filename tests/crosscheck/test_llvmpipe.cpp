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
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "agreement.hpp"
#include "gl_renderer.hpp"
#include "raster/msaa/msaa.hpp"
#include "tessera/image_io.hpp"
#include "tessera/renderer.hpp"
#include "tessera/scene.hpp"
#include "test_paths.hpp"

using namespace tessera;
using namespace tessera::crosscheck;

namespace {

// The agreement required of the direct-light scenes.
constexpr double kMinAgreeingFraction = 0.995;      // of all pixels
constexpr double kMinSilhouetteFraction = 0.90;     // of the pixels that disagree
// Decision: at least kMinSilhouetteFraction of the disagreeing pixels must be on a
// silhouette; the rest (interior pixels) may differ only by rounding in the shading,
// bounded by kMaxInteriorDifference.
constexpr int kMaxInteriorDifference = 4;

void check_scene_agrees(const Scene& scene, const std::string& name) {
    gl_reference::GlReferenceRenderer* gl = &gl_renderer();
    const RenderedImage gl_image = gl->render(scene);
    const std::vector<std::uint32_t> gl_ids = gl->render_object_ids(scene);

    Renderer renderer;  // default settings, as `tessera render` uses
    const RenderedImage tessera_image = renderer.render(scene);
    REQUIRE(tessera_image.width == gl_image.width);
    REQUIRE(tessera_image.height == gl_image.height);

    const Agreement a = measure(tessera_image, gl_image, gl_ids);
    const std::string summary = name + " vs " + gl->renderer_name() + ": " + describe(a);
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

void check_scene_agrees(const char* scene_file) {
    check_scene_agrees(load_scene_file(test::scene_path(scene_file)), std::filesystem::path(scene_file).stem().string());
}

// Every material single-sided: Tessera culls back faces in triangle setup, llvmpipe with GL_CULL_FACE.
Scene single_sided(Scene scene) {
    for (Material& material : scene.materials) material.double_sided = false;
    return scene;
}

// Pixels whose red channel is not the clear colour's.
int covered_pixels(const RenderedImage& image, const Scene& scene) {
    const int clear_red = int(std::lround(scene.clear_color.r * 255.0f));
    int count = 0;
    for (std::size_t p = 0; p < image.display.size() / 3; ++p)
        if (std::abs(int(image.display[p * 3]) - clear_red) > kChannelTolerance) ++count;
    return count;
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

TEST_CASE("crosscheck: with back faces culled, spheres and shapes agree with llvmpipe's GL_CULL_FACE") {
    check_scene_agrees(single_sided(load_scene_file(test::scene_path("spheres.toml"))), "spheres_culled");
    check_scene_agrees(single_sided(load_scene_file(test::scene_path("shapes.toml"))), "shapes_culled");
}

TEST_CASE("crosscheck: both cull the same faces of a single-sided plane, mirrored or not, seen from either side") {
    Scene scene;
    scene.width = 64;
    scene.height = 48;
    scene.meshes.push_back(make_plane_mesh());  // normal +Y: its front is seen from above
    Material material;
    material.albedo = {0.8f, 0.8f, 0.8f};
    material.double_sided = false;
    scene.materials.push_back(material);
    scene.lights.push_back(Light{.position = {0, 5, 0}, .color = {50, 50, 50}});
    scene.lights.push_back(Light{.position = {0, -5, 0}, .color = {50, 50, 50}});
    gl_reference::GlReferenceRenderer& gl = gl_renderer();
    Renderer renderer;
    for (const bool mirrored : {false, true}) {
        for (const float camera_y : {3.0f, -3.0f}) {
            // A mirrored model matrix (negative determinant) makes clockwise the front: still seen from above.
            scene.objects = {Object{.mesh = 0, .material = 0,
                                    .model = glm::scale(glm::mat4(1.0f), {mirrored ? -1.0f : 1.0f, 1.0f, 1.0f})}};
            scene.camera.position = {0.0f, camera_y, 2.5f};
            scene.camera.target = {0.0f, 0.0f, 0.0f};
            const int gl_covered = covered_pixels(gl.render(scene), scene);
            const int tessera_covered = covered_pixels(renderer.render(scene), scene);
            CAPTURE(mirrored);
            CAPTURE(camera_y);
            if (camera_y > 0) {
                CHECK(gl_covered > 500);  // the front face is drawn
                CHECK(std::abs(tessera_covered - gl_covered) <= gl_covered / 50);
            } else {
                CHECK(gl_covered == 0);  // only the back face faces the camera: culled
                CHECK(tessera_covered == 0);
            }
        }
    }
}

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

// ---------------------------------------------------------------------------------------
// 4× MSAA against llvmpipe's 4× MSAA (a 4-sample FBO resolved by glBlitFramebuffer).
//
// Measured on llvmpipe (Mesa 22.3.6):
// - GL_SAMPLE_POSITION reports (0.375, 0.125), (0.875, 0.375), (0.125, 0.625), (0.625, 0.875)
//   in window space, y up from the pixel's bottom (thin quads on a 1×1 FBO confirm it);
//   Tessera uses these positions (src/raster/msaa/msaa.hpp).
// - Fragments are shaded at the pixel centre, extrapolated where the triangle misses it
//   (the reference GLSL has no `centroid`); Tessera does the same.
// - The resolve averages in float and rounds ties (the four 8-bit values summing to
//   2 mod 4) mostly to even; Tessera rounds them up, (sum + 2) / 4: at most 1/255 apart.
// So off silhouettes the two agree as closely as without MSAA. On the pixels llvmpipe's
// MSAA changes ("edges"), Tessera's 4× image must be far closer to llvmpipe's than its 1×
// image is, and closer than to llvmpipe drawn upside down (its pattern mirrored top to
// bottom): this fails if Tessera's coverage, resolve, sample count or pattern is off.
namespace {

constexpr double kMaxEdgeDifferenceRatio = 0.05;  // 4× mean / 1× mean; measured 0.007 (0.33 mirrored)

// Mean over "edge pixels" of the largest channel difference, in 8-bit steps. Edge pixels
// are chosen by the reference alone: where llvmpipe's 4× image differs from its 1× image
// by more than kChannelTolerance.
struct EdgeCloseness {
    std::size_t pixels = 0;
    double msaa_mean = 0;    // Tessera 4× against llvmpipe 4×
    double single_mean = 0;  // Tessera 1× against llvmpipe 4×
};

EdgeCloseness measure_edges(const RenderedImage& tessera_msaa, const RenderedImage& tessera_single,
                            const RenderedImage& gl_msaa, const RenderedImage& gl_single) {
    EdgeCloseness e;
    const std::size_t n = std::size_t(gl_msaa.width) * std::size_t(gl_msaa.height);
    for (std::size_t p = 0; p < n; ++p) {
        if (max_channel_difference(gl_msaa, gl_single, p) <= kChannelTolerance) continue;
        ++e.pixels;
        e.msaa_mean += max_channel_difference(tessera_msaa, gl_msaa, p);
        e.single_mean += max_channel_difference(tessera_single, gl_msaa, p);
    }
    if (e.pixels) e.msaa_mean /= double(e.pixels), e.single_mean /= double(e.pixels);
    return e;
}

}  // namespace

TEST_CASE("crosscheck: llvmpipe's 4x sample positions are Tessera's (window space, y up)") {
    const std::vector<glm::vec2> positions = gl_renderer().msaa_sample_positions();
    std::string listed;
    for (const glm::vec2& p : positions) listed += " (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ")";
    MESSAGE("GL_SAMPLE_POSITION, y up:" << listed);
    REQUIRE(positions.size() == std::size_t(raster::kMsaaSamples));
    for (int i = 0; i < raster::kMsaaSamples; ++i) {
        // Tessera's offsets from the pixel centre, image space (y down), in 1/256 pixel.
        CHECK(positions[i].x == 0.5f + float(raster::kSampleOffsetX[i]) / 256.0f);
        CHECK(positions[i].y == 0.5f - float(raster::kSampleOffsetY[i]) / 256.0f);
    }
}

TEST_CASE("crosscheck: spheres_msaa.toml (4x MSAA) agrees with llvmpipe's 4x MSAA") {
    const Scene scene = load_scene_file(test::scene_path("spheres_msaa.toml"));
    REQUIRE(scene.msaa == 4);
    Scene single = scene;
    single.msaa = 1;

    using gl_reference::WindowOrigin;
    gl_reference::GlReferenceRenderer& gl = gl_renderer();
    const RenderedImage gl_msaa = gl.render(scene);
    const RenderedImage gl_single = gl.render(single);
    // Upside down in window space: the pattern mirrored top to bottom.
    const RenderedImage gl_msaa_mirrored = gl.render(scene, WindowOrigin::top_left);
    const RenderedImage gl_single_mirrored = gl.render(single, WindowOrigin::top_left);
    const std::vector<std::uint32_t> gl_ids = gl.render_object_ids(scene);
    Renderer renderer;
    const RenderedImage tessera_msaa = renderer.render(scene);  // copies: render() reuses its image
    const RenderedImage tessera_single = renderer.render(single);
    REQUIRE(tessera_msaa.width == gl_msaa.width);
    REQUIRE(tessera_msaa.height == gl_msaa.height);

    const Agreement a = measure(tessera_msaa, gl_msaa, gl_ids);
    const EdgeCloseness edges = measure_edges(tessera_msaa, tessera_single, gl_msaa, gl_single);
    const EdgeCloseness mirrored = measure_edges(tessera_msaa, tessera_single, gl_msaa_mirrored, gl_single_mirrored);
    MESSAGE("4x vs llvmpipe 4x: " << describe(a));
    MESSAGE("edge pixels (llvmpipe 4x != 1x): " << edges.pixels << "; mean difference to llvmpipe 4x: Tessera 4x "
            << edges.msaa_mean << "/255, Tessera 1x " << edges.single_mean << "/255; to llvmpipe with the pattern "
            << "mirrored: Tessera 4x " << mirrored.msaa_mean << "/255");

    const bool passed = a.agreeing_fraction() >= kMinAgreeingFraction &&
                        a.max_interior_difference <= kMaxInteriorDifference &&
                        edges.msaa_mean <= kMaxEdgeDifferenceRatio * edges.single_mean &&
                        edges.msaa_mean < mirrored.msaa_mean;
    if (!passed) MESSAGE("images: " << write_failure_images(tessera_msaa, gl_msaa, "spheres_msaa"));
    CHECK(a.agreeing_fraction() >= kMinAgreeingFraction);
    CHECK(a.max_interior_difference <= kMaxInteriorDifference);
    CHECK(edges.msaa_mean <= kMaxEdgeDifferenceRatio * edges.single_mean);
    CHECK(edges.msaa_mean < mirrored.msaa_mean);  // the pattern is GL's, not its mirror image
}
