// The display encoding's table lookup (display_encoding.hpp) a vector of
// pixels at a time, compiled once per ISA: the IEEE division c/(c+1) of the
// reference, then integer work on its bits and one gather per channel.
#include <cstdint>

#include "simd/kernel_prelude.hpp"

#include "image/display_encoding.hpp"
#include "simd/hardware_gather.hpp"

namespace tessera::image {
namespace {

using Arch = TESSERA_SIMD_ARCH;
using Float = xsimd::batch<float, Arch>;
using Int = xsimd::batch<std::int32_t, Arch>;
using Table = Unorm8Table;

// unorm8_from_tonemapped of each lane.
[[gnu::always_inline]] inline Int unorm8_of(const Table& table, const Float& tonemapped) {
    const Int bits = xsimd::bitwise_cast<Int>(tonemapped);
    const Int bucket = xsimd::min(xsimd::max((bits >> Table::kLowBits) - Int(Table::kIndexOffset), Int(0)),
                                  Int(Table::kBuckets - 1));
    const Int e = simd::hardware_gather(table.entry.data(), bucket);
    const Int stepped = xsimd::select((bits & Int(Table::kLowMask)) >= (e & Int(Table::kThresholdMask)), Int(1), Int(0));
    const Int value = (e >> Table::kBaseShift) + stepped;
    // As the scalar lookup: -inf gives 255 (pow(-inf, 1/2.2) = +inf), NaN 0.
    const Int minus_infinity(std::int32_t(0xFF800000u)), infinity(0x7F800000);
    return xsimd::select(bits == minus_infinity, Int(255), xsimd::select(bits > infinity, Int(0), value));
}

// The reference's Reinhard c / (c + 1), then the lookup.
[[gnu::always_inline]] inline Int unorm8_of_radiance(const Table& table, const Float& radiance) {
    return unorm8_of(table, radiance / (radiance + Float(1.0f)));
}

}  // namespace

void TESSERA_SIMD_ENTRY(encode_display_unorm8)(const Table& table, std::size_t count, float* r, const float* g,
                                               const float* b) {
    for (std::size_t i = 0; i < count; i += Float::size) {
        const Int red = unorm8_of_radiance(table, Float::load_unaligned(r + i));
        const Int green = unorm8_of_radiance(table, Float::load_unaligned(g + i));
        const Int blue = unorm8_of_radiance(table, Float::load_unaligned(b + i));
        xsimd::bitwise_cast<Float>(red | (green << 8) | (blue << 16)).store_unaligned(r + i);
    }
}

void TESSERA_SIMD_ENTRY(unorm8_from_tonemapped)(const Table& table, std::size_t count, const float* tonemapped,
                                                std::int32_t* out) {
    for (std::size_t i = 0; i < count; i += Float::size)
        unorm8_of(table, Float::load_unaligned(tonemapped + i)).store_unaligned(out + i);
}

}  // namespace tessera::image
