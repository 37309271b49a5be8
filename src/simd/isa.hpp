// Which instruction set the SIMD kernels run with. Kernels are compiled once
// per ISA (cmake/SimdTargets.cmake) and picked at run time, so one binary runs
// on any x86-64. Shared by the stages that have SIMD kernels (raster, shade).
#pragma once

#include <string_view>

namespace tessera::simd {

// `scalar` runs the plain C++ reference code.
enum class Isa { scalar, sse4, avx2, avx512 };

std::string_view isa_name(Isa isa);
bool isa_supported(Isa isa);   // by cpuid, cached
Isa best_supported_isa();      // the widest supported
// Throws std::invalid_argument naming the ISA and the best available one.
void require_supported(Isa isa);

}  // namespace tessera::simd
