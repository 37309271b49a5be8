// The floor under the resolve at 4K: writing a 3840×2160 RGB8 display image
// (25 MB) the way the renderer does, in 32×32 tiles (each tile row 96 bytes,
// so a tile shares a cache line with each neighbour), against row order, with
// plain or non-temporal stores. The bytes come from a row in L1, as a
// resolved tile row would; nothing is computed, so this is what the memory
// system allows. Four images in turn (100 MB, past the 32 MB L3), as a frame
// finds its image evicted by the frame's other data.
#include <immintrin.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

namespace tessera::microbench {
namespace {

constexpr int kWidth = 3840, kHeight = 2160, kTile = 32;
constexpr std::size_t kStride = 3 * std::size_t(kWidth);
constexpr std::size_t kImageBytes = kStride * kHeight;
constexpr int kImages = 4;

std::uint8_t* images() {
    static std::vector<std::uint8_t> buffer = [] {
        std::vector<std::uint8_t> b(kImageBytes * kImages + 64, 1);
        return b;
    }();
    // 64-byte aligned, as the renderer's (huge-page) vector is.
    const auto p = reinterpret_cast<std::uintptr_t>(buffer.data());
    return reinterpret_cast<std::uint8_t*>((p + 63) & ~std::uintptr_t(63));
}

enum class Store { kernel, lines, stream, prefetch };

alignas(64) std::uint8_t source_row[3 * kTile + 64];

// One tile row of 96 bytes at `out` (the tile's x0 * 3 is a multiple of 96).
[[gnu::target("avx2")]] inline void write_tile_row(std::uint8_t* out, Store store) {
    switch (store) {
        case Store::kernel:  // as write_display_rows_avx2: 16 + 8 bytes per 8 pixels
            for (int g = 0; g < 4; ++g) {
                const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(source_row + 24 * g));
                _mm_storeu_si128(reinterpret_cast<__m128i*>(out + 24 * g), v);
                _mm_storel_epi64(reinterpret_cast<__m128i*>(out + 24 * g + 16),
                                 _mm_loadl_epi64(reinterpret_cast<const __m128i*>(source_row + 24 * g + 16)));
            }
            return;
        case Store::lines:  // three 32-byte stores
        case Store::prefetch:
            for (int i = 0; i < 3; ++i)
                _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + 32 * i),
                                    _mm256_load_si256(reinterpret_cast<const __m256i*>(source_row + 32 * i)));
            return;
        case Store::stream: {  // the whole line non-temporal, the shared half line plain
            const bool line_first = (reinterpret_cast<std::uintptr_t>(out) & 63) == 0;
            const __m256i a = _mm256_load_si256(reinterpret_cast<const __m256i*>(source_row));
            const __m256i b = _mm256_load_si256(reinterpret_cast<const __m256i*>(source_row + 32));
            const __m256i c = _mm256_load_si256(reinterpret_cast<const __m256i*>(source_row + 64));
            if (line_first) {
                _mm256_stream_si256(reinterpret_cast<__m256i*>(out), a);
                _mm256_stream_si256(reinterpret_cast<__m256i*>(out + 32), b);
                _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + 64), c);
            } else {
                _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), a);
                _mm256_stream_si256(reinterpret_cast<__m256i*>(out + 32), b);
                _mm256_stream_si256(reinterpret_cast<__m256i*>(out + 64), c);
            }
            return;
        }
    }
}

// Tiles [first, end) of the 120×68 grid (4K), row-major, every `step`-th.
[[gnu::target("avx2")]] void write_tiles(std::uint8_t* image, int first, int end, int step, Store store) {
    constexpr int tiles_x = kWidth / kTile;
    for (int t = first; t < end; t += step) {
        const int x0 = (t % tiles_x) * kTile, y0 = (t / tiles_x) * kTile;
        const int y1 = y0 + kTile < kHeight ? y0 + kTile : kHeight;
        std::uint8_t* out = image + std::size_t(y0) * kStride + 3 * std::size_t(x0);
        if (store == Store::prefetch && t + step < end) {  // the next tile's lines, for writing
            const int nx0 = ((t + step) % tiles_x) * kTile, ny0 = ((t + step) / tiles_x) * kTile;
            std::uint8_t* next = image + std::size_t(ny0) * kStride + 3 * std::size_t(nx0);
            for (int y = 0; y < kTile && ny0 + y < kHeight; ++y) {
                _m_prefetchw(next + y * kStride);
                _m_prefetchw(next + y * kStride + 95);
            }
        }
        for (int y = y0; y < y1; ++y, out += kStride) write_tile_row(out, store);
    }
    _mm_sfence();
}

[[gnu::target("avx2")]] void write_rows(std::uint8_t* image, int first_row, int end_row, bool stream) {
    for (int y = first_row; y < end_row; ++y) {
        std::uint8_t* out = image + std::size_t(y) * kStride;  // kStride is a multiple of 64
        for (std::size_t i = 0; i < kStride; i += 96)
            for (int j = 0; j < 3; ++j) {
                const __m256i v = _mm256_load_si256(reinterpret_cast<const __m256i*>(source_row + 32 * j));
                if (stream) _mm256_stream_si256(reinterpret_cast<__m256i*>(out + i + 32 * j), v);
                else _mm256_store_si256(reinterpret_cast<__m256i*>(out + i + 32 * j), v);
            }
    }
    _mm_sfence();
}

// bytes_per_second: image bytes written. With 2 threads each takes half the
// tiles (contiguous halves, as oneTBB's split gives) or, "interleaved", every
// other tile (neighbouring tiles' shared lines bounce between the cores).
void bench_tiles(benchmark::State& state, Store store, bool interleaved) {
    std::uint8_t* base = images();
    constexpr int tiles = (kWidth / kTile) * ((kHeight + kTile - 1) / kTile);
    const int threads = state.threads(), index = state.thread_index();
    int image = 0;
    for (auto _ : state) {
        std::uint8_t* target = base + kImageBytes * std::size_t(image);
        image = (image + 1) % kImages;
        if (interleaved) write_tiles(target, index, tiles, threads, store);
        else write_tiles(target, tiles * index / threads, tiles * (index + 1) / threads, 1, store);
        benchmark::ClobberMemory();
    }
    state.SetBytesProcessed(state.iterations() * std::int64_t(kImageBytes / std::size_t(threads)));
}

void bench_rows(benchmark::State& state, bool stream) {
    std::uint8_t* base = images();
    const int threads = state.threads(), index = state.thread_index();
    int image = 0;
    for (auto _ : state) {
        std::uint8_t* target = base + kImageBytes * std::size_t(image);
        image = (image + 1) % kImages;
        write_rows(target, kHeight * index / threads, kHeight * (index + 1) / threads, stream);
        benchmark::ClobberMemory();
    }
    state.SetBytesProcessed(state.iterations() * std::int64_t(kImageBytes / std::size_t(threads)));
}

[[maybe_unused]] const bool registered = [] {
    for (int i = 0; i < int(sizeof(source_row)); ++i) source_row[i] = std::uint8_t(i * 7 + 1);
    const auto configure = [](benchmark::internal::Benchmark* b) {
        b->Threads(1)->Threads(2)->UseRealTime()->Unit(benchmark::kMillisecond);
    };
    configure(benchmark::RegisterBenchmark("display_write/rows/plain", bench_rows, false));
    configure(benchmark::RegisterBenchmark("display_write/rows/stream", bench_rows, true));
    const std::pair<const char*, Store> stores[] = {{"kernel", Store::kernel},
                                                    {"lines", Store::lines},
                                                    {"stream", Store::stream},
                                                    {"prefetchw", Store::prefetch}};
    for (const auto& [label, store] : stores) {
        configure(benchmark::RegisterBenchmark(("display_write/tiles/" + std::string(label)).c_str(), bench_tiles,
                                               store, false));
    }
    configure(benchmark::RegisterBenchmark("display_write/tiles_interleaved/kernel", bench_tiles, Store::kernel, true));
    return true;
}();

}  // namespace
}  // namespace tessera::microbench
