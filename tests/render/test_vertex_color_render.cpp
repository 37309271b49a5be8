// Vertex colours (Mesh::colors, glTF COLOR_0): they multiply the albedo and
// alpha, interpolated perspective-correctly; every ISA and thread count agree.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>

#include "tessera/renderer.hpp"
#include "render/isa_agreement.hpp"

using namespace tessera;

namespace {

constexpr float kNearZ = -1.0f, kFarZ = -9.0f;
const glm::vec4 kNearColor{1.0f, 0.2f, 0.0f, 1.0f}, kFarColor{0.0f, 0.6f, 1.0f, 0.5f};

// A floor receding from the camera: its colour runs from kNearColor at z = -1
// to kFarColor at z = -9 (linear in world space), so perspective-correct
// interpolation and screen-linear interpolation differ a lot.
Scene floor_scene() {
    Scene scene;
    scene.width = 64, scene.height = 64;
    scene.camera.position = {0, 1, 0};
    scene.camera.target = {0, 0, -4};
    Mesh floor;
    floor.name = "floor";
    floor.positions = {{-3, 0, kNearZ}, {3, 0, kNearZ}, {3, 0, kFarZ}, {-3, 0, kFarZ}};
    floor.normals.assign(4, glm::vec3(0, 1, 0));
    floor.colors = {kNearColor, kNearColor, kFarColor, kFarColor};
    floor.indices = {0, 1, 2, 0, 2, 3};
    scene.meshes.push_back(floor);
    Material white;
    white.albedo = glm::vec3(0.8f);
    scene.materials.push_back(white);
    scene.objects.push_back(Object{0, 0, glm::mat4(1.0f)});
    Light light;
    light.type = LightType::directional;
    light.direction = glm::normalize(glm::vec3(0.2f, -1.0f, -0.3f));
    light.color = {2, 2, 2};
    scene.lights.push_back(light);
    return scene;
}

// Where the ray through pixel (x, y)'s centre meets the floor y = 0.
glm::vec3 floor_hit(const Scene& scene, int x, int y) {
    const glm::mat4 inverse = glm::inverse(projection_matrix(scene.camera, scene.width, scene.height) *
                                           view_matrix(scene.camera));
    const float ndc_x = (x + 0.5f) / scene.width * 2 - 1, ndc_y = 1 - (y + 0.5f) / scene.height * 2;
    const glm::vec4 far_point = inverse * glm::vec4(ndc_x, ndc_y, 1, 1);
    const glm::vec3 origin = scene.camera.position;
    const glm::vec3 dir = glm::vec3(far_point) / far_point.w - origin;
    return origin - origin.y / dir.y * dir;
}

glm::vec3 albedo_at(const RenderedImage& image, int x, int y) {
    const std::size_t i = 3 * (std::size_t(y) * image.width + x);
    return {image.aov.albedo[i], image.aov.albedo[i + 1], image.aov.albedo[i + 2]};
}

}  // namespace

TEST_CASE("vertex colours multiply the albedo, interpolated perspective-correctly") {
    const Scene scene = floor_scene();
    RenderSettings settings{.threads = 2};
    settings.aovs.insert(Aov::albedo);
    Renderer renderer(settings);
    const RenderedImage& image = renderer.render(scene);
    int checked = 0;
    for (int y = 34; y < 64; y += 3) {
        const int x = 32;
        const glm::vec3 hit = floor_hit(scene, x, y);
        if (hit.z > kNearZ || hit.z < kFarZ) continue;
        CAPTURE(y);
        const float t = (hit.z - kNearZ) / (kFarZ - kNearZ);  // world-space position along the floor
        const glm::vec3 expected = 0.8f * glm::vec3(kNearColor + t * (kFarColor - kNearColor));
        const glm::vec3 rendered = albedo_at(image, x, y);
        for (int c = 0; c < 3; ++c) CHECK(rendered[c] == doctest::Approx(expected[c]).epsilon(1e-3));
        ++checked;
    }
    CHECK(checked >= 5);
    // The test can tell: halfway up the floor on screen, screen-linear interpolation
    // would be far from the perspective-correct value.
    const glm::vec3 near_hit = floor_hit(scene, 32, 63);
    int horizon_row = 33;
    while (floor_hit(scene, 32, horizon_row).z < kFarZ) ++horizon_row;
    const int mid_row = (63 + horizon_row) / 2;
    const float t_mid = (floor_hit(scene, 32, mid_row).z - kNearZ) / (kFarZ - kNearZ);
    const float t_near = (near_hit.z - kNearZ) / (kFarZ - kNearZ);
    CHECK(std::abs(t_mid - (t_near + 1.0f) * 0.5f) > 0.1f);
}

TEST_CASE("vertex colours: meshes without them are unchanged, and colour alpha scales alpha") {
    Scene scene = floor_scene();
    Renderer renderer({.threads = 1});
    Scene plain = scene;
    plain.meshes[0].colors.clear();
    const RenderedImage without = renderer.render(plain);
    Scene white = scene;
    white.meshes[0].colors.assign(4, glm::vec4(1.0f));
    CHECK(renderer.render(white).radiance == without.radiance);  // × 1 exactly
    // A blended material: colour alpha 0 makes the floor vanish into the background.
    Scene clear_floor = scene;
    clear_floor.meshes[0].colors.assign(4, glm::vec4(1, 1, 1, 0));
    clear_floor.materials[0].alpha_mode = AlphaMode::blend;
    Scene empty = scene;
    empty.objects.clear();
    CHECK(renderer.render(clear_floor).display == renderer.render(empty).display);
    // A masked one: alpha 0.5 → 1 along the floor against cutoff 0.75 keeps only the near part.
    Scene masked = scene;
    masked.materials[0].alpha_mode = AlphaMode::mask;
    masked.materials[0].alpha_cutoff = 0.75f;
    const RenderedImage& cut = renderer.render(masked);
    const std::size_t near_pixel = 3 * (std::size_t(60) * 64 + 32), far_pixel = 3 * (std::size_t(36) * 64 + 32);
    CHECK(cut.radiance[near_pixel] > 0.0f);
    const RenderedImage& background = renderer.render(empty);
    CHECK(cut.radiance[far_pixel] == background.radiance[far_pixel]);
}

TEST_CASE("vertex colours: every ISA within 1/255 of scalar, every thread count and clipping alike") {
    Scene scene = floor_scene();
    scene.camera.position = {0, 1, -1.5f};  // the near plane cuts the floor: clipped corners get colours
    scene.camera.near_plane = 0.6f;
    scene.width = 160, scene.height = 96;
    Renderer scalar({.threads = 1, .isa = "scalar"});
    const RenderedImage reference = scalar.render(scene);
    for (const int threads : {2, 8}) {
        Renderer renderer({.threads = threads, .isa = "scalar"});
        CHECK(renderer.render(scene).radiance == reference.radiance);
    }
    test::check_every_isa_within(scene, reference, 1, {.threads = 2});
    // The clipped floor still shows the colours' gradient near the camera: red there.
    const std::size_t bottom = 3 * (std::size_t(95) * 160 + 80);
    CHECK(reference.radiance[bottom] > 2.0f * reference.radiance[bottom + 2]);
}
