// Tests for src/scene/scene_file.cpp: the scene format, its validation messages,
// and the bundled scenes. Also the camera matrices of src/scene/camera.cpp.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include <doctest/doctest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "tessera/scene.hpp"
#include "test_paths.hpp"

namespace {

using tessera::Scene;
using tessera::SceneError;

const std::filesystem::path kSourceDir{tessera::test::source_dir()};

// A camera that passes validation; tests append what they are about (lines 1-3).
constexpr std::string_view kCamera =
    "[camera]\n"
    "position = [0, 0, 5]\n"
    "target = [0, 0, 0]\n";

std::string with_camera(std::string_view rest) { return std::string(kCamera) + std::string(rest); }

// The message parse_scene throws for text, or "" (and a failed check) if it does not throw.
std::string error_of(std::string_view text) {
    try {
        tessera::parse_scene(text, "test.toml");
    } catch (const SceneError& error) {
        return error.what();
    }
    FAIL_CHECK("no SceneError for:\n" << text);
    return "";
}

bool contains(const std::string& text, std::string_view part) {
    return text.find(part) != std::string::npos;
}

#define CHECK_ERROR(text, ...)                                           \
    do {                                                                 \
        const std::string message_ = error_of(text);                     \
        for (const std::string_view part_ : {__VA_ARGS__}) {             \
            CHECK_MESSAGE(contains(message_, part_),                     \
                          "'" << part_ << "' not in: " << message_);     \
        }                                                                \
    } while (false)

void check_mat_near(const glm::mat4& a, const glm::mat4& b, float tolerance) {
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) CHECK(a[c][r] == doctest::Approx(b[c][r]).epsilon(tolerance));
    }
}

}  // namespace

TEST_CASE("spheres.toml is the reference demo scene") {
    const Scene scene = tessera::load_scene_file(kSourceDir / "scenes" / "spheres.toml");
    CHECK(scene.width == 1280);
    CHECK(scene.height == 720);
    CHECK(scene.clear_color == glm::vec3(0.1f));
    CHECK(scene.camera.position == glm::vec3(0, 0, 22));
    CHECK(scene.camera.target == glm::vec3(0));
    CHECK(scene.camera.up == glm::vec3(0, 1, 0));
    CHECK(scene.camera.fov_y_degrees == 45.0f);
    CHECK(scene.camera.near_plane == 0.1f);
    CHECK(scene.camera.far_plane == 100.0f);

    REQUIRE(scene.lights.size() == 4);
    const glm::vec3 light_positions[4] = {{-10, 10, 10}, {10, 10, 10}, {-10, -10, 10}, {10, -10, 10}};
    for (std::size_t i = 0; i < 4; ++i) {
        CHECK(scene.lights[i].position == light_positions[i]);
        CHECK(scene.lights[i].color == glm::vec3(300.0f));
    }

    REQUIRE(scene.meshes.size() == 1);  // one sphere shared by every object
    CHECK(scene.meshes[0].positions.size() == 65u * 65u);
    REQUIRE(scene.objects.size() == 49);
    REQUIRE(scene.materials.size() == 49);
    for (int row = 0; row < 7; ++row) {
        for (int col = 0; col < 7; ++col) {
            CAPTURE(row);
            CAPTURE(col);
            const tessera::Object& object = scene.objects[static_cast<std::size_t>(row * 7 + col)];
            CHECK(object.mesh == 0);
            // As the reference demo computes them, in float.
            const glm::mat4 model = glm::translate(
                glm::mat4(1.0f), glm::vec3(static_cast<float>(col - 3) * 2.5f,
                                           static_cast<float>(row - 3) * 2.5f, 0.0f));
            CHECK(object.model == model);
            REQUIRE(object.material < scene.materials.size());
            const tessera::Material& material = scene.materials[object.material];
            CHECK(material.albedo == glm::vec3(0.5f, 0.0f, 0.0f));
            CHECK(material.metallic == static_cast<float>(row) / 7.0f);
            CHECK(material.roughness == glm::clamp(static_cast<float>(col) / 7.0f, 0.05f, 1.0f));
            CHECK(material.ao == 1.0f);
        }
    }
}

TEST_CASE("camera matrices follow OpenGL conventions") {
    const Scene scene = tessera::load_scene_file(kSourceDir / "scenes" / "spheres.toml");
    const glm::mat4 view = tessera::view_matrix(scene.camera);
    const glm::mat4 projection = tessera::projection_matrix(scene.camera, scene.width, scene.height);
    CHECK(view == glm::lookAt(glm::vec3(0, 0, 22), glm::vec3(0), glm::vec3(0, 1, 0)));
    CHECK(projection == glm::perspective(glm::radians(45.0f), 1280.0f / 720.0f, 0.1f, 100.0f));
    // Right-handed: the camera looks down -Z; clip z runs from -w at near to +w at far.
    const glm::vec4 near_point = projection * view * glm::vec4(0, 0, 22.0f - 0.1f, 1);
    const glm::vec4 far_point = projection * view * glm::vec4(0, 0, 22.0f - 100.0f, 1);
    CHECK(near_point.z / near_point.w == doctest::Approx(-1.0).epsilon(1e-5));
    CHECK(far_point.z / far_point.w == doctest::Approx(1.0).epsilon(1e-5));
}

TEST_CASE("shapes.toml loads and frames every object") {
    const Scene scene = tessera::load_scene_file(kSourceDir / "scenes" / "shapes.toml");
    CHECK(scene.width == 640);
    CHECK(scene.height == 360);
    CHECK(scene.lights.size() == 3);
    CHECK(scene.meshes.size() == 3);
    REQUIRE(scene.objects.size() == 4);
    CHECK(scene.materials.size() == 4);  // floor, copper, two inline

    const glm::mat4 view_projection = tessera::projection_matrix(scene.camera, scene.width, scene.height) *
                                      tessera::view_matrix(scene.camera);
    for (const tessera::Object& object : scene.objects) {
        for (const glm::vec3& p : scene.meshes[object.mesh].positions) {
            const glm::vec4 clip = view_projection * object.model * glm::vec4(p, 1.0f);
            REQUIRE(clip.w > 0.0f);
            const glm::vec3 ndc = glm::vec3(clip) / clip.w;
            CHECK(std::abs(ndc.x) < 0.98f);
            CHECK(std::abs(ndc.y) < 0.98f);
            CHECK(std::abs(ndc.z) < 1.0f);
        }
    }
}

TEST_CASE("defaults, integer numbers, and shared meshes and materials") {
    const Scene scene = tessera::parse_scene(with_camera(R"(
[materials.red]
albedo = [1, 0, 0]

[[objects]]
mesh = "sphere"
material = "red"

[[objects]]
mesh = "cube"

[[objects]]
mesh = "sphere"
material = "red"

[[objects]]
mesh = "plane"
material = { metallic = 1 }
)"),
                                             "test.toml");
    CHECK(scene.source == "test.toml");
    CHECK(scene.width == 1280);
    CHECK(scene.height == 720);
    CHECK(scene.clear_color == glm::vec3(0.1f));
    CHECK(scene.camera.position == glm::vec3(0, 0, 5));
    CHECK(scene.camera.up == glm::vec3(0, 1, 0));
    CHECK(scene.camera.fov_y_degrees == 45.0f);
    CHECK(scene.camera.near_plane == 0.1f);
    CHECK(scene.camera.far_plane == 100.0f);
    CHECK(scene.lights.empty());

    REQUIRE(scene.objects.size() == 4);
    REQUIRE(scene.meshes.size() == 3);
    CHECK(scene.objects[0].mesh == scene.objects[2].mesh);
    CHECK(scene.meshes[scene.objects[0].mesh].name == "sphere");
    CHECK(scene.meshes[scene.objects[1].mesh].name == "cube");
    CHECK(scene.meshes[scene.objects[3].mesh].name == "plane");

    REQUIRE(scene.materials.size() == 3);  // red (shared), the default, the inline one
    CHECK(scene.objects[0].material == scene.objects[2].material);
    const tessera::Material& red = scene.materials[scene.objects[0].material];
    CHECK(red.albedo == glm::vec3(1, 0, 0));
    CHECK(red.metallic == 0.0f);
    CHECK(red.roughness == 0.5f);
    const tessera::Material& fallback = scene.materials[scene.objects[1].material];
    CHECK(fallback.albedo == tessera::Material{}.albedo);
    CHECK(fallback.roughness == tessera::Material{}.roughness);
    CHECK(scene.materials[scene.objects[3].material].metallic == 1.0f);
    CHECK(scene.objects[1].model == glm::mat4(1.0f));
}

TEST_CASE("model = translate * Rz * Ry * Rx * scale") {
    const Scene scene = tessera::parse_scene(with_camera(R"(
[[objects]]
mesh = "cube"
translate = [1, -2, 3.5]
rotate = [10, 20, 30]
scale = [0.5, 2, 3]

[[objects]]
mesh = "cube"
scale = 2
)"),
                                             "test.toml");
    REQUIRE(scene.objects.size() == 2);
    const glm::mat4 identity(1.0f);
    const glm::mat4 expected = glm::translate(identity, glm::vec3(1, -2, 3.5f)) *
                               glm::rotate(identity, glm::radians(30.0f), glm::vec3(0, 0, 1)) *
                               glm::rotate(identity, glm::radians(20.0f), glm::vec3(0, 1, 0)) *
                               glm::rotate(identity, glm::radians(10.0f), glm::vec3(1, 0, 0)) *
                               glm::scale(identity, glm::vec3(0.5f, 2, 3));
    check_mat_near(scene.objects[0].model, expected, 1e-6f);
    CHECK(scene.objects[1].model == glm::scale(identity, glm::vec3(2.0f)));
}

TEST_CASE("scene errors: file and syntax") {
    SUBCASE("missing file") {
        const std::filesystem::path path = kSourceDir / "scenes" / "no_such_scene.toml";
        CHECK_THROWS_WITH_AS(tessera::load_scene_file(path),
                             (path.string() + ": cannot open scene file: no such file").c_str(), SceneError);
    }
    SUBCASE("a directory is not a scene file") {
        CHECK_THROWS_WITH_AS(tessera::load_scene_file(kSourceDir / "scenes"),
                             ((kSourceDir / "scenes").string() +
                              ": cannot read scene file: it is a folder, not a regular file").c_str(),
                             SceneError);
    }
    SUBCASE("TOML syntax error, with file:line:col") {
        CHECK_ERROR(with_camera("fov_y = \n"), "test.toml:4:");
        CHECK_ERROR("[camera\nposition = [0, 0, 1]\n", "test.toml:1:");
        CHECK_ERROR(with_camera("[output]\nwidth = 1\nwidth = 2\n"), "test.toml:6:");
    }
    SUBCASE("errors from a file name the file") {
        const std::filesystem::path path =
            std::filesystem::temp_directory_path() / "tessera_test_scene_error.toml";
        {
            std::ofstream file(path);
            file << "[camera]\nposition = [0, 0, 5]\n";
        }
        CHECK_THROWS_WITH_AS(tessera::load_scene_file(path),
                             (path.string() + ":1:1: missing required key 'camera.target'").c_str(),
                             SceneError);
        std::filesystem::remove(path);
    }
}

TEST_CASE("scene errors: structure") {
    SUBCASE("missing [camera]") {
        CHECK_ERROR("[output]\nwidth = 10\n", "test.toml: missing required table [camera]");
        CHECK_ERROR("", "test.toml: missing required table [camera]");
    }
    SUBCASE("missing required keys point at their table") {
        CHECK_ERROR("[camera]\nposition = [0, 0, 5]\n", "test.toml:1:1: missing required key 'camera.target'");
        CHECK_ERROR("\n[camera]\ntarget = [0, 0, 5]\n", "test.toml:2:1: missing required key 'camera.position'");
        CHECK_ERROR(with_camera("[[lights]]\nposition = [1, 2, 3]\n"),
                    "test.toml:4:1: missing required key 'lights[0].color'");
        CHECK_ERROR(with_camera("[[lights]]\ncolor = [1, 2, 3]\n"),
                    "test.toml:4:1: missing required key 'lights[0].position'");
        CHECK_ERROR(with_camera("[[objects]]\nmesh = \"cube\"\n[[objects]]\nscale = 2\n"),
                    "test.toml:6:1: missing required key 'objects[1].mesh'");
    }
    SUBCASE("unknown keys are errors listing the valid keys") {
        CHECK_ERROR(with_camera("fovy = 45\n"),
                    "test.toml:4:1: unknown key 'fovy' in 'camera'; valid keys: position, target, up, "
                    "fov_y, near, far");
        CHECK_ERROR(with_camera("[output]\nwidht = 640\n"),
                    "test.toml:5:1: unknown key 'widht' in 'output'; valid keys: width, height, clear_color");
        CHECK_ERROR(with_camera("[[light]]\nposition = [1, 2, 3]\n"),
                    "test.toml:4:", "unknown key 'light' at top level",
                    "valid keys: output, camera, lights, environment, materials, objects");
        CHECK_ERROR(with_camera("[[lights]]\nposition = [1, 2, 3]\ncolour = [1, 1, 1]\n"),
                    "test.toml:6:1: unknown key 'colour' in 'lights[0]'; valid keys: type, position, color, direction, "
                    "inner_cone, outer_cone, range");
        CHECK_ERROR(with_camera("[materials.m]\nmetalic = 1\n"),
                    "test.toml:5:1: unknown key 'metalic' in 'materials.m'; valid keys: albedo, metallic, "
                    "roughness, ao");
        CHECK_ERROR(with_camera("[[objects]]\nmesh = \"cube\"\nmaterial = { rough = 1 }\n"),
                    "test.toml:6:14: unknown key 'rough' in 'objects[0].material'");
        CHECK_ERROR(with_camera("[[objects]]\nmesh = \"cube\"\nrotation = [0, 1, 0]\n"),
                    "test.toml:6:1: unknown key 'rotation' in 'objects[0]'; valid keys: mesh, material, "
                    "translate, rotate, scale, uv_scale");
    }
    SUBCASE("tables and arrays of the wrong kind") {
        CHECK_ERROR("camera = 5\n", "test.toml:1:10: expected a table for 'camera', got integer");
        CHECK_ERROR("lights = \"all\"\n" + std::string(kCamera),
                    "test.toml:1:10: expected an array of tables for 'lights', got string");
        CHECK_ERROR("objects = [1]\n" + std::string(kCamera), "test.toml:1:12: expected a table for 'objects[0]', got integer");
        CHECK_ERROR(with_camera("[materials]\nm = 3\n"),
                    "test.toml:5:5: expected a table for 'materials.m', got integer");
    }
}

TEST_CASE("scene errors: values") {
    SUBCASE("wrong types") {
        CHECK_ERROR(with_camera("[materials.m]\nmetallic = \"high\"\n"),
                    "test.toml:5:12: expected a number for 'materials.m.metallic', got string");
        CHECK_ERROR(with_camera("[output]\nwidth = 640.0\n"),
                    "test.toml:5:9: expected an integer for 'output.width', got floating-point");
        CHECK_ERROR(with_camera("fov_y = true\n"), "test.toml:4:9: expected a number for 'camera.fov_y', got boolean");
        CHECK_ERROR("[camera]\nposition = 5\ntarget = [0, 0, 0]\n",
                    "test.toml:2:12: expected an array of 3 numbers for 'camera.position', got integer");
        CHECK_ERROR("[camera]\nposition = [0, \"a\", 5]\ntarget = [0, 0, 0]\n",
                    "test.toml:2:16: expected a number for 'camera.position[1]', got string");
        CHECK_ERROR(with_camera("[[lights]]\ntype = 1\nposition = [1, 2, 3]\ncolor = [1, 1, 1]\n"),
                    "test.toml:5:8: expected a string for 'lights[0].type', got integer");
        CHECK_ERROR(with_camera("[[objects]]\nmesh = 1\n"), "test.toml:5:8: expected a string for 'objects[0].mesh', got integer");
        CHECK_ERROR(with_camera("[[objects]]\nmesh = \"cube\"\nmaterial = 2\n"),
                    "test.toml:6:12: expected a material name or an inline material table for "
                    "'objects[0].material', got integer");
        CHECK_ERROR(with_camera("[[objects]]\nmesh = \"cube\"\nscale = \"big\"\n"),
                    "test.toml:6:9: expected a number or an array of 3 numbers for 'objects[0].scale', got string");
    }
    SUBCASE("arrays of the wrong length") {
        CHECK_ERROR("[camera]\nposition = [0, 0]\ntarget = [0, 0, 0]\n",
                    "test.toml:2:12: expected an array of 3 numbers for 'camera.position', got 2 elements");
        CHECK_ERROR(with_camera("[[objects]]\nmesh = \"cube\"\ntranslate = [1, 2, 3, 4]\n"),
                    "test.toml:6:13: expected an array of 3 numbers for 'objects[0].translate', got 4 elements");
    }
    SUBCASE("NaN and infinity") {
        CHECK_ERROR(with_camera("fov_y = nan\n"), "test.toml:4:9: expected a finite number for 'camera.fov_y'");
        CHECK_ERROR(with_camera("[[lights]]\nposition = [1, 2, 3]\ncolor = [inf, 1, 1]\n"),
                    "test.toml:6:10: expected a finite number for 'lights[0].color[0]'");
        CHECK_ERROR(with_camera("[[objects]]\nmesh = \"cube\"\ntranslate = [0, -inf, 0]\n"),
                    "test.toml:6:17: expected a finite number for 'objects[0].translate[1]'");
        // Finite as a double but not as a float.
        CHECK_ERROR(with_camera("far = 1e300\n"), "test.toml:4:7: expected a finite number for 'camera.far'");
    }
    SUBCASE("out of range") {
        CHECK_ERROR(with_camera("[[lights]]\nposition = [1, 2, 3]\ncolor = [1, -1, 1]\n"),
                    "test.toml:6:13: expected 'lights[0].color[1]' to be >= 0, got -1");
        CHECK_ERROR(with_camera("[materials.m]\nmetallic = 1.5\n"),
                    "test.toml:5:12: expected 'materials.m.metallic' to be in [0, 1], got 1.5");
        CHECK_ERROR(with_camera("[materials.m]\nroughness = -0.25\n"),
                    "test.toml:5:13: expected 'materials.m.roughness' to be in [0, 1], got -0.25");
        CHECK_ERROR(with_camera("[materials.m]\nao = 2\n"), "expected 'materials.m.ao' to be in [0, 1], got 2");
        CHECK_ERROR(with_camera("[materials.m]\nalbedo = [0.5, 0.5, 1.25]\n"),
                    "test.toml:5:21: expected 'materials.m.albedo[2]' to be in [0, 1], got 1.25");
        CHECK_ERROR(with_camera("[output]\nclear_color = [0, 0, 255]\n"),
                    "test.toml:5:22: expected 'output.clear_color[2]' to be in [0, 1], got 255");
        CHECK_ERROR(with_camera("fov_y = 180\n"), "test.toml:4:9: expected 'camera.fov_y' to be in (0, 180) degrees, got 180");
        CHECK_ERROR(with_camera("fov_y = 0\n"), "test.toml:4:9: expected 'camera.fov_y' to be in (0, 180) degrees, got 0");
        CHECK_ERROR(with_camera("near = 0\n"), "test.toml:4:8: expected 'camera.near' to be > 0, got 0");
        CHECK_ERROR(with_camera("near = -1\n"), "test.toml:4:8: expected 'camera.near' to be > 0, got -1");
        CHECK_ERROR(with_camera("near = 10\nfar = 10\n"),
                    "test.toml:5:7: expected 'camera.near' < 'camera.far', got near = 10, far = 10");
        CHECK_ERROR(with_camera("near = 200\n"),
                    "test.toml:4:8: expected 'camera.near' < 'camera.far', got near = 200, far = 100");
        CHECK_ERROR(with_camera("[output]\nwidth = 0\n"), "test.toml:5:9: expected 'output.width' to be in 1..16384, got 0");
        CHECK_ERROR(with_camera("[output]\nheight = 16385\n"),
                    "test.toml:5:10: expected 'output.height' to be in 1..16384, got 16385");
        CHECK_ERROR(with_camera("[[objects]]\nmesh = \"cube\"\nscale = 0\n"),
                    "test.toml:6:9: expected every component of 'objects[0].scale' to be non-zero");
        CHECK_ERROR(with_camera("[[objects]]\nmesh = \"cube\"\nscale = [1, 0.0, 1]\n"),
                    "test.toml:6:9: expected every component of 'objects[0].scale' to be non-zero");
    }
    SUBCASE("uv_scale: a number or [u, v], each > 0") {
        CHECK_ERROR(with_camera("[[objects]]\nmesh = \"plane\"\nuv_scale = 0\n"),
                    "test.toml:6:12: expected 'objects[0].uv_scale' to be > 0, got 0");
        CHECK_ERROR(with_camera("[[objects]]\nmesh = \"plane\"\nuv_scale = [2, -1]\n"),
                    "test.toml:6:16: expected 'objects[0].uv_scale[1]' to be > 0, got -1");
        CHECK_ERROR(with_camera("[[objects]]\nmesh = \"plane\"\nuv_scale = [1, 2, 3]\n"),
                    "test.toml:6:12: expected an array [u, v] of 2 numbers for 'objects[0].uv_scale', got 3 elements");
        CHECK_ERROR(with_camera("[[objects]]\nmesh = \"plane\"\nuv_scale = \"tiled\"\n"),
                    "test.toml:6:12: expected a number or an array [u, v] of 2 numbers for 'objects[0].uv_scale', "
                    "got string");
        CHECK_ERROR(with_camera("[[objects]]\nmesh = \"plane\"\nuv_scale = nan\n"), "test.toml:6:12:",
                    "'objects[0].uv_scale'");
        const Scene scene = tessera::parse_scene(with_camera("[[objects]]\nmesh = \"plane\"\nuv_scale = 4\n"), "t.toml");
        REQUIRE(scene.meshes.size() == 1);
        CHECK(scene.meshes[0].uvs[0] == glm::vec2(0, 4));  // the corner at (-1, 0, 1): u 0, v 1, times 4
    }
    SUBCASE("unknown names") {
        CHECK_ERROR(with_camera("[[objects]]\nmesh = \"teapot\"\n"),
                    "test.toml:5:8: unknown mesh 'teapot' for 'objects[0].mesh'; built-in meshes: sphere, "
                    "plane, cube");
        CHECK_ERROR(with_camera("[materials.gold]\n[materials.steel]\n[[objects]]\nmesh = \"cube\"\nmaterial = \"copper\"\n"),
                    "test.toml:8:12: unknown material 'copper' for 'objects[0].material'; defined materials: "
                    "gold, steel");
        CHECK_ERROR(with_camera("[[objects]]\nmesh = \"cube\"\nmaterial = \"copper\"\n"),
                    "test.toml:6:12: unknown material 'copper'", "no materials are defined");
        CHECK_ERROR(with_camera("[[lights]]\ntype = \"area\"\nposition = [1, 2, 3]\ncolor = [1, 1, 1]\n"),
                    "test.toml:5:8: unsupported light type 'area' for 'lights[0].type'; supported types: point, "
                    "directional, spot");
    }
    SUBCASE("degenerate camera") {
        CHECK_ERROR("[camera]\nposition = [1, 2, 3]\ntarget = [1, 2, 3]\n",
                    "test.toml:3:10: expected 'camera.target' to differ from 'camera.position'");
        CHECK_ERROR(with_camera("up = [0, 0, 2]\n"),
                    "test.toml:4:6: expected 'camera.up' to be non-zero and not parallel to the view direction");
        CHECK_ERROR(with_camera("up = [0, 0, 0]\n"), "test.toml:4:6: expected 'camera.up' to be non-zero");
        // The default up (0, 1, 0) is parallel to a camera looking straight down.
        CHECK_ERROR("[camera]\nposition = [0, 5, 0]\ntarget = [0, 0, 0]\n",
                    "test.toml:1:1: expected 'camera.up' to be non-zero and not parallel");
    }
}

TEST_CASE("textured.toml: one shared rust material, maps loaded once, factors 1") {
    const std::filesystem::path path = tessera::test::source_dir() / "scenes" / "textured.toml";
    const tessera::Scene scene = tessera::load_scene_file(path);
    REQUIRE(scene.materials.size() == 1);
    CHECK(scene.objects.size() == 49);
    CHECK(scene.lights.size() == 1);
    CHECK(scene.textures.size() == 5);
    const tessera::Material& m = scene.materials[0];
    CHECK(m.albedo == glm::vec3(1.0f));
    CHECK(m.metallic == 1.0f);
    CHECK(m.roughness == 1.0f);
    CHECK(m.albedo_decode == tessera::AlbedoDecode::pow_2_2_after_filter);
    CHECK(m.derived_tangent_frame == tessera::DerivedTangentFrame::learnopengl);
    for (const tessera::TextureSlot* slot : {&m.albedo_map, &m.metallic_map, &m.roughness_map, &m.ao_map, &m.normal_map})
        CHECK(slot->present());
    CHECK_FALSE(m.emissive_map.present());
    // A factor written next to its map multiplies it.
    const std::string text = "[camera]\nposition = [0, 0, 5]\ntarget = [0, 0, 0]\n[[objects]]\nmesh = \"plane\"\n"
                             "material = { roughness_map = \"textures/rust/roughness.png\", roughness = 0.5 }\n";
    const tessera::Scene inline_scene = tessera::parse_scene(text, (path.parent_path() / "inline.toml").string());
    CHECK(inline_scene.materials.at(0).roughness == 0.5f);
    CHECK(inline_scene.materials.at(0).roughness_map.present());
}

TEST_CASE("scene file: light types") {
    using tessera::LightType;
    const Scene scene = tessera::parse_scene(with_camera(R"(
[[lights]]
position = [1, 2, 3]
color = [4, 5, 6]

[[lights]]
type = "directional"
direction = [0, -3, 4]
color = [0.5, 1, 2]

[[lights]]
type = "spot"
position = [0, 5, 0]
direction = [0, -2, 0]
color = [100, 100, 100]
inner_cone = 10
outer_cone = 30.5
range = 12.5

[[lights]]
type = "spot"
position = [0, 5, 0]
direction = [1, 0, 0]
color = [1, 9, 4]
range = "auto"

[[lights]]
type = "point"
position = [0, 0, 0]
color = [0, 0, 0]
range = "auto"
)"), "test.toml");
    REQUIRE(scene.lights.size() == 5);
    const tessera::Light& point = scene.lights[0];
    CHECK(point.type == LightType::point);
    CHECK(point.position == glm::vec3(1, 2, 3));
    CHECK(point.color == glm::vec3(4, 5, 6));
    CHECK(point.range == 0.0f);  // unlimited unless given

    const tessera::Light& sun = scene.lights[1];
    CHECK(sun.type == LightType::directional);
    CHECK(sun.color == glm::vec3(0.5f, 1.0f, 2.0f));
    // Normalized at load: (0, −3, 4) / 5.
    CHECK(sun.direction.x == 0.0f);
    CHECK(sun.direction.y == doctest::Approx(-0.6));
    CHECK(sun.direction.z == doctest::Approx(0.8));

    const tessera::Light& spot = scene.lights[2];
    CHECK(spot.type == LightType::spot);
    CHECK(spot.position == glm::vec3(0, 5, 0));
    CHECK(spot.direction == glm::vec3(0, -1, 0));
    CHECK(spot.inner_cone_degrees == 10.0f);
    CHECK(spot.outer_cone_degrees == 30.5f);
    CHECK(spot.range == 12.5f);

    // Cone defaults 0 and 45; range "auto" = sqrt(max(color) / (1/4096)) = sqrt(9·4096) = 192.
    const tessera::Light& default_spot = scene.lights[3];
    CHECK(default_spot.inner_cone_degrees == 0.0f);
    CHECK(default_spot.outer_cone_degrees == 45.0f);
    CHECK(default_spot.range == doctest::Approx(192.0));
    CHECK(tessera::auto_light_range(glm::vec3(0.25f, 1.0f, 0.5f)) == doctest::Approx(64.0));
    // A black light's auto range is the smallest there is, not 0 (= unlimited).
    CHECK(scene.lights[4].range > 0.0f);
    CHECK(scene.lights[4].range < 1e-30f);
}

TEST_CASE("scene errors: light types") {
    SUBCASE("direction") {
        CHECK_ERROR(with_camera("[[lights]]\ntype = \"directional\"\ncolor = [1, 1, 1]\n"),
                    "test.toml:4:1: missing required key 'lights[0].direction'");
        CHECK_ERROR(with_camera("[[lights]]\ntype = \"spot\"\nposition = [0, 0, 0]\ncolor = [1, 1, 1]\ndirection = [0, 0, 0]\n"),
                    "test.toml:8:13: expected 'lights[0].direction' to be non-zero");
        CHECK_ERROR(with_camera("[[lights]]\nposition = [0, 0, 0]\ncolor = [1, 1, 1]\ndirection = [0, 0, 1]\n"),
                    "test.toml:7:13: 'lights[0].direction' does not apply to a point light");
        CHECK_ERROR(with_camera("[[lights]]\ntype = \"directional\"\ndirection = [0, nan, 1]\ncolor = [1, 1, 1]\n"),
                    "test.toml:6:", "expected a finite number for 'lights[0].direction[1]'");
    }
    SUBCASE("keys that do not apply to the type") {
        CHECK_ERROR(with_camera("[[lights]]\ntype = \"directional\"\nposition = [0, 0, 0]\ndirection = [0, 0, 1]\n"
                                "color = [1, 1, 1]\n"),
                    "test.toml:6:12: 'lights[0].position' does not apply to a directional light");
        CHECK_ERROR(with_camera("[[lights]]\ntype = \"directional\"\ndirection = [0, 0, 1]\ncolor = [1, 1, 1]\n"
                                "range = 5\n"),
                    "test.toml:8:9: 'lights[0].range' does not apply to a directional light");
        CHECK_ERROR(with_camera("[[lights]]\nposition = [0, 0, 0]\ncolor = [1, 1, 1]\nouter_cone = 30\n"),
                    "test.toml:7:14: 'lights[0].outer_cone' does not apply to a point light");
    }
    SUBCASE("cones: 0 <= inner < outer <= 90") {
        const std::string spot = "[[lights]]\ntype = \"spot\"\nposition = [0, 0, 0]\ndirection = [0, 0, 1]\ncolor = [1, 1, 1]\n";
        CHECK_ERROR(with_camera(spot + "inner_cone = -1\n"),
                    "test.toml:9:14: expected 'lights[0].inner_cone' to be in [0, 90] degrees, got -1");
        CHECK_ERROR(with_camera(spot + "outer_cone = 91\n"),
                    "test.toml:9:14: expected 'lights[0].outer_cone' to be in [0, 90] degrees, got 91");
        CHECK_ERROR(with_camera(spot + "inner_cone = 30\nouter_cone = 30\n"),
                    "test.toml:9:14: expected 'lights[0].inner_cone' < 'lights[0].outer_cone', got inner = 30, outer = 30");
        // The default outer cone is 45.
        CHECK_ERROR(with_camera(spot + "inner_cone = 50\n"),
                    "test.toml:9:14: expected 'lights[0].inner_cone' < 'lights[0].outer_cone', got inner = 50, outer = 45");
        CHECK_ERROR(with_camera(spot + "outer_cone = 0\n"), "test.toml:9:14: expected 'lights[0].inner_cone' < ");
    }
    SUBCASE("range") {
        const std::string point = "[[lights]]\nposition = [0, 0, 0]\ncolor = [1, 1, 1]\n";
        CHECK_ERROR(with_camera(point + "range = 0\n"),
                    "test.toml:7:9: expected 'lights[0].range' to be > 0 (leave it out for unlimited), got 0");
        CHECK_ERROR(with_camera(point + "range = -2.5\n"), "test.toml:7:9: expected 'lights[0].range' to be > 0");
        CHECK_ERROR(with_camera(point + "range = \"far\"\n"),
                    "test.toml:7:9: expected a number > 0 or \"auto\" for 'lights[0].range', got \"far\"");
        CHECK_ERROR(with_camera(point + "range = true\n"),
                    "test.toml:7:9: expected a number > 0 or \"auto\" for 'lights[0].range', got boolean");
        CHECK_ERROR(with_camera(point + "range = inf\n"), "test.toml:7:9: expected a finite number for 'lights[0].range'");
    }
}
