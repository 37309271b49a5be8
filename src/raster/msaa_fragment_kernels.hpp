// The second half of collect_fragments() (msaa.hpp) in SIMD, compiled once
// per ISA (msaa_fragment_simd.cpp): each fragment's λ1, λ2 at its pixel
// centre, bit-identical to screen_barycentrics().
#pragma once

#include <cstddef>
#include <cstdint>

#include "raster/triangle_setup.hpp"

namespace tessera::raster {

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
