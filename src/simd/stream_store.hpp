// Non-temporal copies for kernels compiled per ISA (kernel_prelude.hpp first).
//
// On the 2-vCPU Zen 5 VMs a plain store to a line that the other core has
// read (in the frame before) waits for that copy to be invalidated: writing
// 14 MB read by the other core took 8x as long as writing it after reading it
// on the same core, and 3x as long as non-temporal stores, which need no
// read for ownership. So output that the next pass reads on any core is
// streamed when a frame runs on several threads.
#pragma once

#include <immintrin.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace tessera::simd {

// bytes [dst, dst + n) from src: the whole 64-byte lines of dst by
// non-temporal stores, the partial lines at either end plainly. The caller
// issues an sfence (stream_fence) before another thread reads them.
inline void stream_copy(void* dst, const void* src, std::size_t n) {
    char* const to = static_cast<char*>(dst);
    const char* const from = static_cast<const char*>(src);
    const auto address = reinterpret_cast<std::uintptr_t>(to);
    const std::size_t head = std::min(n, std::size_t(((address + 63) & ~std::uintptr_t(63)) - address));
    std::memcpy(to, from, head);
    std::size_t i = head;
    for (; i + 64 <= n; i += 64) {
        // Two 32-byte halves even with AVX-512 (the write-combining buffer
        // joins them), which the emulated AVX-512 build compiles too.
#if defined(__AVX__)
        for (std::size_t half = 0; half < 64; half += 32)
            _mm256_stream_si256(reinterpret_cast<__m256i*>(to + i + half),
                                _mm256_loadu_si256(reinterpret_cast<const __m256i*>(from + i + half)));
#else
        for (std::size_t quarter = 0; quarter < 64; quarter += 16)
            _mm_stream_si128(reinterpret_cast<__m128i*>(to + i + quarter),
                             _mm_loadu_si128(reinterpret_cast<const __m128i*>(from + i + quarter)));
#endif
    }
    std::memcpy(to + i, from + i, n - i);
}

// Orders the streamed stores before any later store (the hand-over to other threads).
inline void stream_fence() { _mm_sfence(); }

}  // namespace tessera::simd
