// Animation: what a scene file's [animation] table says changes from frame to
// frame, and how a frame's Scene is computed from it. A frame is a pure
// function of its number: the same frame gives the same Scene (and so the same
// image, bit for bit) whichever frames were evaluated before, in any process.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "tessera/scene.hpp"

namespace tessera {

// How a property moves between two keys.
enum class Interpolation {
    linear,  // straight lines between keys, a corner at each key
    // A cubic Hermite spline through every key (Catmull-Rom tangents for
    // uneven key spacing: (p[i+1] − p[i−1]) / (t[i+1] − t[i−1])), with zero
    // velocity at the first and last key: smooth through the keys, easing in
    // and out at the ends. It may overshoot between keys: colours are clamped
    // to their valid range afterwards.
    smooth,
};

// One animated property: keys at frame numbers (strictly increasing; frames
// may be fractional). Before the first key it holds the first value, after
// the last the last.
template <typename Value>
struct Track {
    std::vector<double> frames;
    std::vector<Value> values;  // one per frame
    bool empty() const { return frames.empty(); }
};

// A camera circling a target at constant speed (a turntable seen from the
// camera). At frame f: angle = start_angle + 360° · turns · f / Animation::frame_count,
// position = target + (radius · sin(angle), height, radius · cos(angle)), so
// angle 0 is on +Z and a whole number of turns loops seamlessly.
struct CameraOrbit {
    glm::vec3 target{0.0f};      // world space
    float radius = 1.0f;         // world units, > 0, in the XZ plane
    float height = 0.0f;         // world units above the target (Y)
    float start_angle_degrees = 0.0f;
    float turns = 1.0f;          // may be negative (clockwise seen from above) or fractional
};

// An object's placement and colour over time. Scene::objects[object].model is
// translate · Rz · Ry · Rx · scale of the tracks' values (the static values
// where a track is empty), as [[objects]] places it.
struct ObjectAnimation {
    std::uint32_t object = 0;  // index into Scene::objects
    Interpolation interpolation = Interpolation::linear;
    glm::vec3 base_translate{0.0f};
    glm::vec3 base_rotate_degrees{0.0f};  // Euler angles, interpolated per component (0 → 360 is a full turn)
    glm::vec3 base_scale{1.0f};
    Track<glm::vec3> translate;
    Track<glm::vec3> rotate_degrees;
    Track<glm::vec3> scale;
    Track<glm::vec3> color;  // the material's albedo, linear RGB clamped to [0, 1]; the object owns its material
};

// A light's position and colour over time (the tracks it has).
struct LightAnimation {
    std::uint32_t light = 0;  // index into Scene::lights
    Interpolation interpolation = Interpolation::linear;
    Track<glm::vec3> position;  // world space; point and spot lights
    Track<glm::vec3> color;     // linear RGB clamped to >= 0
};

struct Animation {
    int frame_count = 1;     // frames 0 .. frame_count − 1
    double fps = 24.0;       // frames per second, > 0: frame f is at time f / fps seconds
    std::optional<CameraOrbit> orbit;  // at most one of orbit and the camera tracks
    Interpolation camera_interpolation = Interpolation::smooth;
    Track<glm::vec3> camera_position;
    Track<glm::vec3> camera_target;
    Track<float> camera_fov_y_degrees;
    std::vector<ObjectAnimation> objects;
    std::vector<LightAnimation> lights;
};

// Puts `scene` at `frame` (0 <= frame < frame_count): overwrites every
// animated value, nothing else. Since each animated value is recomputed from
// the frame number alone, a scene may be moved from frame to frame in place
// (no copy of its meshes) and frame k is the same whichever frame came before.
// A scene without animation is left as it is. Throws std::out_of_range for a
// frame outside the animation.
void set_scene_frame(Scene& scene, int frame);

// The number of frames: Animation::frame_count, or 1 for a still scene.
int scene_frame_count(const Scene& scene);

// set_scene_frame also poses each Scene::posed_models entry that plays an
// animation, at start_seconds + speed · frame / fps seconds into it.

// The CLI's --time: poses every glTF model of the scene with animations at
// `seconds` into its animation (start_seconds + speed · seconds for a
// [[models]] entry that chose one; else the one `animation_selector` names,
// an index or a name; empty = the first). Models without animations keep
// their rest pose; the rest of the scene is as loaded. Throws SceneError
// "source: ..." for a time that is not a finite number >= 0, a selector no
// model's animations match, or a scene whose models have no animation at all.
void set_scene_time(Scene& scene, double seconds, const std::string& animation_selector = "");

// The CLI's --frames on a glTF file alone: gives `scene` (make_gltf_scene's)
// an Animation at `fps` frames per second that plays the file's animation the
// selector names (as above): frames 0 .. round(duration · fps), so the last
// frame shows the animation's end. The scene is put at frame 0. Returns false
// (and changes nothing) for a file without animations and an empty selector;
// throws SceneError for a selector matching none.
bool play_gltf_animation(Scene& scene, const std::string& animation_selector = "", double fps = 24.0);

}  // namespace tessera
