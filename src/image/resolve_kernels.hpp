// The resolve's per-ISA pixel loop (resolve_simd.cpp): a tile's display rows
// from its coverage and its encoded fragments. Plain data, so the copies
// compiled per ISA share nothing else with resolve.cpp.
#pragma once

#include <cstddef>
#include <cstdint>

namespace tessera::image {

struct DisplayRows {
    const float* depth;        // the tile's depth buffer (covered where < 1), row stride `side`
    int side;
    int width, height;         // pixels of the tile to write
    const float* encoded;      // the covered pixels' colours in row-major order (encode_display_unorm8)
    std::size_t count;         // how many
    std::uint32_t clear;       // the clear colour, packed as encoded
    std::uint8_t* display;     // RGB8 of the tile's first pixel in the image
    std::size_t stride;        // bytes per image row
};

// Covered pixels take the next encoded colour, the others the clear colour;
// nothing outside the rows' 3 × width bytes is written. (Isa::scalar has the
// plain loop in resolve.cpp.)
void write_display_rows_sse4(const DisplayRows& rows);
void write_display_rows_avx2(const DisplayRows& rows);
void write_display_rows_avx512(const DisplayRows& rows);

}  // namespace tessera::image
