// A contact sheet: the frames of a range tiled into one image, to look at a
// whole animation (or a farm's output) at a glance.
#pragma once

#include <string>
#include <vector>

#include "tessera/renderer.hpp"

namespace tessera::batch {

struct ContactSheetLayout {
    int columns = 6;         // frames per row, >= 1; rows follow from the frame count
    int tile_width = 320;    // pixels per frame, >= 8; the height keeps the first frame's aspect ratio
    int gap = 4;             // pixels between tiles and around them, >= 0, in the background colour
    unsigned char background[3] = {0, 0, 0};
};

// Reads each file (any format OpenImageIO reads; its first three channels,
// display-referred), shrinks it to a tile with OpenImageIO's resize filter and
// places it left to right, top to bottom in the order given. Throws
// std::runtime_error naming the file that cannot be read.
RenderedImage make_contact_sheet(const std::vector<std::string>& files, const ContactSheetLayout& layout);

}  // namespace tessera::batch
