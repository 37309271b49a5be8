// glTF features beyond the basics (issue #14): extensions required and used,
// doubleSided, alphaMode. Each test builds its small file from the test
// document of gltf_test_files.hpp.
#include <doctest/doctest.h>

#include "scene/gltf/gltf_import.hpp"
#include "scene/gltf_text_import.hpp"
#include "scene/gltf_test_files.hpp"

using namespace tessera;

namespace {

GltfContent import_text(const std::string& text, const std::string& name = "test.gltf") {
    return test::import_gltf_text(text, name);
}

std::string error_of(const std::string& text) { return test::gltf_import_error(text); }

// The test document with these extension lists instead of its own.
std::string with_extensions(const std::string& used, const std::string& required) {
    std::string lists = R"("extensionsUsed": [)" + used + "]";
    if (!required.empty()) lists += R"(, "extensionsRequired": [)" + required + "]";
    const std::string opaque = test::replaced(test::embedded_test_gltf(), R"("alphaMode": "BLEND")", R"("alphaMode": "OPAQUE")");
    return test::replaced(opaque, R"("extensionsUsed": ["KHR_lights_punctual"])", lists);
}

}  // namespace

TEST_CASE("glTF extensions: a required unsupported one is refused by name, used ones are warned about once") {
    SUBCASE("supported extensions, required or used, load without warnings") {
        const GltfContent content = import_text(
            with_extensions(R"("KHR_lights_punctual", "KHR_materials_emissive_strength")", R"("KHR_lights_punctual")"));
        CHECK(content.warnings.empty());
        CHECK(content.lights.size() == 3);
    }
    SUBCASE("a required extension that is not supported") {
        const std::string message = error_of(with_extensions(
            R"("KHR_lights_punctual", "KHR_texture_basisu")", R"("KHR_texture_basisu")"));
        CHECK(message.starts_with("bad.gltf: the file requires the extension 'KHR_texture_basisu', which is not supported"));
        CHECK(message.find("ktx extract") != std::string::npos);  // says how to convert
    }
    SUBCASE("used but not required: ignored, one warning each, however often listed") {
        const GltfContent content = import_text(with_extensions(
            R"("KHR_lights_punctual", "KHR_materials_sheen", "KHR_materials_sheen", "EXT_foo")", ""));
        REQUIRE(content.warnings.size() == 2);
        CHECK(content.warnings[0] == "extension 'KHR_materials_sheen' changes shading beyond the reference shader; it is ignored");
        CHECK(content.warnings[1] == "extension 'EXT_foo' is not supported and is ignored");
        CHECK(content.meshes.size() == 3);  // drawn as if the extension were absent
    }
}

TEST_CASE("glTF doubleSided: false by default (back faces culled), true when the material says so") {
    const std::string good = test::embedded_test_gltf();
    const GltfContent single = import_text(good);
    REQUIRE(single.materials.size() == 2);  // 'painted' and glTF's default material
    for (const Material& material : single.materials) CHECK_FALSE(material.double_sided);
    const GltfContent both = import_text(test::replaced(good, R"("alphaMode": "BLEND",)", R"("doubleSided": true,)"));
    CHECK(both.materials[0].double_sided);
}

TEST_CASE("scene files: materials are double-sided unless double_sided = false") {
    const Scene scene = parse_scene("[camera]\nposition = [0, 0, 5]\ntarget = [0, 0, 0]\n"
                                    "[materials.one]\ndouble_sided = false\n[materials.two]\n"
                                    "[[objects]]\nmesh = \"plane\"\nmaterial = \"one\"\n"
                                    "[[objects]]\nmesh = \"plane\"\nmaterial = \"two\"\n",
                                    "sides.toml");
    REQUIRE(scene.objects.size() == 2);
    CHECK_FALSE(scene.materials[scene.objects[0].material].double_sided);
    CHECK(scene.materials[scene.objects[1].material].double_sided);
}

TEST_CASE("glTF alphaMode: MASK with its cutoff and the base colour alpha, BLEND with that alpha") {
    const std::string good = test::embedded_test_gltf();
    const GltfContent masked =
        import_text(test::replaced(good, R"("alphaMode": "BLEND",)", R"("alphaMode": "MASK", "alphaCutoff": 0.3,)"));
    CHECK(masked.materials[0].alpha_mode == AlphaMode::mask);
    CHECK(masked.materials[0].alpha_cutoff == doctest::Approx(0.3));
    CHECK(masked.materials[0].alpha_factor == doctest::Approx(0.5));  // baseColorFactor[3]
    CHECK(masked.warnings.empty());
    const GltfContent default_cutoff = import_text(test::replaced(good, R"("alphaMode": "BLEND",)", R"("alphaMode": "MASK",)"));
    CHECK(default_cutoff.materials[0].alpha_cutoff == 0.5f);
    CHECK(default_cutoff.materials[1].alpha_mode == AlphaMode::opaque);  // glTF's default material
    const GltfContent blended = import_text(good);
    CHECK(blended.materials[0].alpha_mode == AlphaMode::blend);
    CHECK(blended.materials[0].alpha_factor == 0.5f);
    CHECK(blended.warnings.empty());

    CHECK(error_of(test::replaced(good, R"("alphaMode": "BLEND",)", R"("alphaMode": "MASK", "alphaCutoff": -0.5,)")) ==
          "bad.gltf: materials[0] 'painted' alphaCutoff is -0.500000, expected a finite number >= 0");
    CHECK(error_of(test::replaced(good, R"("alphaMode": "BLEND",)", R"("alphaMode": "MASK", "alphaCutoff": 1e39,)"))
              .find("alphaCutoff is 999999999999999939709166371603178586112.000000, expected a finite number >= 0") !=
          std::string::npos);
    CHECK(error_of(test::replaced(good, R"("alphaMode": "BLEND",)", R"("alphaMode": "CUTOUT",)")) ==
          "bad.gltf: materials[0] 'painted' alphaMode is 'CUTOUT', expected OPAQUE, MASK or BLEND");
    CHECK(error_of(test::replaced(good, "[0.2, 0.4, 0.6, 0.5]", "[0.2, 0.4, 0.6, 1.5]")) ==
          "bad.gltf: materials[0] 'painted' baseColorFactor alpha is 1.500000, expected a number in [0, 1]");
}

namespace {

// The test document with a second VEC2 accessor (6: the floats 0 0 0 1 0 0 of
// bufferView 4) as primitive 0's TEXCOORD_1, and `base_color` as material 0's
// baseColorTexture.
std::string with_base_color_texture(const std::string& base_color) {
    std::string text = test::replaced(test::embedded_test_gltf(), R"("alphaMode": "BLEND",)", "");
    text = test::replaced(text, R"("TEXCOORD_0": 2})", R"("TEXCOORD_0": 2, "TEXCOORD_1": 6})");
    text = test::replaced(text, R"({"bufferView": 5, "componentType": 5121, "count": 4, "type": "SCALAR"})",
                          R"({"bufferView": 5, "componentType": 5121, "count": 4, "type": "SCALAR"},
    {"bufferView": 4, "componentType": 5126, "count": 3, "type": "VEC2"})");
    return test::replaced(text, R"("baseColorTexture": {"index": 0})", R"("baseColorTexture": )" + base_color);
}


}  // namespace

TEST_CASE("glTF KHR_texture_transform and TEXCOORD_1: each map's own mapping") {
    SUBCASE("offset, rotation and scale, as the extension's GLSL: uv' = T·R·S·uv") {
        const GltfContent content = import_text(with_base_color_texture(
            R"({"index": 0, "extensions": {"KHR_texture_transform": {"offset": [0.5, 0], "rotation": 1.5707963268, "scale": [2, 3]}}})"));
        // The other maps have no transform: the uvs stay TEXCOORD_0, (0,0) (1,0) (0,1), and the
        // base colour's slot transforms them when sampling.
        CHECK(content.meshes[0].uvs == std::vector<glm::vec2>{{0, 0}, {1, 0}, {0, 1}});
        const TextureSlot& base = content.materials[0].albedo_map;
        REQUIRE(base.uv_transformed);
        CHECK_FALSE(content.materials[0].emissive_map.uv_transformed);
        std::vector<glm::vec2> uvs;
        for (const glm::vec2& uv : content.meshes[0].uvs) uvs.push_back(glm::vec2(base.uv_transform * glm::vec3(uv, 1.0f)));
        REQUIRE(uvs.size() == 3);
        CHECK(uvs[0].x == doctest::Approx(0.5f));
        CHECK(uvs[0].y == doctest::Approx(0.0f));
        // (1,0) scaled to (2,0), rotated: u' = cos·u + sin·v = 0, v' = −sin·u + cos·v = −2; plus the offset.
        CHECK(uvs[1].x == doctest::Approx(0.5f).epsilon(1e-5));
        CHECK(uvs[1].y == doctest::Approx(-2.0f));
        CHECK(uvs[2].x == doctest::Approx(3.5f));
        CHECK(uvs[2].y == doctest::Approx(0.0f).epsilon(1e-5));
        CHECK(content.warnings.empty());  // maps that disagree are no longer forced to agree
    }
    SUBCASE("texCoord 1 reads TEXCOORD_1; the extension's texCoord overrides the textureInfo's") {
        const GltfContent second = import_text(with_base_color_texture(R"({"index": 0, "texCoord": 1})"));
        CHECK(second.meshes[0].uvs == std::vector<glm::vec2>{{0, 0}, {0, 1}, {0, 0}});
        const GltfContent overridden = import_text(with_base_color_texture(
            R"({"index": 0, "texCoord": 1, "extensions": {"KHR_texture_transform": {"texCoord": 0}}})"));
        CHECK(overridden.meshes[0].uvs == std::vector<glm::vec2>{{0, 0}, {1, 0}, {0, 1}});
    }
    SUBCASE("without either, the uvs are TEXCOORD_0 as stored, and no warning") {
        const GltfContent plain = import_text(with_base_color_texture(R"({"index": 0})"));
        CHECK(plain.meshes[0].uvs == std::vector<glm::vec2>{{0, 0}, {1, 0}, {0, 1}});
        CHECK(plain.warnings.empty());
    }
    SUBCASE("bad transforms and sets are refused") {
        CHECK(error_of(with_base_color_texture(
                  R"({"index": 0, "extensions": {"KHR_texture_transform": {"rotation": "quarter"}}})")) ==
              "bad.gltf: materials[0] 'painted' baseColorTexture KHR_texture_transform rotation is not a finite number");
        CHECK(error_of(with_base_color_texture(
                  R"({"index": 0, "extensions": {"KHR_texture_transform": {"scale": [1]}}})")) ==
              "bad.gltf: materials[0] 'painted' baseColorTexture KHR_texture_transform scale is not an array of 2 numbers");
        CHECK(error_of(with_base_color_texture(R"({"index": 0, "texCoord": 12})")) ==
              "bad.gltf: materials[0] 'painted' baseColorTexture uses TEXCOORD_12; expected a set from 0 to 9");
    }
}

TEST_CASE("glTF cameras: every camera selectable by index or name, unplaced ones refused clearly") {
    // Cameras 1 ('top', on node 'high' at y = 20) and 2 (orthographic) besides the document's unnamed camera 0.
    std::string text = test::replaced(
        test::embedded_test_gltf(), R"("cameras": [{"type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1, "aspectRatio": 2.0}}])",
        R"("cameras": [{"type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1, "aspectRatio": 2.0}},
    {"name": "top", "type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.5, "zfar": 50}},
    {"name": "plan", "type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 10}},
    {"name": "spare", "type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.5}}])");
    text = test::replaced(text, R"({"name": "sun",)",
                          R"({"name": "high", "translation": [0, 20, 0], "rotation": [-0.70710678, 0, 0, 0.70710678], "camera": 1},
    {"name": "flat", "camera": 2},
    {"name": "sun",)");
    text = test::replaced(text, R"("nodes": [0, 2, 3, 4, 5, 6]})", R"("nodes": [0, 2, 3, 4, 5, 6, 7, 8]})");
    const GltfContent content = import_text(text);
    REQUIRE(content.cameras.size() == 4);
    CHECK(content.cameras[0].name == "camera");
    const Scene first = make_gltf_scene(content, "m.gltf");
    CHECK(first.camera.position == glm::vec3(0, 0, 10));
    CHECK(first.height == 640);  // 1280 / aspectRatio 2
    for (const char* selector : {"1", "top", "high"}) {
        CAPTURE(selector);
        if (std::string(selector) == "high") {  // a named camera goes by its own name only
            CHECK_THROWS_AS(make_gltf_scene(content, "m.gltf", selector), SceneError);
            continue;
        }
        const Scene top = make_gltf_scene(content, "m.gltf", selector);
        CHECK(glm::length(top.camera.position - glm::vec3(0, 20, 0)) < 1e-5f);
        CHECK(glm::length(top.camera.target - glm::vec3(0, 19, 0)) < 1e-4f);  // looking down its node's -Z
        CHECK(top.camera.far_plane == 50.0f);
        CHECK(top.camera.fov_y_degrees == doctest::Approx(0.8 * 57.29577951308232));
    }
    const auto message = [&](const char* selector) {
        try {
            make_gltf_scene(content, "m.gltf", selector);
        } catch (const SceneError& e) {
            return std::string(e.what());
        }
        return std::string("(accepted)");
    };
    CHECK(make_gltf_scene(content, "m.gltf", "plan").camera.projection == Projection::orthographic);  // issue 31
    CHECK(message("3") == "m.gltf: --camera '3' is not placed by any node of the scene");
    CHECK(message("9") == "m.gltf: --camera '9' names no camera of the file; its cameras: 0 'camera' (perspective), "
                          "1 'top' (perspective), 2 'plan' (orthographic), 3 'spare' (perspective, not placed)");
}
