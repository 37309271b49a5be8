// glTF skins, morph targets and animations (issue #14; #15's glTF part):
// posed vertices and node transforms checked against values worked out by hand
// from the glTF spec's formulas (skinning §3.7.4, morphing §3.7.3,
// interpolation Appendix C), on the small files of gltf_animation_files.hpp.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>

#include <doctest/doctest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <tiny_gltf.h>

#include "scene/gltf/gltf_animation.hpp"
#include "scene/gltf_animation_files.hpp"
#include "scene/gltf/gltf_import.hpp"
#include "tessera/animation.hpp"
#include "test_paths.hpp"

using namespace tessera;

namespace {

GltfContent import_text(const std::string& text, const std::string& name = "test.gltf") {
    const auto* bytes = reinterpret_cast<const std::uint8_t*>(text.data());
    return import_gltf({bytes, text.size()}, name, "");
}

Scene scene_of(const std::string& text, const std::string& name = "test.gltf") {
    return make_gltf_scene(import_text(text, name), name);
}

std::string error_of(const std::function<void()>& action) {
    try {
        action();
    } catch (const SceneError& e) {
        return e.what();
    }
    return "(accepted)";
}

void check_near(const glm::vec3& got, const glm::vec3& want, float tolerance = 1e-5f) {
    INFO("got (", got.x, ", ", got.y, ", ", got.z, "), want (", want.x, ", ", want.y, ", ", want.z, ")");
    CHECK(glm::length(got - want) <= tolerance);
}

// Where an object's model matrix puts a point.
glm::vec3 placed(const Object& object, const glm::vec3& point) { return glm::vec3(object.model * glm::vec4(point, 1.0f)); }

const float kHalfRoot2 = std::sqrt(0.5f);

}  // namespace

TEST_CASE("a skinned mesh is drawn at its joints' rest pose, ignoring its node's transform") {
    const GltfContent content = import_text(test::skinned_strip_gltf());
    REQUIRE(content.rig);
    REQUIRE(content.meshes.size() == 1);
    // The joints' own TRS are the bind pose here: joint · inverseBind = identity for both.
    const std::vector<glm::vec3> bind = {{-0.5f, 0, 0}, {0.5f, 0, 0}, {-0.5f, 1, 0}, {0.5f, 1, 0}, {-0.5f, 2, 0}, {0.5f, 2, 0}};
    for (std::size_t v = 0; v < bind.size(); ++v) check_near(content.meshes[0].positions[v], bind[v]);
    // The node's translation (5, 0, 0) is not applied (spec §3.7.4).
    CHECK(content.objects[0].model == glm::mat4(1.0f));
    CHECK(content.bounds.max.x == doctest::Approx(0.5f));
    CHECK(content.rig->animations.size() == 1);
    CHECK(content.rig->animations[0].name == "bend");
    CHECK(content.rig->animations[0].duration == doctest::Approx(1.0));
}

TEST_CASE("--time poses a skin: linear-blend skinning with the joints' animated transforms") {
    Scene scene = scene_of(test::skinned_strip_gltf());
    SUBCASE("t = 1: the tip joint turned 90° about +Z around (0, 1, 0)") {
        set_scene_time(scene, 1.0);
        const Mesh& mesh = scene.meshes[0];
        // Root-bound row unmoved.
        check_near(mesh.positions[0], {-0.5f, 0, 0});
        check_near(mesh.positions[1], {0.5f, 0, 0});
        // Tip row: (x, y) − (0, 1) turned by 90° is (−(y − 1), x), + (0, 1).
        check_near(mesh.positions[4], {-1.0f, 0.5f, 0});
        check_near(mesh.positions[5], {-1.0f, 1.5f, 0});
        // Middle row: half unmoved, half turned: (0.5, 1) and (0, 1.5) average to (0.25, 1.25).
        check_near(mesh.positions[3], {0.25f, 1.25f, 0});
        check_near(mesh.positions[2], {-0.25f, 0.75f, 0});
        // A rotation about Z keeps +Z normals.
        for (const glm::vec3& n : mesh.normals) check_near(n, {0, 0, 1});
    }
    SUBCASE("t = 0.5: slerp halfway, 45°") {
        set_scene_time(scene, 0.5);
        // (0.5, 1) turned by 45°: (0.5c − s, 0.5s + c) with c = s = √½, then + (0, 1).
        check_near(scene.meshes[0].positions[5], {-0.5f * kHalfRoot2, 1.5f * kHalfRoot2 + 1.0f, 0});
    }
    SUBCASE("past the last key the last value holds") {
        set_scene_time(scene, 7.0);
        check_near(scene.meshes[0].positions[5], {-1.0f, 1.5f, 0});
    }
}

TEST_CASE("morph targets: rest weights from the mesh or the node, animated weights by LINEAR and STEP") {
    SUBCASE("the mesh's weights [0.5, 0] at rest") {
        const GltfContent content = import_text(test::morph_triangle_gltf());
        REQUIRE(content.rig);
        check_near(content.meshes[0].positions[2], {0, 1, 0.5f});
        check_near(content.meshes[0].positions[0], {0, 0, 0});
        // Normal (0, 0, 1) + 0.5 · (0, −1, 0), renormalized.
        check_near(content.meshes[0].normals[2], glm::normalize(glm::vec3(0, -0.5f, 1)));
        check_near(content.meshes[0].normals[0], {0, 0, 1});
    }
    SUBCASE("the node's weights override the mesh's") {
        const GltfContent content = import_text(test::morph_triangle_gltf(R"(, "weights": [0, 1])"));
        check_near(content.meshes[0].positions[0], {1, 0, 0});
        check_near(content.meshes[0].positions[2], {0, 1, 0});
    }
    SUBCASE("LINEAR weights [0, 0] → [1, 1] over 2 s") {
        Scene scene = scene_of(test::morph_triangle_gltf());
        set_scene_time(scene, 1.0, "morph");
        check_near(scene.meshes[0].positions[0], {0.5f, 0, 0});
        check_near(scene.meshes[0].positions[2], {0, 1, 0.5f});
        set_scene_time(scene, 3.0, "0");
        check_near(scene.meshes[0].positions[0], {1, 0, 0});
        check_near(scene.meshes[0].positions[2], {0, 1, 1});
    }
    SUBCASE("STEP holds each key's weights until the next key") {
        Scene scene = scene_of(test::morph_triangle_gltf());
        set_scene_time(scene, 0.999, "morph_step");
        check_near(scene.meshes[0].positions[0], {1, 0, 0});
        check_near(scene.meshes[0].positions[2], {0, 1, 0});
        set_scene_time(scene, 1.0, "morph_step");
        check_near(scene.meshes[0].positions[0], {0, 0, 0});
        check_near(scene.meshes[0].positions[2], {0, 1, 1});
    }
}

TEST_CASE("node animations: translation, rotation and scale by LINEAR, STEP and CUBICSPLINE under a parent") {
    Scene scene = scene_of(test::animated_node_gltf());
    SUBCASE("at rest: the parent's translation only") {
        check_near(placed(scene.objects[0], {0, 0, 0}), {0, 0, -1});
        check_near(placed(scene.objects[0], {1, 0, 0}), {1, 0, -1});
    }
    SUBCASE("LINEAR at t = 1: T = (1, 2, 0), scale 2, 45° about +Y (slerp)") {
        set_scene_time(scene, 1.0, "linear");
        check_near(placed(scene.objects[0], {0, 0, 0}), {1, 2, -1});
        // (1, 0, 0) scaled to (2, 0, 0), turned 45° about Y to (2c, 0, −2s), moved by (1, 2, 0) and the parent's (0, 0, −1).
        check_near(placed(scene.objects[0], {1, 0, 0}), {1 + 2 * kHalfRoot2, 2, -1 - 2 * kHalfRoot2});
    }
    SUBCASE("STEP: each key's value from its time on") {
        set_scene_time(scene, 0.5, "step");
        check_near(placed(scene.objects[0], {0, 0, 0}), {0, 0, -1});
        set_scene_time(scene, 1.0, "step");
        check_near(placed(scene.objects[0], {0, 0, 0}), {1, 0, -1});
        set_scene_time(scene, 1.5, "step");
        check_near(placed(scene.objects[0], {0, 0, 0}), {1, 0, -1});
        set_scene_time(scene, 2.0, "step");
        check_near(placed(scene.objects[0], {0, 0, 0}), {5, 0, -1});
    }
    SUBCASE("CUBICSPLINE: the Hermite formula with tangents × the key interval") {
        // td = 2; at u: (2u³−3u²+1)·0 + td(u³−2u²+u)·1 + (−2u³+3u²)·4 + td(u³−u²)·2.
        set_scene_time(scene, 1.0, "cubic");  // u = 0.5: 2·0.125 + 0.5·4 − 2·0.125·2 = 1.75
        check_near(placed(scene.objects[0], {0, 0, 0}), {1.75f, 0, -1});
        set_scene_time(scene, 0.5, "cubic");  // u = 0.25: 2·0.140625 + 0.15625·4 − 2·0.046875·2 = 0.71875
        check_near(placed(scene.objects[0], {0, 0, 0}), {0.71875f, 0, -1});
    }
}

TEST_CASE("skinned normals follow the inverse transpose, tangents the matrix, under scales and mirrors") {
    // One joint (node 0) with an identity inverse bind matrix; one vertex fully bound to it.
    GltfRig rig;
    rig.nodes.resize(2);
    rig.nodes[1].skin = 0;
    rig.skins.push_back({{0}, {glm::mat4(1.0f)}});
    gltf::DeformedMesh deformed;
    deformed.node = 1;
    deformed.positions = {{1, 2, 3}};
    deformed.normals = {glm::normalize(glm::vec3(1, 1, 0))};
    deformed.tangents = {{1, -1, 0, -1}};
    deformed.influences_per_vertex = 4;
    deformed.joints = {0, 0, 0, 0};
    deformed.weights = {1, 0, 0, 0};
    Mesh out;
    out.positions.resize(1), out.normals.resize(1), out.tangents.resize(1);
    gltf::NodePose pose;
    pose.weights.resize(2);
    const auto pose_with = [&](const glm::mat4& joint_world) {
        pose.world = {joint_world, glm::mat4(1.0f)};
        gltf::deform_mesh(rig, deformed, pose, out);
    };
    SUBCASE("scale (2, 1, 1): the normal of the plane x + y = c becomes that of x/2 + y = c") {
        pose_with(glm::scale(glm::mat4(1.0f), glm::vec3(2, 1, 1)));
        check_near(out.positions[0], {2, 2, 3});
        check_near(out.normals[0], glm::normalize(glm::vec3(0.5f, 1, 0)));
        check_near(glm::vec3(out.tangents[0]), glm::normalize(glm::vec3(2, -1, 0)));
        CHECK(out.tangents[0].w == -1.0f);  // handedness kept
    }
    SUBCASE("mirror in X: the normal mirrors too (the cofactor's sign is fixed)") {
        pose_with(glm::scale(glm::mat4(1.0f), glm::vec3(-1, 1, 1)));
        check_near(out.positions[0], {-1, 2, 3});
        check_near(out.normals[0], glm::normalize(glm::vec3(-1, 1, 0)));
    }
    SUBCASE("weights summing to 0 leave the vertex at rest") {
        deformed.weights = {0, 0, 0, 0};
        pose_with(glm::translate(glm::mat4(1.0f), glm::vec3(5, 0, 0)));
        check_near(out.positions[0], {1, 2, 3});
    }
}

TEST_CASE("LINEAR rotation keys slerp along the shorter arc (q and −q are one rotation)") {
    gltf::RigSampler sampler;
    sampler.width = 4;
    sampler.times = {0.0f, 1.0f};
    // Identity, then 90° about Z given as its negative (−x, −y, −z, −w).
    sampler.values = {0, 0, 0, 1, 0, 0, -kHalfRoot2, -kHalfRoot2};
    float q[4];
    gltf::sample(sampler, 0.5, true, q);
    // 45° about Z: ±(0, 0, sin 22.5°, cos 22.5°), not a turn the long way round.
    const float s = std::sin(glm::radians(22.5f)), c = std::cos(glm::radians(22.5f));
    const float sign = q[3] < 0.0f ? -1.0f : 1.0f;
    CHECK(sign * q[2] == doctest::Approx(s));
    CHECK(sign * q[3] == doctest::Approx(c));
    CHECK(q[0] == doctest::Approx(0.0f));
}

TEST_CASE("frames of a glTF animation: 24 fps over its duration, each a pure function of its number") {
    Scene scene = scene_of(test::skinned_strip_gltf());
    REQUIRE(play_gltf_animation(scene));
    REQUIRE(scene.animation);
    CHECK(scene.animation->frame_count == 25);  // t = 0, 1/24, ..., 1 s
    const glm::vec3* positions = scene.meshes[0].positions.data();
    set_scene_frame(scene, 24);
    check_near(scene.meshes[0].positions[5], {-1.0f, 1.5f, 0});
    const Mesh last = scene.meshes[0];
    // Frame 7 straight after loading, and after frames 24 and 3: the same bytes.
    Scene fresh = scene_of(test::skinned_strip_gltf());
    play_gltf_animation(fresh);
    set_scene_frame(fresh, 7);
    set_scene_frame(scene, 3);
    set_scene_frame(scene, 7);
    REQUIRE(fresh.meshes[0].positions.size() == scene.meshes[0].positions.size());
    CHECK(std::memcmp(fresh.meshes[0].positions.data(), scene.meshes[0].positions.data(),
                      sizeof(glm::vec3) * scene.meshes[0].positions.size()) == 0);
    CHECK(std::memcmp(fresh.meshes[0].normals.data(), scene.meshes[0].normals.data(),
                      sizeof(glm::vec3) * scene.meshes[0].normals.size()) == 0);
    // Posed in place: the vertex arrays are the ones loaded, not new ones.
    CHECK(scene.meshes[0].positions.data() == positions);
    set_scene_frame(scene, 24);
    CHECK(std::memcmp(last.positions.data(), scene.meshes[0].positions.data(), sizeof(glm::vec3) * last.positions.size()) == 0);
    // --time t equals the frame at t · 24.
    Scene timed = scene_of(test::skinned_strip_gltf());
    set_scene_time(timed, 0.5);
    set_scene_frame(scene, 12);
    CHECK(std::memcmp(timed.meshes[0].positions.data(), scene.meshes[0].positions.data(),
                      sizeof(glm::vec3) * last.positions.size()) == 0);
}

TEST_CASE("--time and --animation refuse what they cannot do, naming the file") {
    Scene scene = scene_of(test::skinned_strip_gltf(), "strip.gltf");
    CHECK(error_of([&] { set_scene_time(scene, std::numeric_limits<double>::quiet_NaN()); }) ==
          "strip.gltf: --time nan: expected a finite number of seconds >= 0");
    CHECK(error_of([&] { set_scene_time(scene, -1.0); }) == "strip.gltf: --time -1: expected a finite number of seconds >= 0");
    CHECK(error_of([&] { set_scene_time(scene, std::numeric_limits<double>::infinity()); }).find("expected a finite number") !=
          std::string::npos);
    CHECK(error_of([&] { set_scene_time(scene, 1.0, "walk"); }) ==
          "strip.gltf: --animation 'walk' names no animation of the file; its animations: 0 'bend' (1 s)");
    CHECK(error_of([&] { set_scene_time(scene, 1.0, "1"); }).find("--animation '1' names no animation") != std::string::npos);
    Scene still = scene_of(test::embedded_test_gltf(), "still.gltf");
    CHECK(error_of([&] { set_scene_time(still, 1.0); }) == "still.gltf: --time: no glTF model in the scene has an animation to sample");
    CHECK_FALSE(play_gltf_animation(still));
    CHECK(error_of([&] { play_gltf_animation(still, "0"); }) == "still.gltf: --animation '0': the file has no animations");
}

TEST_CASE("[[models]] animation plays a glTF file's animation over [animation]'s frames") {
    const std::filesystem::path dir = test::output_dir("gltf_animation_models");
    std::ofstream(dir / "strip.gltf") << test::skinned_strip_gltf();
    const auto write_scene = [&](const std::string& model_keys) {
        std::ofstream(dir / "scene.toml") << "[camera]\nposition = [0, 1, 6]\ntarget = [0, 1, 0]\n"
                                             "[animation]\nframes = 49\nfps = 24\n"
                                             "[[models]]\nfile = \"strip.gltf\"\ntranslate = [10, 0, 0]\n" +
                                                 model_keys;
        return dir / "scene.toml";
    };
    SUBCASE("by name; frame f at f / fps seconds; the placement applies") {
        Scene scene = load_scene_file(write_scene("animation = \"bend\"\n"));
        REQUIRE(scene.posed_models.size() == 1);
        check_near(placed(scene.objects[0], scene.meshes[0].positions[5]), {10.5f, 2, 0});  // frame 0: t = 0
        set_scene_frame(scene, 24);
        check_near(placed(scene.objects[0], scene.meshes[0].positions[5]), {9, 1.5f, 0});
    }
    SUBCASE("start, speed and loop") {
        Scene scene = load_scene_file(write_scene("animation = 0\nanimation_start = 0.5\nanimation_speed = 0.5\n"));
        // Frame 0 at 0.5 s.
        check_near(scene.meshes[0].positions[5], {-0.5f * kHalfRoot2, 1.5f * kHalfRoot2 + 1.0f, 0});
        set_scene_frame(scene, 24);  // 0.5 + 0.5 · 1 = 1 s
        check_near(scene.meshes[0].positions[5], {-1.0f, 1.5f, 0});
        Scene looped = load_scene_file(write_scene("animation = 0\nanimation_speed = 1.5\nanimation_loop = true\n"));
        set_scene_frame(looped, 24);  // 1.5 · 24 / 24 = 1.5 s wraps to 0.5 s
        check_near(looped.meshes[0].positions[5], {-0.5f * kHalfRoot2, 1.5f * kHalfRoot2 + 1.0f, 0});
    }
    SUBCASE("a model that does not opt in keeps its rest pose in frames") {
        Scene scene = load_scene_file(write_scene(""));
        set_scene_frame(scene, 24);
        check_near(scene.meshes[0].positions[5], {0.5f, 2, 0});
    }
    SUBCASE("--time in a TOML scene: a model's own choice and timing, else its first animation") {
        Scene chosen = load_scene_file(write_scene("animation = \"bend\"\nanimation_start = 0.5\nanimation_speed = 0.5\n"));
        set_scene_time(chosen, 1.0);  // 0.5 + 0.5 · 1 = 1 s
        check_near(chosen.meshes[0].positions[5], {-1.0f, 1.5f, 0});
        Scene first = load_scene_file(write_scene(""));
        set_scene_time(first, 0.5);
        check_near(first.meshes[0].positions[5], {-0.5f * kHalfRoot2, 1.5f * kHalfRoot2 + 1.0f, 0});
    }
    SUBCASE("bad keys name file, line and column") {
        const std::string file = (dir / "scene.toml").string();
        CHECK(error_of([&] { load_scene_file(write_scene("animation = \"walk\"\n")); }) ==
              file + ":10:13: expected 'models[0].animation' to name one of the file's animations (0 'bend' (1 s)), got 'walk'");
        CHECK(error_of([&] { load_scene_file(write_scene("animation = 3\n")); }) ==
              file + ":10:13: expected 'models[0].animation' to be the index of one of the file's animations (0 'bend' (1 s)), got 3");
        CHECK(error_of([&] { load_scene_file(write_scene("animation = true\n")); }).find(
                  ":10:13: expected an animation's index (an integer) or name (a string) for 'models[0].animation'") !=
              std::string::npos);
        CHECK(error_of([&] { load_scene_file(write_scene("animation_speed = 2\n")); }) ==
              file + ":10:19: 'models[0].animation_speed' times the file's animation: give 'models[0].animation' too");
        CHECK(error_of([&] { load_scene_file(write_scene("animation = 0\nanimation_start = nan\n")); }).find(
                  ":11:19: expected a finite number for 'models[0].animation_start'") != std::string::npos);
    }
}

TEST_CASE("the Khronos sample models get a rig exactly when they have skins, morph targets or animations") {
    if (test::skip_without_assets()) return;
    const std::filesystem::path models = test::assets_dir() / "gltf";
    // Static files must import without a rig (they pay nothing for posing); files that can
    // move must get one. What a file has is read with tinygltf directly, not by the importer.
    int checked = 0, rigged = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(models)) {
        if (!is_gltf_path(entry.path())) continue;
        CAPTURE(entry.path().string());
        tinygltf::Model model;
        tinygltf::TinyGLTF loader;
        std::string error, warning;
        const std::string path = entry.path().string();
        const bool loaded = entry.path().extension() == ".glb" ? loader.LoadBinaryFromFile(&model, &error, &warning, path)
                                                               : loader.LoadASCIIFromFile(&model, &error, &warning, path);
        REQUIRE_MESSAGE(loaded, error);
        bool can_move = !model.skins.empty() || !model.animations.empty();
        for (const auto& mesh : model.meshes)
            for (const auto& primitive : mesh.primitives) can_move = can_move || !primitive.targets.empty();
        GltfContent content;
        try {
            content = import_gltf_file(entry.path());
        } catch (const std::exception& refused) {
            // Files the importer refuses (a required extension it lacks) are other tests' business.
            MESSAGE("not imported: " << refused.what());
            continue;
        }
        CHECK(static_cast<bool>(content.rig) == can_move);
        rigged += can_move ? 1 : 0;
        ++checked;
    }
    MESSAGE(checked << " sample models checked, " << rigged << " of them animated or deformable");
    CHECK(checked > 0);
}
