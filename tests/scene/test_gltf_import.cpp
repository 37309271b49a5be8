// glTF import (src/scene/gltf/gltf_import.hpp): the test document of
// gltf_test_files.hpp read as .gltf, .glb and with an external buffer, every
// mapping checked against numbers worked out by hand; then the real sample
// models in ../shared/assets when that folder exists.
#include <chrono>
#include <cmath>

#include <doctest/doctest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "scene/framing.hpp"
#include "scene/gltf/gltf_import.hpp"
#include "scene/gltf_test_files.hpp"
#include "test_paths.hpp"
#include "texture/texture.hpp"

using namespace tessera;
namespace fs = std::filesystem;

namespace {

GltfContent import_text(const std::string& text, const std::string& name = "test.gltf") {
    const auto* bytes = reinterpret_cast<const std::uint8_t*>(text.data());
    return import_gltf({bytes, text.size()}, name, "");
}

bool near(const glm::vec3& a, const glm::vec3& b, float tolerance = 1e-5f) { return glm::length(a - b) <= tolerance; }

std::string error_of(const std::string& text, const std::string& name = "bad.gltf") {
    try {
        import_text(text, name);
    } catch (const SceneError& e) {
        return e.what();
    }
    return "(accepted)";
}

// Checks everything the test document maps; the same for every way it is stored.
void check_test_document(const GltfContent& content) {
    // Mesh 0 has four primitives: three surfaces and a LINES of 3 vertices (skipped). It is
    // placed by two nodes but converted once.
    REQUIRE(content.meshes.size() == 3);
    CHECK(content.skipped_primitives == 1);
    REQUIRE(content.objects.size() == 6);

    const Mesh& indexed = content.meshes[0];
    CHECK(indexed.positions.size() == 3);
    CHECK(indexed.indices == std::vector<std::uint32_t>{0, 1, 2});
    CHECK(near(indexed.normals[1], {0, 0, 1}));
    REQUIRE(indexed.uvs.size() == 3);
    CHECK(indexed.uvs[1] == glm::vec2(1, 0));
    CHECK(indexed.tangents.empty());

    // No NORMAL: flat normals, the vertices split per triangle.
    const Mesh& flat = content.meshes[1];
    CHECK(flat.indices == std::vector<std::uint32_t>{0, 1, 2, 3, 4, 5});
    CHECK(near(flat.normals[0], {0, 0, 1}));
    CHECK(near(flat.normals[4], {0, 1, 0}));

    // TRIANGLE_STRIP 0 1 2 0: triangles (0 1 2) and (1 0 2), winding kept.
    CHECK(content.meshes[2].indices == std::vector<std::uint32_t>{0, 1, 2, 1, 0, 2});

    // World = T(1, 2, 3) · R_y(90°) · S(2): x = (1, 0, 0) goes to (1, 2, 3) + (0, 0, -2).
    const glm::mat4& child = content.objects[0].model;
    CHECK(near(glm::vec3(child * glm::vec4(1, 0, 0, 1)), {1, 2, 1}));
    CHECK(near(glm::vec3(child * glm::vec4(0, 1, 0, 1)), {1, 4, 3}));
    // The second instance, by a matrix: the same meshes moved down by 4.
    CHECK(content.objects[3].mesh == content.objects[0].mesh);
    CHECK(near(glm::vec3(content.objects[3].model * glm::vec4(0, 1, 0, 1)), {0, -3, 0}));

    // Bounds of both instances: the second's (0, 0, 1) lands at (0, -4, 1), the
    // first's at (1, 2, 3) + R_y(90°)·(0, 0, 2) = (3, 2, 3).
    CHECK(near(content.bounds.min, {0, -4, 0}));
    CHECK(near(content.bounds.max, {3, 4, 3}));

    // Materials: the file's for primitives 0 and 2 (one entry), glTF's default for primitive 1.
    REQUIRE(content.materials.size() == 2);
    CHECK(content.objects[0].material == content.objects[2].material);
    const Material& painted = content.materials[content.objects[0].material];
    CHECK(near(painted.albedo, {0.2f, 0.4f, 0.6f}));  // alpha 0.5 and BLEND ignored
    CHECK(painted.metallic == doctest::Approx(0.3));
    CHECK(painted.roughness == doctest::Approx(0.7));
    CHECK(near(painted.emissive, {1.0f, 0.5f, 0.0f}));
    CHECK(painted.albedo_decode == AlbedoDecode::linear);
    const Material& fallback = content.materials[content.objects[1].material];
    CHECK(fallback.albedo == glm::vec3(1.0f));
    CHECK(fallback.metallic == 1.0f);
    CHECK(fallback.roughness == 1.0f);
    CHECK_FALSE(fallback.has_maps());

    // One image used as sRGB (base colour, emissive) and as linear (the rest): two textures.
    REQUIRE(content.textures.size() == 2);
    CHECK(painted.albedo_map.present());
    CHECK(painted.emissive_map.texture == painted.albedo_map.texture);
    CHECK(painted.metallic_map.texture != painted.albedo_map.texture);
    CHECK(painted.roughness_map.texture == painted.metallic_map.texture);
    CHECK(painted.normal_map.texture == painted.metallic_map.texture);
    CHECK(painted.ao_map.texture == painted.metallic_map.texture);
    CHECK(painted.metallic_channel == 2);
    CHECK(painted.roughness_channel == 1);
    CHECK(painted.normal_scale == doctest::Approx(0.5));
    CHECK(painted.ao_strength == doctest::Approx(0.8));
    CHECK(painted.albedo_map.wrap_s == TextureWrap::clamp_to_edge);  // texture 0's sampler: wrapS clamps,
    CHECK(painted.albedo_map.wrap_t == TextureWrap::repeat);         // wrapT repeats
    CHECK(painted.metallic_map.wrap_s == TextureWrap::repeat);     // texture 1 has none
    // No flip: texel (0, 0) is the PNG's top-left (red), (0, 1) the bottom-left (blue).
    const texture::Texture& albedo = *content.textures[std::size_t(painted.albedo_map.texture)];
    CHECK(albedo.width() == 2);
    CHECK(near(glm::vec3(albedo.texel(0, 0, 0)), {1, 0, 0}));
    CHECK(near(glm::vec3(albedo.texel(0, 0, 1)), {0, 0, 1}));
    // A grey level would differ between the two decodes; white and black do not, so
    // check the colour space by the texture's identity above and its values here.
    CHECK(near(glm::vec3(content.textures[std::size_t(painted.metallic_map.texture)]->texel(0, 1, 1)), {1, 1, 1}));

    // Camera: at (0, 0, 10) looking down -Z; yfov 0.5 rad; no zfar, so one past the model.
    REQUIRE(content.camera.has_value());
    const Camera& camera = content.camera->camera;
    CHECK(near(camera.position, {0, 0, 10}));
    CHECK(near(glm::normalize(camera.target - camera.position), {0, 0, -1}));
    CHECK(near(camera.up, {0, 1, 0}));
    CHECK(camera.fov_y_degrees == doctest::Approx(0.5 * 180.0 / M_PI));
    CHECK(camera.near_plane == doctest::Approx(0.1));
    CHECK(std::isfinite(camera.far_plane));
    CHECK(camera.far_plane > glm::length(content.bounds.min - camera.position));
    CHECK(content.camera->aspect_ratio == doctest::Approx(2.0));

    // Lights, in node order: spot, point, directional.
    REQUIRE(content.lights.size() == 3);
    const Light& spot = content.lights[0];
    CHECK(spot.type == LightType::spot);
    CHECK(near(spot.position, {0, 5, 0}));
    CHECK(near(spot.direction, {0, -1, 0}));  // -Z turned by -90° about X
    CHECK(near(spot.color, {4.0f, 2.0f, 1.0f}));
    CHECK(spot.inner_cone_degrees == doctest::Approx(0.1 * 180.0 / M_PI));
    CHECK(spot.outer_cone_degrees == doctest::Approx(0.5 * 180.0 / M_PI));
    CHECK(spot.range == doctest::Approx(20.0));
    CHECK(content.lights[1].type == LightType::point);
    CHECK(near(content.lights[1].position, {3, 0, 0}));
    CHECK(near(content.lights[1].color, {2, 2, 2}));
    CHECK(content.lights[1].range == 0.0f);
    CHECK(content.lights[2].type == LightType::directional);
    CHECK(near(content.lights[2].direction, {0, 0, -1}));
    CHECK(near(content.lights[2].color, {1.5f, 1.5f, 1.5f}));
}

}  // namespace

TEST_CASE("glTF import: the test document as .gltf with embedded buffers") {
    check_test_document(import_text(test::embedded_test_gltf()));
}

TEST_CASE("glTF import: the test document as .glb and with an external .bin") {
    const fs::path dir = test::output_dir("gltf_import");
    SUBCASE(".glb") {
        test::write_bytes(dir / "document.glb", test::test_glb());
        check_test_document(import_gltf_file(dir / "document.glb"));
    }
    SUBCASE(".gltf + .bin, found beside the .gltf whatever the working folder") {
        test::write_bytes(dir / "external.bin", test::test_gltf_buffer());
        test::write_bytes(dir / "external.gltf", test::test_gltf_json("external.bin"));
        check_test_document(import_gltf_file(dir / "external.gltf"));
    }
}

TEST_CASE("glTF import: a whole scene from one file") {
    const fs::path dir = test::output_dir("gltf_import");
    test::write_bytes(dir / "scene.gltf", test::embedded_test_gltf());
    const Scene scene = load_scene_file(dir / "scene.gltf");
    CHECK(scene.source == (dir / "scene.gltf").string());
    CHECK(scene.width == 1280);
    CHECK(scene.height == 640);  // aspectRatio 2
    CHECK(scene.lights.size() == 3);
    CHECK(scene.objects.size() == 6);
    CHECK(near(scene.camera.position, {0, 0, 10}));
}

TEST_CASE("glTF import: without camera or lights, the scene frames the model and lights it") {
    // Drop the camera and light nodes from the scene.
    const std::string text = test::replaced(test::embedded_test_gltf(), R"("nodes": [0, 2, 3, 4, 5, 6])", R"("nodes": [0, 6])");
    const GltfContent content = import_text(text);
    CHECK_FALSE(content.camera.has_value());
    CHECK(content.lights.empty());
    const Scene scene = make_gltf_scene(content, "framed.gltf");
    CHECK(scene.width == 1280);
    CHECK(scene.height == 720);
    // Every corner of the model's box is inside the view frustum, between the planes.
    const glm::mat4 clip_from_world = projection_matrix(scene.camera, scene.width, scene.height) * view_matrix(scene.camera);
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p{corner & 1 ? content.bounds.max.x : content.bounds.min.x,
                          corner & 2 ? content.bounds.max.y : content.bounds.min.y,
                          corner & 4 ? content.bounds.max.z : content.bounds.min.z};
        const glm::vec4 clip = clip_from_world * glm::vec4(p, 1.0f);
        CAPTURE(corner);
        CHECK(std::abs(clip.x) <= clip.w);
        CHECK(std::abs(clip.y) <= clip.w);
        CHECK(std::abs(clip.z) <= clip.w);
    }
    CHECK(near(scene.camera.target, content.bounds.center()));
    CHECK(scene.camera.position.z > content.bounds.max.z);  // on the +Z side, looking down -Z
    // Four lights, each giving radiance 1.5 at the model's centre.
    REQUIRE(scene.lights.size() == 4);
    for (const Light& light : scene.lights) {
        const float d = glm::length(light.position - content.bounds.center());
        CHECK(light.color.x / (d * d) == doctest::Approx(1.5));
    }
}

TEST_CASE("glTF import: default scene choice, strips, fans and normalized texture coordinates") {
    SUBCASE("no scenes: every root node") {
        std::string text = test::replaced(test::embedded_test_gltf(), R"("scene": 0,)", "");
        text = test::replaced(text, R"("scenes": [{"nodes": [0, 2, 3, 4, 5, 6]}],)", "");
        const GltfContent content = import_text(text);
        CHECK(content.objects.size() == 6);
        CHECK(content.lights.size() == 3);
    }
    SUBCASE("a fan 0 1 2 0 gives (1 2 0) and (2 0 0)") {
        const GltfContent content = import_text(test::replaced(test::embedded_test_gltf(), R"("mode": 5)", R"("mode": 6)"));
        CHECK(content.meshes[2].indices == std::vector<std::uint32_t>{1, 2, 0, 2, 0, 0});
    }
    SUBCASE("u8 indices read as TEXCOORD_0 are refused unless normalized") {
        // Accessor 2's floats retyped as u16 pairs.
        const std::string text = test::replaced(test::embedded_test_gltf(),
                                                R"({"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"})",
                                                R"({"bufferView": 2, "componentType": 5123, "count": 3, "type": "VEC2"})");
        CHECK(error_of(text).find("TEXCOORD_0 (accessor 2) holds UNSIGNED_SHORT values that are not normalized") !=
              std::string::npos);
        const GltfContent content = import_text(test::replaced(
            text, R"("componentType": 5123, "count": 3, "type": "VEC2")",
            R"("componentType": 5123, "normalized": true, "count": 3, "type": "VEC2")"));
        // The floats 0, 0, 1, 0, 0, 1 read as u16 pairs: element 2 is 1.0f's bits, (0, 0x3F80).
        CHECK(content.meshes[0].uvs[0] == glm::vec2(0.0f, 0.0f));
        CHECK(content.meshes[0].uvs[2].y == doctest::Approx(0x3F80 / 65535.0));
    }
}

TEST_CASE("glTF import: bad files are SceneErrors naming the file and the part at fault") {
    const std::string good = test::embedded_test_gltf();
    struct Row {
        const char* what;
        std::string text;
        const char* expected;
    };
    const Row rows[] = {
        {"accessor past its buffer view", test::replaced(good, R"("count": 6)", R"("count": 60)"),
         "bad.gltf: meshes[0] 'parts' primitives[1] POSITION (accessor 4) is out of range"},
        {"buffer view past its buffer", test::replaced(good, R"("byteOffset": 176, "byteLength": 4)", R"("byteOffset": 176, "byteLength": 40)"),
         "bufferView 5 (for meshes[0] 'parts' primitives[2] indices (accessor 5)) spans bytes 176 + 40, past the end of buffer 0"},
        {"wrong accessor type", test::replaced(good, R"("POSITION": 4})", R"("POSITION": 2})"),
         "POSITION (accessor 2) is VEC2, expected VEC3"},
        {"missing accessor", test::replaced(good, R"("POSITION": 4})", R"("POSITION": 40})"),
         "meshes[0] 'parts' primitives[1] POSITION uses accessor 40 but the file has 6 accessors"},
        {"a node cycle", test::replaced(good, R"("mesh": 0},)", R"("mesh": 0, "children": [0]},)"),
         "nodes[0] 'root' is its own ancestor (a cycle of children); glTF nodes form a forest"},
        {"a missing node", test::replaced(good, R"("children": [1])", R"("children": [99])"),
         "nodes[0] 'root' has child 99 but the file has 7 nodes"},
        {"a colour factor above 1", test::replaced(good, "[0.2, 0.4, 0.6, 0.5]", "[2, 0.4, 0.6, 0.5]"),
         "materials[0] 'painted' baseColorFactor has 2.000000, expected numbers in [0, 1]"},
        {"spot cone inside out", test::replaced(good, R"("innerConeAngle": 0.1)", R"("innerConeAngle": 0.7)"),
         "KHR_lights_punctual lights[0] cone angles are inner 0.700000, outer 0.500000"},
        {"not JSON", "{\"asset\": ", "bad.gltf: invalid glTF: "},
        {"a missing external buffer", test::test_gltf_json("nowhere.bin"), "bad.gltf: invalid glTF: File not found : nowhere.bin"},
    };
    for (const Row& row : rows) {
        const std::string what = row.what;
        CAPTURE(what);
        const std::string message = error_of(row.text);
        if (std::string_view(row.expected).empty()) {
            CHECK(message == "(accepted)");
        } else {
            CHECK_MESSAGE(message.find(row.expected) != std::string::npos, message);
        }
    }
    // Index out of range: the triangle's u16 indices pointed at a 3-vertex accessor, one raised to 7.
    std::vector<std::uint8_t> buffer = test::test_gltf_buffer();
    buffer[100] = 7;  // the third u16 index
    const std::string text = test::test_gltf_json("data:application/octet-stream;base64," + test::base64(buffer));
    CHECK(error_of(text).find("meshes[0] 'parts' primitives[0] indices (accessor 3): index 7 at [2] is out of range; "
                              "the primitive has 3 vertices") != std::string::npos);
}

TEST_CASE("glTF import: a TOML scene places models next to built-in objects") {
    const fs::path dir = test::output_dir("gltf_models");
    fs::create_directories(dir / "models");
    test::write_bytes(dir / "models" / "document.glb", test::test_glb());
    const std::string scene_text =
        "[camera]\nposition = [0, 0, 20]\ntarget = [0, 0, 0]\n"
        "[[objects]]\nmesh = \"sphere\"\n"
        "[[models]]\nfile = \"models/document.glb\"\ntranslate = [10, 0, 0]\n"
        "[[models]]\nfile = \"models/document.glb\"\nlights = false\nscale = 2\n";
    test::write_bytes(dir / "with_models.toml", scene_text);
    const Scene scene = load_scene_file(dir / "with_models.toml");
    CHECK(scene.objects.size() == 1 + 6 + 6);
    CHECK(scene.meshes.size() == 1 + 3 + 3);
    CHECK(scene.lights.size() == 3);  // the first model's only
    CHECK(scene.textures.size() == 4);
    CHECK(near(scene.camera.position, {0, 0, 20}));  // the file's camera is not used
    // The first model moved by (10, 0, 0): its child node's (1, 0, 0) lands at (11, 2, 1).
    CHECK(near(glm::vec3(scene.objects[1].model * glm::vec4(1, 0, 0, 1)), {11, 2, 1}));
    CHECK(near(scene.lights[0].position, {10, 5, 0}));
    // Indices shifted into the scene's arrays.
    CHECK(scene.objects[7].mesh == 4);
    CHECK(scene.materials[scene.objects[7].material].albedo_map.texture >= 2);

    SUBCASE("a missing model file names the scene position and the file") {
        const std::string bad = "[camera]\nposition = [0, 0, 20]\ntarget = [0, 0, 0]\n[[models]]\nfile = \"nowhere.glb\"\n";
        test::write_bytes(dir / "missing_model.toml", bad);
        std::string message;
        try {
            load_scene_file(dir / "missing_model.toml");
        } catch (const SceneError& e) {
            message = e.what();
        }
        CHECK_MESSAGE(message.find("missing_model.toml:5:8: in 'models[0].file': ") != std::string::npos, message);
        CHECK_MESSAGE(message.find("nowhere.glb: cannot open glTF file") != std::string::npos, message);
    }
}

// The sample models (TESSERA_ASSETS_DIR; Skipped without them): each loads, with the counts its README gives.
TEST_CASE("glTF import: the shared sample models") {
    if (test::skip_without_assets()) return;
    const fs::path assets = test::assets_dir() / "gltf";
    const auto triangles = [](const GltfContent& content) {
        std::size_t count = 0;
        for (const Object& object : content.objects) count += content.meshes[object.mesh].indices.size() / 3;
        return count;
    };
    const auto timed_import = [](const fs::path& path) {
        const auto start = std::chrono::steady_clock::now();
        GltfContent content = import_gltf_file(path);
        MESSAGE(path.filename().string() << " loaded in "
                                         << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
                                         << " s");
        return content;
    };
    SUBCASE("MetalRoughSpheresNoTextures: a million triangles of factors") {
        const GltfContent c = timed_import(assets / "MetalRoughSpheresNoTextures" / "MetalRoughSpheresNoTextures.glb");
        CHECK(triangles(c) == 1040409);
        CHECK(c.textures.empty());
    }
    SUBCASE("DamagedHelmet: every metal-rough texture, no stored tangents") {
        const GltfContent c = timed_import(assets / "DamagedHelmet" / "DamagedHelmet.glb");
        CHECK(triangles(c) == 15452);
        REQUIRE(c.materials.size() == 1);
        const Material& m = c.materials[0];
        CHECK((m.albedo_map.present() && m.metallic_map.present() && m.normal_map.present() && m.ao_map.present() &&
               m.emissive_map.present()));
        CHECK(c.textures.size() == 5);
        CHECK(c.meshes[0].tangents.empty());
    }
    SUBCASE("NormalTangentMirrorTest: stored tangents") {
        const GltfContent c = timed_import(assets / "NormalTangentMirrorTest" / "NormalTangentMirrorTest.glb");
        CHECK(triangles(c) == 5240);
        for (const Mesh& mesh : c.meshes) CHECK(mesh.tangents.size() == mesh.positions.size());
        CHECK_FALSE(c.meshes.front().tangents.empty());
    }
    SUBCASE("NormalTangentTest and TextureCoordinateTest") {
        CHECK(triangles(timed_import(assets / "NormalTangentTest" / "NormalTangentTest.glb")) == 7774);
        CHECK(triangles(timed_import(assets / "TextureCoordinateTest" / "TextureCoordinateTest.glb")) == 10);
    }
    SUBCASE("BoomBox: a .gltf with a separate .bin and PNG files") {
        const GltfContent c = timed_import(assets / "BoomBox" / "BoomBox.gltf");
        CHECK(triangles(c) == 6036);
        CHECK(c.textures.size() == 5);  // the spec-gloss extension's two images are not decoded
    }
    SUBCASE("LightsPunctualLamp: five point lights") {
        const GltfContent c = timed_import(assets / "LightsPunctualLamp" / "LightsPunctualLamp.gltf");
        CHECK(triangles(c) == 6000);
        CHECK(c.lights.size() == 5);
        for (const Light& light : c.lights) CHECK(light.type == LightType::point);
    }
}
