// Tests for src/batch/contact_sheet.cpp: tiles in order, sized by the first
// frame's aspect ratio, the gaps and empty slots in the background colour.
#include <array>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "batch/contact_sheet.hpp"
#include "tessera/image_io.hpp"
#include "test_paths.hpp"

using namespace tessera;

namespace {

// A 16×8 frame of one colour, written as PNG.
std::string solid_frame(const std::filesystem::path& dir, int index, std::array<std::uint8_t, 3> rgb) {
    RenderedImage image;
    image.width = 16;
    image.height = 8;
    for (int p = 0; p < 16 * 8; ++p) image.display.insert(image.display.end(), rgb.begin(), rgb.end());
    const std::string path = (dir / ("frame_" + std::to_string(index) + ".png")).string();
    write_image(image, path);
    return path;
}

std::array<std::uint8_t, 3> pixel(const RenderedImage& image, int x, int y) {
    const std::size_t at = (std::size_t(y) * std::size_t(image.width) + std::size_t(x)) * 3;
    return {image.display[at], image.display[at + 1], image.display[at + 2]};
}

}  // namespace

TEST_CASE("contact sheet: frames tiled left to right, top to bottom, with gaps") {
    const std::filesystem::path dir = test::output_dir("contact_sheet");
    const std::vector<std::string> files{solid_frame(dir, 0, {255, 0, 0}), solid_frame(dir, 1, {0, 255, 0}),
                                         solid_frame(dir, 2, {0, 0, 255})};
    batch::ContactSheetLayout layout;
    layout.columns = 2;
    layout.tile_width = 8;  // 16×8 frames become 8×4 tiles
    layout.gap = 2;
    const RenderedImage sheet = batch::make_contact_sheet(files, layout);
    CHECK(sheet.width == 2 + 2 * (8 + 2));
    CHECK(sheet.height == 2 + 2 * (4 + 2));
    CHECK(pixel(sheet, 2 + 4, 2 + 2) == std::array<std::uint8_t, 3>{255, 0, 0});            // row 0, column 0
    CHECK(pixel(sheet, 2 + 10 + 4, 2 + 2) == std::array<std::uint8_t, 3>{0, 255, 0});       // row 0, column 1
    CHECK(pixel(sheet, 2 + 4, 2 + 6 + 2) == std::array<std::uint8_t, 3>{0, 0, 255});        // row 1, column 0
    CHECK(pixel(sheet, 2 + 10 + 4, 2 + 6 + 2) == std::array<std::uint8_t, 3>{0, 0, 0});     // empty slot
    CHECK(pixel(sheet, 1, 1) == std::array<std::uint8_t, 3>{0, 0, 0});                      // the gap
    CHECK(pixel(sheet, 2 + 8, 2 + 2) == std::array<std::uint8_t, 3>{0, 0, 0});              // between tiles
    const std::string missing = (dir / "missing.png").string();
    std::string message;
    try {
        batch::make_contact_sheet({missing}, layout);
    } catch (const std::runtime_error& error) {
        message = error.what();
    }
    CHECK(message.find(missing + ": cannot read the frame") == 0);
}
