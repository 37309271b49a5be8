// Masked materials (AlphaMode::mask): a fragment whose alpha is below the
// cutoff is discarded before the depth write, so the surface behind shows;
// alpha = factor × the albedo map's alpha. The same image for every ISA,
// thread count, and (per pixel) with 4× MSAA.
#include <doctest/doctest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "tessera/renderer.hpp"
#include "texture/texture.hpp"

using namespace tessera;

namespace {

// Seen from above: a red 4×4 plane at y = 1, its albedo map transparent on its
// left half (u < 0.5, alpha 0) and opaque on its right half, over a blue 8×8
// plane at y = 0.
Scene masked_scene(float alpha_factor, float cutoff, bool with_map) {
    Scene scene;
    scene.width = 64, scene.height = 64;
    scene.clear_color = glm::vec3(0.0f);
    scene.camera.position = {0, 6, 0};
    scene.camera.target = {0, 0, 0};
    scene.camera.up = {0, 0, -1};  // image x along world +X, which is the planes' +u
    scene.meshes.push_back(make_plane_mesh());
    const float texels[4 * 4] = {1, 1, 1, 0, 1, 1, 1, 0, 1, 1, 1, 1, 1, 1, 1, 1};  // RGBA, alpha 0 0 1 1
    scene.textures.push_back(std::make_shared<const texture::Texture>(
        texture::Texture::from_pixels(4, 1, 4, texels, texture::ColorSpace::linear)));
    Material front;
    front.albedo = {1, 0, 0};
    front.alpha_mode = AlphaMode::mask;
    front.alpha_factor = alpha_factor;
    front.alpha_cutoff = cutoff;
    if (with_map) front.albedo_map.texture = 0;
    Material back;
    back.albedo = {0, 0, 1};
    scene.materials = {front, back};
    // The masked plane first, so its discarded fragments must not hide the plane drawn later.
    scene.objects.push_back(Object{0, 0, glm::scale(glm::translate(glm::mat4(1.0f), {0, 1, 0}), glm::vec3(2.0f))});
    scene.objects.push_back(Object{0, 1, glm::scale(glm::mat4(1.0f), glm::vec3(4.0f))});
    Light light;
    light.type = LightType::directional;
    light.direction = glm::normalize(glm::vec3(0.5f, -1.0f, 0.3f));
    light.color = {3, 3, 3};
    scene.lights.push_back(light);
    return scene;
}

enum class Seen { front, back, nothing };

Seen seen_at(const RenderedImage& image, int x, int y) {
    const std::size_t i = 3 * (std::size_t(y) * image.width + x);
    // Red or blue albedo under a white light: the other channel has only the
    // (white) specular reflection, well below the diffuse one.
    const float r = image.radiance[i], b = image.radiance[i + 2];
    if (r > 2.0f * b + 0.01f) return Seen::front;
    if (b > 2.0f * r + 0.01f) return Seen::back;
    return Seen::nothing;
}

}  // namespace

TEST_CASE("alpha mask: the map's transparent half shows the plane behind, its opaque half hides it") {
    Renderer renderer;
    const RenderedImage& image = renderer.render(masked_scene(1.0f, 0.5f, true));
    // The front plane spans x ≈ 17..47 of the 64-pixel row; u = 0.5 is the middle column.
    for (const int y : {24, 32, 40}) {
        CAPTURE(y);
        CHECK(seen_at(image, 22, y) == Seen::back);   // u ≈ 0.2: alpha 0, discarded
        CHECK(seen_at(image, 42, y) == Seen::front);  // u ≈ 0.8: alpha 1
        CHECK(seen_at(image, 4, y) == Seen::back);    // beside the front plane
    }
}

TEST_CASE("alpha mask: alpha × factor against the cutoff, glTF's rule (alpha >= cutoff is drawn)") {
    Renderer renderer;
    // No map: alpha is the factor alone.
    CHECK(seen_at(renderer.render(masked_scene(0.25f, 0.5f, false)), 42, 32) == Seen::back);
    CHECK(seen_at(renderer.render(masked_scene(0.5f, 0.5f, false)), 42, 32) == Seen::front);  // equal: drawn
    CHECK(seen_at(renderer.render(masked_scene(0.5f, 0.0f, false)), 22, 32) == Seen::front);
    // With the map, the factor scales its alpha: 0.4 × 1 < 0.5 discards the opaque half too.
    CHECK(seen_at(renderer.render(masked_scene(0.4f, 0.5f, true)), 42, 32) == Seen::back);
    // Opaque materials ignore alpha altogether.
    Scene opaque = masked_scene(0.0f, 0.5f, true);
    opaque.materials[0].alpha_mode = AlphaMode::opaque;
    CHECK(seen_at(renderer.render(opaque), 22, 32) == Seen::front);
}

TEST_CASE("alpha mask: every ISA and thread count give the scalar image, 4x MSAA agrees away from edges") {
    Scene scene = masked_scene(1.0f, 0.5f, true);
    scene.objects[0].model = glm::rotate(scene.objects[0].model, 0.4f, glm::vec3(0, 1, 0));  // slanted mask edge
    Renderer scalar({.threads = 1, .isa = "scalar"});
    const RenderedImage reference = scalar.render(scene);
    for (const char* isa : {"sse4", "avx2", "avx512", "auto"}) {
        CAPTURE(isa);
        try {
            Renderer renderer({.threads = 3, .isa = isa});
            CHECK(renderer.render(scene).display == reference.display);
        } catch (const std::invalid_argument&) {
            MESSAGE("skipped: this CPU cannot run " << isa);
        }
    }
    scene.msaa = 4;
    const RenderedImage four = scalar.render(scene);
    CHECK(seen_at(four, 22, 32) == Seen::back);
    CHECK(seen_at(four, 42, 32) == Seen::front);
}
