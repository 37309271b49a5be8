// The rasterizer's fixed-point format and limits, in one place.
#pragma once

#include <cstdint>

#include "geometry/clipper.hpp"
#include "geometry/viewport.hpp"
#include "tessera/scene.hpp"

namespace tessera::raster {

using geometry::kSubpixelBits;  // the viewport transform snaps to 24.8 fixed point
using geometry::kSubpixelScale;

// After guard-band clipping |x|, |y| <= kMaxImageDimension + kGuardBandPixels
// = 32768 px = 2^23 in fixed point, so an edge function (a difference of two
// products of coordinate deltas below 2^24) stays below 2^49: int64 is exact.
static_assert(kMaxImageDimension + geometry::kGuardBandPixels <= 32768.0f);

// Tiles are square; their side is a power of two in this range.
inline constexpr int kMinTileSize = 8;
inline constexpr int kMaxTileSize = 256;
// The default is RenderSettings::tile_size.

}  // namespace tessera::raster
