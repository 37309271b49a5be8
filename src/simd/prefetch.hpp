// Prefetching a line for writing. __builtin_prefetch(p, 1) emits prefetchw
// only where the target has PRFCHW, which no -march we build for names, so it
// becomes a plain prefetcht0 there: a line another core holds then arrives
// shared, and the store that follows must wait for the other copy to go too
// (machine/handover in tools/bench/microbench). prefetchw asks for the line
// exclusive at once. Every x86-64 CPU since AMD K8 and Intel Broadwell runs
// it; older Intel ones decode it as a no-op.
#pragma once

namespace tessera::simd {

inline void prefetch_for_write(const void* address) {
    asm volatile("prefetchw %0" : : "m"(*static_cast<const char*>(address)));
}

}  // namespace tessera::simd
