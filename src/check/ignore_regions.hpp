// Regions of a scene's image that its check does not compare: rectangles in
// pixels and/or a mask image (a manifest's [[override]] ignore / ignore_mask,
// docs/check.md). Ignored pixels count as equal and are left out of the pixel
// count that ratios, the mean and the RMS are taken over.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace tessera::check {

// x, y: the top-left pixel (row 0 at the top of the image); width, height > 0.
// A rectangle reaching past the image is clipped to it.
struct IgnoreRect {
    int x = 0, y = 0, width = 0, height = 0;
};

struct IgnoreRegions {
    std::vector<IgnoreRect> rects;
    // A mask image the size of the render: a pixel whose first channel is 0.5
    // or more (white) is ignored. Empty: none.
    std::filesystem::path mask;
    bool empty() const { return rects.empty() && mask.empty(); }
};

// One byte per pixel, row by row, 1 where the pixel is ignored; empty when
// `regions` is. Throws std::runtime_error naming the mask file when it cannot
// be read or its size is not width × height.
std::vector<std::uint8_t> ignore_mask(const IgnoreRegions& regions, int width, int height);

}  // namespace tessera::check
