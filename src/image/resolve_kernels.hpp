// The resolve's per-ISA pixel loops (resolve_simd.cpp): a tile's display rows
// from its coverage and its encoded fragments, and its radiance rows (when the
// image keeps radiance) from its shaded fragments. Plain data, so the copies
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

struct RadianceRows {
    const float* depth;        // the tile's depth buffer (covered where < 1), row stride `side`
    int side;
    int width, height;         // pixels of the tile to write
    const float* plane[3];     // the covered pixels' radiance r, g, b in row-major order (as shaded)
    float clear[3];            // the background's radiance
    float* radiance;           // RGB float of the tile's first pixel in the image
    std::size_t stride;        // floats per image row
};

// Covered pixels take the next shaded radiance, the others the background's,
// bit for bit as the scalar loop in resolve.cpp; nothing outside the rows'
// 3 × width floats is written.
void write_radiance_rows_sse4(const RadianceRows& rows);
void write_radiance_rows_avx2(const RadianceRows& rows);
void write_radiance_rows_avx512(const RadianceRows& rows);

}  // namespace tessera::image
