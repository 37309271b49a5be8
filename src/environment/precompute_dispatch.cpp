// Run-time choice of the pre-computation's kernels (precompute_simd.cpp).
#include "environment/precompute_kernels.hpp"

namespace tessera::environment {

#define TESSERA_DECLARE_PRECOMPUTE_ENTRY(suffix)                                                                   \
    void irradiance_sums_##suffix(const IrradianceKernelInput& in, std::size_t first, std::size_t count,          \
                                  const SumOutputs& out);                                                          \
    void prefilter_sums_##suffix(const PrefilterKernelInput& in, std::size_t first, std::size_t count,            \
                                 const SumOutputs& out);                                                           \
    void brdf_sums_##suffix(const BrdfKernelInput& in, std::size_t count, float* out_a, float* out_b);
TESSERA_DECLARE_PRECOMPUTE_ENTRY(sse4)
TESSERA_DECLARE_PRECOMPUTE_ENTRY(avx2)
TESSERA_DECLARE_PRECOMPUTE_ENTRY(avx512)
#undef TESSERA_DECLARE_PRECOMPUTE_ENTRY

// Isa::scalar never comes here: precompute.cpp runs its reference loops.
void irradiance_sums(simd::Isa isa, const IrradianceKernelInput& in, std::size_t first, std::size_t count,
                     const SumOutputs& out) {
    switch (isa) {
        case simd::Isa::avx512: return irradiance_sums_avx512(in, first, count, out);
        case simd::Isa::avx2: return irradiance_sums_avx2(in, first, count, out);
        default: return irradiance_sums_sse4(in, first, count, out);
    }
}

void prefilter_sums(simd::Isa isa, const PrefilterKernelInput& in, std::size_t first, std::size_t count,
                    const SumOutputs& out) {
    switch (isa) {
        case simd::Isa::avx512: return prefilter_sums_avx512(in, first, count, out);
        case simd::Isa::avx2: return prefilter_sums_avx2(in, first, count, out);
        default: return prefilter_sums_sse4(in, first, count, out);
    }
}

void brdf_sums(simd::Isa isa, const BrdfKernelInput& in, std::size_t count, float* out_a, float* out_b) {
    switch (isa) {
        case simd::Isa::avx512: return brdf_sums_avx512(in, count, out_a, out_b);
        case simd::Isa::avx2: return brdf_sums_avx2(in, count, out_a, out_b);
        default: return brdf_sums_sse4(in, count, out_a, out_b);
    }
}

}  // namespace tessera::environment
