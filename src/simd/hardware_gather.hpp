// base[index[lane]] for every lane, with the hardware gather (vpgatherdd /
// vgatherdps) on AVX2 and AVX-512: xsimd 8.1's batch::gather loads lane by lane.
// For kernel sources only (compiled per ISA): the #if picks the instruction by
// the -march this copy is built with.
#pragma once

#include <cstdint>
#include <type_traits>

#include "simd/kernel_prelude.hpp"

namespace tessera::simd {

template <class T, class Arch>
xsimd::batch<T, Arch> hardware_gather(const T* base, const xsimd::batch<std::int32_t, Arch>& index) {
    static_assert(sizeof(T) == 4, "32-bit elements");
#if defined(__AVX512F__)
    if constexpr (xsimd::batch<T, Arch>::size == 16) {
        if constexpr (std::is_same_v<T, float>) return _mm512_i32gather_ps(index, base, 4);
        else return _mm512_i32gather_epi32(index, base, 4);
    }
#endif
#if defined(__AVX2__)
    if constexpr (xsimd::batch<T, Arch>::size == 8) {
        if constexpr (std::is_same_v<T, float>) return _mm256_i32gather_ps(base, index, 4);
        else return _mm256_i32gather_epi32(reinterpret_cast<const int*>(base), index, 4);
    }
#endif
    return xsimd::batch<T, Arch>::gather(base, index);
}

}  // namespace tessera::simd
