#include "cli/contact_sheet_command.hpp"

#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "batch/contact_sheet.hpp"
#include "cli/output_paths.hpp"
#include "cli/usage.hpp"
#include "batch/frames.hpp"
#include "tessera/image_io.hpp"

namespace tessera::cli {

CLI::App* add_contact_sheet_command(CLI::App& app, ContactSheetCommand& cmd) {
    CLI::App* command = app.add_subcommand(
        "contact-sheet", "Tile frames into one image: render's -o pattern with --frames, or a list of image files");
    command->add_option("input", cmd.inputs, "Image files, or one pattern with {frame} (and {scene}) given --frames")
        ->required();
    command->add_option("--frames", cmd.frames, "Frames to tile, A-B[:STEP] as for render; the input is then a pattern");
    command->add_option("--scene", cmd.scene, "What {scene} stands for in the pattern");
    command->add_option("-o,--output", cmd.output, "The sheet (.png)")->required();
    command->add_option("--columns", cmd.columns, "Frames per row")->check(CLI::Range(1, 1000));
    command->add_option("--tile-width", cmd.tile_width, "Width of each frame on the sheet, pixels")
        ->check(CLI::Range(8, 4096));
    return command;
}

int run_contact_sheet(const ContactSheetCommand& cmd) {
    std::vector<std::string> files;
    if (cmd.frames.empty()) {
        files = cmd.inputs;
    } else {
        if (cmd.inputs.size() != 1)
            throw UsageError("with --frames give one pattern (as render's -o), not " +
                                        std::to_string(cmd.inputs.size()) + " inputs");
        const std::string& pattern = cmd.inputs.front();
        batch::check_output_pattern(pattern);
        if (pattern.find("{scene}") != std::string::npos && cmd.scene.empty())
            throw UsageError("the pattern holds {scene}: give --scene STEM");
        for (const int frame : batch::parse_frame_ranges(cmd.frames))
            files.push_back(batch::expand_output_pattern(pattern, cmd.scene, frame));
    }
    if (std::filesystem::path(cmd.output).extension() != ".png")
        throw UsageError(cmd.output + ": a contact sheet is written as .png (display-referred, as the frames)");
    create_parent_folders(cmd.output, "the contact sheet");
    check_writable_file(cmd.output, "the contact sheet");
    batch::ContactSheetLayout layout;
    layout.columns = cmd.columns;
    layout.tile_width = cmd.tile_width;
    const RenderedImage sheet = batch::make_contact_sheet(files, layout);
    write_image(sheet, cmd.output);
    std::printf("%s: %zu frames, %d per row, %dx%d\n", cmd.output.c_str(), files.size(),
                std::min<int>(cmd.columns, int(files.size())), sheet.width, sheet.height);
    return 0;
}

}  // namespace tessera::cli
