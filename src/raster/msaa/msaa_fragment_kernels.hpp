// collect_fragments() (msaa.hpp) compiled once per ISA (msaa_fragment_simd.cpp):
// the listing of a tile's fragments from its samples (msaa_list_kernel.hpp),
// and each fragment's λ1, λ2 at its pixel centre, bit-identical to
// screen_barycentrics(). Plain data, so the copies share nothing else with msaa.cpp.
#pragma once

#include <cstddef>
#include <cstdint>

#include "raster/triangle_setup.hpp"

namespace tessera::raster {

// A tile's samples (TileSamples) and where its fragments' pixels and
// triangles go (TileFragments, padded by kMsaaSamples: a pixel's 4 possible
// fragments are written every time).
struct SampleListing {
    const float* depth;             // per sample, 1 = background
    const std::uint32_t* triangle;  // per sample
    std::int32_t* fragment;         // per sample, set: its fragment, or -1
    int side;                       // pixels per row of the sample arrays
    int width, height;              // the tile's pixels
    int box_x0, box_x1, box_y0, box_y1;  // outside this box every depth is 1 (TileSamples' written box)
    std::uint16_t *x, *y;
    std::uint32_t* fragment_triangle;
};

#define TESSERA_DECLARE_LIST_KERNEL(suffix) std::size_t list_fragments_##suffix(const SampleListing& samples);
TESSERA_DECLARE_LIST_KERNEL(sse4)
TESSERA_DECLARE_LIST_KERNEL(avx2)
TESSERA_DECLARE_LIST_KERNEL(avx512)
#undef TESSERA_DECLARE_LIST_KERNEL

// The listed fragments (TileFragments) and where their λ go.
struct FragmentCentres {
    const RasterTriangle* const* triangle;  // per fragment, its triangle
    const std::uint16_t *x, *y;             // tile-relative pixel
    int origin_x, origin_y;                 // the tile's first pixel in the image
    std::size_t count;
    float *lambda1, *lambda2;
};

// Edge functions as exact integers in double (|corner| <= 2^23 in 24.8 fixed
// point, raster_limits.hpp, so every product and difference is below 2^53),
// rounded once to float as float(int64) is, times inv_area.
#define TESSERA_DECLARE_FRAGMENT_KERNEL(suffix) void fragment_barycentrics_##suffix(const FragmentCentres& fragments);
TESSERA_DECLARE_FRAGMENT_KERNEL(sse4)
TESSERA_DECLARE_FRAGMENT_KERNEL(avx2)
TESSERA_DECLARE_FRAGMENT_KERNEL(avx512)
#undef TESSERA_DECLARE_FRAGMENT_KERNEL

}  // namespace tessera::raster
