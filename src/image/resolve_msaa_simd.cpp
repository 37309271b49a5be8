// The 4× MSAA resolve (resolve_msaa_kernels.hpp), compiled once per ISA. A
// pixel's 4 samples are 4 consecutive fragment indices, so a 128-bit vector
// holds one pixel's samples (two pixels per AVX2 vector; the AVX-512 copy
// runs the AVX2 code): their values come by gather (masked, the background's
// where the index is -1), and horizontal adds sum each pixel's four — first
// samples 0+1 and 2+3, then those two, as the scalar loop adds them.
// Hand-written intrinsics: xsimd 8.1 has neither masked gathers, horizontal
// adds of pairs nor byte shuffles.
#include <cstring>

#include "simd/kernel_prelude.hpp"

#include "image/resolve_msaa_kernels.hpp"

namespace tessera::image {
namespace {

// One pixel the scalar way (the rows' tails), exactly as resolve.cpp.
inline void radiance_pixel(const MsaaResolveRows& rows, const std::int32_t* fragment, float* out) {
    for (int c = 0; c < 3; ++c) {
        float v[4];
        for (int s = 0; s < 4; ++s) v[s] = fragment[s] >= 0 ? rows.plane[c][fragment[s]] : rows.clear_radiance[c];
        out[c] = ((v[0] + v[1]) + (v[2] + v[3])) * 0.25f;
    }
}

inline std::uint32_t sample_display(const MsaaResolveRows& rows, std::int32_t fragment) {
    std::uint32_t value;
    if (fragment < 0) return rows.clear_display;
    std::memcpy(&value, rows.encoded + fragment, 4);
    return value;
}

inline void display_pixel(const MsaaResolveRows& rows, const std::int32_t* fragment, std::uint8_t* out) {
    std::uint32_t value[4];
    for (int s = 0; s < 4; ++s) value[s] = sample_display(rows, fragment[s]);
    for (int c = 0; c < 3; ++c) {
        unsigned sum = 0;
        for (int s = 0; s < 4; ++s) sum += (value[s] >> (8 * c)) & 0xFFu;
        out[c] = std::uint8_t((sum + 2) / 4);
    }
}

// Four packed RGBX samples (one pixel, 4 lanes) as their channels' sums:
// red and blue in the 16-bit halves of `low`, green (and the zero 4th byte)
// in those of `high` (4 × 255 fits in 16 bits).
inline void split_channels(__m128i v, __m128i& low, __m128i& high) {
    const __m128i bytes02 = _mm_set1_epi32(0x00FF00FF);
    low = _mm_and_si128(v, bytes02);
    high = _mm_and_si128(_mm_srli_epi32(v, 8), bytes02);
}

// Lane i of the sums of four pixels' channel fields (from split_channels):
// rounded means, packed back to RGBX.
inline __m128i rounded_means(__m128i low_sums, __m128i high_sums) {
    const __m128i bytes02 = _mm_set1_epi32(0x00FF00FF), two = _mm_set1_epi32(0x00020002);
    const __m128i low = _mm_and_si128(_mm_srli_epi32(_mm_add_epi32(low_sums, two), 2), bytes02);
    const __m128i high = _mm_and_si128(_mm_srli_epi32(_mm_add_epi32(high_sums, two), 2), bytes02);
    return _mm_or_si128(low, _mm_slli_epi32(high, 8));
}

inline __m128i pixel_samples_sse(const MsaaResolveRows& rows, const std::int32_t* fragment) {
    return _mm_setr_epi32(std::int32_t(sample_display(rows, fragment[0])), std::int32_t(sample_display(rows, fragment[1])),
                          std::int32_t(sample_display(rows, fragment[2])), std::int32_t(sample_display(rows, fragment[3])));
}

#if defined(__AVX2__)
// Two pixels' samples (8 fragment indices): the encoded values, the clear colour where -1.
inline __m256i pixel_pair_samples(const MsaaResolveRows& rows, const std::int32_t* fragment) {
    const __m256i index = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(fragment));
    const __m256i shaded = _mm256_cmpgt_epi32(index, _mm256_set1_epi32(-1));
    return _mm256_mask_i32gather_epi32(_mm256_set1_epi32(std::int32_t(rows.clear_display)),
                                       reinterpret_cast<const int*>(rows.encoded), index, shaded, 4);
}
#endif

}  // namespace

void TESSERA_SIMD_ENTRY(resolve_msaa_radiance_rows)(const MsaaResolveRows& rows) {
    for (int y = 0; y < rows.height; ++y) {
        const std::int32_t* fragment = rows.fragment + std::size_t(4) * rows.side * y;
        float* out = rows.radiance + rows.radiance_stride * y;
        int x = 0;
#if defined(__AVX2__)
        const __m256 quarter = _mm256_set1_ps(0.25f);
        // Two pixels a step; 4 floats stored per pixel (the 4th overwritten
        // by the next pixel), so the pair stops before the row's last pixel.
        // Two background pixels: the mean of four equal values is that value
        // (2c, 4c and c/4 are exact), so they store the background's, ungathered.
        const __m128 clear_pixel = _mm_setr_ps(rows.clear_radiance[0], rows.clear_radiance[1], rows.clear_radiance[2], 0.0f);
        for (; x + 2 < rows.width; x += 2) {
            const __m256i index = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(fragment + 4 * x));
            if (_mm256_testc_si256(index, _mm256_set1_epi32(-1))) {  // all eight samples -1
                _mm_storeu_ps(out + 3 * x, clear_pixel);
                _mm_storeu_ps(out + 3 * x + 3, clear_pixel);
                continue;
            }
            const __m256 shaded = _mm256_castsi256_ps(_mm256_cmpgt_epi32(index, _mm256_set1_epi32(-1)));
            __m256 v[3];
            for (int c = 0; c < 3; ++c)
                v[c] = _mm256_mask_i32gather_ps(_mm256_set1_ps(rows.clear_radiance[c]), rows.plane[c], index, shaded, 4);
            // Per 128-bit half: (s0+s1, s2+s3) of r, g, then b; then those pairs summed.
            const __m256 sums = _mm256_hadd_ps(_mm256_hadd_ps(v[0], v[1]), _mm256_hadd_ps(v[2], v[2]));
            const __m256 mean = _mm256_mul_ps(sums, quarter);
            _mm_storeu_ps(out + 3 * x, _mm256_castps256_ps128(mean));
            _mm_storeu_ps(out + 3 * x + 3, _mm256_extractf128_ps(mean, 1));
        }
#else
        const __m128 quarter = _mm_set1_ps(0.25f);
        for (; x + 1 < rows.width; ++x) {
            const std::int32_t* f = fragment + 4 * x;
            __m128 v[3];
            for (int c = 0; c < 3; ++c) {
                float value[4];
                for (int s = 0; s < 4; ++s) value[s] = f[s] >= 0 ? rows.plane[c][f[s]] : rows.clear_radiance[c];
                v[c] = _mm_loadu_ps(value);
            }
            const __m128 sums = _mm_hadd_ps(_mm_hadd_ps(v[0], v[1]), _mm_hadd_ps(v[2], v[2]));
            _mm_storeu_ps(out + 3 * x, _mm_mul_ps(sums, quarter));
        }
#endif
        for (; x < rows.width; ++x) radiance_pixel(rows, fragment + 4 * x, out + 3 * x);
    }
}

void TESSERA_SIMD_ENTRY(resolve_msaa_display_rows)(const MsaaResolveRows& rows) {
    for (int y = 0; y < rows.height; ++y) {
        const std::int32_t* fragment = rows.fragment + std::size_t(4) * rows.side * y;
        std::uint8_t* out = rows.display + rows.display_stride * y;
        int x = 0;
#if defined(__AVX2__)
        // Eight pixels a step: four vectors of two pixels' samples, their
        // channel fields summed per pixel by three rounds of horizontal adds,
        // which leave pixels 0 2 4 6 | 1 3 5 7 in the two halves.
        const __m256i bytes02 = _mm256_set1_epi32(0x00FF00FF);
        const __m256i pixel_order = _mm256_setr_epi32(0, 4, 1, 5, 2, 6, 3, 7);
        // RGBX → RGB within each 128-bit half (12 bytes, then 4 zero bytes), then the halves joined.
        const __m256i pack_bytes = _mm256_setr_epi8(0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1,
                                                    0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1);
        const __m256i join_halves = _mm256_setr_epi32(0, 1, 2, 4, 5, 6, 3, 7);
        // Eight pixels of the clear colour, packed as the loop below stores them.
        const __m256i clear_rgb = _mm256_permutevar8x32_epi32(
            _mm256_shuffle_epi8(_mm256_set1_epi32(std::int32_t(rows.clear_display)), pack_bytes), join_halves);
        for (; x + 8 <= rows.width; x += 8) {
            // Eight pixels whose 32 samples all show the background (common
            // beside the objects in a tile) are the clear colour: no gathers.
            const __m256i* indices = reinterpret_cast<const __m256i*>(fragment + 4 * x);
            const __m256i all_samples =
                _mm256_and_si256(_mm256_and_si256(_mm256_loadu_si256(indices), _mm256_loadu_si256(indices + 1)),
                                 _mm256_and_si256(_mm256_loadu_si256(indices + 2), _mm256_loadu_si256(indices + 3)));
            if (_mm256_testc_si256(all_samples, _mm256_set1_epi32(-1))) {  // every index -1
                _mm_storeu_si128(reinterpret_cast<__m128i*>(out + 3 * x), _mm256_castsi256_si128(clear_rgb));
                _mm_storel_epi64(reinterpret_cast<__m128i*>(out + 3 * x + 16), _mm256_extracti128_si256(clear_rgb, 1));
                continue;
            }
            __m256i low[4], high[4];
            for (int p = 0; p < 4; ++p) {
                const __m256i v = pixel_pair_samples(rows, fragment + 4 * (x + 2 * p));
                low[p] = _mm256_and_si256(v, bytes02);
                high[p] = _mm256_and_si256(_mm256_srli_epi32(v, 8), bytes02);
            }
            const __m256i low_sums = _mm256_hadd_epi32(_mm256_hadd_epi32(low[0], low[1]), _mm256_hadd_epi32(low[2], low[3]));
            const __m256i high_sums =
                _mm256_hadd_epi32(_mm256_hadd_epi32(high[0], high[1]), _mm256_hadd_epi32(high[2], high[3]));
            const __m256i two = _mm256_set1_epi32(0x00020002);
            const __m256i l = _mm256_and_si256(_mm256_srli_epi32(_mm256_add_epi32(low_sums, two), 2), bytes02);
            const __m256i h = _mm256_and_si256(_mm256_srli_epi32(_mm256_add_epi32(high_sums, two), 2), bytes02);
            const __m256i pixels = _mm256_permutevar8x32_epi32(_mm256_or_si256(l, _mm256_slli_epi32(h, 8)), pixel_order);
            const __m256i rgb = _mm256_permutevar8x32_epi32(_mm256_shuffle_epi8(pixels, pack_bytes), join_halves);
            _mm_storeu_si128(reinterpret_cast<__m128i*>(out + 3 * x), _mm256_castsi256_si128(rgb));
            _mm_storel_epi64(reinterpret_cast<__m128i*>(out + 3 * x + 16), _mm256_extracti128_si256(rgb, 1));
        }
#else
        // Four pixels a step, one vector of samples each.
        const __m128i pack_bytes = _mm_setr_epi8(0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1);
        for (; x + 4 <= rows.width; x += 4) {
            __m128i low[4], high[4];
            for (int p = 0; p < 4; ++p) split_channels(pixel_samples_sse(rows, fragment + 4 * (x + p)), low[p], high[p]);
            const __m128i pixels =
                rounded_means(_mm_hadd_epi32(_mm_hadd_epi32(low[0], low[1]), _mm_hadd_epi32(low[2], low[3])),
                              _mm_hadd_epi32(_mm_hadd_epi32(high[0], high[1]), _mm_hadd_epi32(high[2], high[3])));
            const __m128i rgb = _mm_shuffle_epi8(pixels, pack_bytes);
            _mm_storel_epi64(reinterpret_cast<__m128i*>(out + 3 * x), rgb);
            const std::int32_t last = _mm_extract_epi32(rgb, 2);
            std::memcpy(out + 3 * x + 8, &last, 4);
        }
#endif
        for (; x < rows.width; ++x) display_pixel(rows, fragment + 4 * x, out + 3 * x);
    }
}

}  // namespace tessera::image
