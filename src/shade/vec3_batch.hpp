// 3-vectors of xsimd batches, one vector per lane, and the vector math the
// shading kernels share (shade_kernels_simd.cpp, material_kernels_simd.cpp).
// Compiled once per ISA with its includers (TESSERA_SIMD_ARCH), so everything
// is in an anonymous namespace: the sse4/avx2/avx512 copies never meet at link
// time (a shared inline function would be one definition built three ways,
// and the linker would keep any one of them). `inline` here only keeps the
// helpers a kernel does not use from warning.
#pragma once

#include <cstddef>

#include "simd/kernel_prelude.hpp"

namespace tessera::shade {
namespace {

using Arch = TESSERA_SIMD_ARCH;
using Batch = xsimd::batch<float, Arch>;
using Mask = xsimd::batch_bool<float, Arch>;

// a·b + c and c − a·b, fused where the ISA has FMA. xsimd 8.1's avx512 backend
// has no fma kernel (its generic one is a·b + c, fused only by the compiler's
// contraction, and not at all in a file built without it), hence the intrinsics.
inline Batch fma(const Batch& a, const Batch& b, const Batch& c) {
#if XSIMD_WITH_AVX512F
    return _mm512_fmadd_ps(a, b, c);
#else
    return xsimd::fma(a, b, c);
#endif
}
inline Batch fnma(const Batch& a, const Batch& b, const Batch& c) {
#if XSIMD_WITH_AVX512F
    return _mm512_fnmadd_ps(a, b, c);
#else
    return xsimd::fnma(a, b, c);
#endif
}

struct Vec3 {
    Batch x, y, z;
};

inline Vec3 operator+(const Vec3& a, const Vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator-(const Vec3& a) { return {-a.x, -a.y, -a.z}; }
inline Vec3 operator*(const Vec3& a, const Batch& s) { return {a.x * s, a.y * s, a.z * s}; }
// (x·x' + y·y') + z·z' with the products after the first fused where the ISA has
// FMA: written out, because a file built without contraction (shade_kernels_simd.cpp)
// must still fuse them, and one built with it must not leave it to the context.
inline Batch dot(const Vec3& a, const Vec3& b) { return fma(a.z, b.z, fma(a.y, b.y, a.x * b.x)); }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// a where m is set, b elsewhere, per lane.
inline Vec3 select(const Mask& m, const Vec3& a, const Vec3& b) {
    return {xsimd::select(m, a.x, b.x), xsimd::select(m, a.y, b.y), xsimd::select(m, a.z, b.z)};
}

// 1/sqrt, not xsimd::rsqrt: that does not compile for AVX-512 in xsimd 8.1 and
// is only 12 bits on SSE/AVX2.
inline Batch inverse_length(const Vec3& a) { return Batch(1.0f) / xsimd::sqrt(dot(a, a)); }
inline Vec3 normalize(const Vec3& a) { return a * inverse_length(a); }

// |a|² as (x² + y²) + z², the products rounded before the sums as the scalar
// distance_squared (pbr_reference.hpp) rounds them: the empty asm hides them
// from the compiler, which would otherwise fuse them into FMAs on some ISAs
// and not on others (xsimd has no way to forbid that), and a range's edge
// would fall differently.
inline Batch length_squared_unfused(const Vec3& a) {
    Batch x = a.x * a.x, y = a.y * a.y, z = a.z * a.z;
#if defined(TESSERA_EMULATE_AVX512)
    // Emulated 512-bit batches live in no single register (simd/avx512_emulation.hpp).
    asm("" : "+m"(x.data), "+m"(y.data), "+m"(z.data));
#else
    asm("" : "+x"(x.data), "+x"(y.data), "+x"(z.data));
#endif
    return (x + y) + z;
}

// Lanes i .. i + Batch::size of three planes.
inline Vec3 load3(const float* x, const float* y, const float* z, std::size_t i) {
    return {xsimd::load_unaligned(x + i), xsimd::load_unaligned(y + i), xsimd::load_unaligned(z + i)};
}

}  // namespace
}  // namespace tessera::shade
