#include "batch/contact_sheet.hpp"

#include <algorithm>
#include <stdexcept>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "io/input_file.hpp"
#include "io/memory_budget.hpp"

namespace tessera::batch {

RenderedImage make_contact_sheet(const std::vector<std::string>& files, const ContactSheetLayout& layout) {
    if (files.empty()) throw std::invalid_argument("a contact sheet needs at least one frame");
    if (layout.columns < 1 || layout.tile_width < 8 || layout.gap < 0)
        throw std::invalid_argument("contact sheet: columns >= 1, tile width >= 8 and gap >= 0 expected");
    int tile_height = 0;
    const int columns = std::min<int>(layout.columns, int(files.size()));
    const int rows = (int(files.size()) + columns - 1) / columns;
    RenderedImage sheet;
    for (std::size_t i = 0; i < files.size(); ++i) {
        std::uint64_t file_bytes = 0;
        try {  // a FIFO or device would block the read or never end
            file_bytes = io::check_input_file(files[i], io::memory_budget(), "frame");
        } catch (const io::InputFileError& e) {
            // "cannot open frame: no such file" -> "F: cannot read the frame: no such file"
            const std::string reason = e.reason().substr(std::min(e.reason().find(": ") + 2, e.reason().size()));
            throw std::runtime_error(files[i] + ": cannot read the frame: " + reason);
        }
        OIIO::ImageBuf frame(files[i]);
        const OIIO::ImageSpec& header = frame.spec();  // the header only: its size is checked before the pixels
        if (header.width < 1 || header.height < 1 || header.nchannels < 1)
            throw std::runtime_error(files[i] + ": cannot read the frame: " +
                                     (frame.has_error() ? frame.geterror() : std::string("no pixels")));
        try {
            io::check_decoded_size(file_bytes,
                                   io::saturating_mul(std::uint64_t(header.width) * std::uint64_t(header.height),
                                                      std::uint64_t(header.nchannels)),
                                   "the " + std::to_string(header.width) + "x" + std::to_string(header.height) +
                                       " frame");
        } catch (const io::MemoryBudgetError& e) {
            throw std::runtime_error(files[i] + ": " + e.what());
        }
        if (!frame.read(0, 0, true, OIIO::TypeDesc::UINT8) || frame.nchannels() < 1)
            throw std::runtime_error(files[i] + ": cannot read the frame: " + frame.geterror());
        const OIIO::ROI size = frame.roi();
        if (tile_height == 0) {
            // Every tile gets the first frame's aspect ratio. In 64 bits and checked
            // before narrowing: a tall frame or a wide tile overflowed int here.
            const double scaled = double(layout.tile_width) * size.height() / size.width() + 0.5;
            const long long height = scaled > double(kMaxImagePixels) ? kMaxImagePixels + 1
                                                                       : std::max(1LL, (long long)scaled);
            const long long width_total = layout.gap + (long long)columns * ((long long)layout.tile_width + layout.gap);
            const long long height_total = layout.gap + (long long)rows * (height + (long long)layout.gap);
            if (double(width_total) * double(height_total) > double(kMaxImagePixels) || height > kMaxImagePixels)
                throw std::invalid_argument("contact sheet: " + std::to_string(width_total) + "x" +
                                            std::to_string(height_total) + " pixels is too large (at most " +
                                            std::to_string(kMaxImagePixels) +
                                            "); use fewer frames or smaller tiles");
            tile_height = int(height);
            sheet.width = int(width_total);
            sheet.height = int(height_total);
            sheet.display.resize(std::size_t(sheet.width) * std::size_t(sheet.height) * 3);
            for (std::size_t p = 0; p < sheet.display.size(); ++p) sheet.display[p] = layout.background[p % 3];
        }
        OIIO::ImageBuf tile;
        if (!OIIO::ImageBufAlgo::resize(tile, frame, "", 0.0f, OIIO::ROI(0, layout.tile_width, 0, tile_height, 0, 1, 0, frame.nchannels())))
            throw std::runtime_error(files[i] + ": cannot resize the frame: " + tile.geterror());
        // Grey frames (one channel) fill all three; extra channels (alpha) are left out.
        const int channels = std::min(frame.nchannels(), 3);
        std::vector<unsigned char> read(std::size_t(layout.tile_width) * std::size_t(tile_height) * std::size_t(tile.nchannels()));
        tile.get_pixels(tile.roi(), OIIO::TypeDesc::UINT8, read.data());
        const int x0 = layout.gap + int(i % std::size_t(columns)) * (layout.tile_width + layout.gap);
        const int y0 = layout.gap + int(i / std::size_t(columns)) * (tile_height + layout.gap);
        for (int y = 0; y < tile_height; ++y) {
            for (int x = 0; x < layout.tile_width; ++x) {
                const unsigned char* from = &read[(std::size_t(y) * layout.tile_width + x) * std::size_t(tile.nchannels())];
                unsigned char* to = &sheet.display[(std::size_t(y0 + y) * sheet.width + std::size_t(x0 + x)) * 3];
                for (int c = 0; c < 3; ++c) to[c] = from[channels == 3 ? c : 0];
            }
        }
    }
    return sheet;
}

}  // namespace tessera::batch
