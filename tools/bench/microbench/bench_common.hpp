// What both benchmark files share: the ISAs to run, the fixed seed, and how an
// ISA this CPU lacks is reported.
#pragma once

#include <cstdint>
#include <string>

#include <benchmark/benchmark.h>

#include "simd/isa.hpp"

namespace tessera::microbench {

using simd::Isa;

// Every run draws the same inputs, so numbers compare across runs and machines.
inline constexpr std::uint32_t kSeed = 0x7e55e7a;

inline constexpr Isa kIsas[] = {Isa::scalar, Isa::sse4, Isa::avx2, Isa::avx512};

// True (and the benchmark marked as skipped) when this CPU cannot run `isa`.
inline bool skip_if_unsupported(benchmark::State& state, Isa isa) {
    if (simd::isa_supported(isa)) return false;
    state.SkipWithError((std::string(simd::isa_name(isa)) + " not supported by this CPU").c_str());
    return true;
}

// Time per unit of work, from the CPU time: `units_per_iteration` units each
// iteration. The console prints it with its unit (e.g. "1.34ns"); JSON and CSV
// output give it in seconds, Google Benchmark's unit for inverted rates.
inline benchmark::Counter time_per_unit(double units_per_iteration) {
    return benchmark::Counter(units_per_iteration,
                              benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace tessera::microbench
