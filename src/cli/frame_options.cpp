#include "cli/frame_options.hpp"

#include <cmath>

#include "environment/environment_cache.hpp"
#include "scene/gltf/gltf_import.hpp"
#include "cli/usage.hpp"
#include "tessera/scene.hpp"

namespace tessera::cli {

void add_frame_options(CLI::App* command, int& width, int& height, int& msaa, RenderSettings& settings) {
    // 0 (the scene's own) is no value a user can give: no "=0" in --help.
    no_default_shown(command->add_option("--msaa", msaa, "Samples per pixel, 1 or 4 (default: the scene's output.msaa)"))
        ->check(CLI::IsMember({1, 4}));
    no_default_shown(command->add_option("--width", width, "Image width in pixels (default: the scene's output.width)"))
        ->check(CLI::Range(1, tessera::kMaxImageDimension));
    no_default_shown(command->add_option("--height", height, "Image height in pixels (default: the scene's output.height)"))
        ->check(CLI::Range(1, tessera::kMaxImageDimension));
    command->add_option("--threads", settings.threads, "Worker threads (0 = one per hardware thread)")
        ->check(CLI::Range(0, 1024));
    command->add_option("--tile-size", settings.tile_size, "Screen tile side in pixels (power of two, 8-256)");
    command->add_option("--isa", settings.isa, "SIMD kernels: auto, scalar, sse4, avx2, avx512");
    command->add_flag_callback(
        "--no-light-culling", [&settings] { settings.light_culling = false; },
        "Ignore light ranges: shade every light at every pixel, as the reference shader does");
}

}  // namespace tessera::cli

namespace tessera::cli {

void add_lighting_options(CLI::App* command, LightingOptions& options) {
    command->add_option("--environment", options.environment,
                        "Light the scene with this equirectangular HDR image (.hdr or .exr), shown as the "
                        "background (image-based lighting, docs/scene-format.md [environment])");
    command->add_option_function<float>(
        "--environment-intensity",
        [&options](float value) {
            if (!(std::isfinite(value) && value >= 0.0f))
                throw CLI::ValidationError("--environment-intensity", "expected a finite number >= 0");
            options.environment_intensity = value, options.intensity_given = true;
        },
        "Scale the environment's radiance (default: the scene's, else 1)");
    command->add_option_function<float>(
        "--exposure",
        [&options](float value) {
            if (!(std::isfinite(value) && std::fabs(value) <= 64.0f))
                throw CLI::ValidationError("--exposure", "expected a finite number of stops in [-64, 64]");
            options.exposure = value;
        },
        "Scale radiance by 2^EV before tonemapping (default 0: unchanged)");
    command->add_option("--lighting", options.lighting,
                        "auto: a glTF file on its own gets the shipped environment and a key light; reference: "
                        "the reference shader's direct light and 0.03 ambient only")
        ->check(CLI::IsMember({"auto", "reference"}));
    command->add_flag_callback(
        "--no-environment-cache", [] { environment::set_disk_cache_enabled(false); },
        "Do not read or write pre-computed environment maps on disk (TESSERA_NO_ENVIRONMENT_CACHE=1 does the same)");
}

std::filesystem::path shipped_environment_path() {
    constexpr const char* kFile = "studio_256.exr";
    std::error_code error;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
    if (!error) {
        const std::filesystem::path installed = exe.parent_path() / ".." / "share" / "tessera" / "environments" / kFile;
        if (std::filesystem::exists(installed, error)) return installed.lexically_normal();
    }
    return std::filesystem::path(TESSERA_SOURCE_DIR) / "scenes" / "environments" / kFile;
}

namespace {

// Where a key light shines from: above, left of and in front of the camera;
// it casts shadows (a 2048² map: one light, fitted to what the camera sees).
Light key_light(const Camera& camera) {
    const glm::vec3 forward = glm::normalize(camera.target - camera.position);
    const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
    const glm::vec3 up = glm::cross(right, forward);
    Light light;
    light.type = LightType::directional;
    light.direction = -glm::normalize(up * 1.0f - right * 0.6f - forward * 0.8f);
    light.color = glm::vec3(kKeyLightRadiance);
    light.shadows = true;
    light.shadow_map_size = kKeyLightShadowMapSize;
    return light;
}

}  // namespace

void apply_lighting_options(const LightingOptions& options, const std::string& scene_path, Scene& scene) {
    scene.exposure_ev = options.exposure;
    if (options.lighting == "reference") {
        scene.environment = {};
        return;
    }
    const bool gltf_alone = is_gltf_path(scene_path);
    std::filesystem::path file = options.environment;
    if (file.empty() && gltf_alone) file = shipped_environment_path();
    if (!file.empty()) {
        try {
            scene.environment.maps = environment::acquire_environment(file);
        } catch (const environment::EnvironmentError& e) {
            throw SceneError(std::string("--environment: ") + e.what());
        }
        scene.environment.file = file.string();
        if (gltf_alone) {
            if (scene.default_lights) {
                scene.lights = {key_light(scene.camera)};
                scene.default_lights = false;
            } else {
                scene.environment.intensity = kEnvironmentBesideLights;
            }
        }
    }
    if (options.intensity_given) scene.environment.intensity = options.environment_intensity;
}

}  // namespace tessera::cli
