// The 4× MSAA resolve's per-ISA pixel loops (resolve_msaa_simd.cpp): a
// multisampled tile's radiance and display rows from its samples' fragments.
// Plain data, so the copies compiled per ISA share nothing else with resolve.cpp.
#pragma once

#include <cstddef>
#include <cstdint>

namespace tessera::image {

struct MsaaResolveRows {
    const std::int32_t* fragment;  // TileSamples::fragment: 4 per pixel, -1 = background; row stride 4 · side
    int side;
    int width, height;             // pixels of the tile to write
    // Radiance: each channel the mean of the samples' values, summed in pairs.
    const float* plane[3];         // shaded r, g, b by fragment
    float clear_radiance[3];
    float* radiance;               // RGB float of the tile's first pixel in the image
    std::size_t radiance_stride;   // floats per image row
    // Display: each byte the rounded mean of the samples' 8-bit values.
    const float* encoded;          // encode_display_unorm8's output by fragment
    std::uint32_t clear_display;   // the clear colour, packed as encoded
    std::uint8_t* display;         // RGB8 of the tile's first pixel in the image
    std::size_t display_stride;    // bytes per image row
};

// Each writes only its rows' 3 × width values; Isa::scalar has the plain
// loops in resolve.cpp, which these match bit for bit.
#define TESSERA_DECLARE_MSAA_RESOLVE_KERNEL(suffix) \
    void resolve_msaa_radiance_rows_##suffix(const MsaaResolveRows& rows); \
    void resolve_msaa_display_rows_##suffix(const MsaaResolveRows& rows);
TESSERA_DECLARE_MSAA_RESOLVE_KERNEL(sse4)
TESSERA_DECLARE_MSAA_RESOLVE_KERNEL(avx2)
TESSERA_DECLARE_MSAA_RESOLVE_KERNEL(avx512)
#undef TESSERA_DECLARE_MSAA_RESOLVE_KERNEL

}  // namespace tessera::image
