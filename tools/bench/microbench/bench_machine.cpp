// The machine's own limits, the ceilings the pipeline's stages are measured
// against (tools/bench/stage_limits.py): the peak rate of independent multiply-adds
// per ISA (no memory traffic, no dependency chains), and memory bandwidth
// (streaming read, write and copy of buffers far larger than the caches), on
// one thread and on two; and what it costs to write lines another core has
// just read (machine/handover).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <immintrin.h>
#include <pthread.h>
#include <sched.h>

#include <thread>

#include <benchmark/benchmark.h>

#include "bench_common.hpp"
#include "simd/prefetch.hpp"

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

// A frame hands data from core to core: the vertex stage's output is read
// by the tile pass on every core, and rewritten next frame. Here one 14 MB
// buffer (the 720p spheres' shaded vertices) is read, then written and timed:
// read on the writing core, or on the other core (the lines are then shared
// with it, and each plain store waits for its copy to go), then written
// plainly, plainly after a prefetchw 4 KiB ahead (simd/prefetch.hpp, what the
// frame's stages do), or non-temporally. Needs two CPUs; both threads are pinned.
constexpr std::size_t kHandoverBytes = std::size_t(14) << 20;
enum class Store { plain, prefetched, streamed };
struct Handover {
    bool other_core;  // the buffer is read on the other core before it is written
    Store store;
};

void pin_to(int cpu) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(cpu, &set);
    pthread_setaffinity_np(pthread_self(), sizeof set, &set);
}

[[gnu::target("avx2")]] void write_buffer(std::uint64_t* out, std::size_t words, std::uint64_t value, Store store) {
    const __m256i v = _mm256_set1_epi64x(std::int64_t(value));
    constexpr std::size_t kAheadWords = 4096 / sizeof(std::uint64_t);
    for (std::size_t i = 0; i < words; i += 4) {
        if (store == Store::streamed) {
            _mm256_stream_si256(reinterpret_cast<__m256i*>(out + i), v);
            continue;
        }
        if (store == Store::prefetched && i % 8 == 0 && i + kAheadWords < words)
            simd::prefetch_for_write(out + i + kAheadWords);
        _mm256_store_si256(reinterpret_cast<__m256i*>(out + i), v);
    }
    _mm_sfence();
}

std::uint64_t read_buffer(const std::uint64_t* in, std::size_t words) {
    std::uint64_t sum = 0;
    for (std::size_t i = 0; i < words; i += 8) sum += in[i];  // one word a line
    return sum;
}

// bytes_per_second: the write's bytes over its time alone.
void bench_handover(benchmark::State& state, Handover handover) {
    cpu_set_t allowed;
    std::vector<int> cpus;
    if (sched_getaffinity(0, sizeof allowed, &allowed) == 0)
        for (int cpu = 0; cpu < CPU_SETSIZE && cpus.size() < 2; ++cpu)
            if (CPU_ISSET(cpu, &allowed)) cpus.push_back(cpu);
    if (cpus.size() < 2) return state.SkipWithError("needs two CPUs");
    cpu_set_t before;
    pthread_getaffinity_np(pthread_self(), sizeof before, &before);
    pin_to(cpus[0]);
    const std::size_t words = kHandoverBytes / sizeof(std::uint64_t);
    auto* buffer = static_cast<std::uint64_t*>(std::aligned_alloc(64, kHandoverBytes));
    std::memset(buffer, 1, kHandoverBytes);
    // The other core reads the buffer whenever `request` passes `served`.
    std::atomic<std::uint64_t> request{0}, served{0};
    std::atomic<bool> stop{false};
    std::thread reader([&] {
        pin_to(cpus[1]);
        std::uint64_t done = 0, sink = 0;
        while (!stop.load(std::memory_order_acquire)) {
            if (request.load(std::memory_order_acquire) == done) continue;
            sink += read_buffer(buffer, words);
            served.store(++done, std::memory_order_release);
        }
        benchmark::DoNotOptimize(sink);
    });
    std::uint64_t round = 0, sink = 0;
    for (auto _ : state) {
        ++round;
        if (!handover.other_core) {
            sink += read_buffer(buffer, words);
        } else {
            request.store(round, std::memory_order_release);
            while (served.load(std::memory_order_acquire) != round) {}
        }
        const auto start = std::chrono::steady_clock::now();
        write_buffer(buffer, words, round, handover.store);
        state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    benchmark::DoNotOptimize(sink);
    stop.store(true, std::memory_order_release);
    reader.join();
    std::free(buffer);
    pthread_setaffinity_np(pthread_self(), sizeof before, &before);
    state.SetBytesProcessed(state.iterations() * std::int64_t(kHandoverBytes));
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
    const std::pair<const char*, Handover> handovers[] = {{"same_core", {false, Store::plain}},
                                                          {"other_core", {true, Store::plain}},
                                                          {"other_core_prefetched", {true, Store::prefetched}},
                                                          {"other_core_streamed", {true, Store::streamed}}};
    for (const auto& [label, handover] : handovers)
        benchmark::RegisterBenchmark(("machine/handover/" + std::string(label)).c_str(), bench_handover, handover)
            ->UseManualTime()
            ->Unit(benchmark::kMicrosecond);
    return true;
}();

}  // namespace
}  // namespace tessera::microbench
