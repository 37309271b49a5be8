// `tessera contact-sheet`: a frame range (or a list of images) tiled into one PNG.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace tessera::cli {

struct ContactSheetCommand {
    std::vector<std::string> inputs;  // image files, or one output pattern with {frame} when frames is given
    std::string frames;               // --frames A-B[:S]
    std::string scene;                // --scene STEM: what {scene} stands for in the pattern
    std::string output;
    int columns = 6;
    int tile_width = 320;
};

CLI::App* add_contact_sheet_command(CLI::App& app, ContactSheetCommand& cmd);
int run_contact_sheet(const ContactSheetCommand& cmd);

}  // namespace tessera::cli
