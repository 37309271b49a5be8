// The machine's own limits, the ceilings the pipeline's stages are measured
// against (tools/stage_limits.py): the peak rate of independent multiply-adds
// per ISA (no memory traffic, no dependency chains), and memory bandwidth
// (streaming read, write and copy of buffers far larger than the caches), on
// one thread and on two.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <immintrin.h>

#include <benchmark/benchmark.h>

#include "bench_common.hpp"

namespace tessera::microbench {
namespace {

// Enough independent accumulators to cover the FMA latency (4 cycles) on two
// ports: 8 in flight, 12 to spare. Each round is kChains multiply-adds.
constexpr int kChains = 12;
constexpr int kRounds = 4096;

// Returns the multiply-adds done (each is 2 flops per lane).
[[gnu::target("sse4.1")]] float madd_sse4(float seed) {
    __m128 acc[kChains];
    for (int c = 0; c < kChains; ++c) acc[c] = _mm_set1_ps(seed + float(c));
    const __m128 a = _mm_set1_ps(0.999f), b = _mm_set1_ps(0.001f);
    for (int r = 0; r < kRounds; ++r)
        for (int c = 0; c < kChains; ++c) acc[c] = _mm_add_ps(_mm_mul_ps(acc[c], a), b);  // SSE4 has no FMA
    __m128 sum = acc[0];
    for (int c = 1; c < kChains; ++c) sum = _mm_add_ps(sum, acc[c]);
    return _mm_cvtss_f32(sum);
}

[[gnu::target("avx2,fma")]] float madd_avx2(float seed) {
    __m256 acc[kChains];
    for (int c = 0; c < kChains; ++c) acc[c] = _mm256_set1_ps(seed + float(c));
    const __m256 a = _mm256_set1_ps(0.999f), b = _mm256_set1_ps(0.001f);
    for (int r = 0; r < kRounds; ++r)
        for (int c = 0; c < kChains; ++c) acc[c] = _mm256_fmadd_ps(acc[c], a, b);
    __m256 sum = acc[0];
    for (int c = 1; c < kChains; ++c) sum = _mm256_add_ps(sum, acc[c]);
    return _mm256_cvtss_f32(sum);
}

[[gnu::target("avx512f")]] float madd_avx512(float seed) {
    __m512 acc[kChains];
    for (int c = 0; c < kChains; ++c) acc[c] = _mm512_set1_ps(seed + float(c));
    const __m512 a = _mm512_set1_ps(0.999f), b = _mm512_set1_ps(0.001f);
    for (int r = 0; r < kRounds; ++r)
        for (int c = 0; c < kChains; ++c) acc[c] = _mm512_fmadd_ps(acc[c], a, b);
    __m512 sum = acc[0];
    for (int c = 1; c < kChains; ++c) sum = _mm512_add_ps(sum, acc[c]);
    alignas(64) float lanes[16];
    _mm512_store_ps(lanes, sum);
    return lanes[0] + lanes[15];
}

// items_per_second: flops per second (a multiply-add is 2 flops per lane).
void bench_flops(benchmark::State& state, Isa isa) {
    if (skip_if_unsupported(state, isa)) return;
    int lanes = 0;
    float (*madd)(float) = nullptr;
    switch (isa) {
        case Isa::sse4: lanes = 4, madd = madd_sse4; break;
        case Isa::avx2: lanes = 8, madd = madd_avx2; break;
        case Isa::avx512: lanes = 16, madd = madd_avx512; break;
        default: state.SkipWithError("no multiply-add kernel for this ISA"); return;
    }
    float seed = 1.0f;
    for (auto _ : state) {
        seed = madd(seed) * 1e-30f + 1.0f;
        benchmark::DoNotOptimize(seed);
    }
    state.SetItemsProcessed(state.iterations() * std::int64_t(kRounds) * kChains * lanes * 2);
}

// 1 GiB in all: far beyond any cache, so every byte comes from DRAM. Each
// thread streams its own half (or all of it, alone).
constexpr std::size_t kBufferBytes = std::size_t(1) << 30;

std::vector<std::uint64_t>& source_buffer() {
    static std::vector<std::uint64_t> buffer(kBufferBytes / sizeof(std::uint64_t), 1);
    return buffer;
}
std::vector<std::uint64_t>& target_buffer() {
    static std::vector<std::uint64_t> buffer(kBufferBytes / sizeof(std::uint64_t), 2);
    return buffer;
}

enum class Traffic { read, write, copy };

// bytes_per_second: bytes moved over the interconnect as the program sees them
// (a copy counts what it reads plus what it writes; a write's read-for-ownership is not counted).
void bench_memory(benchmark::State& state, Traffic traffic) {
    std::vector<std::uint64_t>& source = source_buffer();
    std::vector<std::uint64_t>& target = target_buffer();
    const std::size_t words = source.size() / std::size_t(state.threads());
    const std::size_t first = words * std::size_t(state.thread_index());
    std::uint64_t* in = source.data() + first;
    std::uint64_t* out = target.data() + first;
    for (auto _ : state) {
        if (traffic == Traffic::read) {
            std::uint64_t sum[4] = {0, 0, 0, 0};
            for (std::size_t i = 0; i < words; i += 4)
                sum[0] += in[i], sum[1] += in[i + 1], sum[2] += in[i + 2], sum[3] += in[i + 3];
            benchmark::DoNotOptimize(sum);
        } else if (traffic == Traffic::write) {
            std::memset(out, state.iterations() & 0xff, words * sizeof(std::uint64_t));
        } else {
            std::memcpy(out, in, words * sizeof(std::uint64_t));
        }
        benchmark::ClobberMemory();
    }
    const std::int64_t bytes = std::int64_t(words * sizeof(std::uint64_t)) * (traffic == Traffic::copy ? 2 : 1);
    state.SetBytesProcessed(state.iterations() * bytes);
}

[[maybe_unused]] const bool registered = [] {
    for (const Isa isa : {Isa::sse4, Isa::avx2, Isa::avx512}) {
        const std::string name = "machine/flops/" + std::string(simd::isa_name(isa));
        benchmark::RegisterBenchmark(name.c_str(), bench_flops, isa)->Threads(1)->Threads(2)->UseRealTime();
    }
    const std::pair<const char*, Traffic> kinds[] = {
        {"read", Traffic::read}, {"write", Traffic::write}, {"copy", Traffic::copy}};
    for (const auto& [label, traffic] : kinds)
        benchmark::RegisterBenchmark(("machine/memory/" + std::string(label)).c_str(), bench_memory, traffic)
            ->Threads(1)
            ->Threads(2)
            ->UseRealTime()
            ->Unit(benchmark::kMillisecond);
    return true;
}();

}  // namespace
}  // namespace tessera::microbench
