// CubeMap's sampling rule (cube_map.cpp: face_coords, sample_bilinear) over
// xsimd batches, one direction a lane, for the sources compiled once per ISA
// (cmake/SimdTargets.cmake): the IBL shading kernels (shade/ibl_kernels_simd.cpp)
// and the pre-computation's (precompute_simd.cpp). Every operation is the
// scalar code's, in its order; built without contraction, the lanes give the
// scalar bits. Taps are hardware gathers of the bordered faces; texel indices
// are computed in float (integers below 2^24, so exact: CubeArraysFit).
#pragma once

#include <cstddef>
#include <cstdint>

#include "simd/kernel_prelude.hpp"

#include "simd/hardware_gather.hpp"

namespace tessera::environment::cube_simd {
namespace {

using Arch = TESSERA_SIMD_ARCH;
using Batch = xsimd::batch<float, Arch>;
using Mask = xsimd::batch_bool<float, Arch>;

struct V3 {
    Batch x, y, z;
};
inline V3 operator+(const V3& a, const V3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(const V3& a, const V3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator*(const V3& a, const Batch& s) { return {a.x * s, a.y * s, a.z * s}; }
inline V3 operator*(const V3& a, const V3& b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
// glm's order: (x·x' + y·y') + z·z', no fused operations.
inline Batch dot(const V3& a, const V3& b) { return (a.x * b.x + a.y * b.y) + a.z * b.z; }
// glm::normalize: v · inversesqrt(v·v), inversesqrt = 1 / sqrt.
inline V3 normalize(const V3& v) {
    const Batch inv = Batch(1.0f) / xsimd::sqrt(dot(v, v));
    return v * inv;
}
// glm::max(a, b) on floats: a < b ? b : a.
inline Batch gmax(const Batch& a, const Batch& b) { return xsimd::select(a < b, b, a); }
inline V3 load3(const float* x, const float* y, const float* z, std::size_t i) {
    return {xsimd::load_unaligned(x + i), xsimd::load_unaligned(y + i), xsimd::load_unaligned(z + i)};
}
inline Batch gather(const float* base, const Batch& index) { return simd::hardware_gather(base, xsimd::to_int(index)); }
inline V3 gather3(const float* base, const Batch& index) {
    return {gather(base, index), gather(base, index + Batch(1.0f)), gather(base, index + Batch(2.0f))};
}

// environment::face_coords per lane.
struct Face {
    Batch face, s, t;
};
inline Face face_coords(const V3& d) {
    const Batch zero(0.0f);
    const Batch ax = xsimd::abs(d.x), ay = xsimd::abs(d.y), az = xsimd::abs(d.z);
    const Mask is_x = (ax >= ay) && (ax >= az);
    const Mask is_y = !is_x && (ay >= az);
    const Mask x_pos = d.x >= zero, y_pos = d.y >= zero, z_pos = d.z >= zero;
    const Batch face = xsimd::select(is_x, xsimd::select(x_pos, Batch(0.0f), Batch(1.0f)),
                                     xsimd::select(is_y, xsimd::select(y_pos, Batch(2.0f), Batch(3.0f)),
                                                   xsimd::select(z_pos, Batch(4.0f), Batch(5.0f))));
    const Batch ma = xsimd::select(is_x, ax, xsimd::select(is_y, ay, az));
    const Batch sc = xsimd::select(is_x, xsimd::select(x_pos, -d.z, d.z),
                                   xsimd::select(is_y, d.x, xsimd::select(z_pos, d.x, -d.x)));
    const Batch tc = xsimd::select(is_y, xsimd::select(y_pos, d.z, -d.z), -d.y);
    return {face, Batch(0.5f) * (sc / ma + Batch(1.0f)), Batch(0.5f) * (tc / ma + Batch(1.0f))};
}

// The four taps' texels and the bilinear weights.
inline V3 blend_taps(const V3& t00, const V3& t10, const V3& t01, const V3& t11, const Batch& fx, const Batch& fy) {
    const V3 top = t00 + (t10 - t00) * fx;
    const V3 bottom = t01 + (t11 - t01) * fx;
    return top + (bottom - top) * fy;
}

// The tap coordinates of CubeMap::sample_bilinear: the texel x0, y0 (border
// −1 and n included) and the weights.
struct Taps {
    Batch x0, y0, fx, fy;
};
inline Taps bilinear_taps(const Face& c, const Batch& n) {
    const Batch u = c.s * n - Batch(0.5f), v = c.t * n - Batch(0.5f);
    const Batch x0f = xsimd::floor(u), y0f = xsimd::floor(v);
    const Batch last = n - Batch(1.0f);
    // NaN goes to −1, as the reference's clamp_nan_low: max(NaN, −1) is −1.
    return {xsimd::min(xsimd::max(x0f, Batch(-1.0f)), last), xsimd::min(xsimd::max(y0f, Batch(-1.0f)), last), u - x0f,
            v - y0f};
}

#if defined(__AVX512F__)
// The two neighbouring taps (x0, y) and (x0 + 1, y) of every lane: six floats
// from `index` on, read as three 64-bit gathers of 8 lanes each per half
// (half the elements of six 32-bit gathers), split into channels by
// two-register permutes (xsimd 8.1 has neither 64-bit gathers of float pairs
// nor vpermt2ps). The same floats as gather3, so the same bits.
inline void gather_tap_pair(const float* texels, const Batch& index, V3& left, V3& right) {
    const __m512i lanes = xsimd::to_int(index);
    const __m256i low = _mm512_castsi512_si256(lanes), high = _mm512_extracti64x4_epi64(lanes, 1);
    const __m512i even = _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30);
    const __m512i odd = _mm512_setr_epi32(1, 3, 5, 7, 9, 11, 13, 15, 17, 19, 21, 23, 25, 27, 29, 31);
    Batch first[3], second[3];
    for (int p = 0; p < 3; ++p) {
        const float* base = texels + 2 * p;
        const __m512 a = _mm512_castsi512_ps(_mm512_i32gather_epi64(low, base, 4));
        const __m512 b = _mm512_castsi512_ps(_mm512_i32gather_epi64(high, base, 4));
        first[p] = _mm512_permutex2var_ps(a, even, b), second[p] = _mm512_permutex2var_ps(a, odd, b);
    }
    left = {first[0], second[0], first[1]};    // R0 G0 B0
    right = {second[1], first[2], second[2]};  // R1 G1 B1
}
#endif

// base[index], base[index + 1] of every lane (a texel of two floats).
inline void gather_float_pair(const float* base, const Batch& index, Batch& first, Batch& second) {
#if defined(__AVX512F__)
    const __m512i lanes = xsimd::to_int(index);
    const __m512 a = _mm512_castsi512_ps(_mm512_i32gather_epi64(_mm512_castsi512_si256(lanes), base, 4));
    const __m512 b = _mm512_castsi512_ps(_mm512_i32gather_epi64(_mm512_extracti64x4_epi64(lanes, 1), base, 4));
    first = _mm512_permutex2var_ps(a, _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30), b);
    second = _mm512_permutex2var_ps(a, _mm512_setr_epi32(1, 3, 5, 7, 9, 11, 13, 15, 17, 19, 21, 23, 25, 27, 29, 31), b);
#else
    first = gather(base, index), second = gather(base, index + Batch(1.0f));
#endif
}

inline V3 gather_bilinear(const float* texels, const Face& c, const Taps& t, const Batch& n, const Batch& offset) {
    const Batch row = n + Batch(2.0f);
    const Batch i00 = Batch(3.0f) * (offset + c.face * (row * row) + (t.y0 + Batch(1.0f)) * row + (t.x0 + Batch(1.0f)));
#if defined(__AVX512F__)
    V3 t00, t10, t01, t11;
    gather_tap_pair(texels, i00, t00, t10);
    gather_tap_pair(texels, i00 + Batch(3.0f) * row, t01, t11);
#else
    const V3 t00 = gather3(texels, i00);
    const V3 t10 = gather3(texels, i00 + Batch(3.0f));
    const V3 t01 = gather3(texels, i00 + Batch(3.0f) * row);
    const V3 t11 = gather3(texels, i00 + Batch(3.0f) * row + Batch(3.0f));
#endif
    return blend_taps(t00, t10, t01, t11, t.fx, t.fy);
}

// CubeMap::sample_bilinear at per-lane level sides n and first-texel offsets
// (in texels) of the RGB array `texels`.
inline V3 sample_bilinear(const float* texels, const Face& c, const Batch& n, const Batch& offset) {
    return gather_bilinear(texels, c, bilinear_taps(c, n), n, offset);
}

#if defined(__AVX512F__)
// Lanes that look up neighbouring directions (a row of background pixels, a
// smooth surface's normals) read a few neighbouring texels: when all lanes'
// taps lie on one face within 10 texels of two (or three) rows, those rows'
// 32-float windows are loaded once and each lane's texels picked out of them
// by a two-register permute (xsimd 8.1 has no such operation: AVX-512's
// vpermt2ps). The same texels as the gathers read, so the same bits.
inline float lanes_min(const Batch& v) { return _mm512_reduce_min_ps(v); }
inline float lanes_max(const Batch& v) { return _mm512_reduce_max_ps(v); }
inline bool lanes_uniform(const Batch& v, float& value) {
    value = lanes_min(v);
    return value == lanes_max(v);
}

struct Window {
    __m512 lo, hi;
};
inline Window load_window(const float* p) { return {_mm512_loadu_ps(p), _mm512_loadu_ps(p + 16)}; }
inline Batch pick(const Window& w, const __m512i& k) { return _mm512_permutex2var_ps(w.lo, k, w.hi); }
// The tap pair (x0, x0 + 1) of every lane from one window, k = 3·(x0 − window's x).
inline void pick_pair(const Window& w, const __m512i k[6], V3& left, V3& right) {
    left = {pick(w, k[0]), pick(w, k[1]), pick(w, k[2])};
    right = {pick(w, k[3]), pick(w, k[4]), pick(w, k[5])};
}

// false: the lanes' taps do not fit (other faces, far apart, the array's end).
inline bool window_bilinear(const float* texels, std::size_t float_count, const Face& c, const Taps& t, float n,
                            float offset, V3& out) {
    float face, x_min, y_min;
    if (!lanes_uniform(c.face, face)) return false;
    x_min = lanes_min(t.x0), y_min = lanes_min(t.y0);
    const float x_span = lanes_max(t.x0) - x_min, y_span = lanes_max(t.y0) - y_min;
    if (!(x_span <= 8.0f && y_span <= 1.0f)) return false;
    const float row = n + 2.0f;
    const float first = 3.0f * (offset + face * (row * row) + (y_min + 1.0f) * row + (x_min + 1.0f));
    const float last = first + 3.0f * row * (y_span + 1.0f);  // the last window's start
    if (!(first >= 0.0f) || std::size_t(last) + 32 > float_count) return false;
    const std::size_t start = std::size_t(first), stride = 3 * std::size_t(row);
    const __m512i k0 = _mm512_cvttps_epi32(Batch(3.0f) * (t.x0 - Batch(x_min)));
    const __m512i k[6] = {k0,
                          _mm512_add_epi32(k0, _mm512_set1_epi32(1)),
                          _mm512_add_epi32(k0, _mm512_set1_epi32(2)),
                          _mm512_add_epi32(k0, _mm512_set1_epi32(3)),
                          _mm512_add_epi32(k0, _mm512_set1_epi32(4)),
                          _mm512_add_epi32(k0, _mm512_set1_epi32(5))};
    V3 t00, t10, t01, t11;
    pick_pair(load_window(texels + start), k, t00, t10);
    const Window second = load_window(texels + start + stride);
    pick_pair(second, k, t01, t11);
    if (y_span > 0.0f) {  // lanes one row down read rows y_min + 1 and + 2
        const Mask first_row = t.y0 == Batch(y_min);
        V3 d00, d10, d01, d11;
        pick_pair(second, k, d00, d10);
        pick_pair(load_window(texels + start + 2 * stride), k, d01, d11);
        const auto choose = [&](const V3& a, const V3& b) {
            return V3{xsimd::select(first_row, a.x, b.x), xsimd::select(first_row, a.y, b.y),
                      xsimd::select(first_row, a.z, b.z)};
        };
        t00 = choose(t00, d00), t10 = choose(t10, d10), t01 = choose(t01, d01), t11 = choose(t11, d11);
    }
    out = blend_taps(t00, t10, t01, t11, t.fx, t.fy);
    return true;
}
#endif

// sample_bilinear at one level for every lane (side n, first texel offset, of
// an array of float_count floats): the windows where they fit, else gathers.
inline V3 sample_bilinear_level(const float* texels, std::size_t float_count, const Face& c, float n, float offset) {
    const Batch n_batch(n);
    const Taps t = bilinear_taps(c, n_batch);
#if defined(__AVX512F__)
    V3 out;
    if (window_bilinear(texels, float_count, c, t, n, offset, out)) return out;
#else
    (void)float_count;
#endif
    return gather_bilinear(texels, c, t, n_batch, Batch(offset));
}

}  // namespace
}  // namespace tessera::environment::cube_simd
