// Included first by every source that cmake/SimdTargets.cmake compiles once
// per ISA: xsimd, and the macro that gives this copy's entry points their
// ISA suffix (shade_fragments_avx2, ...). Everything else in such a file goes
// in an anonymous namespace, so the copies never meet at link time.
#pragma once

#if defined(TESSERA_EMULATE_AVX512)
#include "simd/avx512_emulation.hpp"  // the avx512 copy of a -DTESSERA_EMULATE_AVX512=ON build
#endif

// g++ 12 warns that _mm512_undefined_ps() & co. are "used uninitialized" once
// xsimd's exp/log are inlined: false positives inside the system header.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#include <xsimd/xsimd.hpp>
#pragma GCC diagnostic pop

#if !defined(TESSERA_SIMD_ARCH) || !defined(TESSERA_SIMD_SUFFIX)
#error "build SIMD kernels with tessera_add_simd_kernels(): it defines TESSERA_SIMD_ARCH and TESSERA_SIMD_SUFFIX"
#endif

#define TESSERA_SIMD_PASTE_(name, suffix) name##_##suffix
#define TESSERA_SIMD_PASTE(name, suffix) TESSERA_SIMD_PASTE_(name, suffix)
// The entry point `name` of this ISA's copy: name_sse4, name_avx2 or name_avx512.
#define TESSERA_SIMD_ENTRY(name) TESSERA_SIMD_PASTE(name, TESSERA_SIMD_SUFFIX)
