// Materials through the renderer (issue 31): unlit materials show their base
// colour, maps on a second uv set and with their own transforms sample what
// the same map on baked uvs samples, and samplers reach the pixels; the same
// for every ISA as for the scalar path.
#include <doctest/doctest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "render/isa_agreement.hpp"
#include "tessera/renderer.hpp"
#include "texture/texture.hpp"

using namespace tessera;

namespace {

// A plane (normal +Y, uv over [0, 1]²) filling most of a 40×32 image, seen from above, one light.
Scene plane_scene() {
    Scene scene;
    scene.width = 40, scene.height = 32;
    scene.clear_color = glm::vec3(0.0f);
    scene.camera.position = {0, 4, 0};
    scene.camera.target = {0, 0, 0};
    scene.camera.up = {0, 0, -1};
    scene.meshes.push_back(make_plane_mesh());
    scene.materials.push_back(Material{});
    scene.objects.push_back(Object{0, 0, glm::scale(glm::mat4(1.0f), glm::vec3(2.0f))});
    scene.lights.push_back(Light{});
    scene.lights.back().type = LightType::directional;
    scene.lights.back().direction = glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f));
    scene.lights.back().color = {2, 2, 2};
    return scene;
}

// An 8×8 RGB texture of distinct colours.
std::shared_ptr<const texture::Texture> checker() {
    std::vector<float> pixels;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x)
            for (float c : {float(x) / 7.0f, float(y) / 7.0f, float((x + y) % 2)}) pixels.push_back(c);
    return std::make_shared<const texture::Texture>(
        texture::Texture::from_pixels(8, 8, 3, pixels.data(), texture::ColorSpace::srgb));
}

int worst_difference(const RenderedImage& a, const RenderedImage& b) {
    int worst = 0;
    for (std::size_t i = 0; i < a.display.size(); ++i) worst = std::max(worst, std::abs(int(a.display[i]) - int(b.display[i])));
    return worst;
}

std::uint8_t srgb8(float linear) {
    const float e = linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
    return std::uint8_t(std::lround(255.0f * e));
}

}  // namespace

TEST_CASE("an unlit material shows its base colour, sRGB-encoded, whatever the lights") {
    Scene scene = plane_scene();
    scene.materials[0].albedo = {0.2f, 0.5f, 0.9f};
    scene.materials[0].unlit = true;
    scene.materials[0].emissive = {3, 0, 0};  // unused when unlit
    Renderer renderer({.isa = "scalar"});
    const RenderedImage image = renderer.render(scene);
    const std::size_t centre = 3 * (std::size_t(scene.height / 2) * scene.width + scene.width / 2);
    for (int c = 0; c < 3; ++c)
        CHECK(std::abs(int(image.display[centre + c]) - int(srgb8(scene.materials[0].albedo[c]))) <= 1);
    // No light changes it.
    scene.lights.clear();
    CHECK(Renderer({.isa = "scalar"}).render(scene).display == image.display);
    test::check_every_isa_within(scene, image, 0);
    // With a map and vertex colours: albedo × map × colour is shown.
    scene.textures.push_back(checker());
    scene.materials[0].albedo_map.texture = 0;
    scene.meshes[0].colors.assign(scene.meshes[0].positions.size(), glm::vec4(0.5f, 1.0f, 1.0f, 1.0f));
    const RenderedImage mapped = Renderer({.isa = "scalar"}).render(scene);
    test::check_every_isa_within(scene, mapped, 0);
}

TEST_CASE("a map on the second uv set samples as the same map on the first set does") {
    Scene baked = plane_scene();
    baked.textures.push_back(checker());
    Mesh& mesh = baked.meshes[0];
    std::vector<glm::vec2> second;
    for (const glm::vec2& uv : mesh.uvs) second.push_back(glm::vec2(0.25f) + 0.5f * glm::vec2(uv.y, uv.x));
    Scene two_sets = baked;
    baked.meshes[0].uvs = second;
    baked.materials[0].albedo_map.texture = 0;
    two_sets.meshes[0].uvs1 = second;
    two_sets.materials[0].albedo_map.texture = 0;
    two_sets.materials[0].albedo_map.uv_set = 1;
    // A second map on set 0 (ao, all ones): the material reads both sets.
    const float white[] = {1, 1, 1};
    two_sets.textures.push_back(std::make_shared<const texture::Texture>(
        texture::Texture::from_pixels(1, 1, 3, white, texture::ColorSpace::linear)));
    two_sets.materials[0].ao_map.texture = 1;
    for (const bool near_clipped : {false, true}) {
        CAPTURE(near_clipped);
        if (near_clipped) {  // the near plane cuts the plane: clipping makes corners with their own second uvs
            for (Scene* s : {&baked, &two_sets}) s->camera.position = {0, 0.3f, 1.2f}, s->camera.near_plane = 0.5f;
        }
        const RenderedImage reference = Renderer({.isa = "scalar"}).render(baked);
        const RenderedImage image = Renderer({.isa = "scalar"}).render(two_sets);
        CHECK(worst_difference(reference, image) <= 1);
        test::check_every_isa_within(two_sets, reference, 1);
    }
}

TEST_CASE("a map's own uv transform samples as the transform baked into the uvs does") {
    Scene baked = plane_scene();
    baked.textures.push_back(checker());
    const glm::mat3 transform(0.5f, 0.2f, 0, -0.3f, 0.7f, 0, 0.1f, 0.4f, 1);  // column-major: scale, shear, offset
    Scene sampled = baked;
    for (glm::vec2& uv : baked.meshes[0].uvs) uv = glm::vec2(transform * glm::vec3(uv, 1.0f));
    baked.materials[0].albedo_map.texture = 0;
    sampled.materials[0].albedo_map.texture = 0;
    sampled.materials[0].albedo_map.uv_transformed = true;
    sampled.materials[0].albedo_map.uv_transform = transform;
    const RenderedImage reference = Renderer({.isa = "scalar"}).render(baked);
    CHECK(worst_difference(reference, Renderer({.isa = "scalar"}).render(sampled)) <= 1);
    test::check_every_isa_within(sampled, reference, 1);
}

TEST_CASE("samplers reach the pixels: nearest magnification and mirrored wraps, every ISA as scalar") {
    Scene scene = plane_scene();
    scene.textures.push_back(checker());
    for (glm::vec2& uv : scene.meshes[0].uvs) uv = uv * 3.0f - 1.0f;  // three copies across, past both edges
    TextureSlot& slot = scene.materials[0].albedo_map;
    slot.texture = 0;
    const RenderedImage linear = Renderer({.isa = "scalar"}).render(scene);
    slot.wrap_s = TextureWrap::mirrored_repeat, slot.wrap_t = TextureWrap::clamp_to_edge;
    slot.mag_filter = TextureFilter::nearest, slot.min_filter = TextureFilter::nearest_mipmap_nearest;
    const RenderedImage nearest = Renderer({.isa = "scalar"}).render(scene);
    CHECK(worst_difference(linear, nearest) > 20);  // the sampler changed the picture
    test::check_every_isa_within(scene, nearest, 0);
}
