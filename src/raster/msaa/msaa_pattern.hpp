// The 4× sample pattern, in its own header so that the per-ISA kernels
// (msaa_simd.cpp) share it without the rest of msaa.hpp.
#pragma once

#include <array>
#include <cstdint>

namespace tessera::raster {

inline constexpr int kMsaaSamples = 4;

// GL's 4× pattern, as llvmpipe reports it (GL_SAMPLE_POSITION) in window space,
// y up from the pixel's bottom: (0.375, 0.125), (0.875, 0.375), (0.125, 0.625),
// (0.625, 0.875) — the standard numbers of D3D and Vulkan, which measure y down
// instead. In image space (y down from the pixel's top) they are (0.375, 0.875),
// (0.875, 0.625), (0.125, 0.375), (0.625, 0.125); as offsets from the pixel
// centre in 24.8 fixed point, exact multiples of 32.
inline constexpr std::array<std::int32_t, kMsaaSamples> kSampleOffsetX = {-32, 96, -96, 32};
inline constexpr std::array<std::int32_t, kMsaaSamples> kSampleOffsetY = {96, 32, -32, -96};

}  // namespace tessera::raster
