// The options `tessera render` and `tessera bench` share: output size and how the renderer runs.
#pragma once

#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>

#include "tessera/renderer.hpp"

namespace tessera::cli {

void add_frame_options(CLI::App* command, int& width, int& height, int& msaa, RenderSettings& settings);

}  // namespace tessera::cli

namespace tessera::cli {

// How a scene is lit (docs/cli.md): an environment from the command line,
// the exposure, and the default look of a glTF file rendered on its own.
struct LightingOptions {
    std::string environment;                      // --environment FILE: light every scene with it
    float environment_intensity = -1.0f;          // --environment-intensity; < 0: not given
    bool intensity_given = false;
    float exposure = 0.0f;                        // --exposure EV
    std::string lighting = "auto";                // --lighting auto | reference
};
void add_lighting_options(CLI::App* command, LightingOptions& options);
// Applies the options to a loaded scene. "auto": a glTF file on its own gets
// the shipped environment (or --environment's) and, if it has no lights of its
// own, one key light in place of the default rig; if it has lights, they stay
// and the environment comes in at kEnvironmentBesideLights. "reference": no
// environment, the scene's lights (a glTF file's default rig), as before IBL.
inline constexpr float kKeyLightRadiance = 2.5f;
inline constexpr int kKeyLightShadowMapSize = 2048;
inline constexpr float kEnvironmentBesideLights = 0.3f;
void apply_lighting_options(const LightingOptions& options, const std::string& scene_path, Scene& scene);
// The environment image shipped with tessera: beside an installed binary
// (../share/tessera/environments/), else in the source tree it was built from.
std::filesystem::path shipped_environment_path();

}  // namespace tessera::cli
