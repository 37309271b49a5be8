// Display encoding of radiance for the 8-bit image: Reinhard c/(c+1), gamma
// 1/2.2, quantized to UNORM8, exactly as the scalar reference computes it, but
// without the pow: a table on the tonemapped value's bits.
//
// Why a table is exact: the 8-bit result depends on c only through the float
// L = c/(c+1) (the same IEEE division in every ISA), and for L in [0, 1] it is
// a non-decreasing step function of L with 255 steps. Non-negative floats
// order like their bit patterns, so the step positions are 255 thresholds on
// L's bits, found once from the reference itself. The bits' exponent and top
// kMantissaBits mantissa bits pick a bucket narrower than the gap between two
// thresholds (gamma 1/2.2 steps at least 0.87 % apart in L, a bucket spans at
// most 1/128 = 0.78 %), so a bucket holds at most one threshold, and the
// value is the bucket's base plus one compare against it. tests/image/
// test_display_encoding.cpp checks every float in the range where steps
// happen against the reference.
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>

#include "simd/isa.hpp"

namespace tessera::image {

// 8-bit value of a display-referred channel, rounded to nearest as a UNORM8
// framebuffer stores it; out-of-range values clamp, NaN becomes 0.
inline std::uint8_t quantize_unorm8(float display) {
    const float c = display > 0.0f ? (display < 1.0f ? display : 1.0f) : 0.0f;
    return static_cast<std::uint8_t>(c * 255.0f + 0.5f);
}

// The scalar reference: quantize_unorm8(pow(tonemapped, 1/2.2)), where
// tonemapped = c/(c+1) is the Reinhard value (shade::display_from_radiance).
std::uint8_t unorm8_from_tonemapped_reference(float tonemapped);
// The same from radiance c (c/(c+1) first): what the display image stores.
std::uint8_t unorm8_from_radiance_reference(float radiance);

// The table. A bucket covers tonemapped values whose bits agree above the
// low kLowBits; bucket 0 is everything below 2^-kExponentsBelowOne (all 0),
// the last one 1 and above (all 255).
struct Unorm8Table {
    static constexpr int kMantissaBits = 7;
    static constexpr int kLowBits = 23 - kMantissaBits;
    static constexpr int kExponentsBelowOne = 20;  // the first step (~1.1e-6) lies above 2^-20
    static constexpr int kBuckets = kExponentsBelowOne * (1 << kMantissaBits) + 2;
    // Bucket of bits b (as int32): clamp((b >> kLowBits) - kIndexOffset, 0, kBuckets - 1).
    static constexpr std::int32_t kIndexOffset = ((127 - kExponentsBelowOne) << kMantissaBits) - 1;
    static constexpr int kBaseShift = kLowBits + 1;
    static constexpr std::int32_t kLowMask = (1 << kLowBits) - 1;
    static constexpr std::int32_t kThresholdMask = (1 << kBaseShift) - 1;
    // (value at the bucket's start) << kBaseShift | (low bits where it steps up
    // by one, or 1 << kLowBits if it does not).
    alignas(64) std::array<std::int32_t, kBuckets> entry;
};

// Built from the reference on first use (thread-safe); throws std::logic_error
// if the reference is not the step function the table can hold.
const Unorm8Table& unorm8_table();

// The table lookup for one value, any float: what the SIMD kernels compute per lane.
std::uint8_t unorm8_from_tonemapped(const Unorm8Table& table, float tonemapped);

// In place over count pixels of radiance channels (arrays padded as
// simd::padded_count(count): whole vectors run past count): r[i] becomes the
// bit pattern of pixel i's 8-bit colour, read back with packed_unorm8(r[i]):
// red, green, blue in bytes 0, 1, 2 (byte 3 is 0), each equal to
// unorm8_from_radiance_reference of its channel. In place because the
// radiance is not needed afterwards and the tile's scratch already holds it.
// Isa::scalar calls the reference.
void encode_display_unorm8(simd::Isa isa, std::size_t count, float* r, const float* g, const float* b);
inline std::uint32_t packed_unorm8(float encoded) { return std::bit_cast<std::uint32_t>(encoded); }
// The table part alone, from tonemapped values (for tests): out[i] =
// unorm8_from_tonemapped_reference(tonemapped[i]); arrays padded as above.
void unorm8_from_tonemapped(simd::Isa isa, std::size_t count, const float* tonemapped, std::int32_t* out);

}  // namespace tessera::image
