// Shadow mapping end to end: the depth passes through the frame's own stages
// (render/shadow_pass.hpp), the chapters' lookups on the maps they make
// (shade/shadow_maps.hpp), and the frame with them.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include <OpenImageIO/imageio.h>

#include "cli_runner.hpp"
#include "render/isa_agreement.hpp"
#include "scene/gltf_test_files.hpp"
#include "test_paths.hpp"
#include "render/shadow_pass.hpp"
#include "shade/shadow_maps.hpp"
#include "simd/isa.hpp"
#include "tessera/renderer.hpp"
#include "tessera/scene.hpp"

namespace {

using namespace tessera;

// A 10×10 floor at y = 0 and, unless `occluder` is false, a cube of side 1 over
// its centre (y from 0.5 to 1.5), lit by `light` (a [[lights]] table's keys).
Scene floor_scene(const std::string& light, bool occluder = true, int size = 160) {
    std::string text = "[output]\nwidth = " + std::to_string(size) + "\nheight = " + std::to_string(size * 3 / 4) +
                       "\n[camera]\nposition = [0, 7, 9]\ntarget = [0, 0, 0]\n"
                       "[[lights]]\n" + light + "\n"
                       "[[objects]]\nmesh = \"plane\"\nscale = 5\n"
                       "material = { albedo = [0.8, 0.8, 0.8], roughness = 0.6 }\n";
    if (occluder)
        text += "[[objects]]\nmesh = \"cube\"\ntranslate = [0, 1, 0]\nscale = 0.5\n"
                "material = { albedo = [0.2, 0.4, 0.8], roughness = 0.4 }\n";
    return parse_scene(text, "floor_scene");
}

const char* const kDirectional =
    "type = \"directional\"\ndirection = [0.1, -1.0, 0.05]\ncolor = [3, 3, 3]\nshadows = true\nshadow_map_size = 512";
const char* const kSpot =
    "type = \"spot\"\nposition = [0, 6, 0]\ndirection = [0, -1, 0]\nouter_cone = 60\ncolor = [200, 200, 200]\n"
    "shadows = true\nshadow_map_size = 512";
const char* const kPoint = "type = \"point\"\nposition = [0.3, 4, 0.2]\ncolor = [100, 100, 100]\nshadows = true\n"
                           "shadow_map_size = 256";

const std::string kCamera = "[camera]\nposition = [0, 0, 5]\ntarget = [0, 0, 0]\n";

struct Maps {
    std::vector<shade::ShadowMap> maps;
    std::vector<const shade::ShadowMap*> by_light;
};
Maps render_maps(const Scene& scene, simd::Isa isa = simd::best_supported_isa()) {
    render::ShadowPass pass;
    Maps m;
    pass.render_maps(isa, scene, m.maps, m.by_light);
    return m;
}

}  // namespace

TEST_CASE("shadow depth pass: a known quad's window depth, nearest wins, nothing elsewhere") {
    // The plane mesh (x, z in [-1, 1] at y = 0) seen from y = 2 straight down
    // through an orthographic box 4 wide and 4 deep: it covers the middle half
    // of the map at view depth 2, window depth 0.5. A second quad at y = 1,
    // over x in [0, 1] only, is nearer (window depth 0.25) where it lies.
    const Scene scene = parse_scene(R"(
[camera]
position = [0, 0, 5]
target = [0, 0, 0]
[[objects]]
mesh = "plane"
[[objects]]
mesh = "plane"
translate = [0.5, 1, 0]
scale = [0.5, 1, 1]
)",
                                    "quad");
    const glm::mat4 view_projection = glm::ortho(-2.0f, 2.0f, -2.0f, 2.0f, 0.0f, 4.0f) *
                                      glm::lookAt(glm::vec3(0, 2, 0), glm::vec3(0, 0, 0), glm::vec3(0, 0, -1));
    for (const simd::Isa isa : {simd::Isa::scalar, simd::best_supported_isa()}) {
        CAPTURE(simd::isa_name(isa));
        render::ShadowPass pass;
        pass.prepare(scene);
        const int size = 64;
        std::vector<float> depth(size * size, -1.0f);
        pass.render_depth(isa, scene, view_projection, size, depth);
        int wrong = 0;
        for (int row = 0; row < size; ++row) {
            for (int column = 0; column < size; ++column) {
                const bool on_floor = column >= 16 && column < 48 && row >= 16 && row < 48;
                const bool on_upper = on_floor && column >= 32;  // x >= 0: the image's right half
                const float expected = on_upper ? 0.25f : on_floor ? 0.5f : 1.0f;
                if (std::abs(depth[row * size + column] - expected) > 1e-6f) ++wrong;
            }
        }
        CHECK(wrong == 0);
    }
}

TEST_CASE("shadows: a point behind an occluder gets visibility 0, a lit one 1, for each light type") {
    for (const char* light : {kDirectional, kSpot, kPoint}) {
        CAPTURE(light);
        const Scene scene = floor_scene(light);
        const Maps m = render_maps(scene);
        REQUIRE(m.by_light.size() == 1);
        REQUIRE(m.by_light[0] != nullptr);
        const shade::ShadowMap& map = *m.by_light[0];
        const glm::vec3 up(0, 1, 0), camera = scene.camera.position;
        CHECK(shadow_visibility(map, {0.0f, 0.0f, 0.0f}, up, camera) == 0.0f);    // under the cube
        CHECK(shadow_visibility(map, {2.5f, 0.0f, 2.0f}, up, camera) == 1.0f);    // open floor
        CHECK(shadow_visibility(map, {0.0f, 1.5f, 0.0f}, up, camera) == 1.0f);    // the cube's top
        CHECK(shadow_visibility(map, {-2.0f, 0.0f, -2.5f}, up, camera) == 1.0f);  // open floor
    }
}

TEST_CASE("shadows: the bias keeps an unoccluded floor facing the light free of acne") {
    const char* const tilted = "type = \"directional\"\ndirection = [0.5, -0.8, 0.3]\ncolor = [3, 3, 3]\n"
                               "shadows = true\nshadow_map_size = 512";
    for (const char* light : {kDirectional, tilted, kSpot, kPoint}) {
        CAPTURE(light);
        const Scene scene = floor_scene(light, false);
        const Maps m = render_maps(scene);
        const shade::ShadowMap& map = *m.by_light[0];
        int shadowed = 0, points = 0;
        for (float x = -4.95f; x < 5.0f; x += 0.1f) {
            for (float z = -4.95f; z < 5.0f; z += 0.1f) {
                const glm::vec3 p(x, 0.0f, z);
                // The spot lights a disc only; past its cone the map says nothing.
                if (scene.lights[0].type == LightType::spot && glm::length(glm::vec2(x, z)) > 6.0f * 1.6f) continue;
                ++points;
                shadowed += shadow_visibility(map, p, {0, 1, 0}, scene.camera.position) != 1.0f;
            }
        }
        CHECK(points > 9000);
        CHECK(shadowed == 0);
    }
}

TEST_CASE("shadows: PCF softens the rendered shadow's edge, and only shadowed light dims") {
    Scene scene = floor_scene(kDirectional, true, 240);
    Renderer renderer({.threads = 2, .keep_radiance = true});
    const std::vector<float> shadowed = renderer.render(scene).radiance;
    scene.lights[0].shadows = false;
    const std::vector<float> unshadowed = renderer.render(scene).radiance;
    REQUIRE(shadowed.size() == unshadowed.size());
    std::size_t darker = 0, equal = 0, brighter = 0;
    for (std::size_t i = 0; i < shadowed.size(); ++i) {
        if (shadowed[i] < unshadowed[i]) ++darker;
        else if (shadowed[i] == unshadowed[i]) ++equal;
        else ++brighter;
    }
    CHECK(brighter == 0);
    CHECK(darker > 300);       // the cube's shadow on the floor
    CHECK(equal > darker * 5);  // lit pixels keep their bits
    // Fractions at the edge: some shadowed pixels keep more than the ambient
    // term and less than the full light.
    std::size_t partial = 0;
    for (std::size_t i = 0; i < shadowed.size(); i += 3) {
        const float ambient = 0.03f * 0.8f;  // the floor's ambient, red channel
        if (shadowed[i] > ambient * 1.5f && shadowed[i] < unshadowed[i] * 0.9f) ++partial;
    }
    CHECK(partial > 10);
}

TEST_CASE("shadows: the same bits on 1, 2 and 8 threads, every ISA within a step of the scalar path") {
    Scene scene = parse_scene(R"(
[output]
width = 200
height = 150
[camera]
position = [0, 7, 9]
target = [0, 0, 0]
[[lights]]
type = "directional"
direction = [0.3, -1, -0.2]
color = [2, 2, 2]
shadows = true
shadow_map_size = 300
[[lights]]
type = "spot"
position = [-3, 5, 2]
direction = [0.5, -1, -0.3]
color = [150, 120, 100]
shadows = true
shadow_filter_radius = 2
[[lights]]
type = "point"
position = [2, 3, 1]
color = [40, 40, 50]
shadows = true
shadow_map_size = 128
[[lights]]
position = [0, 5, 5]
color = [20, 20, 20]
[[objects]]
mesh = "plane"
scale = 5
[[objects]]
mesh = "sphere"
translate = [0, 1, 0]
[[objects]]
mesh = "cube"
translate = [-2, 0.5, 1]
scale = 0.5
)",
                              "three_lights");
    Renderer one({.threads = 1, .keep_radiance = true});
    const RenderedImage reference = one.render(scene);
    CHECK(one.render(scene).radiance == reference.radiance);  // a second frame from reused memory
    for (const int threads : {2, 8}) {
        CAPTURE(threads);
        Renderer renderer({.threads = threads, .keep_radiance = true});
        CHECK(renderer.render(scene).radiance == reference.radiance);
    }
    Renderer scalar({.threads = 2, .isa = "scalar"});
    const RenderedImage scalar_image = scalar.render(scene);
    test::check_every_isa_within(scene, scalar_image, 1, {.threads = 2});
    // With light culling (ranges), the same visibility scales the same light.
    for (Light& light : scene.lights)
        if (light.type != LightType::directional) light.range = 30.0f;
    Renderer culled({.threads = 2, .keep_radiance = true});
    Renderer uncut({.threads = 2, .keep_radiance = true, .light_culling = false});
    CHECK(culled.render(scene).radiance == uncut.render(scene).radiance);
}

// The maps kept from frame to frame (ShadowPass::render_maps): kept only while
// nothing they depend on changed, and then the same picture as drawn anew.
TEST_CASE("shadows: maps are kept while lights and casters stay, drawn again when one changes") {
    Scene scene = floor_scene(std::string(kPoint) + "\n[[lights]]\n" + kDirectional + "\n[[lights]]\n" + kSpot);
    scene.materials.push_back(scene.materials[scene.objects[1].material]);
    scene.materials.back().alpha_mode = AlphaMode::mask;  // a second cube, alpha-tested, cut by its alpha
    scene.objects.push_back(scene.objects[1]);
    scene.objects.back().material = std::uint32_t(scene.materials.size() - 1);
    scene.objects.back().model = glm::translate(glm::mat4(1.0f), glm::vec3(2.0f, 0.5f, 0.0f)) * scene.objects[1].model;
    Renderer renderer({.threads = 2, .keep_radiance = true});
    // The picture a renderer with no maps kept makes of the scene as it is now.
    const auto fresh = [&] { return Renderer({.threads = 2, .keep_radiance = true}).render(scene).radiance; };
    const auto frame = [&](std::uint32_t drawn, std::uint32_t kept) {
        const std::vector<float> radiance = renderer.render(scene).radiance;
        CHECK(renderer.last_frame_stats().shadow_maps_drawn == drawn);
        CHECK(renderer.last_frame_stats().shadow_maps_kept == kept);
        CHECK(radiance == fresh());
        return radiance;
    };
    const std::vector<float> first = frame(3, 0);
    CHECK(frame(0, 3) == first);  // a still scene: every map kept
    SUBCASE("the camera moves: the point and spot maps stay (the directional one is refitted, if what it sees changed)") {
        scene.camera.position += glm::vec3(1.0f, 0.5f, -0.5f);
        CHECK(renderer.render(scene).radiance == fresh());
        CHECK(renderer.last_frame_stats().shadow_maps_kept >= 2);
        CHECK(renderer.last_frame_stats().shadow_maps_drawn + renderer.last_frame_stats().shadow_maps_kept == 3);
    }
    SUBCASE("a caster moves") {
        scene.objects[1].model = glm::translate(scene.objects[1].model, glm::vec3(0.4f, 0.0f, 0.0f));
        CHECK(frame(3, 0) != first);
    }
    SUBCASE("a mesh's vertices change in place") {
        Mesh& cube = scene.meshes[scene.objects[1].mesh];
        for (glm::vec3& p : cube.positions) p.y *= 1.5f;
        CHECK(frame(3, 0) != first);
    }
    SUBCASE("an alpha cutoff changes: the masked cube stops casting") {
        scene.materials.back().alpha_cutoff = 2.0f;
        CHECK(frame(3, 0) != first);
    }
    SUBCASE("a light moves") {
        scene.lights[0].position.x += 0.5f;
        CHECK(frame(1, 2) != first);
    }
    SUBCASE("TESSERA_NO_SHADOW_CACHE=1 draws every map") {
        setenv("TESSERA_NO_SHADOW_CACHE", "1", 1);
        const std::vector<float> again = frame(3, 0);
        unsetenv("TESSERA_NO_SHADOW_CACHE");
        CHECK(again == first);
    }
}

TEST_CASE("shadows: bad map sizes and filter radii are refused with a clear error") {
    const auto load = [](const std::string& keys) {
        return parse_scene(kCamera + "[[lights]]\nposition = [0, 1, 0]\ncolor = [1, 1, 1]\nshadows = true\n" + keys,
                           "bad");
    };
    CHECK_NOTHROW(load("shadow_map_size = 16\nshadow_filter_radius = 0"));
    for (const char* keys : {"shadow_map_size = -1", "shadow_map_size = 0", "shadow_map_size = 100000",
                             "shadow_map_size = nan", "shadow_map_size = 512.5", "shadow_filter_radius = -1",
                             "shadow_filter_radius = 9", "shadow_filter_radius = nan", "shadows = 1"}) {
        CAPTURE(keys);
        CHECK_THROWS_AS(load(keys), SceneError);
    }
    CHECK_THROWS_WITH_AS(load("shadow_map_size = 100000"),
                         doctest::Contains("'lights[0].shadow_map_size' to be in 16..8192"), SceneError);
    CHECK_THROWS_WITH_AS(parse_scene(kCamera + "[shadows]\nmap_size = -4\n", "bad"),
                         doctest::Contains("'shadows.map_size' to be in 16..8192"), SceneError);
    CHECK_THROWS_AS(parse_scene(kCamera + "[shadows]\nsoftness = 1\n", "bad"), SceneError);
    // Built in code: the renderer refuses it too.
    Scene scene = load("");
    scene.lights[0].shadow_map_size = 1 << 20;
    Renderer renderer({.threads = 1});
    CHECK_THROWS_WITH_AS(renderer.render(scene), doctest::Contains("shadow map size"), std::invalid_argument);
    scene.lights[0].shadow_map_size = 64, scene.lights[0].shadow_filter_radius = -3;
    CHECK_THROWS_AS(renderer.render(scene), std::invalid_argument);
}

TEST_CASE("shadows: [shadows] sets every light's default, a light's own keys win") {
    const Scene scene = parse_scene(kCamera + R"(
[shadows]
enabled = true
map_size = 256
filter_radius = 2
[[lights]]
position = [0, 1, 0]
color = [1, 1, 1]
[[lights]]
position = [0, 2, 0]
color = [1, 1, 1]
shadows = false
[[lights]]
type = "directional"
direction = [0, -1, 0]
color = [1, 1, 1]
shadow_map_size = 2048
)",
                                    "defaults");
    REQUIRE(scene.lights.size() == 3);
    CHECK(scene.lights[0].shadows);
    CHECK(scene.lights[0].shadow_map_size == 256);
    CHECK(scene.lights[0].shadow_filter_radius == 2);
    CHECK(!scene.lights[1].shadows);
    CHECK(scene.lights[2].shadows);
    CHECK(scene.lights[2].shadow_map_size == 2048);
    const Scene plain = parse_scene(kCamera + "[[lights]]\nposition = [0, 1, 0]\ncolor = [1, 1, 1]\n", "plain");
    CHECK(!plain.lights[0].shadows);
    CHECK(plain.lights[0].shadow_map_size == kDefaultShadowMapSize);
}

TEST_CASE("shadows: the shadow AOV is the mean visibility of the lights that cast shadows") {
    // Two shadowed lights, from above and from the side: the cube's two
    // shadows on the floor are 1/2 where they do not overlap.
    Scene scene = floor_scene(kDirectional, true, 200);
    Light side = scene.lights[0];
    side.direction = glm::normalize(glm::vec3(-1.0f, -0.6f, 0.0f));
    scene.lights.push_back(side);
    RenderSettings settings{.threads = 2};
    settings.aovs.insert(Aov::shadow);
    settings.aovs.insert(Aov::position);
    Renderer renderer(settings);
    const RenderedImage& image = renderer.render(scene);
    REQUIRE(image.aov.shadow.size() == std::size_t(image.width) * image.height);
    std::size_t half = 0, lit = 0, dark = 0, outside = 0;
    for (std::size_t i = 0; i < image.aov.shadow.size(); ++i) {
        const float v = image.aov.shadow[i];
        half += v == 0.5f, lit += v == 1.0f, dark += v == 0.0f;
        outside += !(v >= 0.0f && v <= 1.0f);
    }
    CHECK(outside == 0);
    CHECK(half > 200);  // in one of the two shadows
    CHECK(lit > half);
    // Straight under the cube (the floor at the origin) only the light from above is blocked: 1/2.
    const glm::mat4 view_projection = projection_matrix(scene.camera, scene.width, scene.height) * view_matrix(scene.camera);
    const glm::vec4 clip = view_projection * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    const int x = int((clip.x / clip.w * 0.5f + 0.5f) * float(scene.width));
    const int y = int((0.5f - clip.y / clip.w * 0.5f) * float(scene.height));
    CHECK(image.aov.shadow[std::size_t(y) * scene.width + x] == 0.5f);
    CHECK(dark < half / 20);  // the floor's two shadows do not overlap; a few cube pixels face away from both
    // Without shadows: 1 everywhere.
    for (Light& light : scene.lights) light.shadows = false;
    const RenderedImage& plain = renderer.render(scene);
    CHECK(std::all_of(plain.aov.shadow.begin(), plain.aov.shadow.end(), [](float v) { return v == 1.0f; }));
}

TEST_CASE("shadows: the depth pass summarizes a cube map tile by tile as the whole map would be") {
    // 200 texels a side: tiles and blocks cut short at the edges; the faces
    // looking up see no caster (the pass's empty path).
    Scene scene = floor_scene(kPoint);
    scene.lights[0].shadow_map_size = 200;
    Maps m = render_maps(scene);
    REQUIRE(m.maps.size() == 1);
    const shade::ShadowMap& drawn = m.maps[0];
    REQUIRE(drawn.blocks_per_side == 50);
    shade::ShadowMap whole = drawn;
    whole.block_min.assign(whole.block_min.size(), 0.0f), whole.block_max.assign(whole.block_max.size(), 0.0f);
    shade::summarize_cube_blocks(whole);
    CHECK(whole.block_min == drawn.block_min);
    CHECK(whole.block_max == drawn.block_max);
    CHECK(std::count(drawn.block_min.begin(), drawn.block_min.end(), 1.0f) > 0);  // nothing seen
    CHECK(std::count_if(drawn.block_min.begin(), drawn.block_min.end(), [](float v) { return v < 1.0f; }) > 0);
}

TEST_CASE("shadows: point lights' lookups skipped where the surface faces away leave the picture as it was") {
    // Two shadowed point lights, one over the floor and one under it: the
    // floor faces away from the second, whose lookups there are skipped unless
    // the shadow AOV asks for every visibility.
    Scene scene = floor_scene(kPoint, true, 200);
    Light other = scene.lights[0];
    other.position = {-2.0f, -1.5f, 1.0f};
    scene.lights[0].position = {3.0f, 2.5f, -0.5f};
    scene.lights.push_back(other);
    Renderer picture_only(RenderSettings{.threads = 2});
    const RenderedImage picture = picture_only.render(scene);
    const FrameStats skipped = picture_only.last_frame_stats();
    RenderSettings with_aov{.threads = 2};
    with_aov.aovs.insert(Aov::shadow);
    Renderer every(with_aov);
    const RenderedImage& all = every.render(scene);
    const FrameStats tapped = every.last_frame_stats();
    CHECK(picture.display == all.display);
    CHECK(picture.radiance == all.radiance);
    if (simd::best_supported_isa() != simd::Isa::scalar) {
        CHECK(skipped.shadow_lookups_facing_away > skipped.fragments_shaded / 2);
        CHECK(tapped.shadow_lookups_facing_away == 0);
        CHECK(skipped.shadow_lookups_settled > 1000);
        CHECK(tapped.shadow_lookups_settled + tapped.shadow_lookups_tapped == 2 * tapped.fragments_shaded);
    }
}

TEST_CASE("shadows: a masked caster casts where its alpha test keeps it, a blended one not at all") {
    const auto visibility_under_cube = [](const std::string& cube_material) {
        const Scene scene = parse_scene(
            "[camera]\nposition = [0, 7, 9]\ntarget = [0, 0, 0]\n[[lights]]\n" + std::string(kDirectional) +
                "\n[[objects]]\nmesh = \"plane\"\nscale = 5\n"
                "[[objects]]\nmesh = \"cube\"\ntranslate = [0, 1, 0]\nscale = 0.5\nmaterial = " + cube_material + "\n",
            "masked");
        const Maps m = render_maps(scene);
        return shadow_visibility(*m.by_light[0], {0.0f, 0.0f, 0.0f}, {0, 1, 0}, scene.camera.position);
    };
    CHECK(visibility_under_cube("{ alpha_mode = \"mask\", alpha = 0.8 }") == 0.0f);        // kept
    CHECK(visibility_under_cube("{ alpha_mode = \"mask\", alpha = 0.3 }") == 1.0f);        // discarded
    CHECK(visibility_under_cube("{ alpha_mode = \"blend\", alpha = 0.9 }") == 1.0f);       // never cast
    CHECK(visibility_under_cube("{ albedo = [0.5, 0.5, 0.5] }") == 0.0f);                   // opaque
}

// A glTF file on its own (no camera, no lights): `tessera render` frames it and
// lights it with the shipped environment and a key light that casts shadows.
TEST_CASE("shadows: a glTF file on its own gets a key light with shadows (tessera render --aov shadow)") {
    // A 10×10 wall at z = 0 and a 2×2 square in front of it at z = 1.5, both facing +z
    // (the default framing looks along −z), unindexed.
    std::vector<std::uint8_t> bytes;
    const auto quad = [&](float half, float z) {
        // Counter-clockwise seen from +z: glTF's front faces (the material is single-sided).
        const float q[6][2] = {{-half, -half}, {half, -half}, {half, half}, {-half, -half}, {half, half}, {-half, half}};
        for (const auto& corner : q) test::append_floats(bytes, {corner[0], corner[1], z});
    };
    quad(5.0f, 0.0f);
    quad(1.0f, 1.5f);
    for (int i = 0; i < 12; ++i) test::append_floats(bytes, {0.0f, 0.0f, 1.0f});
    const std::string json = R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}}]}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 12, "type": "VEC3", "min": [-5, -5, 0], "max": [5, 5, 1.5]},
    {"bufferView": 1, "componentType": 5126, "count": 12, "type": "VEC3"}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 144}, {"buffer": 0, "byteOffset": 144, "byteLength": 144}],
  "buffers": [{"byteLength": 288, "uri": "data:application/octet-stream;base64,)" +
                             test::base64(bytes) + R"("}]})";
    const auto dir = test::output_dir("shadows_gltf_alone");
    test::write_bytes(dir / "wall.gltf", json);
    const auto shadow_channel = [&](const std::string& lighting) {
        const auto exr = dir / ("wall_" + lighting + ".exr");
        const test::CliRun run = test::run_tessera(dir, "render", {(dir / "wall.gltf").string(), "-o", exr.string(),
                                                                   "--aov", "shadow", "--width", "160", "--height",
                                                                   "90", "--lighting", lighting});
        REQUIRE_MESSAGE(run.status == 0, run.err);
        auto in = OIIO::ImageInput::open(exr.string());
        REQUIRE(in);
        const OIIO::ImageSpec spec = in->spec();
        const int channel = spec.channelindex("shadow");
        REQUIRE(channel >= 0);
        std::vector<float> values(std::size_t(spec.width) * spec.height);
        REQUIRE(in->read_image(0, 0, channel, channel + 1, OIIO::TypeDesc::FLOAT, values.data()));
        return values;
    };
    const std::vector<float> auto_look = shadow_channel("auto");
    const std::size_t shadowed = std::count_if(auto_look.begin(), auto_look.end(), [](float v) { return v < 0.5f; });
    CHECK(shadowed > 100);  // the square's shadow on the wall
    CHECK(shadowed < auto_look.size() / 4);
    // The reference look's four point lights cast none.
    const std::vector<float> reference = shadow_channel("reference");
    CHECK(std::all_of(reference.begin(), reference.end(), [](float v) { return v == 1.0f; }));
}

TEST_CASE("shadows: maps that would take more than kMaxShadowMapBytes together are refused") {
    Scene scene = floor_scene(kPoint);
    // 6 × 8192² × 4 bytes = 1.5 GiB, and its summaries 2 × 6 × 2048² × 4 bytes
    // = 192 MiB: allowed alone.
    scene.lights[0].shadow_map_size = kMaxShadowMapSize;
    Light second = scene.lights[0];
    second.position.x += 1.0f;
    scene.lights.push_back(second);  // 3456 MiB
    Renderer renderer({.threads = 1});
    CHECK_THROWS_WITH_AS(renderer.render(scene), doctest::Contains("shadow maps would take 3456 MiB, more than 2048 MiB"),
                         std::invalid_argument);
}
