// Arrays handed to the SIMD kernels hold a multiple of kLanePadding floats, so a
// kernel may run whole vectors past its `count`: lanes beyond it compute values
// nobody reads. 16 floats is one AVX-512 vector.
#pragma once

#include <cstddef>

namespace tessera::simd {

inline constexpr std::size_t kLanePadding = 16;
inline constexpr std::size_t padded_count(std::size_t n) { return (n + kLanePadding - 1) / kLanePadding * kLanePadding; }

}  // namespace tessera::simd
