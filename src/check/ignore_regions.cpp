#include "check/ignore_regions.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include <OpenImageIO/imagebuf.h>

namespace tessera::check {

std::vector<std::uint8_t> ignore_mask(const IgnoreRegions& regions, int width, int height) {
    if (regions.empty()) return {};
    std::vector<std::uint8_t> ignored(std::size_t(width) * std::size_t(height), 0);
    for (const IgnoreRect& r : regions.rects) {
        const int x0 = std::clamp(r.x, 0, width), x1 = std::clamp(r.x + r.width, 0, width);
        const int y0 = std::clamp(r.y, 0, height), y1 = std::clamp(r.y + r.height, 0, height);
        for (int y = y0; y < y1; ++y)
            std::fill(ignored.begin() + std::ptrdiff_t(y) * width + x0, ignored.begin() + std::ptrdiff_t(y) * width + x1,
                      std::uint8_t(1));
    }
    if (!regions.mask.empty()) {
        OIIO::ImageBuf mask(regions.mask.string());
        if (!mask.read(0, 0, true, OIIO::TypeDesc::FLOAT))
            throw std::runtime_error(regions.mask.string() + ": cannot read ignore mask: " + mask.geterror());
        const OIIO::ImageSpec& spec = mask.spec();
        if (spec.width != width || spec.height != height)
            throw std::runtime_error(regions.mask.string() + ": the ignore mask is " + std::to_string(spec.width) + "x" +
                                     std::to_string(spec.height) + ", the render " + std::to_string(width) + "x" +
                                     std::to_string(height));
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                if (mask.getchannel(spec.x + x, spec.y + y, 0, 0) >= 0.5f) ignored[std::size_t(y) * width + x] = 1;
    }
    return ignored;
}

}  // namespace tessera::check
