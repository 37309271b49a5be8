// Evaluating an Animation at a frame: keyframe interpolation and the camera
// orbit, written into the Scene in place.
#include "tessera/animation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/animation_eval.hpp"

namespace tessera {
namespace {

glm::dvec3 widen(const glm::vec3& v) { return glm::dvec3(v); }
double widen(float v) { return double(v); }

// Hermite basis on u in [0, 1] over a segment `span` frames long, with the
// end tangents m0, m1 in value per frame.
template <typename D>
D hermite(const D& p0, const D& m0, const D& p1, const D& m1, double u, double span) {
    const double u2 = u * u, u3 = u2 * u;
    return (2 * u3 - 3 * u2 + 1) * p0 + (u3 - 2 * u2 + u) * span * m0 + (-2 * u3 + 3 * u2) * p1 +
           (u3 - u2) * span * m1;
}

}  // namespace

template <typename Value>
Value sample_track(const Track<Value>& track, Interpolation interpolation, double frame) {
    const std::vector<double>& t = track.frames;
    const std::size_t n = t.size();
    if (frame <= t.front()) return track.values.front();
    if (frame >= t.back()) return track.values.back();
    // The segment [t[i], t[i+1]) holding the frame.
    const std::size_t i = std::size_t(std::upper_bound(t.begin(), t.end(), frame) - t.begin()) - 1;
    const double span = t[i + 1] - t[i];
    const double u = (frame - t[i]) / span;
    const auto p = [&](std::size_t k) { return widen(track.values[k]); };
    if (interpolation == Interpolation::linear) return Value((1.0 - u) * p(i) + u * p(i + 1));
    using Wide = decltype(p(0));
    // Catmull-Rom tangents for uneven spacing; zero at the ends (ease in and out).
    const auto tangent = [&](std::size_t k) {
        if (k == 0 || k == n - 1) return Wide(0.0);
        return (p(k + 1) - p(k - 1)) / (t[k + 1] - t[k - 1]);
    };
    return Value(hermite(p(i), tangent(i), p(i + 1), tangent(i + 1), u, span));
}

template glm::vec3 sample_track(const Track<glm::vec3>&, Interpolation, double);
template float sample_track(const Track<float>&, Interpolation, double);

glm::vec3 orbit_position(const CameraOrbit& orbit, int frame_count, double frame) {
    // In double, so that the last frames of a long animation are as exact as the first.
    const double degrees =
        double(orbit.start_angle_degrees) + 360.0 * double(orbit.turns) * frame / double(frame_count);
    const double angle = glm::radians(degrees);
    return glm::vec3(glm::dvec3(orbit.target) +
                     glm::dvec3(orbit.radius * std::sin(angle), orbit.height, orbit.radius * std::cos(angle)));
}

glm::mat4 placement_matrix(const glm::vec3& translate, const glm::vec3& rotate_degrees, const glm::vec3& scale) {
    // Zero angles are skipped so that unrotated objects get exactly the reference's matrix;
    // X rotation is applied first. scene_file.cpp places [[objects]] and [[models]] with it too.
    glm::mat4 model = glm::translate(glm::mat4(1.0f), translate);
    if (rotate_degrees.z != 0.0f) model = glm::rotate(model, glm::radians(rotate_degrees.z), {0, 0, 1});
    if (rotate_degrees.y != 0.0f) model = glm::rotate(model, glm::radians(rotate_degrees.y), {0, 1, 0});
    if (rotate_degrees.x != 0.0f) model = glm::rotate(model, glm::radians(rotate_degrees.x), {1, 0, 0});
    if (scale != glm::vec3(1.0f)) model = glm::scale(model, scale);
    return model;
}

void evaluate_camera(const Animation& animation, double frame, Camera& camera) {
    if (animation.orbit) {
        camera.target = animation.orbit->target;
        camera.position = orbit_position(*animation.orbit, animation.frame_count, frame);
        return;
    }
    const Interpolation how = animation.camera_interpolation;
    if (!animation.camera_position.empty()) camera.position = sample_track(animation.camera_position, how, frame);
    if (!animation.camera_target.empty()) camera.target = sample_track(animation.camera_target, how, frame);
    if (!animation.camera_fov_y_degrees.empty())
        camera.fov_y_degrees = sample_track(animation.camera_fov_y_degrees, how, frame);
}

void set_scene_frame(Scene& scene, int frame) {
    if (!scene.animation) {
        if (frame != 0) throw std::out_of_range(scene.source + ": frame " + std::to_string(frame) +
                                                " of a scene without [animation] (it has only frame 0)");
        return;
    }
    const Animation& animation = *scene.animation;
    if (frame < 0 || frame >= animation.frame_count) {
        throw std::out_of_range(scene.source + ": frame " + std::to_string(frame) + " is outside the animation's " +
                                "frames 0-" + std::to_string(animation.frame_count - 1));
    }
    const double at = double(frame);
    evaluate_camera(animation, at, scene.camera);
    for (const ObjectAnimation& track : animation.objects) {
        Object& object = scene.objects[track.object];
        const Interpolation how = track.interpolation;
        const glm::vec3 translate =
            track.translate.empty() ? track.base_translate : sample_track(track.translate, how, at);
        const glm::vec3 rotate =
            track.rotate_degrees.empty() ? track.base_rotate_degrees : sample_track(track.rotate_degrees, how, at);
        const glm::vec3 scale = track.scale.empty() ? track.base_scale : sample_track(track.scale, how, at);
        object.model = placement_matrix(translate, rotate, scale);
        if (!track.color.empty())
            scene.materials[object.material].albedo =
                glm::clamp(sample_track(track.color, how, at), glm::vec3(0.0f), glm::vec3(1.0f));
    }
    for (const LightAnimation& track : animation.lights) {
        Light& light = scene.lights[track.light];
        if (!track.position.empty()) light.position = sample_track(track.position, track.interpolation, at);
        if (!track.color.empty())
            light.color = glm::max(sample_track(track.color, track.interpolation, at), glm::vec3(0.0f));
    }
    pose_models_at_frame(scene, frame, animation.fps);
}

int scene_frame_count(const Scene& scene) { return scene.animation ? scene.animation->frame_count : 1; }

}  // namespace tessera
