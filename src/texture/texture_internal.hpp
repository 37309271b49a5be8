// What the texture sources share inside src/texture/ (texture.cpp: storage and colour
// encodings; texture_load.cpp: decoding files; mip_chain.cpp; texture_sampling.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>

namespace tessera::texture::detail {

// source: "texture 'path'", "texture from_pixels", or the caller's label for an image in memory.
[[noreturn]] void fail(const std::string& source, const std::string& what);
// Refuses a zero or oversized image, and one the memory budget cannot hold with its mips.
void check_size(const std::string& source, long long width, long long height);
std::int64_t nanoseconds_since(std::chrono::steady_clock::time_point start);
// `count` texels of `channels` bytes each → RGBA8 words: grey → (g, g, g, 1),
// grey + alpha → (g, g, g, a), RGB → (r, g, b, 1), RGBA and more: the first four.
void expand_to_rgba8(const std::uint8_t* in, int channels, std::size_t count, std::uint32_t* out);

// min(hi, max(lo, x)) in this operand order: std::max returns its first
// argument when the comparison fails, so NaN becomes lo (as xsimd::max(x, lo)
// does in the kernels, by the hardware rule).
inline float clamp_nan_low(float x, float lo, float hi) { return std::min(hi, std::max(lo, x)); }

// round(255·x) for x clamped to [0, 1]: floor(255·x + ½), and floor is the
// integer conversion for these non-negative values (no libm call).
inline std::uint8_t unorm8_from_linear(float linear) {
    return static_cast<std::uint8_t>(static_cast<int>(clamp_nan_low(linear, 0.0f, 1.0f) * 255.0f + 0.5f));
}

// round(255·encode(x)) steps from k to k+1 where encode(x) = (k + ½)/255,
// that is at x = decode((k + ½)/255): 255 thresholds in linear light.
// first_code[i] is the code of x = i/kBins; the code of x in [i/kBins,
// (i+1)/kBins) is then at most a step or two above (the steepest part of the
// curve, slope 12.92·255 near 0, puts 0.8 steps in a bin): exact, no pow.
struct SrgbEncoder {
    static constexpr int kBins = 4096;
    std::array<float, 256> thresholds{};  // [255] = +∞, a sentinel
    std::array<std::uint8_t, kBins> first_code{};

    SrgbEncoder() {
        for (int k = 0; k < 255; ++k) {
            const double c = (k + 0.5) / 255.0;
            thresholds[static_cast<std::size_t>(k)] =
                static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
        }
        thresholds[255] = INFINITY;
        for (int i = 0; i < kBins; ++i) first_code[static_cast<std::size_t>(i)] = search(static_cast<float>(i) / kBins);
    }
    std::uint8_t search(float x) const {
        return static_cast<std::uint8_t>(std::upper_bound(thresholds.begin(), thresholds.end() - 1, x) - thresholds.begin());
    }
    std::uint8_t encode(float x) const {
        x = clamp_nan_low(x, 0.0f, 1.0f);
        const int bin = std::min(kBins - 1, static_cast<int>(x * kBins));
        // x >= bin/kBins up to float rounding of x·kBins: start one bin lower to be safe.
        unsigned code = first_code[static_cast<std::size_t>(std::max(0, bin - 1))];
        while (x >= thresholds[code]) ++code;
        return static_cast<std::uint8_t>(code);
    }
};

// The one encoder of the process (its tables are built on first use).
const SrgbEncoder& srgb_encoder();

}  // namespace tessera::texture::detail
