#include "image/display_encoding.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/glm.hpp>

#include "shade/pbr_reference.hpp"

namespace tessera::image {

// The SIMD copies (display_encoding_simd.cpp).
#define TESSERA_DECLARE_DISPLAY_KERNELS(suffix)                                                                  \
    void encode_display_unorm8_##suffix(const Unorm8Table& table, std::size_t count, float* r, const float* g, \
                                        const float* b);                                                        \
    void unorm8_from_tonemapped_##suffix(const Unorm8Table& table, std::size_t count, const float* tonemapped,  \
                                         std::int32_t* out);
TESSERA_DECLARE_DISPLAY_KERNELS(sse4)
TESSERA_DECLARE_DISPLAY_KERNELS(avx2)
TESSERA_DECLARE_DISPLAY_KERNELS(avx512)
#undef TESSERA_DECLARE_DISPLAY_KERNELS

std::uint8_t unorm8_from_tonemapped_reference(float tonemapped) {
    return quantize_unorm8(shade::gamma_encode(glm::vec3(tonemapped)).r);
}

std::uint8_t unorm8_from_radiance_reference(float radiance) {
    return quantize_unorm8(shade::display_from_radiance(glm::vec3(radiance)).r);
}

namespace {

using Table = Unorm8Table;

std::uint8_t reference_of_bits(std::uint32_t bits) {
    return unorm8_from_tonemapped_reference(std::bit_cast<float>(bits));
}

[[noreturn]] void not_a_step_function(const std::string& what) {
    throw std::logic_error("display encoding table: the reference tonemap+gamma+quantize is not the step function "
                           "the table assumes (" + what + ")");
}

Table build_table() {
    constexpr std::uint32_t kOne = 0x3F800000;  // 1.0f
    if (reference_of_bits(0) != 0 || reference_of_bits(kOne) != 255) not_a_step_function("ends");
    // threshold[k]: the bits of the smallest tonemapped value in [0, 1] whose
    // 8-bit value is at least k (binary search: the exhaustive test proves the
    // reference non-decreasing there).
    std::array<std::uint32_t, 256> threshold{};
    for (int k = 1; k <= 255; ++k) {
        std::uint32_t lo = 0, hi = kOne;  // value(lo) < k <= value(hi)
        while (hi - lo > 1) {
            const std::uint32_t mid = lo + (hi - lo) / 2;
            (reference_of_bits(mid) >= k ? hi : lo) = mid;
        }
        threshold[std::size_t(k)] = hi;
    }
    const std::uint32_t first_bucket_bits = std::uint32_t(Table::kIndexOffset + 1) << Table::kLowBits;
    if (threshold[1] < first_bucket_bits) not_a_step_function("a step below 2^-kExponentsBelowOne");

    Table table;
    const auto entry = [](int base, std::uint32_t low_threshold) {
        return std::int32_t((std::uint32_t(base) << Table::kBaseShift) | low_threshold);
    };
    constexpr std::uint32_t kNoStep = 1u << Table::kLowBits;
    table.entry.front() = entry(0, kNoStep);
    table.entry.back() = entry(255, kNoStep);
    for (int bucket = 1; bucket + 1 < Table::kBuckets; ++bucket) {
        const std::uint32_t begin = std::uint32_t(bucket + Table::kIndexOffset) << Table::kLowBits;
        const std::uint32_t end = begin + kNoStep;
        const int base = reference_of_bits(begin);
        std::uint32_t low = kNoStep;
        for (int k = base + 1; k <= 255 && threshold[std::size_t(k)] < end; ++k) {
            if (k > base + 1) not_a_step_function("two steps in one bucket");
            low = threshold[std::size_t(k)] - begin;
        }
        table.entry[std::size_t(bucket)] = entry(base, low);
    }
    return table;
}

}  // namespace

const Unorm8Table& unorm8_table() {
    static const Unorm8Table table = build_table();
    return table;
}

std::uint8_t unorm8_from_tonemapped(const Unorm8Table& table, float tonemapped) {
    const std::int32_t bits = std::bit_cast<std::int32_t>(tonemapped);
    const std::int32_t bucket = std::clamp((bits >> Table::kLowBits) - Table::kIndexOffset, 0, Table::kBuckets - 1);
    const std::int32_t e = table.entry[std::size_t(bucket)];
    const std::int32_t value = (e >> Table::kBaseShift) + ((bits & Table::kLowMask) >= (e & Table::kThresholdMask));
    // Outside [0, +inf] the buckets say 0 (negative) or 255 (NaN): pow(-inf, 1/2.2) is +inf, NaN stays NaN.
    if (bits == std::bit_cast<std::int32_t>(-INFINITY)) return 255;
    if (bits > std::bit_cast<std::int32_t>(INFINITY)) return 0;
    return std::uint8_t(value);
}

void encode_display_unorm8(simd::Isa isa, std::size_t count, float* r, const float* g, const float* b) {
    simd::require_supported(isa);
    switch (isa) {
        case simd::Isa::scalar:
            for (std::size_t i = 0; i < count; ++i) {
                const std::uint32_t packed = std::uint32_t(unorm8_from_radiance_reference(r[i])) |
                                             std::uint32_t(unorm8_from_radiance_reference(g[i])) << 8 |
                                             std::uint32_t(unorm8_from_radiance_reference(b[i])) << 16;
                r[i] = std::bit_cast<float>(packed);
            }
            return;
        case simd::Isa::sse4: return encode_display_unorm8_sse4(unorm8_table(), count, r, g, b);
        case simd::Isa::avx2: return encode_display_unorm8_avx2(unorm8_table(), count, r, g, b);
        case simd::Isa::avx512: return encode_display_unorm8_avx512(unorm8_table(), count, r, g, b);
    }
}

void unorm8_from_tonemapped(simd::Isa isa, std::size_t count, const float* tonemapped, std::int32_t* out) {
    simd::require_supported(isa);
    switch (isa) {
        case simd::Isa::scalar:
            for (std::size_t i = 0; i < count; ++i) out[i] = unorm8_from_tonemapped(unorm8_table(), tonemapped[i]);
            return;
        case simd::Isa::sse4: return unorm8_from_tonemapped_sse4(unorm8_table(), count, tonemapped, out);
        case simd::Isa::avx2: return unorm8_from_tonemapped_avx2(unorm8_table(), count, tonemapped, out);
        case simd::Isa::avx512: return unorm8_from_tonemapped_avx512(unorm8_table(), count, tonemapped, out);
    }
}

}  // namespace tessera::image
