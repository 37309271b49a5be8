// Tests for src/scene/animation*.cpp: the [animation] table, its errors, and
// the evaluation of frames (orbit, keyframes, in-place moves between frames).
#include <cmath>
#include <string>
#include <string_view>

#include <doctest/doctest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "scene/animation_eval.hpp"
#include "tessera/animation.hpp"
#include "tessera/scene.hpp"

using namespace tessera;

namespace {

// Two spheres, two lights (a point and a directional one), a named material
// the spheres share; tests append their [animation].
constexpr std::string_view kBase =
    "[camera]\nposition = [0, 3, 10]\ntarget = [0, 0, 0]\n"
    "[[lights]]\nposition = [5, 5, 5]\ncolor = [10, 10, 10]\n"
    "[[lights]]\ntype = \"directional\"\ndirection = [0, -1, 0]\ncolor = [1, 1, 1]\n"
    "[materials.shared]\nalbedo = [0.5, 0.5, 0.5]\n"
    "[[objects]]\nmesh = \"sphere\"\nmaterial = \"shared\"\ntranslate = [1, 2, 3]\nscale = 2\n"
    "[[objects]]\nmesh = \"sphere\"\nmaterial = \"shared\"\n";

Scene parse(std::string_view animation) { return parse_scene(std::string(kBase) + std::string(animation), "anim.toml"); }

std::string error_of(std::string_view animation) {
    try {
        parse(animation);
    } catch (const SceneError& error) {
        return error.what();
    }
    FAIL_CHECK("no SceneError for:\n" << animation);
    return "";
}

bool near(const glm::vec3& a, const glm::vec3& b, float tolerance = 1e-5f) {
    return glm::length(a - b) <= tolerance * std::max(1.0f, glm::length(b));
}

}  // namespace

TEST_CASE("a scene without [animation] is still: one frame, frame 0 only") {
    Scene scene = parse("");
    CHECK(scene.animation == nullptr);
    CHECK(scene_frame_count(scene) == 1);
    CHECK_NOTHROW(set_scene_frame(scene, 0));
    CHECK_THROWS_AS(set_scene_frame(scene, 1), std::out_of_range);
}

TEST_CASE("orbit: defaults start at [camera], a quarter of the frames is a quarter turn") {
    Scene scene = parse("[animation]\nframes = 8\nfps = 30\n[animation.orbit]\n");
    REQUIRE(scene.animation != nullptr);
    CHECK(scene_frame_count(scene) == 8);
    CHECK(scene.animation->fps == 30.0);
    // As loaded, the scene is frame 0: the [camera] position, from the orbit's defaults.
    CHECK(near(scene.camera.position, {0, 3, 10}));
    set_scene_frame(scene, 2);  // 2 of 8 frames: 90°, from +Z to +X
    CHECK(near(scene.camera.position, {10, 3, 0}));
    CHECK(near(scene.camera.target, {0, 0, 0}));
    set_scene_frame(scene, 4);
    CHECK(near(scene.camera.position, {0, 3, -10}));
    // The last frame is one step short of closing the loop.
    const CameraOrbit orbit = *scene.animation->orbit;
    CHECK(near(orbit_position(orbit, 8, 8.0), orbit_position(orbit, 8, 0.0)));
}

TEST_CASE("orbit keys override the defaults") {
    Scene scene = parse("[animation]\nframes = 4\n[animation.orbit]\ntarget = [1, 0, 0]\nradius = 2\nheight = -1\n"
                        "start_angle = 90\nturns = -1\n");
    CHECK(near(scene.camera.position, {3, -1, 0}));
    CHECK(near(scene.camera.target, {1, 0, 0}));
    set_scene_frame(scene, 1);  // −90°: from +X back to +Z
    CHECK(near(scene.camera.position, {1, -1, 2}));
}

TEST_CASE("camera keyframes: linear is exact between keys, smooth passes through keys and eases at the ends") {
    const std::string keys = "keys = [ { frame = 0, position = [0, 0, 10], fov_y = 40 }, { frame = 10, position = [10, 0, 10] },"
                             " { frame = 20, position = [10, 0, 20], fov_y = 60 } ]\n";
    Scene linear = parse("[animation]\nframes = 21\n[animation.camera]\ninterpolation = \"linear\"\n" + keys);
    set_scene_frame(linear, 5);
    CHECK(near(linear.camera.position, {5, 0, 10}));
    CHECK(linear.camera.fov_y_degrees == doctest::Approx(45.0f));
    CHECK(near(linear.camera.target, {0, 0, 0}));  // no target keys: [camera]'s

    Scene smooth = parse("[animation]\nframes = 21\n[animation.camera]\n" + keys);  // smooth by default
    set_scene_frame(smooth, 10);
    CHECK(near(smooth.camera.position, {10, 0, 10}));
    set_scene_frame(smooth, 20);
    CHECK(near(smooth.camera.position, {10, 0, 20}));
    // Zero velocity at the first key: frame 1 has moved much less than a tenth of the way.
    set_scene_frame(smooth, 1);
    CHECK(smooth.camera.position.x > 0.0f);
    CHECK(smooth.camera.position.x < 0.5f);
    // Through the middle key it keeps moving (Catmull-Rom tangent (p2 − p0) / 20 = (0.5, 0, 0.5) per frame).
    Track<glm::vec3> track;
    track.frames = {0, 10, 20};
    track.values = {{0, 0, 10}, {10, 0, 10}, {10, 0, 20}};
    const glm::vec3 before = sample_track(track, Interpolation::smooth, 9.999);
    const glm::vec3 after = sample_track(track, Interpolation::smooth, 10.001);
    CHECK(near((after - before) / 0.002f, {0.5f, 0, 0.5f}, 1e-2f));
}

TEST_CASE("object keyframes: rotate, translate, scale and colour, a shared material keeps its colour elsewhere") {
    Scene scene = parse("[animation]\nframes = 5\n"
                        "[[animation.objects]]\nobject = 0\n"
                        "keys = [ { frame = 0, rotate = [0, 0, 0], color = [1, 0, 0] }, { frame = 4, rotate = [0, 360, 0], color = [0, 0, 1] } ]\n"
                        "[[animation.objects]]\nobject = 1\nkeys = [ { frame = 2, translate = [0, 1, 0] } ]\n");
    const std::uint32_t own = scene.objects[0].material;
    CHECK(own != scene.objects[1].material);
    CHECK(near(scene.materials[own].albedo, {1, 0, 0}));
    CHECK(near(scene.materials[scene.objects[1].material].albedo, {0.5f, 0.5f, 0.5f}));
    set_scene_frame(scene, 1);  // 90° about Y, around the object's [[objects]] translate and scale
    const glm::mat4 expected = glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), {1, 2, 3}), glm::radians(90.0f), {0, 1, 0}),
                                          glm::vec3(2.0f));
    for (int c = 0; c < 4; ++c) CHECK(near(glm::vec3(scene.objects[0].model[c]), glm::vec3(expected[c])));
    CHECK(near(scene.materials[own].albedo, {0.75f, 0, 0.25f}));
    CHECK(near(scene.materials[scene.objects[1].material].albedo, {0.5f, 0.5f, 0.5f}));
    // One key holds its value everywhere.
    CHECK(near(glm::vec3(scene.objects[1].model[3]), {0, 1, 0}));
}

TEST_CASE("light keyframes: position and colour, colour clamped at 0 where smooth overshoots") {
    Scene scene = parse("[animation]\nframes = 11\n"
                        "[[animation.lights]]\nlight = 0\ninterpolation = \"smooth\"\n"
                        "keys = [ { frame = 0, color = [0, 0, 0], position = [0, 5, 0] }, { frame = 5, color = [0, 10, 0] },"
                        " { frame = 6, color = [0, 0, 0] }, { frame = 10, color = [0, 0, 0], position = [10, 5, 0] } ]\n"
                        "[[animation.lights]]\nlight = 1\nkeys = [ { frame = 0, color = [2, 2, 2] } ]\n");
    set_scene_frame(scene, 5);
    CHECK(near(scene.lights[0].color, {0, 10, 0}));
    CHECK(near(scene.lights[0].position, {5, 5, 0}, 0.5f));  // smooth: near the middle, eased
    CHECK(near(scene.lights[1].color, {2, 2, 2}));
    for (int f = 0; f <= 10; ++f) {
        set_scene_frame(scene, f);
        CHECK(scene.lights[0].color.g >= 0.0f);  // the spline dips below 0 after the peak; clamped
    }
    // The raw spline does overshoot there, so the clamp is what keeps the colour valid.
    CHECK(sample_track(scene.animation->lights[0].color, Interpolation::smooth, 7.5).g < 0.0f);
}

TEST_CASE("a frame depends on its number only, not on the frames evaluated before") {
    const std::string animation =
        "[animation]\nframes = 30\n[animation.camera]\nkeys = [ { frame = 0, position = [0, 3, 10] }, "
        "{ frame = 29, position = [8, 1, 6], target = [1, 1, 1] } ]\n"
        "[[animation.objects]]\nobject = 1\ninterpolation = \"smooth\"\nkeys = [ { frame = 0, scale = 1 }, { frame = 12, scale = [1, 3, 1] }, "
        "{ frame = 29, rotate = [10, 20, 30], color = [0.2, 0.4, 0.6] } ]\n"
        "[[animation.lights]]\nlight = 0\nkeys = [ { frame = 3, position = [1, 2, 3] }, { frame = 20, position = [3, 2, 1] } ]\n";
    Scene walked = parse(animation);
    for (int f : {29, 3, 17, 0, 28}) set_scene_frame(walked, f);
    set_scene_frame(walked, 17);
    Scene fresh = parse(animation);
    set_scene_frame(fresh, 17);
    CHECK(walked.camera.position == fresh.camera.position);
    CHECK(walked.camera.target == fresh.camera.target);
    CHECK(walked.objects[1].model == fresh.objects[1].model);
    CHECK(walked.materials[walked.objects[1].material].albedo == fresh.materials[fresh.objects[1].material].albedo);
    CHECK(walked.lights[0].position == fresh.lights[0].position);
    CHECK_THROWS_AS(set_scene_frame(fresh, 30), std::out_of_range);
    CHECK_THROWS_AS(set_scene_frame(fresh, -1), std::out_of_range);
}

TEST_CASE("[animation] errors name file:line:column and what was expected") {
    // The base text is 20 lines; the animation starts on line 21.
    CHECK(error_of("[animation]\nfps = 24\n") == "anim.toml:21:1: missing required key 'animation.frames'");
    CHECK(error_of("[animation]\nframes = 0\n") == "anim.toml:22:10: expected 'animation.frames' to be in 1..1000000, got 0");
    CHECK(error_of("[animation]\nframes = 10\nfps = 0\n") == "anim.toml:23:7: expected 'animation.fps' to be > 0, got 0");
    CHECK(error_of("[animation]\nframes = 10\nspeed = 2\n").find("anim.toml:23:1: unknown key 'speed' in 'animation'") == 0);
    CHECK(error_of("[animation]\nframes = 10\n[animation.orbit]\n[animation.camera]\nkeys = [{frame = 0}]\n")
              .find("anim.toml:24:1: 'animation.camera' (keyframes) and 'animation.orbit' both move the camera") == 0);
    CHECK(error_of("[animation]\nframes = 10\n[animation.camera]\nkeys = [{frame = 5}, {frame = 5}]\n") ==
          "anim.toml:24:31: expected 'animation.camera.keys[1].frame' to be greater than the previous key's frame 5, got 5");
    CHECK(error_of("[animation]\nframes = 10\n[animation.camera]\ninterpolation = \"cubic\"\nkeys = [{frame = 0}]\n") ==
          "anim.toml:24:17: expected \"linear\" or \"smooth\" for 'animation.camera.interpolation'");
    CHECK(error_of("[animation]\nframes = 10\n[[animation.objects]]\nobject = 2\nkeys = [{frame = 0}]\n") ==
          "anim.toml:24:10: expected 'animation.objects[0].object' to be the index of one of the 2 [[objects]] (0..1), got 2");
    CHECK(error_of("[animation]\nframes = 10\n[[animation.objects]]\nobject = 0\nkeys = []\n") ==
          "anim.toml:25:8: expected at least one key in 'animation.objects[0].keys'");
    CHECK(error_of("[animation]\nframes = 10\n[[animation.objects]]\nobject = 0\nkeys = [{frame = 0, color = [2, 0, 0]}]\n") ==
          "anim.toml:25:30: expected 'animation.objects[0].keys[0].color[0]' to be in [0, 1], got 2");
    // The scene file's wording (toml_reader.hpp): the type found, the element count, a light's colour ">= 0".
    CHECK(error_of("[animation]\nframes = \"ten\"\n") ==
          "anim.toml:22:10: expected an integer for 'animation.frames', got string");
    CHECK(error_of("[animation]\nframes = 10\n[animation.orbit]\ntarget = [0, 0]\n") ==
          "anim.toml:24:10: expected an array of 3 numbers for 'animation.orbit.target', got 2 elements");
    CHECK(error_of("[animation]\nframes = 10\n[[animation.lights]]\nlight = 0\nkeys = [{frame = 0, color = [1, -1, 0]}]\n") ==
          "anim.toml:25:33: expected 'animation.lights[0].keys[0].color[1]' to be >= 0, got -1");
    CHECK(error_of("[animation]\nframes = 10\n[[animation.objects]]\nobject = 0\nkeys = [{frame = 0, scale = 0}]\n") ==
          "anim.toml:25:29: expected every component of 'animation.objects[0].keys[0].scale' to be non-zero");
    CHECK(error_of("[animation]\nframes = 10\n[[animation.lights]]\nlight = 1\nkeys = [{frame = 0, position = [0, 1, 0]}]\n") ==
          "anim.toml:25:32: 'animation.lights[0].keys[0].position' does not apply to a directional light");
    CHECK(error_of("[animation]\nframes = 10\n[[animation.lights]]\nlight = 0\nkeys = [{frame = 0}]\n"
                   "[[animation.lights]]\nlight = 0\nkeys = [{frame = 0}]\n") ==
          "anim.toml:27:9: [[lights]] 0 is animated twice");
    // A camera that reaches its target at some frame, or looks straight down its up vector.
    CHECK(error_of("[animation]\nframes = 11\n[animation.camera]\ninterpolation = \"linear\"\n"
                   "keys = [{frame = 0, position = [0, 0, 5]}, {frame = 10, position = [0, 0, -5]}]\n") ==
          "anim.toml:23:1: at frame 5 the camera's target is its position");
    CHECK(error_of("[animation]\nframes = 4\n[animation.orbit]\nradius = 1\nheight = 1\ntarget = [0, 0, 0]\n"
                   "[animation.camera]\nkeys = [{frame = 0}]\n")
              .find("both move the camera") != std::string::npos);
}
