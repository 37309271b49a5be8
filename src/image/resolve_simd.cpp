// The resolve's pixel loop (resolve_kernels.hpp), compiled once per ISA.
// With AVX2 (and in the AVX-512 copy, which runs the same 8-lane code) a row
// goes 8 pixels at a time: their coverage mask picks a permutation that
// spreads the next covered pixels' colours over the covered lanes (an expand:
// AVX-512's vpexpandd, built here from vpermd and a table), and a byte
// shuffle packs 8 RGBX pixels into 24 RGB bytes. Hand-written intrinsics:
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

}  // namespace tessera::image
