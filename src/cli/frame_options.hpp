// The options `tessera render` and `tessera bench` share: output size and how the renderer runs.
#pragma once

#include <CLI/CLI.hpp>

#include "tessera/renderer.hpp"

namespace tessera::cli {

void add_frame_options(CLI::App* command, int& width, int& height, int& msaa, RenderSettings& settings);

}  // namespace tessera::cli
