// Built for x86-64-v3 in the emulated build only (tests/simd/CMakeLists.txt): each shim
// of simd/avx512_emulation.hpp against the AVX2 instruction that does the same per lane,
// on both 256-bit halves. Nothing else here, so no inline function built for AVX2
// can stand in for another object's copy.
#include "simd/avx512_emulation.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>

namespace tessera::test {

namespace {

template <class T>
bool same_bytes(const T& a, const T& b) {
    return std::memcmp(&a, &b, sizeof(T)) == 0;
}

__m256 low_ps(__m512 v) { return simde_mm512_castps512_ps256(v); }
__m256 high_ps(__m512 v) { return simde_mm256_castpd_ps(simde_mm512_extractf64x4_pd(simde_mm512_castps_pd(v), 1)); }
__m256i low_si(__m512i v) { return simde_mm512_castsi512_si256(v); }
__m256i high_si(__m512i v) { return simde_mm512_extracti64x4_epi64(v, 1); }

}  // namespace

// How many shim results differ from AVX2's; `first` names the first difference.
int avx512_emulation_mismatches(std::string& first) {
    int mismatches = 0;
    auto expect = [&](bool ok, const char* what) {
        if (ok) return;
        if (mismatches++ == 0) first = what;
    };
    std::mt19937 rng(512);
    const float specials[] = {0.0f, -0.0f, 0.5f, 1.5f, 2.5f, -2.5f, 2147483520.0f, 2147483648.0f, -2147483648.0f,
                              -2147483904.0f, 1e20f, -1e20f, std::numeric_limits<float>::infinity(),
                              -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN(),
                              std::numeric_limits<float>::denorm_min(), 8388607.5f, -8388607.5f};
    std::uniform_real_distribution<float> wide(-3e9f, 3e9f), narrow(-40.0f, 40.0f);
    std::int32_t table[64];
    for (int i = 0; i < 64; ++i) table[i] = std::int32_t(rng());
    for (int round = 0; round < 2000; ++round) {
        alignas(64) float f[16];
        alignas(64) std::int32_t k[16], m[16], index[16];
        alignas(64) double d[8];
        for (int i = 0; i < 16; ++i) {
            const unsigned pick = rng() % 4;
            f[i] = pick == 0 ? specials[rng() % std::size(specials)] : pick == 1 ? wide(rng) : narrow(rng);
            k[i] = std::int32_t(rng());
            m[i] = rng() % 3 == 0 ? k[i] : std::int32_t(rng() % 5) - 2;
            index[i] = std::int32_t(rng() % 64) - 16;
        }
        for (int i = 0; i < 8; ++i) d[i] = double(narrow(rng)) * (1.0 + 1e-9 * double(rng() % 1000)) + (i == 7 ? 1e40 : 0.0);
        const __m512 vf = simde_mm512_load_ps(f);
        const __m512i vk = simde_mm512_load_si512(k), vm = simde_mm512_load_si512(m), vi = simde_mm512_load_si512(index);
        const __m512d vd = simde_mm512_load_pd(d);

        const __m512i rounded = _mm512_cvtps_epi32(vf), truncated = _mm512_cvttps_epi32(vf);
        expect(same_bytes(low_si(rounded), _mm256_cvtps_epi32(low_ps(vf))) &&
                   same_bytes(high_si(rounded), _mm256_cvtps_epi32(high_ps(vf))), "_mm512_cvtps_epi32");
        expect(same_bytes(low_si(truncated), _mm256_cvttps_epi32(low_ps(vf))) &&
                   same_bytes(high_si(truncated), _mm256_cvttps_epi32(high_ps(vf))), "_mm512_cvttps_epi32");
        const __m512 converted = _mm512_cvtepi32_ps(vk);
        expect(same_bytes(low_ps(converted), _mm256_cvtepi32_ps(low_si(vk))) &&
                   same_bytes(high_ps(converted), _mm256_cvtepi32_ps(high_si(vk))), "_mm512_cvtepi32_ps");
        const __m512d widened = _mm512_cvtepi32_pd(low_si(vk));
        expect(same_bytes(simde_mm512_extractf64x4_pd(widened, 0), _mm256_cvtepi32_pd(_mm256_castsi256_si128(low_si(vk)))) &&
                   same_bytes(simde_mm512_extractf64x4_pd(widened, 1), _mm256_cvtepi32_pd(_mm256_extracti128_si256(low_si(vk), 1))),
               "_mm512_cvtepi32_pd");
        const __m512i zero_extended = _mm512_cvtepu16_epi32(high_si(vk));
        expect(same_bytes(low_si(zero_extended), _mm256_cvtepu16_epi32(_mm256_castsi256_si128(high_si(vk)))) &&
                   same_bytes(high_si(zero_extended), _mm256_cvtepu16_epi32(_mm256_extracti128_si256(high_si(vk), 1))),
               "_mm512_cvtepu16_epi32");
        const __m256 narrowed = _mm512_cvtpd_ps(vd);
        expect(same_bytes(narrowed, _mm256_set_m128(_mm256_cvtpd_ps(_mm256_load_pd(d + 4)), _mm256_cvtpd_ps(_mm256_load_pd(d)))),
               "_mm512_cvtpd_ps");
        for (const unsigned count : {0u, 1u, 7u, 31u, 32u, 200u}) {
            const __m512i shifted = _mm512_srai_epi32(vk, count);
            expect(same_bytes(low_si(shifted), _mm256_srai_epi32(low_si(vk), int(count))) &&
                       same_bytes(high_si(shifted), _mm256_srai_epi32(high_si(vk), int(count))), "_mm512_srai_epi32");
        }
        // Predicates as AVX2 compares: lanes' sign bits to a mask.
        auto bits = [](__m256i lo, __m256i hi) {
            return unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(lo))) |
                   unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(hi))) << 8;
        };
        const __m256i a0 = low_si(vk), a1 = high_si(vk), b0 = low_si(vm), b1 = high_si(vm);
        const unsigned eq = bits(_mm256_cmpeq_epi32(a0, b0), _mm256_cmpeq_epi32(a1, b1));
        const unsigned gt = bits(_mm256_cmpgt_epi32(a0, b0), _mm256_cmpgt_epi32(a1, b1));
        const unsigned lt = bits(_mm256_cmpgt_epi32(b0, a0), _mm256_cmpgt_epi32(b1, a1));
        const unsigned expected[8] = {eq, lt, lt | eq, 0u, 0xFFFFu & ~eq, 0xFFFFu & ~lt, gt, 0xFFFFu};
        expect(_mm512_cmp_epi32_mask(vk, vm, _MM_CMPINT_EQ) == expected[0] &&
                   _mm512_cmp_epi32_mask(vk, vm, _MM_CMPINT_LT) == expected[1] &&
                   _mm512_cmp_epi32_mask(vk, vm, _MM_CMPINT_LE) == expected[2] &&
                   _mm512_cmp_epi32_mask(vk, vm, 3) == expected[3] &&
                   _mm512_cmp_epi32_mask(vk, vm, _MM_CMPINT_NE) == expected[4] &&
                   _mm512_cmp_epi32_mask(vk, vm, _MM_CMPINT_NLT) == expected[5] &&
                   _mm512_cmp_epi32_mask(vk, vm, _MM_CMPINT_NLE) == expected[6] &&
                   _mm512_cmp_epi32_mask(vk, vm, 7) == expected[7],
               "_mm512_cmp_epi32_mask");
        const std::int32_t* base = table + 16;  // indices reach 16 below
        const __m512i gathered = _mm512_i32gather_epi32(vi, base, 4);
        expect(same_bytes(low_si(gathered), _mm256_i32gather_epi32(base, low_si(vi), 4)) &&
                   same_bytes(high_si(gathered), _mm256_i32gather_epi32(base, high_si(vi), 4)), "_mm512_i32gather_epi32");
        const float* fbase = reinterpret_cast<const float*>(base);
        const __m512 gathered_f = _mm512_i32gather_ps(vi, fbase, 4);
        expect(same_bytes(low_ps(gathered_f), _mm256_i32gather_ps(fbase, low_si(vi), 4)) &&
                   same_bytes(high_ps(gathered_f), _mm256_i32gather_ps(fbase, high_si(vi), 4)), "_mm512_i32gather_ps");
        const __m256 upper = _mm512_extractf32x8_ps(vf, 1), lower = _mm512_extractf32x8_ps(vf, 0);
        expect(std::memcmp(&lower, f, 32) == 0 && std::memcmp(&upper, f + 8, 32) == 0, "_mm512_extractf32x8_ps");
        // Masked stores against AVX2's vpmaskmovd (a lane's sign bit as its mask bit).
        const unsigned store_mask = unsigned(rng()) & 0xFFFFu;
        const auto mask_vector = [](unsigned bits) {
            alignas(32) std::int32_t lanes[8];
            for (int i = 0; i < 8; ++i) lanes[i] = (bits >> i) & 1u ? -1 : 0;
            return _mm256_load_si256(reinterpret_cast<const __m256i*>(lanes));
        };
        alignas(64) std::int32_t stored[16], expected_store[16];
        for (int i = 0; i < 16; ++i) stored[i] = expected_store[i] = m[i];
        _mm512_mask_storeu_epi32(stored, store_mask, vk);
        _mm256_maskstore_epi32(expected_store, mask_vector(store_mask & 0xFFu), low_si(vk));
        _mm256_maskstore_epi32(expected_store + 8, mask_vector(store_mask >> 8), high_si(vk));
        expect(std::memcmp(stored, expected_store, sizeof stored) == 0, "_mm512_mask_storeu_epi32");
        for (int i = 0; i < 16; ++i) stored[i] = expected_store[i] = m[i];
        _mm256_mask_storeu_epi32(stored + 3, __mmask8(store_mask), high_si(vk));
        _mm256_maskstore_epi32(expected_store + 3, mask_vector(store_mask & 0xFFu), high_si(vk));
        _mm_mask_storeu_epi32(stored + 11, __mmask8(store_mask >> 8), _mm256_castsi256_si128(low_si(vk)));
        _mm_maskstore_epi32(expected_store + 11, _mm256_castsi256_si128(mask_vector((store_mask >> 8) & 0xFu)),
                            _mm256_castsi256_si128(low_si(vk)));
        expect(std::memcmp(stored, expected_store, sizeof stored) == 0, "_mm256/_mm_mask_storeu_epi32");
        // The masked load against vpmaskmovd's load; the expand against its definition.
        const __m512i loaded = _mm512_maskz_loadu_epi32(__mmask16(store_mask), k);
        expect(same_bytes(low_si(loaded), _mm256_maskload_epi32(k, mask_vector(store_mask & 0xFFu))) &&
                   same_bytes(high_si(loaded), _mm256_maskload_epi32(k + 8, mask_vector(store_mask >> 8))),
               "_mm512_maskz_loadu_epi32");
        alignas(64) std::int32_t expanded[16], expected_expand[16];
        simde_mm512_store_si512(expanded, _mm512_mask_expand_epi32(vm, __mmask16(store_mask), vk));
        for (int i = 0, next = 0; i < 16; ++i) expected_expand[i] = (store_mask >> i) & 1u ? k[next++] : m[i];
        expect(std::memcmp(expanded, expected_expand, sizeof expanded) == 0, "_mm512_mask_expand_epi32");
        // rsqrt14: within the hardware's bound of 2^-14 relative, for positive normal inputs.
        alignas(64) float positive[16], estimate[16];
        for (int i = 0; i < 16; ++i) positive[i] = std::fabs(narrow(rng)) + 1e-3f;
        simde_mm512_store_ps(estimate, _mm512_rsqrt14_ps(simde_mm512_load_ps(positive)));
        for (int i = 0; i < 16; ++i) {
            const double exact = 1.0 / std::sqrt(double(positive[i]));
            expect(std::fabs(estimate[i] - exact) <= exact * 0x1p-14, "_mm512_rsqrt14_ps");
        }
    }
    return mismatches;
}

}  // namespace tessera::test
