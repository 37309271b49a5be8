// The resolve's pixel loop (resolve_kernels.hpp), compiled once per ISA.
// With AVX2 (and in the AVX-512 copy for a row's last 8-15 pixels, after 16
// at a time by vpexpandd) a row goes 8 pixels at a time: their coverage mask
// picks a permutation that spreads the next covered pixels' colours over the
// covered lanes (an expand, built here from vpermd and a table), and a byte
// shuffle packs 8 RGBX pixels into 24 RGB bytes. Radiance rows spread three
// float planes the same way and interleave them into 24 RGB floats.
// Hand-written intrinsics:
// xsimd 8.1 has neither the masked load, the permutation nor byte shuffles.
#include <bit>
#include <cstring>

#include "simd/kernel_prelude.hpp"

#include "image/resolve_kernels.hpp"

namespace tessera::image {
namespace {

// One pixel the scalar way, branch-free: along a row of tiny triangles
// whether a pixel is covered is as good as random.
struct PixelCursor {
    const float* encoded;
    std::uint32_t clear;
    std::size_t k = 0;  // covered pixels met so far
    std::uint32_t next(float depth) {
        const std::uint32_t covered = depth < 1.0f;
        const std::uint32_t mask = 0u - covered;
        const std::uint32_t value = (std::bit_cast<std::uint32_t>(encoded[k & mask]) & mask) | (clear & ~mask);
        k += covered;
        return value;
    }
};

// Pixels [x, width) of a row: 4 bytes a pixel, the 4th overwritten by the
// next one; the row's last pixel writes 3.
inline void write_tail(PixelCursor& cursor, const float* depth, std::uint8_t* display, int x, int width) {
    for (; x + 1 < width; ++x) {
        const std::uint32_t value = cursor.next(depth[x]);
        std::memcpy(display + 3 * x, &value, 4);
    }
    const std::uint32_t last = cursor.next(depth[width - 1]);
    std::memcpy(display + 3 * (width - 1), &last, 3);
}

// Pixels [x, width) of a radiance row, branch-free as PixelCursor.
inline void write_radiance_tail(const RadianceRows& rows, std::size_t& k, const float* depth, float* out, int x) {
    for (; x < rows.width; ++x) {
        const bool covered = depth[x] < 1.0f;
        for (int c = 0; c < 3; ++c) out[3 * x + c] = *(covered ? rows.plane[c] + k : &rows.clear[c]);
        k += covered;
    }
}

#if defined(__AVX2__)
// kExpand[m][i]: for coverage mask m (bit i: lane i covered), which of the
// next covered colours lane i takes: the number of covered lanes below i.
struct ExpandTable {
    alignas(32) std::int32_t lane[256][8];
    constexpr ExpandTable() : lane{} {
        for (int m = 0; m < 256; ++m)
            for (int i = 0, below = 0; i < 8; ++i) {
                lane[m][i] = below;
                below += (m >> i) & 1;
            }
    }
};
constexpr ExpandTable kExpand;
alignas(32) constexpr std::int32_t kLaneIndex[8] = {0, 1, 2, 3, 4, 5, 6, 7};
#endif

}  // namespace

void TESSERA_SIMD_ENTRY(write_display_rows)(const DisplayRows& rows) {
    PixelCursor cursor{rows.encoded, rows.clear};
    const float* depth = rows.depth;
    std::uint8_t* display = rows.display;
    for (int y = 0; y < rows.height; ++y, depth += rows.side, display += rows.stride) {
        int x = 0;
#if defined(__AVX512F__)
        // 16 pixels at a time: vpexpandd spreads the next covered colours over
        // the covered lanes and keeps the clear colour in the others; RGBX → RGB
        // within each 128-bit quarter, the quarters' 12 bytes joined, 48 bytes stored.
        {
            const __m512 one = _mm512_set1_ps(1.0f);
            const __m512i clear = _mm512_set1_epi32(std::int32_t(rows.clear));
            const __m512i pack_bytes = _mm512_broadcast_i32x4(
                _mm_setr_epi8(0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1));
            const __m512i join_quarters = _mm512_setr_epi32(0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, 3, 7, 11, 15);
            for (; x + 16 <= rows.width; x += 16) {
                const __mmask16 covered_lanes = _mm512_cmp_ps_mask(_mm512_loadu_ps(depth + x), one, _CMP_LT_OQ);
                const unsigned covered = unsigned(std::popcount(unsigned(covered_lanes)));
                // The next `covered` colours (no lane past them is read: the array may end there).
                const __m512i next = _mm512_maskz_loadu_epi32(__mmask16((1u << covered) - 1u), rows.encoded + cursor.k);
                const __m512i pixels = _mm512_mask_expand_epi32(clear, covered_lanes, next);
                cursor.k += covered;
                const __m512i rgb = _mm512_permutexvar_epi32(join_quarters, _mm512_shuffle_epi8(pixels, pack_bytes));
                _mm512_mask_storeu_epi32(display + 3 * x, __mmask16(0x0FFF), rgb);
            }
        }
#endif
#if defined(__AVX2__)
        const __m256 one = _mm256_set1_ps(1.0f);
        const __m256i clear = _mm256_set1_epi32(std::int32_t(rows.clear));
        const __m256i lane = _mm256_load_si256(reinterpret_cast<const __m256i*>(kLaneIndex));
        // RGBX → RGB within each 128-bit half (12 bytes, then 4 zero bytes), then the halves joined.
        const __m256i pack_bytes = _mm256_setr_epi8(0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1,
                                                    0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1);
        const __m256i join_halves = _mm256_setr_epi32(0, 1, 2, 4, 5, 6, 3, 7);
        for (; x + 8 <= rows.width; x += 8) {
            const __m256 covered_lanes = _mm256_cmp_ps(_mm256_loadu_ps(depth + x), one, _CMP_LT_OQ);
            const unsigned mask = unsigned(_mm256_movemask_ps(covered_lanes));
            const int covered = std::popcount(mask);
            // The next `covered` colours (no lane past them is read: the array may end there).
            const __m256i take = _mm256_cmpgt_epi32(_mm256_set1_epi32(covered), lane);
            const __m256i next = _mm256_maskload_epi32(reinterpret_cast<const int*>(rows.encoded + cursor.k), take);
            const __m256i spread = _mm256_permutevar8x32_epi32(
                next, _mm256_load_si256(reinterpret_cast<const __m256i*>(kExpand.lane[mask])));
            const __m256i pixels = _mm256_blendv_epi8(clear, spread, _mm256_castps_si256(covered_lanes));
            cursor.k += std::size_t(covered);
            const __m256i rgb = _mm256_permutevar8x32_epi32(_mm256_shuffle_epi8(pixels, pack_bytes), join_halves);
            _mm_storeu_si128(reinterpret_cast<__m128i*>(display + 3 * x), _mm256_castsi256_si128(rgb));
            _mm_storel_epi64(reinterpret_cast<__m128i*>(display + 3 * x + 16), _mm256_extracti128_si256(rgb, 1));
        }
#endif
        if (x < rows.width) write_tail(cursor, depth, display, x, rows.width);
    }
}

void TESSERA_SIMD_ENTRY(write_radiance_rows)(const RadianceRows& rows) {
    std::size_t k = 0;  // covered pixels met so far
    const float* depth = rows.depth;
    float* out = rows.radiance;
    for (int y = 0; y < rows.height; ++y, depth += rows.side, out += rows.stride) {
        int x = 0;
#if defined(__AVX2__)
        const __m256 one = _mm256_set1_ps(1.0f);
        const __m256i lane = _mm256_load_si256(reinterpret_cast<const __m256i*>(kLaneIndex));
        __m256 clear[3];
        for (int c = 0; c < 3; ++c) clear[c] = _mm256_set1_ps(rows.clear[c]);
        // Output float j of 8 interleaved pixels is pixel j / 3's channel j % 3:
        // each 8-float store takes its pixels from every plane by one permutation,
        // then its channels by two blends (set bits: the later operand).
        const __m256i first = _mm256_setr_epi32(0, 0, 0, 1, 1, 1, 2, 2);   // floats 0-7
        const __m256i second = _mm256_setr_epi32(2, 3, 3, 3, 4, 4, 4, 5);  // floats 8-15
        const __m256i third = _mm256_setr_epi32(5, 5, 6, 6, 6, 7, 7, 7);   // floats 16-23
        for (; x + 8 <= rows.width; x += 8) {
            const __m256 covered_lanes = _mm256_cmp_ps(_mm256_loadu_ps(depth + x), one, _CMP_LT_OQ);
            const unsigned mask = unsigned(_mm256_movemask_ps(covered_lanes));
            const int covered = std::popcount(mask);
            const __m256i take = _mm256_cmpgt_epi32(_mm256_set1_epi32(covered), lane);
            const __m256i spread = _mm256_load_si256(reinterpret_cast<const __m256i*>(kExpand.lane[mask]));
            __m256 v[3];
            for (int c = 0; c < 3; ++c) {
                const __m256 next = _mm256_maskload_ps(rows.plane[c] + k, take);
                v[c] = _mm256_blendv_ps(clear[c], _mm256_permutevar8x32_ps(next, spread), covered_lanes);
            }
            k += std::size_t(covered);
            // The channel at positions 0 3 6 of the store, then 1 4 7 (the next
            // channel), then 2 5 (the last).
            const auto interleave = [&](const __m256i& pixels, int at036, int at25) {
                const __m256 a = _mm256_permutevar8x32_ps(v[at036], pixels);
                const __m256 b = _mm256_permutevar8x32_ps(v[(at036 + 1) % 3], pixels);
                const __m256 c = _mm256_permutevar8x32_ps(v[at25], pixels);
                return _mm256_blend_ps(_mm256_blend_ps(a, b, 0x92), c, 0x24);
            };
            _mm256_storeu_ps(out + 3 * x, interleave(first, 0, 2));
            _mm256_storeu_ps(out + 3 * x + 8, interleave(second, 2, 1));
            _mm256_storeu_ps(out + 3 * x + 16, interleave(third, 1, 0));
        }
#endif
        write_radiance_tail(rows, k, depth, out, x);
    }
}

}  // namespace tessera::image
