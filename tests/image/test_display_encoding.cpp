#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <tbb/parallel_for.h>

#include "image/display_encoding.hpp"
#include "image/resolve.hpp"
#include "shade/pbr_reference.hpp"
#include "simd/lane_padding.hpp"

using namespace tessera;
using simd::Isa;

namespace {

constexpr Isa kIsas[] = {Isa::scalar, Isa::sse4, Isa::avx2, Isa::avx512};

std::vector<Isa> supported_isas() {
    std::vector<Isa> isas;
    for (Isa isa : kIsas) {
        if (simd::isa_supported(isa)) isas.push_back(isa);
        else MESSAGE("skipping ", simd::isa_name(isa), ": not supported by this CPU");
    }
    return isas;
}

// Counts lanes where each ISA's table lookup differs from the reference, over
// tonemapped values with bits [first, last] (inclusive), in parallel blocks.
std::uint64_t lookup_mismatches(std::uint32_t first, std::uint32_t last, std::uint32_t stride,
                                const std::vector<Isa>& isas) {
    constexpr std::uint64_t kBlock = 1 << 14;
    const std::uint64_t count = (std::uint64_t(last) - first) / stride + 1;
    std::atomic<std::uint64_t> mismatches{0};
    tbb::parallel_for(std::uint64_t(0), (count + kBlock - 1) / kBlock, [&](std::uint64_t block) {
        const std::uint64_t begin = block * kBlock, n = std::min(kBlock, count - begin);
        std::vector<float> tonemapped(simd::padded_count(n), 0.0f);
        std::vector<std::uint8_t> expected(n);
        std::vector<std::int32_t> got(simd::padded_count(n));
        for (std::uint64_t i = 0; i < n; ++i) {
            tonemapped[i] = std::bit_cast<float>(std::uint32_t(first + (begin + i) * stride));
            expected[i] = image::unorm8_from_tonemapped_reference(tonemapped[i]);
        }
        std::uint64_t wrong = 0;
        for (Isa isa : isas) {
            image::unorm8_from_tonemapped(isa, n, tonemapped.data(), got.data());
            for (std::uint64_t i = 0; i < n; ++i) wrong += got[i] != expected[i];
        }
        mismatches += wrong;
    });
    return mismatches;
}

// Radiance values whose 8-bit results are the interesting ones: zeros, the
// infinities and NaNs, around -1 (where c/(c+1) blows up), denormals, and each
// side of every step of the reference.
std::vector<float> special_radiances() {
    std::vector<float> values = {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, 2.0f, 1e6f, -1e6f, 1e-30f, -1e-30f,
                                 std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                                 std::numeric_limits<float>::quiet_NaN(), -std::numeric_limits<float>::quiet_NaN(),
                                 std::numeric_limits<float>::signaling_NaN(), std::numeric_limits<float>::denorm_min(),
                                 std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest(),
                                 std::numeric_limits<float>::min()};
    for (float v : {-1.0f, 1.0f, 0.0f}) {
        float down = v, up = v;
        for (int i = 0; i < 8; ++i) {
            down = std::nextafter(down, -INFINITY), up = std::nextafter(up, INFINITY);
            values.push_back(down), values.push_back(up);
        }
    }
    // Each step k of the display value sits at tonemapped L_k = ((k - 0.5)/255)^2.2,
    // radiance L/(1-L): a few floats either side of it.
    for (int k = 1; k <= 255; ++k) {
        const double l = std::pow((k - 0.5) / 255.0, 2.2), c = l / (1.0 - l);
        float v = float(c);
        for (int i = 0; i < 6; ++i) v = std::nextafter(v, -INFINITY);
        for (int i = 0; i < 12; ++i) values.push_back(v), v = std::nextafter(v, INFINITY);
    }
    return values;
}

}  // namespace

TEST_CASE("the display encoding's reference is the shader's tonemap, gamma and quantization") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> exponent(-8.0f, 6.0f);
    for (int i = 0; i < 2000; ++i) {
        const float c = std::pow(10.0f, exponent(rng));
        const glm::vec3 display = shade::display_from_radiance(glm::vec3(c));
        CHECK(image::unorm8_from_radiance_reference(c) == image::quantize_unorm8(display.r));
        CHECK(image::unorm8_from_tonemapped_reference(c / (c + 1.0f)) == image::quantize_unorm8(display.r));
    }
}

// The table lookup against the reference for every float where the 8-bit
// value can step (tonemapped values from 2^-21, a factor of two below the
// first step, to 1): 176 M values, each ISA. Below and above that range,
// and for negative values, infinities and NaNs, a strided sample of all
// 2^32 bit patterns.
TEST_CASE("display encoding table: every ISA equals the reference for every tonemapped float in [2^-21, 1]") {
    const std::vector<Isa> isas = supported_isas();
    const std::uint32_t from = std::bit_cast<std::uint32_t>(std::ldexp(1.0f, -21)), to = std::bit_cast<std::uint32_t>(1.0f);
    CHECK(lookup_mismatches(from, to, 1, isas) == 0);
    // Every 4099th pattern of the whole space (a prime stride meets every mantissa
    // and exponent), and every 64th below 2^-21.
    CHECK(lookup_mismatches(0, 0xFFFFFFFFu - 4098, 4099, isas) == 0);
    CHECK(lookup_mismatches(0, from, 64, isas) == 0);
    CHECK(lookup_mismatches(0x80000000u, 0xFFFFFFFFu, 65537, isas) == 0);
}

TEST_CASE("encode_display_unorm8 packs each channel's reference value, in every ISA") {
    std::vector<float> values = special_radiances();
    std::mt19937 rng(11);
    std::uniform_int_distribution<std::uint32_t> bits;
    std::uniform_real_distribution<float> exponent(-7.0f, 4.0f);
    while (values.size() < 40000) {
        values.push_back(std::bit_cast<float>(bits(rng)));  // any pattern
        values.push_back(std::pow(10.0f, exponent(rng)));   // radiances a frame has
    }
    const std::size_t n = values.size();
    for (Isa isa : supported_isas()) {
        CAPTURE(simd::isa_name(isa));
        // Channels rotated against each other, so every byte meets every value.
        std::vector<float> r(simd::padded_count(n)), g(r.size()), b(r.size());
        for (std::size_t i = 0; i < n; ++i) r[i] = values[i], g[i] = values[(i + 1) % n], b[i] = values[(i + 2) % n];
        image::encode_display_unorm8(isa, n, r.data(), g.data(), b.data());
        int mismatches = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const std::uint32_t expected = std::uint32_t(image::unorm8_from_radiance_reference(values[i])) |
                                           std::uint32_t(image::unorm8_from_radiance_reference(values[(i + 1) % n])) << 8 |
                                           std::uint32_t(image::unorm8_from_radiance_reference(values[(i + 2) % n])) << 16;
            mismatches += image::packed_unorm8(r[i]) != expected;
        }
        CHECK(mismatches == 0);
    }
}

// The proof over the whole input space, not only the tonemapped range: every
// 2^32 radiance bit pattern through each ISA's kernel against the reference.
// Minutes of powf: run by hand (tessera_tests -tc='*2^32*' --no-skip).
TEST_CASE("encode_display_unorm8 equals the reference for all 2^32 radiance bit patterns" * doctest::skip()) {
    const std::vector<Isa> isas = supported_isas();
    constexpr std::uint64_t kBlock = 1 << 16;
    std::atomic<std::uint64_t> mismatches{0};
    tbb::parallel_for(std::uint64_t(0), (std::uint64_t(1) << 32) / kBlock, [&](std::uint64_t block) {
        std::vector<float> radiance(kBlock), r(kBlock), zero(kBlock, 0.0f);
        std::vector<std::uint8_t> expected(kBlock);
        for (std::uint64_t i = 0; i < kBlock; ++i) {
            radiance[i] = std::bit_cast<float>(std::uint32_t(block * kBlock + i));
            expected[i] = image::unorm8_from_radiance_reference(radiance[i]);
        }
        std::uint64_t wrong = 0;
        for (Isa isa : isas) {
            r = radiance;
            image::encode_display_unorm8(isa, kBlock, r.data(), zero.data(), zero.data());
            for (std::uint64_t i = 0; i < kBlock; ++i) wrong += image::packed_unorm8(r[i]) != expected[i];
        }
        mismatches += wrong;
    });
    CHECK(mismatches == 0);
}
