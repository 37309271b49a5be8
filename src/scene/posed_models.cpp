// Posing a scene's glTF models (Scene::posed_models) at a frame or a time:
// each model's meshes and objects recomputed from its rig's rest data, in
// place (gltf_animation.hpp).
#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <string>

#include "scene/animation_eval.hpp"
#include "scene/gltf/gltf_animation.hpp"
#include "tessera/animation.hpp"

namespace tessera {
namespace {

// The model's time for a scene time: start + speed · seconds, wrapped when looping.
double model_seconds(const PosedGltfModel& model, double seconds) {
    double t = model.start_seconds + model.speed * seconds;
    const double duration = model.rig->animations[std::size_t(model.animation)].duration;
    if (model.loop && duration > 0.0) {
        t = std::fmod(t, duration);
        if (t < 0.0) t += duration;
    }
    return t;
}

void pose_model(Scene& scene, const PosedGltfModel& model, int animation, double seconds) {
    gltf::NodePose pose;
    gltf::evaluate_pose(*model.rig, animation, seconds, pose);
    gltf::apply_pose(*model.rig, pose, model.placement, scene.meshes, model.first_mesh, scene.objects, model.first_object);
}

std::string text(double value) {
    std::ostringstream out;
    out << value;
    return out.str();
}

}  // namespace

void pose_models_at_frame(Scene& scene, int frame, double fps) {
    for (const PosedGltfModel& model : scene.posed_models)
        if (model.animation >= 0) pose_model(scene, model, model.animation, model_seconds(model, double(frame) / fps));
}

void set_scene_time(Scene& scene, double seconds, const std::string& animation_selector) {
    const std::string source = scene.source.empty() ? "scene" : scene.source;
    if (!std::isfinite(seconds) || seconds < 0.0)
        throw SceneError(source + ": --time " + text(seconds) + ": expected a finite number of seconds >= 0");
    bool posed = false;
    for (const PosedGltfModel& model : scene.posed_models) {
        if (model.rig->animations.empty()) continue;
        if (model.animation >= 0) {
            pose_model(scene, model, model.animation, model_seconds(model, seconds));
        } else {
            pose_model(scene, model, gltf::find_animation(*model.rig, animation_selector, "--animation"), seconds);
        }
        posed = true;
    }
    if (!posed) throw SceneError(source + ": --time: no glTF model in the scene has an animation to sample");
}

bool play_gltf_animation(Scene& scene, const std::string& animation_selector, double fps) {
    PosedGltfModel* playing = nullptr;
    for (PosedGltfModel& model : scene.posed_models)
        if (!model.rig->animations.empty()) playing = &model;
    if (playing == nullptr) {
        if (animation_selector.empty()) return false;
        throw SceneError((scene.source.empty() ? "scene" : scene.source) + ": --animation '" + animation_selector +
                         "': the file has no animations");
    }
    playing->animation = gltf::find_animation(*playing->rig, animation_selector, "--animation");
    const double duration = playing->rig->animations[std::size_t(playing->animation)].duration;
    auto animation = std::make_shared<Animation>();
    animation->fps = fps;
    // In double: a file's last key may be at any finite time (capped like [animation].frames).
    animation->frame_count = int(std::min(std::round(duration * fps), 999999.0)) + 1;
    scene.animation = animation;
    set_scene_frame(scene, 0);
    return true;
}

}  // namespace tessera
