// Blended materials (AlphaMode::blend): drawn after the opaque objects, back to
// front per object, tested against the opaque depth without writing it, and
// composited "over" in scene-linear radiance: src·α + dst·(1 − α).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>

#include "image/resolve.hpp"
#include "render/isa_agreement.hpp"
#include "shade/pbr_reference.hpp"
#include "tessera/renderer.hpp"

using namespace tessera;

namespace {

constexpr int kSize = 64;

Light test_light() {
    Light light;
    light.type = LightType::directional;
    light.direction = glm::normalize(glm::vec3(0.5f, -1.0f, 0.3f));
    light.color = {3, 3, 3};
    return light;
}

Material flat(const glm::vec3& albedo, AlphaMode mode = AlphaMode::opaque, float alpha = 1.0f) {
    Material m;
    m.albedo = albedo;
    m.alpha_mode = mode;
    m.alpha_factor = alpha;
    return m;
}

// Seen from above (image x = world +X, image y = world +Z): planes of the given
// half-size at the given height, centred at (x, height, 0).
struct Quad {
    Material material;
    float height;
    float half_size;
    float x = 0.0f;
};

Scene quad_scene(const std::vector<Quad>& quads) {
    Scene scene;
    scene.width = scene.height = kSize;
    scene.clear_color = glm::vec3(0.2f, 0.3f, 0.1f);
    scene.camera.position = {0, 6, 0};
    scene.camera.target = {0, 0, 0};
    scene.camera.up = {0, 0, -1};
    scene.meshes.push_back(make_plane_mesh());
    for (const Quad& q : quads) {
        scene.materials.push_back(q.material);
        const glm::mat4 model = glm::scale(glm::translate(glm::mat4(1.0f), {q.x, q.height, 0}), glm::vec3(q.half_size));
        scene.objects.push_back(Object{0, std::uint32_t(scene.materials.size() - 1), model});
    }
    scene.lights.push_back(test_light());
    return scene;
}

glm::vec3 radiance_at(const RenderedImage& image, int x, int y) {
    const std::size_t i = 3 * (std::size_t(y) * image.width + x);
    return {image.radiance[i], image.radiance[i + 1], image.radiance[i + 2]};
}

// The point of the plane y = height seen through pixel (x, y)'s centre.
glm::vec3 hit_on_plane(const Scene& scene, int x, int y, float height) {
    const glm::mat4 inverse = glm::inverse(projection_matrix(scene.camera, scene.width, scene.height) *
                                           view_matrix(scene.camera));
    const float ndc_x = (x + 0.5f) / scene.width * 2 - 1, ndc_y = 1 - (y + 0.5f) / scene.height * 2;
    const glm::vec4 far_point = inverse * glm::vec4(ndc_x, ndc_y, 1, 1);
    const glm::vec3 origin = scene.camera.position;
    const glm::vec3 dir = glm::vec3(far_point) / far_point.w - origin;
    return origin + (height - origin.y) / dir.y * dir;
}

const glm::vec3 kRed{1, 0, 0}, kBlue{0, 0, 1}, kGreen{0, 1, 0};

}  // namespace

TEST_CASE("blend: a red quad at alpha 0.5 over a blue one is the over of the reference shader's two radiances") {
    const Scene scene = quad_scene({{flat(kRed, AlphaMode::blend, 0.5f), 1.0f, 1.0f}, {flat(kBlue), 0.0f, 3.0f}});
    Renderer renderer({.threads = 2, .isa = "scalar"});
    const RenderedImage& image = renderer.render(scene);
    for (const auto& [x, y] : {std::pair{32, 32}, std::pair{28, 36}, std::pair{37, 27}}) {
        CAPTURE(x);
        CAPTURE(y);
        const glm::vec3 red = shade::shade_pbr(hit_on_plane(scene, x, y, 1.0f), {0, 1, 0}, scene.materials[0],
                                               scene.camera.position, scene.lights);
        const glm::vec3 blue = shade::shade_pbr(hit_on_plane(scene, x, y, 0.0f), {0, 1, 0}, scene.materials[1],
                                                scene.camera.position, scene.lights);
        const glm::vec3 expected = red * 0.5f + blue * (1.0f - 0.5f);
        const glm::vec3 rendered = radiance_at(image, x, y);
        for (int c = 0; c < 3; ++c) CHECK(rendered[c] == doctest::Approx(expected[c]).epsilon(1e-4));
        // The PNG value is the blended radiance tonemapped, as for any pixel.
        const glm::vec3 display = shade::display_from_radiance(expected);
        const std::size_t i = 3 * (std::size_t(y) * kSize + x);
        for (int c = 0; c < 3; ++c) CHECK(std::abs(float(image.display[i + c]) - display[c] * 255.0f) <= 1.0f);
    }
}

TEST_CASE("blend: the composite is exactly src*alpha + dst*(1-alpha) of the layers rendered alone") {
    const Quad blue{flat(kBlue), 0.0f, 3.0f};
    Renderer renderer({.threads = 1});
    const RenderedImage over = renderer.render(quad_scene({{flat(kRed, AlphaMode::blend, 0.25f), 1.0f, 1.0f}, blue}));
    const RenderedImage red_alone = renderer.render(quad_scene({{flat(kRed), 1.0f, 1.0f}, blue}));
    const RenderedImage blue_alone = renderer.render(quad_scene({blue}));
    const RenderedImage nothing = renderer.render(quad_scene({}));
    // Inside the red quad: over blue. Outside it: the blue alone, bit for bit.
    for (int c = 0; c < 3; ++c) {
        const float src = radiance_at(red_alone, 32, 32)[c], dst = radiance_at(blue_alone, 32, 32)[c];
        CHECK(radiance_at(over, 32, 32)[c] == src * 0.25f + dst * (1.0f - 0.25f));
        CHECK(radiance_at(over, 8, 8)[c] == radiance_at(blue_alone, 8, 8)[c]);
    }
    // Tiles with blended triangles keep the display values of pixels the red quad misses, bit for bit.
    int outside = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            if (radiance_at(red_alone, x, y) == radiance_at(blue_alone, x, y)) {
                const std::size_t i = 3 * (std::size_t(y) * kSize + x);
                for (int c = 0; c < 3; ++c) REQUIRE(over.display[i + c] == blue_alone.display[i + c]);
                ++outside;
            }
    CHECK(outside > kSize * kSize / 2);
    // Over the background: the clear colour's radiance is the destination.
    const RenderedImage lone = renderer.render(quad_scene({{flat(kRed, AlphaMode::blend, 0.25f), 1.0f, 1.0f}}));
    for (int c = 0; c < 3; ++c) {
        const float src = radiance_at(red_alone, 32, 32)[c], dst = radiance_at(nothing, 32, 32)[c];
        CHECK(radiance_at(lone, 32, 32)[c] == src * 0.25f + dst * (1.0f - 0.25f));
    }
}

TEST_CASE("blend: behind an opaque surface a blended one is hidden (depth test, no depth write)") {
    Renderer renderer({.threads = 1});
    const RenderedImage hidden =
        renderer.render(quad_scene({{flat(kBlue), 1.0f, 2.0f}, {flat(kRed, AlphaMode::blend, 0.5f), 0.0f, 1.0f}}));
    const RenderedImage blue_alone = renderer.render(quad_scene({{flat(kBlue), 1.0f, 2.0f}}));
    CHECK(hidden.radiance == blue_alone.radiance);
    CHECK(hidden.display == blue_alone.display);
}

TEST_CASE("blend: blended fragments write no depth, so a nearer one drawn first does not hide a farther one") {
    // N is tilted: its centre (height 0.5) is farther than F's (height 1), so it is
    // drawn first, but on its raised side (x > 0.7) it is nearer than F.
    const Quad blue{flat(kBlue), 0.0f, 3.0f};
    const Quad n{flat(kRed, AlphaMode::blend, 0.5f), 0.5f, 2.0f};
    const Quad f{flat(kGreen, AlphaMode::blend, 0.5f), 1.0f, 2.0f};
    const glm::mat4 tilt = glm::rotate(glm::mat4(1.0f), 0.7f, glm::vec3(0, 0, 1));
    Scene both = quad_scene({n, f, blue});
    both.objects[0].model = both.objects[0].model * tilt;
    Scene n_only = quad_scene({n, blue});
    n_only.objects[0].model = n_only.objects[0].model * tilt;
    Renderer renderer({.threads = 1});
    const RenderedImage with_f = renderer.render(both);
    const RenderedImage without_f = renderer.render(n_only);
    const int x = 50, y = 32;  // world x ≈ 1.1: N at height ≈ 1.4, above F
    REQUIRE(hit_on_plane(both, x, y, 1.0f).x > 1.0f);
    // A depth write by N would have kept F out of this pixel: the same as N alone.
    CHECK(radiance_at(with_f, x, y).g > radiance_at(without_f, x, y).g + 0.01f);
}

TEST_CASE("blend: objects are sorted back to front, so the scene order of blended objects does not matter") {
    const Quad blue{flat(kBlue), 0.0f, 3.0f};
    const Quad red{flat(kRed, AlphaMode::blend, 0.5f), 1.0f, 1.5f, -0.3f};
    const Quad green{flat(kGreen, AlphaMode::blend, 0.4f), 2.0f, 1.0f, 0.4f};
    Renderer renderer({.threads = 2});
    const RenderedImage a = renderer.render(quad_scene({red, green, blue}));
    const RenderedImage b = renderer.render(quad_scene({green, blue, red}));
    CHECK(a.radiance == b.radiance);
    CHECK(a.display == b.display);
    // And the order is far to near: green (nearer) over (red over blue).
    Quad opaque_red = red, opaque_green = green;
    opaque_red.material.alpha_mode = opaque_green.material.alpha_mode = AlphaMode::opaque;
    const RenderedImage r = renderer.render(quad_scene({opaque_red, blue}));
    const RenderedImage g = renderer.render(quad_scene({opaque_green, blue}));
    const RenderedImage base = renderer.render(quad_scene({blue}));
    const int x = 32, y = 32;  // under both
    for (int c = 0; c < 3; ++c) {
        const float red_over_blue = radiance_at(r, x, y)[c] * 0.5f + radiance_at(base, x, y)[c] * (1.0f - 0.5f);
        CHECK(radiance_at(a, x, y)[c] == radiance_at(g, x, y)[c] * 0.4f + red_over_blue * (1.0f - 0.4f));
    }
}

TEST_CASE("blend: the same image with any thread count and tile size, every ISA within 1/255 of scalar") {
    Scene scene = quad_scene({{flat(kRed, AlphaMode::blend, 0.5f), 1.0f, 1.5f, -0.3f},
                              {flat(kGreen, AlphaMode::blend, 0.4f), 2.0f, 1.0f, 0.4f},
                              {flat(kBlue), 0.0f, 3.0f}});
    scene.objects[0].model = glm::rotate(scene.objects[0].model, 0.4f, glm::vec3(0, 1, 0));
    scene.width = 200, scene.height = 150;  // several tiles, edge tiles cut short
    for (const int msaa : {1, 4}) {
        CAPTURE(msaa);
        scene.msaa = msaa;
        Renderer one({.threads = 1, .tile_size = 32});
        const RenderedImage reference = one.render(scene);
        for (const int threads : {2, 3, 8}) {
            Renderer renderer({.threads = threads, .tile_size = threads == 3 ? 16 : 64});
            const RenderedImage& image = renderer.render(scene);
            CHECK(image.radiance == reference.radiance);
            CHECK(image.display == reference.display);
        }
        Renderer scalar({.threads = 2, .isa = "scalar"});
        const RenderedImage scalar_image = scalar.render(scene);
        test::check_every_isa_within(scene, scalar_image, 1, {.threads = 2});
    }
}

TEST_CASE("blend: with 4x MSAA each covered sample blends, and a pixel inside is the one-sample value") {
    Scene scene = quad_scene({{flat(kRed, AlphaMode::blend, 0.5f), 1.0f, 1.0f}, {flat(kBlue), 0.0f, 3.0f}});
    Renderer renderer({.threads = 2});
    const RenderedImage one = renderer.render(scene);
    scene.msaa = 4;
    const RenderedImage four = renderer.render(scene);
    CHECK(radiance_at(four, 32, 32) == radiance_at(one, 32, 32));
    // On the red quad's edge some samples are blended and some not: between the two.
    int between = 0;
    for (int x = 0; x < kSize; ++x) {
        const float blended = radiance_at(one, 32, 32).r, outside = radiance_at(one, 4, 32).r;
        const float r = radiance_at(four, x, 32).r;
        if (r > outside * 1.01f + 1e-4f && r < blended * 0.99f) ++between;
    }
    CHECK(between >= 2);  // the left and right edges
}
