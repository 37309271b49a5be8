// A scene file's [animation] table: frames, fps, a camera orbit or keyframes,
// object and light keyframes. The format is in docs/scene-format.md
// ("[animation]"), its one description: change the two together. Any key not
// listed there is an error.
//
// Loading gives the scene at frame 0; every frame's camera is checked at load
// (target distinct from position, up not along the view).
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string_view>
#include <utility>
#include <vector>

#include "scene/animation_eval.hpp"
#include "scene/animation_file.hpp"
#include "scene/toml_reader.hpp"

namespace tessera {
namespace {

constexpr std::int64_t kMaxFrames = 1000000;

// The [animation] table's reader: each check that fails throws with the
// offending node's position (toml_reader.hpp).
class AnimationReader : TomlReader {
public:
    AnimationReader(const std::string& source, Scene& scene) : TomlReader(source), scene_(scene) {}

    std::shared_ptr<const Animation> read(const toml::table& root, const toml::node& node) {
        const toml::table& table = table_of(node, "animation");
        check_keys(table, "animation", {"frames", "fps", "orbit", "camera", "objects", "lights"});
        auto animation = std::make_shared<Animation>();
        const toml::node& frames = require(table, "frames", "animation");
        const std::int64_t count = read_integer(frames, "animation.frames");
        if (count < 1 || count > kMaxFrames)
            fail_at(frames.source(), "expected 'animation.frames' to be in 1.." + std::to_string(kMaxFrames) +
                                         ", got " + std::to_string(count));
        animation->frame_count = int(count);
        if (const toml::node* n = table.get("fps")) {
            animation->fps = read_number(*n, "animation.fps");
            if (!(animation->fps > 0.0)) fail_at(n->source(), "expected 'animation.fps' to be > 0, got " + to_text(animation->fps));
        }
        const toml::node* orbit = table.get("orbit");
        const toml::node* camera = table.get("camera");
        if (orbit != nullptr && camera != nullptr)
            fail_at(camera->source(), "'animation.camera' (keyframes) and 'animation.orbit' both move the camera; "
                                      "give one of them");
        if (orbit != nullptr) animation->orbit = read_orbit(table_of(*orbit, "animation.orbit"));
        if (camera != nullptr) read_camera_keys(table_of(*camera, "animation.camera"), *animation);
        if (const toml::node* n = table.get("objects")) read_objects(root, *n, *animation);
        if (const toml::node* n = table.get("lights")) read_lights(root, *n, *animation);
        if (orbit != nullptr || camera != nullptr) check_cameras(*animation, orbit != nullptr ? *orbit : *camera);
        return animation;
    }

private:
    Interpolation read_interpolation(const toml::table& table, const std::string& name, Interpolation fallback) const {
        const toml::node* node = table.get("interpolation");
        if (node == nullptr) return fallback;
        const auto* text = node->as_string();
        if (text != nullptr && text->get() == "linear") return Interpolation::linear;
        if (text != nullptr && text->get() == "smooth") return Interpolation::smooth;
        fail_at(node->source(), "expected \"linear\" or \"smooth\" for '" + child(name, "interpolation") + "'");
    }

    // Calls `read_key(key_table, key_name, frame)` for each key of `table.keys`,
    // checking that frames increase strictly.
    template <typename ReadKey>
    void for_each_key(const toml::table& table, const std::string& name, ReadKey&& read_key) const {
        const std::string keys_name = child(name, "keys");
        const toml::array& keys = array_of(require(table, "keys", name), keys_name, "an array of key tables");
        if (keys.empty()) fail_at(keys.source(), "expected at least one key in '" + keys_name + "'");
        double previous = -std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < keys.size(); ++i) {
            const std::string key_name = keys_name + "[" + std::to_string(i) + "]";
            const toml::table& key = table_of(*keys.get(i), key_name);
            const toml::node& frame_node = require(key, "frame", key_name);
            const double frame = read_number(frame_node, child(key_name, "frame"));
            if (!(frame > previous))
                fail_at(frame_node.source(), "expected '" + child(key_name, "frame") +
                                                 "' to be greater than the previous key's frame " + to_text(previous) +
                                                 ", got " + to_text(frame));
            previous = frame;
            read_key(key, key_name, frame);
        }
    }

    template <typename Value>
    static void add_key(Track<Value>& track, double frame, const Value& value) {
        track.frames.push_back(frame);
        track.values.push_back(value);
    }

    CameraOrbit read_orbit(const toml::table& table) const {
        const std::string name = "animation.orbit";
        check_keys(table, name, {"target", "radius", "height", "start_angle", "turns"});
        const Camera& camera = scene_.camera;
        CameraOrbit orbit;
        orbit.target = camera.target;
        if (const toml::node* n = table.get("target")) orbit.target = read_vec3(*n, child(name, "target"));
        const glm::dvec3 offset = glm::dvec3(camera.position) - glm::dvec3(orbit.target);
        orbit.radius = float(std::hypot(offset.x, offset.z));
        orbit.height = float(offset.y);
        orbit.start_angle_degrees = float(glm::degrees(std::atan2(offset.x, offset.z)));
        if (const toml::node* n = table.get("radius")) {
            orbit.radius = float(read_number(*n, child(name, "radius")));
            if (!(orbit.radius > 0.0f))
                fail_at(n->source(), "expected '" + child(name, "radius") + "' to be > 0, got " + to_text(orbit.radius));
        } else if (!(orbit.radius > 0.0f)) {
            fail_at(table.source(), "'animation.orbit' needs a 'radius': the camera is straight above or below "
                                    "the target, so it gives none");
        }
        if (const toml::node* n = table.get("height")) orbit.height = float(read_number(*n, child(name, "height")));
        if (const toml::node* n = table.get("start_angle"))
            orbit.start_angle_degrees = float(read_number(*n, child(name, "start_angle")));
        if (const toml::node* n = table.get("turns")) orbit.turns = float(read_number(*n, child(name, "turns")));
        return orbit;
    }

    void read_camera_keys(const toml::table& table, Animation& animation) const {
        const std::string name = "animation.camera";
        check_keys(table, name, {"interpolation", "keys"});
        animation.camera_interpolation = read_interpolation(table, name, Interpolation::smooth);
        for_each_key(table, name, [&](const toml::table& key, const std::string& key_name, double frame) {
            check_keys(key, key_name, {"frame", "position", "target", "fov_y"});
            if (const toml::node* n = key.get("position"))
                add_key(animation.camera_position, frame, read_vec3(*n, child(key_name, "position")));
            if (const toml::node* n = key.get("target"))
                add_key(animation.camera_target, frame, read_vec3(*n, child(key_name, "target")));
            if (const toml::node* n = key.get("fov_y")) {
                const double fov = read_number(*n, child(key_name, "fov_y"));
                if (!(fov > 0.0 && fov < 180.0))
                    fail_at(n->source(), "expected '" + child(key_name, "fov_y") + "' to be in (0, 180) degrees, got " +
                                             to_text(fov));
                add_key(animation.camera_fov_y_degrees, frame, float(fov));
            }
        });
        // Smooth interpolation can overshoot: the fov must stay in (0, 180) between keys too.
        if (!animation.camera_fov_y_degrees.empty()) {
            for (int f = 0; f < animation.frame_count; ++f) {
                const float fov = sample_track(animation.camera_fov_y_degrees, animation.camera_interpolation, f);
                if (!(fov > 0.0f && fov < 180.0f))
                    fail_at(table.source(), "the camera's fov_y leaves (0, 180) degrees at frame " + std::to_string(f) +
                                                " (" + to_text(fov) + "): smooth interpolation overshoots; add a key "
                                                "or use \"linear\"");
            }
        }
    }

    // An index into [[objects]] or [[lights]], used at most once.
    std::uint32_t read_index(const toml::table& table, std::string_view key, const std::string& name, std::size_t count,
                             std::string_view what, std::set<std::int64_t>& used) const {
        const toml::node& node = require(table, key, name);
        const std::int64_t index = read_integer(node, child(name, key));
        if (index < 0 || std::uint64_t(index) >= count)
            fail_at(node.source(), "expected '" + child(name, key) + "' to be the index of one of the " +
                                       std::to_string(count) + " " + std::string(what) + " (0.." +
                                       std::to_string(std::int64_t(count) - 1) + "), got " + std::to_string(index));
        if (!used.insert(index).second)
            fail_at(node.source(), std::string(what) + " " + std::to_string(index) + " is animated twice");
        return std::uint32_t(index);
    }

    void read_objects(const toml::table& root, const toml::node& node, Animation& animation) {
        const toml::array& entries = array_of(node, "animation.objects", "an array of tables");
        // [[objects]] are read before [[models]]: scene_.objects[i] is the file's objects[i].
        const toml::array* file_objects = root["objects"].as_array();
        const std::size_t count = file_objects != nullptr ? file_objects->size() : 0;
        std::set<std::int64_t> used;
        for (std::size_t i = 0; i < entries.size(); ++i) {
            const std::string name = "animation.objects[" + std::to_string(i) + "]";
            const toml::table& table = table_of(*entries.get(i), name);
            check_keys(table, name, {"object", "interpolation", "keys"});
            ObjectAnimation track;
            track.object = read_index(table, "object", name, count, "[[objects]]", used);
            track.interpolation = read_interpolation(table, name, Interpolation::linear);
            // The static placement, already validated by the scene reader.
            const toml::table& placed = *file_objects->get(track.object)->as_table();
            if (const toml::node* n = placed.get("translate")) track.base_translate = read_vec3(*n, "translate");
            if (const toml::node* n = placed.get("rotate")) track.base_rotate_degrees = read_vec3(*n, "rotate");
            if (const toml::node* n = placed.get("scale")) track.base_scale = read_scale(*n, "scale");
            for_each_key(table, name, [&](const toml::table& key, const std::string& key_name, double frame) {
                check_keys(key, key_name, {"frame", "translate", "rotate", "scale", "color"});
                if (const toml::node* n = key.get("translate"))
                    add_key(track.translate, frame, read_vec3(*n, child(key_name, "translate")));
                if (const toml::node* n = key.get("rotate"))
                    add_key(track.rotate_degrees, frame, read_vec3(*n, child(key_name, "rotate")));
                if (const toml::node* n = key.get("scale")) add_key(track.scale, frame, read_scale(*n, child(key_name, "scale")));
                if (const toml::node* n = key.get("color"))
                    add_key(track.color, frame, read_vec3(*n, child(key_name, "color"), kUnitInterval));
            });
            if (!track.color.empty()) {
                // Its own material: a named material may be shared with objects that keep their colour.
                Object& object = scene_.objects[track.object];
                scene_.materials.push_back(scene_.materials[object.material]);
                object.material = std::uint32_t(scene_.materials.size() - 1);
            }
            animation.objects.push_back(std::move(track));
        }
    }

    void read_lights(const toml::table& root, const toml::node& node, Animation& animation) const {
        const toml::array& entries = array_of(node, "animation.lights", "an array of tables");
        // [[lights]] are read before [[models]] add theirs: scene_.lights[i] is the file's lights[i].
        const toml::array* file_lights = root["lights"].as_array();
        const std::size_t count = file_lights != nullptr ? file_lights->size() : 0;
        std::set<std::int64_t> used;
        for (std::size_t i = 0; i < entries.size(); ++i) {
            const std::string name = "animation.lights[" + std::to_string(i) + "]";
            const toml::table& table = table_of(*entries.get(i), name);
            check_keys(table, name, {"light", "interpolation", "keys"});
            LightAnimation track;
            track.light = read_index(table, "light", name, count, "[[lights]]", used);
            track.interpolation = read_interpolation(table, name, Interpolation::linear);
            const bool directional = scene_.lights[track.light].type == LightType::directional;
            for_each_key(table, name, [&](const toml::table& key, const std::string& key_name, double frame) {
                check_keys(key, key_name, {"frame", "position", "color"});
                if (const toml::node* n = key.get("position")) {
                    if (directional)
                        fail_at(n->source(), "'" + child(key_name, "position") + "' does not apply to a directional light");
                    add_key(track.position, frame, read_vec3(*n, child(key_name, "position")));
                }
                if (const toml::node* n = key.get("color"))
                    add_key(track.color, frame, read_vec3(*n, child(key_name, "color"), kNonNegative));
            });
            animation.lights.push_back(std::move(track));
        }
    }

    // Every frame's camera must make a view: lookAt needs a direction not along up.
    void check_cameras(const Animation& animation, const toml::node& where) const {
        Camera camera = scene_.camera;
        for (int f = 0; f < animation.frame_count; ++f) {
            evaluate_camera(animation, f, camera);
            const glm::vec3 forward = camera.target - camera.position;
            const float scale = std::max({1.0f, glm::length(camera.position), glm::length(camera.target)});
            if (!(glm::length(forward) > 1e-6f * scale))
                fail_at(where.source(), "at frame " + std::to_string(f) + " the camera's target is its position");
            const float sine = glm::length(glm::cross(glm::normalize(forward), glm::normalize(camera.up)));
            if (!(sine > 1e-5f))
                fail_at(where.source(), "at frame " + std::to_string(f) +
                                            " the camera looks along its up vector ([camera].up): no view is defined");
        }
    }

    Scene& scene_;
};

}  // namespace

std::shared_ptr<const Animation> read_animation(const toml::table& root, const std::string& source, Scene& scene) {
    const toml::node* node = root.get("animation");
    if (node == nullptr) return nullptr;
    return AnimationReader(source, scene).read(root, *node);
}

}  // namespace tessera
