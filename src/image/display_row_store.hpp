// How a tile's display row, built in an L1 buffer, goes into the image. A
// 32-pixel tile row is 96 bytes: one whole 64-byte cache line and half of one
// shared with a neighbouring tile. Whole lines take two aligned 32-byte stores
// (AVX; four 16-byte ones otherwise), the partial lines at either end exact
// smaller stores, so nothing outside the row's bytes is written. Storing 8
// pixels as 16 + 8 unaligned bytes straight into the image took a third
// longer at 4K (tools/microbench: display_write/tiles/kernel against /lines),
// the image being too big to stay cached. Header-only with internal linkage:
// each per-ISA kernel file (and resolve.cpp, plain SSE2) compiles its own copy.
#pragma once

#include <immintrin.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace tessera::image {
namespace {

// bytes < 64 from `src` to `dst`, each exactly once, in as few stores as their bits.
[[gnu::always_inline]] inline void store_short(std::uint8_t* dst, const std::uint8_t* src, std::size_t bytes) {
    if (bytes & 32) {
#if defined(__AVX__)
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(dst), _mm256_loadu_si256(reinterpret_cast<const __m256i*>(src)));
#else
        _mm_storeu_si128(reinterpret_cast<__m128i*>(dst), _mm_loadu_si128(reinterpret_cast<const __m128i*>(src)));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(dst + 16), _mm_loadu_si128(reinterpret_cast<const __m128i*>(src + 16)));
#endif
        dst += 32, src += 32;
    }
    if (bytes & 16) {
        _mm_storeu_si128(reinterpret_cast<__m128i*>(dst), _mm_loadu_si128(reinterpret_cast<const __m128i*>(src)));
        dst += 16, src += 16;
    }
    if (bytes & 8) std::memcpy(dst, src, 8), dst += 8, src += 8;
    if (bytes & 4) std::memcpy(dst, src, 4), dst += 4, src += 4;
    if (bytes & 2) std::memcpy(dst, src, 2), dst += 2, src += 2;
    if (bytes & 1) *dst = *src;
}

// One whole cache line (dst 64-byte aligned).
[[gnu::always_inline]] inline void store_line(std::uint8_t* dst, const std::uint8_t* src) {
#if defined(__AVX__)
    _mm256_store_si256(reinterpret_cast<__m256i*>(dst), _mm256_loadu_si256(reinterpret_cast<const __m256i*>(src)));
    _mm256_store_si256(reinterpret_cast<__m256i*>(dst + 32),
                       _mm256_loadu_si256(reinterpret_cast<const __m256i*>(src + 32)));
#else
    for (int i = 0; i < 64; i += 16)
        _mm_store_si128(reinterpret_cast<__m128i*>(dst + i), _mm_loadu_si128(reinterpret_cast<const __m128i*>(src + i)));
#endif
}

// `bytes` of `src` to `dst`: the partial lines at either end, the whole lines between.
[[gnu::always_inline]] inline void store_display_row(std::uint8_t* dst, const std::uint8_t* src, std::size_t bytes) {
    const std::size_t head = std::min(bytes, (64 - (reinterpret_cast<std::uintptr_t>(dst) & 63)) & 63);
    store_short(dst, src, head);
    dst += head, src += head, bytes -= head;
    for (; bytes >= 64; dst += 64, src += 64, bytes -= 64) store_line(dst, src);
    store_short(dst, src, bytes);
}

}  // namespace
}  // namespace tessera::image
