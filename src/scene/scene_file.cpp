// Scene files: TOML in, a validated tessera::Scene out.
//
// The format — every table, key, default and limit — is docs/scene-format.md,
// its one description: change the two together. Any key not listed there is an
// error, so typos do not pass silently.
//
// A model brings its meshes, materials and textures (gltf_import.hpp says what
// is supported); its cameras are not used ([camera] is). A file placed several
// times is imported once (and once per process with load_scene_file(path,
// ModelCache&), model_cache.hpp); its placements share its textures. An object's model
// matrix is translate · Rz · Ry · Rx · scale. Integers are
// accepted wherever a number is expected; NaN and infinities are rejected.
// Each built-in mesh is created once and shared by all objects that use it (per uv_scale);
// Scene::meshes and Scene::materials hold only what objects use, in order of
// first use (each inline material is its own entry).
//
// load_scene_file also reads a .gltf or .glb file on its own as a whole scene
// (make_gltf_scene: its camera and lights, or ones framing the model).
//
// Errors throw SceneError reading "file:line:column: message", the position
// being that of the offending value (or of its table when a key is missing);
// "file: message" where no position applies. Values are named by their path
// in the document, e.g. 'objects[3].material.metallic'.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <toml++/toml.h>

#include "environment/environment_cache.hpp"
#include "io/input_file.hpp"
#include "io/nesting_depth.hpp"
#include "scene/animation_eval.hpp"
#include "scene/animation_file.hpp"
#include "scene/gltf/gltf_animation.hpp"
#include "scene/gltf/gltf_import.hpp"
#include "scene/model_cache.hpp"
#include "scene/scene_validation.hpp"
#include "scene/toml_reader.hpp"
#include "tessera/scene.hpp"
#include "texture/texture.hpp"

namespace tessera {
namespace {

constexpr std::string_view kSupportedMeshes = "sphere, plane, cube";
constexpr std::string_view kSupportedLightTypes = "point, directional, spot";

// Walks one parsed document; every check that fails throws with the document's
// name and the offending node's position.
class SceneReader : TomlReader {
public:
    explicit SceneReader(std::string source, ModelCache* models = nullptr)
        : TomlReader(std::move(source)), base_dir_(std::filesystem::path(this->source()).parent_path()), models_(models) {}

    Scene read(const toml::table& root) {
        check_keys(root, "", {"output", "camera", "lights", "environment", "materials", "objects", "models", "animation",
                              "shadows"});
        Scene scene;
        scene.source = source();
        if (const toml::node* output = root.get("output")) {
            read_output(table_of(*output, "output"), scene);
        }
        const toml::node* camera = root.get("camera");
        if (camera == nullptr) fail("missing required table [camera]");
        scene.camera = read_camera(table_of(*camera, "camera"));
        if (const toml::node* shadows = root.get("shadows")) read_shadow_defaults(table_of(*shadows, "shadows"));
        if (const toml::node* lights = root.get("lights")) read_lights(*lights, scene);
        if (const toml::node* environment = root.get("environment"))
            read_environment(table_of(*environment, "environment"), scene);
        if (const toml::node* materials = root.get("materials")) read_named_materials(*materials);
        if (const toml::node* objects = root.get("objects")) read_objects(*objects, scene);
        // The file's own textures first: models append theirs after them.
        scene.textures = std::move(textures_);
        if (const toml::node* models = root.get("models")) read_models(*models, scene);
        // [animation] (src/scene/animation_file.cpp): the scene as loaded is its frame 0.
        scene.animation = read_animation(root, source(), scene);
        set_scene_frame(scene, 0);
        if (!scene.animation) pose_models_at_frame(scene, 0, 24.0);  // models playing from their start time
        return scene;
    }

private:
    int read_dimension(const toml::node& node, const std::string& name) const {
        const std::int64_t value = read_integer(node, name);
        if (value < 1 || value > kMaxImageDimension) {
            fail_at(node.source(), "expected '" + name + "' to be in 1.." +
                                       std::to_string(kMaxImageDimension) + ", got " +
                                       std::to_string(value));
        }
        return static_cast<int>(value);
    }

    void read_output(const toml::table& output, Scene& scene) const {
        check_keys(output, "output", {"width", "height", "clear_color", "msaa"});
        if (const toml::node* n = output.get("width")) scene.width = read_dimension(*n, "output.width");
        if (const toml::node* n = output.get("height")) scene.height = read_dimension(*n, "output.height");
        // 16384 per side is allowed, but not both at once: the frame would need ~4 GB.
        const long long pixels = static_cast<long long>(scene.width) * scene.height;
        if (pixels > kMaxImagePixels) {
            const toml::node* at = output.get("height") != nullptr ? output.get("height") : output.get("width");
            fail_at(at != nullptr ? at->source() : output.source(),
                    "output size " + std::to_string(scene.width) + "x" + std::to_string(scene.height) + " is " +
                        std::to_string(pixels) + " pixels; at most " + std::to_string(kMaxImagePixels) +
                        " are allowed");
        }
        if (const toml::node* n = output.get("clear_color")) {
            scene.clear_color = read_vec3(*n, "output.clear_color", kUnitInterval);
        }
        if (const toml::node* n = output.get("msaa")) {
            const std::int64_t msaa = read_integer(*n, "output.msaa");
            if (msaa != 1 && msaa != 4)
                fail_at(n->source(), "expected 'output.msaa' to be 1 or 4, got " + std::to_string(msaa));
            scene.msaa = static_cast<int>(msaa);
        }
    }

    // [environment]: file (an equirectangular .hdr or .exr, relative to the
    // scene file), intensity >= 0, rotation (degrees about +Y), background.
    void read_environment(const toml::table& table, Scene& scene) const {
        check_keys(table, "environment", {"file", "intensity", "rotation", "background"});
        const toml::node& file_node = require(table, "file", "environment");
        const std::filesystem::path file = base_dir_ / read_string(file_node, "environment.file");
        if (const toml::node* n = table.get("intensity"))
            scene.environment.intensity = read_float(*n, "environment.intensity", kNonNegative);
        if (const toml::node* n = table.get("rotation"))
            scene.environment.rotation_degrees = read_float(*n, "environment.rotation");
        if (const toml::node* n = table.get("background"))
            scene.environment.background = read_bool(*n, "environment.background");
        scene.environment.file = file.string();
        try {
            scene.environment.maps = environment::acquire_environment(file);
        } catch (const environment::EnvironmentError& error) {
            fail_at(file_node.source(), "cannot load the environment for 'environment.file': " + std::string(error.what()));
        }
    }

    Camera read_camera(const toml::table& table) const {
        check_keys(table, "camera", {"position", "target", "up", "fov_y", "near", "far", "projection", "xmag", "ymag"});
        Camera camera;
        if (const toml::node* projection = table.get("projection")) {
            const std::string text = read_string(*projection, "camera.projection");
            if (text == "orthographic") camera.projection = Projection::orthographic;
            else if (text != "perspective")
                fail_at(projection->source(), "unsupported camera projection '" + text +
                                                  "' for 'camera.projection'; expected \"perspective\" or \"orthographic\"");
        }
        const bool orthographic = camera.projection == Projection::orthographic;
        for (const char* key : {"xmag", "ymag"}) {
            const toml::node* node = table.get(key);
            if (node == nullptr) continue;
            const std::string name = std::string("camera.") + key;
            if (!orthographic) fail_at(node->source(), "'" + name + "' applies to projection = \"orthographic\" only");
            const float value = read_float(*node, name);
            if (!(value > 0.0f && std::isfinite(value)))
                fail_at(node->source(), "expected '" + name + "' to be a finite number > 0, got " + to_text(value));
            (key[0] == 'x' ? camera.x_magnification : camera.y_magnification) = value;
        }
        if (orthographic && table.get("fov_y") != nullptr)
            fail_at(table.get("fov_y")->source(), "'camera.fov_y' does not apply to an orthographic camera (use xmag, ymag)");
        camera.position = read_vec3(require(table, "position", "camera"), "camera.position");
        const toml::node& target = require(table, "target", "camera");
        camera.target = read_vec3(target, "camera.target");
        const toml::node* up = table.get("up");
        if (up != nullptr) camera.up = read_vec3(*up, "camera.up");

        if (const toml::node* fov = table.get("fov_y")) {
            camera.fov_y_degrees = read_float(*fov, "camera.fov_y");
            if (!(camera.fov_y_degrees > 0.0f && camera.fov_y_degrees < 180.0f)) {
                fail_at(fov->source(), "expected 'camera.fov_y' to be in (0, 180) degrees, got " +
                                           to_text(camera.fov_y_degrees));
            }
        }
        const toml::node* near = table.get("near");
        if (near != nullptr) {
            camera.near_plane = read_float(*near, "camera.near");
            if (!(orthographic ? camera.near_plane >= 0.0f : camera.near_plane > 0.0f)) {
                fail_at(near->source(), std::string("expected 'camera.near' to be ") + (orthographic ? ">= 0" : "> 0") +
                                            ", got " + to_text(camera.near_plane));
            }
        }
        const toml::node* far = table.get("far");
        if (far != nullptr) camera.far_plane = read_float(*far, "camera.far");
        if (!(camera.near_plane < camera.far_plane)) {
            const toml::node* at = far != nullptr ? far : near;
            fail_at(at != nullptr ? at->source() : table.source(), "expected 'camera.near' < 'camera.far', got near = " +
                                      to_text(camera.near_plane) +
                                      ", far = " + to_text(camera.far_plane));
        }

        // lookAt needs a view direction and an up vector not parallel to it.
        const glm::vec3 forward = camera.target - camera.position;
        const float scale = std::max({1.0f, glm::length(camera.position), glm::length(camera.target)});
        if (!(glm::length(forward) > 1e-6f * scale)) {
            fail_at(target.source(), "expected 'camera.target' to differ from 'camera.position'");
        }
        const float up_length = glm::length(camera.up);
        const float sine = up_length > 0.0f
                               ? glm::length(glm::cross(glm::normalize(forward), camera.up / up_length))
                               : 0.0f;
        if (!(sine > 1e-5f)) {
            fail_at(up != nullptr ? up->source() : table.source(),
                    "expected 'camera.up' to be non-zero and not parallel to the view direction "
                    "(target - position)");
        }
        return camera;
    }

    LightType read_light_type(const toml::table& table, const std::string& name) const {
        const toml::node* type = table.get("type");
        if (type == nullptr) return LightType::point;
        const std::string type_text = read_string(*type, child(name, "type"));
        if (type_text == "point") return LightType::point;
        if (type_text == "directional") return LightType::directional;
        if (type_text == "spot") return LightType::spot;
        fail_at(type->source(), "unsupported light type '" + type_text + "' for '" + child(name, "type") +
                                    "'; supported types: " + std::string(kSupportedLightTypes));
    }

    // A key given to a light type it does not apply to: an error, as unknown keys are.
    void refuse_key(const toml::table& table, std::string_view key, const std::string& name,
                    std::string_view type_text) const {
        const toml::node* node = table.get(key);
        if (node == nullptr) return;
        fail_at(node->source(), "'" + child(name, key) + "' does not apply to a " + std::string(type_text) + " light");
    }

    float read_cone_degrees(const toml::node& node, const std::string& name) const {
        const float degrees = read_float(node, name);
        if (!(degrees >= 0.0f && degrees <= 90.0f)) {
            fail_at(node.source(), "expected '" + name + "' to be in [0, 90] degrees, got " + to_text(degrees));
        }
        return degrees;
    }

    // [shadows]: what every light of the file (its own and its models') takes
    // unless it says otherwise.
    void read_shadow_defaults(const toml::table& table) {
        check_keys(table, "shadows", {"enabled", "map_size", "filter_radius"});
        if (const toml::node* n = table.get("enabled")) shadow_defaults_.shadows = read_bool(*n, "shadows.enabled");
        read_shadow_settings(table, "shadows", "map_size", "filter_radius", shadow_defaults_);
    }

    void read_shadow_settings(const toml::table& table, const std::string& name, std::string_view size_key,
                              std::string_view radius_key, Light& light) const {
        if (const toml::node* n = table.get(size_key)) {
            const std::int64_t size = read_integer(*n, child(name, size_key));
            if (size < kMinShadowMapSize || size > kMaxShadowMapSize)
                fail_at(n->source(), "expected '" + child(name, size_key) + "' to be in " +
                                         std::to_string(kMinShadowMapSize) + ".." + std::to_string(kMaxShadowMapSize) +
                                         " texels, got " + std::to_string(size));
            light.shadow_map_size = int(size);
        }
        if (const toml::node* n = table.get(radius_key)) {
            const std::int64_t radius = read_integer(*n, child(name, radius_key));
            if (radius < 0 || radius > kMaxShadowFilterRadius)
                fail_at(n->source(), "expected '" + child(name, radius_key) + "' to be in 0.." +
                                         std::to_string(kMaxShadowFilterRadius) + ", got " + std::to_string(radius));
            light.shadow_filter_radius = int(radius);
        }
    }

    void read_lights(const toml::node& node, Scene& scene) const {
        const toml::array& lights = array_of(node, "lights");
        for (std::size_t i = 0; i < lights.size(); ++i) {
            const std::string name = "lights[" + std::to_string(i) + "]";
            const toml::table& table = table_of(*lights.get(i), name);
            check_keys(table, name, {"type", "position", "color", "direction", "inner_cone", "outer_cone", "range",
                                     "shadows", "shadow_map_size", "shadow_filter_radius"});
            Light light;
            apply_shadow_defaults(light);
            if (const toml::node* n = table.get("shadows")) light.shadows = read_bool(*n, child(name, "shadows"));
            read_shadow_settings(table, name, "shadow_map_size", "shadow_filter_radius", light);
            light.type = read_light_type(table, name);
            const std::string_view type_text = light.type == LightType::point         ? "point"
                                               : light.type == LightType::directional ? "directional"
                                                                                      : "spot";
            light.color = read_vec3(require(table, "color", name), child(name, "color"), kNonNegative);
            if (light.type == LightType::directional) {
                refuse_key(table, "position", name, type_text);
                refuse_key(table, "range", name, type_text);  // everywhere at once: nothing to cull by
            } else {
                light.position = read_vec3(require(table, "position", name), child(name, "position"));
            }
            if (light.type == LightType::point) {
                refuse_key(table, "direction", name, type_text);
            } else {
                const toml::node& direction = require(table, "direction", name);
                const glm::vec3 d = read_vec3(direction, child(name, "direction"));
                // Squared length in double: components near 1e-20 are still a direction.
                const double length = std::sqrt(double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z);
                if (!(length > 0.0)) {
                    fail_at(direction.source(), "expected '" + child(name, "direction") + "' to be non-zero");
                }
                light.direction = glm::vec3(glm::dvec3(d) / length);
            }
            if (light.type != LightType::spot) {
                refuse_key(table, "inner_cone", name, type_text);
                refuse_key(table, "outer_cone", name, type_text);
            } else {
                const toml::node* inner = table.get("inner_cone");
                const toml::node* outer = table.get("outer_cone");
                if (inner != nullptr) light.inner_cone_degrees = read_cone_degrees(*inner, child(name, "inner_cone"));
                if (outer != nullptr) light.outer_cone_degrees = read_cone_degrees(*outer, child(name, "outer_cone"));
                if (!(light.inner_cone_degrees < light.outer_cone_degrees)) {
                    const toml::node* at = inner != nullptr ? inner : outer;
                    fail_at(at->source(), "expected '" + child(name, "inner_cone") + "' < '" +
                                              child(name, "outer_cone") + "', got inner = " +
                                              to_text(light.inner_cone_degrees) +
                                              ", outer = " + to_text(light.outer_cone_degrees));
                }
            }
            if (const toml::node* range = table.get("range")) light.range = read_range(*range, child(name, "range"), light);
            scene.lights.push_back(light);
        }
    }

    float read_range(const toml::node& node, const std::string& name, const Light& light) const {
        if (const auto* text = node.as_string()) {
            if (text->get() != "auto") {
                fail_at(node.source(), "expected a number > 0 or \"auto\" for '" + name + "', got \"" + text->get() + "\"");
            }
            return auto_light_range(light.color);
        }
        if (!node.is_number()) fail_type(node, "a number > 0 or \"auto\"", name);
        const float range = read_float(node, name);
        if (!(range > 0.0f)) {
            fail_at(node.source(), "expected '" + name + "' to be > 0 (leave it out for unlimited), got " + to_text(range));
        }
        return range;
    }

    Material read_material(const toml::table& table, const std::string& name) {
        check_keys(table, name, {"albedo", "metallic", "roughness", "ao", "emissive", "albedo_map", "albedo_map_encoding",
                                 "metallic_map", "roughness_map", "ao_map", "normal_map", "normal_scale",
                                 "emissive_map", "wrap", "wrap_s", "wrap_t", "mag_filter", "min_filter",
                                 "double_sided", "alpha_mode", "alpha", "alpha_cutoff", "unlit"});
        Material material;
        // One name out of `names` (the enum's values in order) for key.
        const auto choice = [&](const char* key, std::initializer_list<const char*> names, int fallback) {
            const toml::node* n = table.get(key);
            if (n == nullptr) return fallback;
            const std::string text = read_string(*n, child(name, key));
            int index = 0;
            for (const char* option : names) {
                if (text == option) return index;
                ++index;
            }
            std::string expected;
            index = 0;
            for (const char* option : names)
                expected += (index++ == 0 ? "'" : index == int(names.size()) ? " or '" : ", '") + std::string(option) + "'";
            fail_at(n->source(), "expected " + expected + " for '" + child(name, key) + "', got '" + text + "'");
        };
        const std::initializer_list<const char*> wraps = {"repeat", "clamp_to_edge", "mirrored_repeat"};
        TextureSlot sampling;  // every map of the material is sampled alike
        const int wrap = choice("wrap", wraps, 0);
        sampling.wrap_s = TextureWrap(choice("wrap_s", wraps, wrap));
        sampling.wrap_t = TextureWrap(choice("wrap_t", wraps, wrap));
        sampling.mag_filter = TextureFilter(choice("mag_filter", {"nearest", "linear"}, 1));
        sampling.min_filter = TextureFilter(choice("min_filter",
                                                   {"nearest", "linear", "nearest_mipmap_nearest", "linear_mipmap_nearest",
                                                    "nearest_mipmap_linear", "linear_mipmap_linear"},
                                                   5));
        // A map multiplies its factor; with a map and no factor, the factor is 1.
        const auto map = [&](std::string_view key, texture::ColorSpace color_space, TextureSlot& slot) {
            const toml::node* n = table.get(key);
            if (n == nullptr) return false;
            slot = sampling;
            slot.texture = texture_index(*n, child(name, key), color_space);
            return true;
        };
        texture::ColorSpace albedo_space = texture::ColorSpace::linear;
        material.albedo_decode = AlbedoDecode::pow_2_2_after_filter;
        if (const toml::node* n = table.get("albedo_map_encoding")) {
            const std::string text = read_string(*n, child(name, "albedo_map_encoding"));
            if (text == "srgb") {
                albedo_space = texture::ColorSpace::srgb, material.albedo_decode = AlbedoDecode::linear;
            } else if (text == "linear") {
                material.albedo_decode = AlbedoDecode::linear;
            } else if (text != "gamma2.2") {
                fail_at(n->source(), "expected 'gamma2.2', 'srgb' or 'linear' for '" +
                                         child(name, "albedo_map_encoding") + "', got '" + text + "'");
            }
        }
        if (map("albedo_map", albedo_space, material.albedo_map)) material.albedo = glm::vec3(1.0f);
        if (map("metallic_map", texture::ColorSpace::linear, material.metallic_map)) material.metallic = 1.0f;
        if (map("roughness_map", texture::ColorSpace::linear, material.roughness_map)) material.roughness = 1.0f;
        map("ao_map", texture::ColorSpace::linear, material.ao_map);
        map("normal_map", texture::ColorSpace::linear, material.normal_map);
        if (map("emissive_map", texture::ColorSpace::srgb, material.emissive_map)) material.emissive = glm::vec3(1.0f);
        if (const toml::node* n = table.get("albedo")) {
            material.albedo = read_vec3(*n, child(name, "albedo"), kUnitInterval);
        }
        if (const toml::node* n = table.get("metallic")) {
            material.metallic = read_float(*n, child(name, "metallic"), kUnitInterval);
        }
        if (const toml::node* n = table.get("roughness")) {
            material.roughness = read_float(*n, child(name, "roughness"), kUnitInterval);
        }
        if (const toml::node* n = table.get("ao")) {
            material.ao = read_float(*n, child(name, "ao"), kUnitInterval);
        }
        if (const toml::node* n = table.get("emissive")) {
            material.emissive = read_vec3(*n, child(name, "emissive"), kNonNegative);
        }
        if (const toml::node* n = table.get("normal_scale")) {
            material.normal_scale = read_float(*n, child(name, "normal_scale"));
        }
        if (const toml::node* n = table.get("double_sided")) material.double_sided = read_bool(*n, child(name, "double_sided"));
        if (const toml::node* n = table.get("unlit")) material.unlit = read_bool(*n, child(name, "unlit"));
        if (const toml::node* n = table.get("alpha_mode")) {
            const std::string text = read_string(*n, child(name, "alpha_mode"));
            if (text == "mask") {
                material.alpha_mode = AlphaMode::mask;
            } else if (text == "blend") {
                material.alpha_mode = AlphaMode::blend;
            } else if (text != "opaque") {
                fail_at(n->source(), "expected 'opaque', 'mask' or 'blend' for '" + child(name, "alpha_mode") + "', got '" +
                                         text + "'");
            }
        }
        if (const toml::node* n = table.get("alpha")) material.alpha_factor = read_float(*n, child(name, "alpha"), kUnitInterval);
        if (const toml::node* n = table.get("alpha_cutoff"))
            material.alpha_cutoff = read_float(*n, child(name, "alpha_cutoff"), kNonNegative);
        return material;
    }

    // The texture a path names (relative to the scene file's folder), loaded
    // once per path and colour space.
    std::int32_t texture_index(const toml::node& node, const std::string& name, texture::ColorSpace color_space) {
        const std::filesystem::path path =
            std::filesystem::path(source()).parent_path() / std::filesystem::path(read_string(node, name));
        const std::string key = path.lexically_normal().string() + (color_space == texture::ColorSpace::srgb ? "|srgb" : "");
        if (const auto loaded = texture_indices_.find(key); loaded != texture_indices_.end()) return loaded->second;
        try {
            textures_.push_back(std::make_shared<const texture::Texture>(texture::Texture::load(path, color_space)));
        } catch (const texture::TextureError& error) {
            fail_at(node.source(), "cannot load the texture for '" + name + "': " + error.what());
        }
        const auto index = static_cast<std::int32_t>(textures_.size() - 1);
        texture_indices_.emplace(key, index);
        return index;
    }

    // All named materials are validated, used or not.
    void read_named_materials(const toml::node& node) {
        const toml::table& materials = table_of(node, "materials");
        for (auto&& [key, value] : materials) {
            const std::string name = child("materials", key.str());
            named_materials_.emplace(std::string(key.str()), read_material(table_of(value, name), name));
        }
    }

    std::uint32_t material_index(const toml::node* node, const std::string& name, Scene& scene) {
        const auto add = [&scene](const Material& material) {
            scene.materials.push_back(material);
            return static_cast<std::uint32_t>(scene.materials.size() - 1);
        };
        if (node == nullptr) {
            if (!default_material_) default_material_ = add(Material{});
            return *default_material_;
        }
        if (const toml::table* inline_table = node->as_table()) {
            return add(read_material(*inline_table, name));
        }
        if (node->as_string() == nullptr) {
            fail_type(*node, "a material name or an inline material table", name);
        }
        const std::string material_name = read_string(*node, name);
        if (const auto used = used_materials_.find(material_name); used != used_materials_.end()) {
            return used->second;
        }
        const auto named = named_materials_.find(material_name);
        if (named == named_materials_.end()) {
            std::string known;
            for (const auto& [known_name, material] : named_materials_) {
                known += (known.empty() ? "" : ", ") + known_name;
            }
            fail_at(node->source(), "unknown material '" + material_name + "' for '" + name + "'; " +
                                        (known.empty() ? "no materials are defined in [materials]"
                                                       : "defined materials: " + known));
        }
        const std::uint32_t index = add(named->second);
        used_materials_.emplace(material_name, index);
        return index;
    }

    // uv_scale: a number or [u, v], each > 0 (and finite): the texture repeats that often across the mesh.
    glm::vec2 read_uv_scale(const toml::node& node, const std::string& name) const {
        constexpr ValueRange kPositive{std::numeric_limits<float>::min(), std::numeric_limits<double>::max(), "> 0"};
        if (node.is_number()) return glm::vec2(read_float(node, name, kPositive));
        const toml::array* array = node.as_array();
        if (array == nullptr) fail_type(node, "a number or an array [u, v] of 2 numbers", name);
        if (array->size() != 2)
            fail_at(node.source(), "expected an array [u, v] of 2 numbers for '" + name + "', got " +
                                       std::to_string(array->size()) + " elements");
        return {read_float(*array->get(0), name + "[0]", kPositive), read_float(*array->get(1), name + "[1]", kPositive)};
    }

    // Objects that tile their texture differently get their own copy of the mesh.
    std::uint32_t mesh_index(const toml::node& node, const std::string& name, glm::vec2 uv_scale, Scene& scene) {
        const std::string mesh_name = read_string(node, name);
        const std::string key = uv_scale == glm::vec2(1.0f)
                                    ? mesh_name
                                    : mesh_name + " (uv_scale " + to_text(uv_scale.x) + " " + to_text(uv_scale.y) + ")";
        if (const auto used = used_meshes_.find(key); used != used_meshes_.end()) {
            return used->second;
        }
        Mesh mesh;
        if (mesh_name == "sphere") {
            mesh = make_sphere_mesh();
        } else if (mesh_name == "plane") {
            mesh = make_plane_mesh();
        } else if (mesh_name == "cube") {
            mesh = make_cube_mesh();
        } else {
            fail_at(node.source(), "unknown mesh '" + mesh_name + "' for '" + name +
                                       "'; built-in meshes: " + std::string(kSupportedMeshes));
        }
        if (key != mesh_name) {
            mesh.name = key;
            for (glm::vec2& uv : mesh.uvs) uv *= uv_scale;
        }
        scene.meshes.push_back(std::move(mesh));
        const auto index = static_cast<std::uint32_t>(scene.meshes.size() - 1);
        used_meshes_.emplace(key, index);
        return index;
    }

    void read_objects(const toml::node& node, Scene& scene) {
        const toml::array& objects = array_of(node, "objects");
        for (std::size_t i = 0; i < objects.size(); ++i) {
            const std::string name = "objects[" + std::to_string(i) + "]";
            const toml::table& table = table_of(*objects.get(i), name);
            check_keys(table, name, {"mesh", "material", "translate", "rotate", "scale", "uv_scale"});
            Object object;
            glm::vec2 uv_scale{1.0f};
            if (const toml::node* n = table.get("uv_scale")) uv_scale = read_uv_scale(*n, child(name, "uv_scale"));
            object.mesh = mesh_index(require(table, "mesh", name), child(name, "mesh"), uv_scale, scene);
            object.material = material_index(table.get("material"), child(name, "material"), scene);

            object.model = read_placement(table, name);
            object.id = std::uint32_t(scene.objects.size() + 1);  // an entry is one object (Object::id)
            scene.objects.push_back(object);
        }
    }

    // translate · Rz · Ry · Rx · scale: X rotation is applied first. Zero
    // angles are skipped so unrotated objects get exactly the reference's matrix.
    glm::mat4 read_placement(const toml::table& table, const std::string& name) const {
        glm::vec3 translate{0.0f};
        glm::vec3 rotate_degrees{0.0f};
        glm::vec3 scale{1.0f};
        if (const toml::node* n = table.get("translate")) translate = read_vec3(*n, child(name, "translate"));
        if (const toml::node* n = table.get("rotate")) rotate_degrees = read_vec3(*n, child(name, "rotate"));
        if (const toml::node* n = table.get("scale")) scale = read_scale(*n, child(name, "scale"));
        return placement_matrix(translate, rotate_degrees, scale);
    }

    static bool finite_matrix(const glm::mat4& m) {
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                if (!std::isfinite(m[c][r])) return false;
        return true;
    }

    void read_models(const toml::node& node, Scene& scene) const {
        const toml::array& models = array_of(node, "models");
        for (std::size_t i = 0; i < models.size(); ++i) {
            const std::string name = "models[" + std::to_string(i) + "]";
            const toml::table& table = table_of(*models.get(i), name);
            check_keys(table, name, {"file", "translate", "rotate", "scale", "lights", "animation", "animation_start",
                                     "animation_speed", "animation_loop", "allow_external_uris"});
            const toml::node& file_node = require(table, "file", name);
            const std::filesystem::path file = base_dir_ / read_string(file_node, child(name, "file"));
            if (!is_gltf_path(file)) {
                fail_at(file_node.source(), "expected a .gltf or .glb file for '" + child(name, "file") + "', got '" +
                                                file.string() + "'");
            }
            bool with_lights = true;
            if (const toml::node* n = table.get("lights")) with_lights = read_bool(*n, child(name, "lights"));
            // Whether the model's URIs may name files outside its folder (GltfReadOptions).
            bool allow_external_uris = false;
            if (const toml::node* n = table.get("allow_external_uris"))
                allow_external_uris = read_bool(*n, child(name, "allow_external_uris"));
            const glm::mat4 placement = read_placement(table, name);
            std::shared_ptr<const GltfContent> content;
            try {
                content = (models_ ? *models_ : own_models_).load(file, allow_external_uris);
            } catch (const SceneError& error) {
                fail_at(file_node.source(), "in '" + child(name, "file") + "': " + error.what());
            }
            const std::size_t first_object = scene.objects.size(), first_light = scene.lights.size();
            // The whole model is one object (Object::id), numbered after the entries before it.
            std::uint32_t entry_id = 1;
            for (const Object& object : scene.objects) entry_id = std::max(entry_id, object.id + 1);
            append_gltf_content(scene, *content, placement, with_lights);
            for (std::size_t l = first_light; l < scene.lights.size(); ++l) apply_shadow_defaults(scene.lights[l]);
            for (std::size_t o = first_object; o < scene.objects.size(); ++o) scene.objects[o].id = entry_id;
            // A finite placement of a finite node can still overflow (1e30 · 1e30).
            bool finite = true;
            for (std::size_t o = first_object; o < scene.objects.size(); ++o) finite = finite && finite_matrix(scene.objects[o].model);
            for (std::size_t l = first_light; l < scene.lights.size(); ++l) {
                const glm::vec3 p = scene.lights[l].position;
                finite = finite && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
            }
            if (!finite) fail_at(table.source(), "placing '" + file.string() + "' by '" + name + "' gives a transform that is not finite");
            read_model_animation(table, name, *content, scene);
        }
    }

    // [[models]].animation and its timing: the model's entry in Scene::posed_models plays.
    void read_model_animation(const toml::table& table, const std::string& name, const GltfContent& content,
                              Scene& scene) const {
        const toml::node* node = table.get("animation");
        if (node == nullptr) {
            for (const char* key : {"animation_start", "animation_speed", "animation_loop"})
                if (const toml::node* n = table.get(key))
                    fail_at(n->source(), "'" + child(name, key) + "' times the file's animation: give '" +
                                             child(name, "animation") + "' too");
            return;
        }
        const std::string key = child(name, "animation");
        if (!content.rig || content.rig->animations.empty())
            fail_at(node->source(), "'" + key + "' plays the file's animation, but the file has none");
        PosedGltfModel& model = scene.posed_models.back();  // appended with the model's content
        const std::vector<gltf::RigAnimation>& animations = content.rig->animations;
        if (const auto* index = node->as_integer()) {
            if (index->get() < 0 || std::uint64_t(index->get()) >= animations.size())
                fail_at(node->source(), "expected '" + key + "' to be the index of one of the file's animations (" +
                                            gltf::list_animations(*content.rig) + "), got " + std::to_string(index->get()));
            model.animation = int(index->get());
        } else if (const auto* text = node->as_string()) {
            for (std::size_t a = 0; a < animations.size() && model.animation < 0; ++a)
                if (animations[a].name == text->get()) model.animation = int(a);
            if (model.animation < 0)
                fail_at(node->source(), "expected '" + key + "' to name one of the file's animations (" +
                                            gltf::list_animations(*content.rig) + "), got '" + text->get() + "'");
        } else {
            fail_type(*node, "an animation's index (an integer) or name (a string)", key);
        }
        if (const toml::node* n = table.get("animation_start")) model.start_seconds = read_number(*n, child(name, "animation_start"));
        if (const toml::node* n = table.get("animation_speed")) model.speed = read_number(*n, child(name, "animation_speed"));
        if (const toml::node* n = table.get("animation_loop")) model.loop = read_bool(*n, child(name, "animation_loop"));
    }

    std::filesystem::path base_dir_;  // the scene file's folder: [[models]] files are relative to it
    std::map<std::string, Material> named_materials_;
    std::map<std::string, std::uint32_t> used_materials_;  // name -> index in Scene::materials
    std::map<std::string, std::uint32_t> used_meshes_;     // name and uv_scale -> index in Scene::meshes
    std::optional<std::uint32_t> default_material_;
    std::vector<std::shared_ptr<const texture::Texture>> textures_;  // becomes Scene::textures
    std::map<std::string, std::int32_t> texture_indices_;            // path and colour space -> index in textures_
    ModelCache* models_ = nullptr;  // where [[models]] files come from; null: own_models_
    mutable ModelCache own_models_;  // this scene's alone: a file placed twice is still read once
    Light shadow_defaults_;  // [shadows]: its shadows, shadow_map_size and shadow_filter_radius
    void apply_shadow_defaults(Light& light) const {
        light.shadows = shadow_defaults_.shadows;
        light.shadow_map_size = shadow_defaults_.shadow_map_size;
        light.shadow_filter_radius = shadow_defaults_.shadow_filter_radius;
    }
};

}  // namespace

float auto_light_range(const glm::vec3& color) {
    const float brightest = std::max({color.r, color.g, color.b});
    return std::max(std::sqrt(brightest / kAutoRangeIrradiance), std::numeric_limits<float>::min());
}

namespace {

// A scene file is a page of TOML; its meshes and textures are other files.
constexpr std::uint64_t kMaxSceneFileBytes = 64ull << 20;

Scene parse_scene_with(std::string_view toml_text, std::string_view source_name, ModelCache* models) {
    const std::string source(source_name);
    toml::table root;
    try {
        io::check_toml_depth(toml_text, io::kMaxTomlDepth, source);  // toml++ recurses per level
    } catch (const std::runtime_error& e) {
        throw SceneError(e.what());
    }
    try {
        root = toml::parse(toml_text, source_name);
    } catch (const toml::parse_error& error) {
        const toml::source_position where = error.source().begin;
        throw SceneError(source + ":" + std::to_string(where.line) + ":" +
                         std::to_string(where.column) + ": " + std::string(error.description()));
    }
    return SceneReader(source, models).read(root);
}

// models: null imports each model file here and keeps nothing. gltf_camera (the CLI's
// --camera NAME|INDEX) picks a glTF file's camera; a TOML file refuses it.
Scene load_scene_with(const std::filesystem::path& path, ModelCache* models, const std::string& gltf_camera) {
    const std::string name = path.string();
    std::error_code ignored;
    if (!std::filesystem::is_directory(path, ignored)) check_scene_file_extension(path);
    if (is_gltf_path(path))
        return make_gltf_scene(models ? *models->load(path) : import_gltf_file(path), name, gltf_camera);
    if (!gltf_camera.empty())
        throw SceneError(name + ": --camera selects a glTF file's camera; a TOML scene has its own [camera]");
    std::string text;
    try {
        text = io::read_input_text(path, kMaxSceneFileBytes, "scene file");
    } catch (const io::InputFileError& e) {
        throw SceneError(e.what());
    }
    return parse_scene_with(text, name, models);
}

}  // namespace

void check_scene_file_extension(const std::filesystem::path& path) {
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (extension != ".toml" && !is_gltf_path(path))
        throw SceneError(path.string() + ": not a scene file (expected .toml, .gltf or .glb)");
}

Scene parse_scene(std::string_view toml_text, std::string_view source_name) {
    return parse_scene_with(toml_text, source_name, nullptr);
}

Scene load_scene_file(const std::filesystem::path& path, const std::string& gltf_camera) {
    return load_scene_with(path, nullptr, gltf_camera);
}

Scene load_scene_file(const std::filesystem::path& path, ModelCache& models, const std::string& gltf_camera) {
    return load_scene_with(path, &models, gltf_camera);
}

}  // namespace tessera
