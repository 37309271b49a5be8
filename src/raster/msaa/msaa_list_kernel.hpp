// The first half of collect_fragments() (msaa.hpp): a tile's 4× MSAA fragments
// listed from its samples, a pixel at a time from a table, without branches.
// Included by msaa.cpp (the baseline copy, SSE2, for Isa::scalar) and by
// msaa_fragment_simd.cpp (a copy per ISA, where pshufb copies a pixel's new
// fragments' triangle ids in one instruction); everything here is in an
// anonymous namespace, so the copies never meet at link time, and it uses no
// std:: template that a wider ISA's copy could lend the baseline one.
#pragma once

#include <cstddef>
#include <cstdint>

#include <emmintrin.h>
#if defined(__SSSE3__)
#include <tmmintrin.h>
#endif

#include "raster/msaa/msaa_fragment_kernels.hpp"
#include "raster/msaa/msaa_pattern.hpp"

namespace tessera::raster {
namespace {

static_assert(kMsaaSamples == 4, "a pixel's samples are one SSE vector");

// What list_sample_fragments() does with a pixel, by which samples are
// covered (bits 0-3) and which pairs of samples have the same triangle id
// (bits 4-9: 01, 02, 03, 12, 13, 23), worked out once by the reference loop's
// rule: a covered sample takes the fragment of the first earlier covered
// sample with its triangle, else a new one. The 1024 keys have few distinct
// patterns: a byte per key names one, so both tables stay in L1 beside the
// tile's samples.
struct alignas(16) PixelPattern {
    std::int32_t fragment[kMsaaSamples];  // offset from the pixel's first fragment; -1: background
    // Fragment k's triangle id is that of the sample it starts at (sample 0
    // past the last fragment): those samples' bytes, a byte shuffle of the
    // pixel's 4 ids.
    std::uint8_t first_sample_bytes[4 * kMsaaSamples];
    std::uint32_t new_fragments;
    constexpr bool operator==(const PixelPattern&) const = default;
};
struct PixelPatterns {
    static constexpr int kMaxDistinct = 128;
    PixelPattern pattern[kMaxDistinct];
    std::uint8_t of_key[1 << 10];
    int distinct = 0;
    constexpr PixelPatterns() : pattern{}, of_key{} {
        constexpr int kPair[4][4] = {{-1, 0, 1, 2}, {0, -1, 3, 4}, {1, 3, -1, 5}, {2, 4, 5, -1}};
        for (int key = 0; key < (1 << 10); ++key) {
            PixelPattern p{};
            int fragments = 0;
            for (int s = 0; s < kMsaaSamples; ++s) {
                p.fragment[s] = -1;
                if (!((key >> s) & 1)) continue;
                for (int t = 0; t < s && p.fragment[s] < 0; ++t)
                    if (((key >> t) & 1) && ((key >> (4 + kPair[t][s])) & 1)) p.fragment[s] = p.fragment[t];
                if (p.fragment[s] < 0) {
                    for (int b = 0; b < 4; ++b) p.first_sample_bytes[4 * fragments + b] = std::uint8_t(4 * s + b);
                    p.fragment[s] = fragments++;
                }
            }
            for (int f = fragments; f < kMsaaSamples; ++f)
                for (int b = 0; b < 4; ++b) p.first_sample_bytes[4 * f + b] = std::uint8_t(b);
            p.new_fragments = std::uint32_t(fragments);
            int i = 0;
            while (i < distinct && !(pattern[i] == p)) ++i;
            if (i == distinct) {
                if (distinct == kMaxDistinct) throw "more distinct pixel patterns than kMaxDistinct";
                pattern[distinct++] = p;
            }
            of_key[key] = std::uint8_t(i);
        }
    }
};
constexpr PixelPatterns kPixelPatterns;

// One pixel (its samples from `first` on): its samples' fragments, and the new
// ones appended from `count` on; returns the new count. No branches (a pixel's
// 0-4 new fragments are hard to predict): its 4 possible fragments are written
// every time, and count moves past the real ones.
[[gnu::always_inline]] inline std::size_t list_pixel(const SampleListing& l, std::size_t first, int x, int y,
                                                     std::size_t count) {
    const __m128 covered = _mm_cmplt_ps(_mm_loadu_ps(l.depth + first), _mm_set1_ps(1.0f));
    // Ids of uncovered samples may be stale: the table ignores their pairs.
    const __m128i id = _mm_loadu_si128(reinterpret_cast<const __m128i*>(l.triangle + first));
    // Pairs 01 02 03 12, then 13 23.
    const __m128i left = _mm_shuffle_epi32(id, _MM_SHUFFLE(1, 0, 0, 0));
    const __m128i right = _mm_shuffle_epi32(id, _MM_SHUFFLE(2, 3, 2, 1));
    const __m128i left2 = _mm_shuffle_epi32(id, _MM_SHUFFLE(0, 0, 2, 1));
    const __m128i right2 = _mm_shuffle_epi32(id, _MM_SHUFFLE(0, 0, 3, 3));
    const int same = _mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(left, right))) |
                     (_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(left2, right2))) & 3) << 4;
    const PixelPattern& p = kPixelPatterns.pattern[kPixelPatterns.of_key[_mm_movemask_ps(covered) | same << 4]];
    // Offsets + the pixel's first fragment index on covered lanes (-1 stays on the others).
    const __m128i base = _mm_and_si128(_mm_castps_si128(covered), _mm_set1_epi32(std::int32_t(count)));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(l.fragment + first),
                     _mm_add_epi32(_mm_load_si128(reinterpret_cast<const __m128i*>(p.fragment)), base));
    _mm_storel_epi64(reinterpret_cast<__m128i*>(l.x + count), _mm_set1_epi16(std::int16_t(x)));
    _mm_storel_epi64(reinterpret_cast<__m128i*>(l.y + count), _mm_set1_epi16(std::int16_t(y)));
#if defined(__SSSE3__)
    _mm_storeu_si128(reinterpret_cast<__m128i*>(l.fragment_triangle + count),
                     _mm_shuffle_epi8(id, _mm_load_si128(reinterpret_cast<const __m128i*>(p.first_sample_bytes))));
#else
    for (int k = 0; k < kMsaaSamples; ++k)
        l.fragment_triangle[count + k] = l.triangle[first + p.first_sample_bytes[4 * k] / 4];
#endif
    return count + p.new_fragments;
}

// Whether any of the 4 pixels' samples from `first` on is covered.
[[gnu::always_inline]] inline bool any_covered4(const float* depth) {
    const __m128 one = _mm_set1_ps(1.0f);
    const __m128 a = _mm_or_ps(_mm_cmplt_ps(_mm_loadu_ps(depth), one), _mm_cmplt_ps(_mm_loadu_ps(depth + 4), one));
    const __m128 b = _mm_or_ps(_mm_cmplt_ps(_mm_loadu_ps(depth + 8), one), _mm_cmplt_ps(_mm_loadu_ps(depth + 12), one));
    return _mm_movemask_ps(_mm_or_ps(a, b)) != 0;
}

// -1 (background) for `pixels` pixels' samples from `at` on.
[[gnu::always_inline]] inline void mark_background(std::int32_t* at, int pixels) {
    for (int i = 0; i < pixels; ++i) _mm_storeu_si128(reinterpret_cast<__m128i*>(at + kMsaaSamples * i), _mm_set1_epi32(-1));
}

// The listing: returns how many fragments it listed.
inline std::size_t list_sample_fragments(const SampleListing& listing) {
    // A local copy: through the caller's, g++ would reload every pointer after
    // each store (they might alias it).
    const SampleListing l = listing;
    std::size_t count = 0;
    for (int y = 0; y < l.height; ++y) {
        const std::size_t row = std::size_t(kMsaaSamples) * std::size_t(y) * l.side;
        std::int32_t* const fragment = l.fragment + row;
        if (y < l.box_y0 || y >= l.box_y1 || l.box_x0 >= l.box_x1) {
            mark_background(fragment, l.width);
            continue;
        }
        mark_background(fragment, l.box_x0);
        mark_background(fragment + std::size_t(kMsaaSamples) * l.box_x1, l.width - l.box_x1);
        for (int x = l.box_x0; x < l.box_x1;) {
            const std::size_t first = row + std::size_t(kMsaaSamples) * x;
            if (x + 4 <= l.box_x1 && !any_covered4(l.depth + first)) {  // 4 background pixels
                mark_background(l.fragment + first, 4);
                x += 4;
                continue;
            }
            const int end = x + 4 < l.box_x1 ? x + 4 : l.box_x1;
            for (; x < end; ++x) count = list_pixel(l, row + std::size_t(kMsaaSamples) * x, x, y, count);
        }
    }
    return count;
}

}  // namespace
}  // namespace tessera::raster
