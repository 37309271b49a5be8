// CubeMap's sampling rule (cube_map.cpp: face_coords, sample_bilinear) over
// xsimd batches, one direction a lane, for the sources compiled once per ISA
// (cmake/SimdTargets.cmake): the IBL shading kernels (shade/ibl_kernels_simd.cpp)
// and the pre-computation's (precompute_simd.cpp). Every operation is the
// scalar code's, in its order; built without contraction, the lanes give the
// scalar bits. Taps are hardware gathers of the bordered faces; texel indices
// are computed in float (integers below 2^24, so exact: CubeArraysFit).
#pragma once

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

// CubeMap::sample_bilinear at per-lane level sides n and first-texel offsets
// (in texels) of the RGB array `texels`.
inline V3 sample_bilinear(const float* texels, const Face& c, const Batch& n, const Batch& offset) {
    const Batch u = c.s * n - Batch(0.5f), v = c.t * n - Batch(0.5f);
    const Batch x0f = xsimd::floor(u), y0f = xsimd::floor(v);
    const Batch fx = u - x0f, fy = v - y0f;
    const Batch last = n - Batch(1.0f);
    // NaN goes to −1, as the reference's clamp_nan_low: max(NaN, −1) is −1.
    const Batch x0 = xsimd::min(xsimd::max(x0f, Batch(-1.0f)), last);
    const Batch y0 = xsimd::min(xsimd::max(y0f, Batch(-1.0f)), last);
    const Batch row = n + Batch(2.0f);
    const Batch i00 = Batch(3.0f) * (offset + c.face * (row * row) + (y0 + Batch(1.0f)) * row + (x0 + Batch(1.0f)));
    const V3 t00 = gather3(texels, i00);
    const V3 t10 = gather3(texels, i00 + Batch(3.0f));
    const V3 t01 = gather3(texels, i00 + Batch(3.0f) * row);
    const V3 t11 = gather3(texels, i00 + Batch(3.0f) * row + Batch(3.0f));
    const V3 top = t00 + (t10 - t00) * fx;
    const V3 bottom = t01 + (t11 - t01) * fx;
    return top + (bottom - top) * fy;
}

}  // namespace
}  // namespace tessera::environment::cube_simd
