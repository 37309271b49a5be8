// The image stage's resolve: a tile's shaded radiance to the display image
// (tonemap, gamma, 8-bit quantization, scattered to the covered pixels).
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench_common.hpp"
#include "image/resolve.hpp"
#include "simd/lane_padding.hpp"

namespace tessera::microbench {
namespace {

// A 32×32 tile (the renderer's default) of a 1280×720 frame, `coverage` of its
// pixels covered at random, as a mesh of tiny triangles leaves them; radiance
// log-uniform over the range a lit scene has. resolve_tile overwrites the red
// channel, so each iteration restores it (a 4 KB copy, timed too). With
// radiance, the image keeps the radiance too, as for EXR output.
void bench_resolve(benchmark::State& state, Isa isa, double coverage, bool radiance) {
    if (skip_if_unsupported(state, isa)) return;
    constexpr int kSide = 32;
    const raster::TileRect rect{640, 352, 640 + kSide, 352 + kSide};
    std::mt19937 rng(kSeed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), exponent(-4.0f, 1.5f);
    raster::TileBuffers tile;
    tile.reset(kSide);
    std::size_t count = 0;
    for (int p = 0; p < kSide * kSide; ++p)
        if (unit(rng) < coverage) tile.depth[std::size_t(p)] = 0.5f, ++count;
    std::vector<float> r(simd::padded_count(count)), g(r.size()), b(r.size());
    for (std::size_t k = 0; k < count; ++k)
        r[k] = std::pow(10.0f, exponent(rng)), g[k] = std::pow(10.0f, exponent(rng)), b[k] = std::pow(10.0f, exponent(rng));
    const std::vector<float> r_saved = r;
    RenderedImage image;
    image.width = 1280, image.height = 720;
    image.display.resize(3 * std::size_t(image.width) * image.height);
    if (radiance) image.radiance.resize(image.display.size());
    const image::ClearValues clear = image::clear_values(glm::vec3(0.1f));
    for (auto _ : state) {
        std::copy(r_saved.begin(), r_saved.end(), r.begin());
        image::resolve_tile(tile, rect, count, {r.data(), g.data(), b.data()}, clear, isa, image);
        benchmark::DoNotOptimize(image.display.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(state.iterations() * kSide * kSide);
    state.counters["ns_per_pixel"] = time_per_unit(double(kSide * kSide));
}

[[maybe_unused]] const bool registered = [] {
    for (const bool radiance : {false, true})
        for (const Isa isa : kIsas)
            for (const int percent : {27, 100})
                benchmark::RegisterBenchmark((std::string(radiance ? "resolve_radiance/" : "resolve/") +
                                              std::string(simd::isa_name(isa)) + "/coverage:" + std::to_string(percent))
                                                 .c_str(),
                                             bench_resolve, isa, percent / 100.0, radiance);
    return true;
}();

}  // namespace
}  // namespace tessera::microbench

namespace tessera::microbench {
namespace {

// encode_display_unorm8 alone on 4096 pixels of log-uniform radiance (random)
// or of slow ramps (smooth, neighbours in nearby table buckets), in L1/L2;
// in place, so each iteration restores the red channel (16 KB, timed too).
void bench_encode(benchmark::State& state, Isa isa, bool smooth) {
    if (skip_if_unsupported(state, isa)) return;
    constexpr std::size_t kCount = 4096;
    std::mt19937 rng(kSeed);
    std::uniform_real_distribution<float> exponent(-4.0f, 1.5f);
    std::vector<float> r(simd::padded_count(kCount)), g(r.size()), b(r.size());
    for (std::size_t k = 0; k < kCount; ++k) {
        r[k] = std::pow(10.0f, exponent(rng)), g[k] = std::pow(10.0f, exponent(rng)), b[k] = std::pow(10.0f, exponent(rng));
        if (smooth) {  // slow ramps, as across a smoothly lit surface at 4K
            const float t = float(k % 256) / 256.0f;
            r[k] = 0.05f + 0.1f * t, g[k] = 0.2f + 0.3f * t * t, b[k] = 0.4f * (1.0f - 0.5f * t);
        }
    }
    const std::vector<float> r_saved = r;
    for (auto _ : state) {
        std::copy(r_saved.begin(), r_saved.end(), r.begin());
        image::encode_display_unorm8(isa, kCount, r.data(), g.data(), b.data());
        benchmark::DoNotOptimize(r.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(state.iterations() * std::int64_t(kCount));
    state.counters["ns_per_pixel"] = time_per_unit(double(kCount));
}

[[maybe_unused]] const bool registered_encode = [] {
    for (const Isa isa : kIsas)
        for (const bool smooth : {false, true})
            benchmark::RegisterBenchmark(
                ("encode_display/" + std::string(simd::isa_name(isa)) + (smooth ? "/smooth" : "/random")).c_str(),
                bench_encode, isa, smooth);
    return true;
}();

}  // namespace
}  // namespace tessera::microbench

namespace tessera::microbench {
namespace {

// The resolve of a whole 3840×2160 frame, tile after tile as one worker does
// it: a quarter of the tiles empty (clear_tile), a quarter fully covered, half
// with 27% of their pixels covered at random (the spheres' edges). Four
// display images in turn (100 MB, past the L3), as a frame finds its image
// evicted by the frame's other data. ns_per_pixel over the frame's pixels.
void bench_resolve_frame(benchmark::State& state, Isa isa) {
    if (skip_if_unsupported(state, isa)) return;
    constexpr int kSide = 32, kWidth = 3840, kHeight = 2160, kImages = 4;
    constexpr int tiles_x = kWidth / kSide, tiles_y = (kHeight + kSide - 1) / kSide;
    std::mt19937 rng(kSeed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), exponent(-4.0f, 1.5f);
    raster::TileBuffers full, partial;
    full.reset(kSide), partial.reset(kSide);
    std::fill(full.depth.begin(), full.depth.end(), 0.5f);
    std::size_t partial_count = 0;
    for (float& d : partial.depth)
        if (unit(rng) < 0.27f) d = 0.5f, ++partial_count;
    const std::size_t n = simd::padded_count(kSide * kSide);
    std::vector<float> r(n), g(n), b(n);
    for (std::size_t k = 0; k < n; ++k)
        r[k] = std::pow(10.0f, exponent(rng)), g[k] = std::pow(10.0f, exponent(rng)), b[k] = std::pow(10.0f, exponent(rng));
    std::vector<float> work = r;
    std::vector<RenderedImage> images(kImages);
    for (RenderedImage& image : images) {
        image.width = kWidth, image.height = kHeight;
        image.display.resize(3 * std::size_t(kWidth) * kHeight);
    }
    const image::ClearValues clear = image::clear_values(glm::vec3(0.1f));
    int next = 0;
    for (auto _ : state) {
        RenderedImage& image = images[std::size_t(next)];
        next = (next + 1) % kImages;
        for (int t = 0; t < tiles_x * tiles_y; ++t) {
            const int x0 = (t % tiles_x) * kSide, y0 = (t / tiles_x) * kSide;
            const raster::TileRect rect{x0, y0, x0 + kSide, std::min(y0 + kSide, kHeight)};
            const unsigned kind = (unsigned(t) * 2654435761u) >> 30;  // 0..3, scattered
            if (kind == 0) {
                image::clear_tile(rect, clear, image);
                continue;
            }
            const raster::TileBuffers& tile = kind == 1 ? full : partial;
            const std::size_t count = kind == 1 ? std::size_t(kSide * rect.height()) : partial_count;
            std::copy(r.begin(), r.end(), work.begin());
            image::resolve_tile(tile, rect, count, {work.data(), g.data(), b.data()}, clear, isa, image);
        }
        benchmark::ClobberMemory();
    }
    state.counters["ns_per_pixel"] = time_per_unit(double(kWidth) * kHeight);
}

[[maybe_unused]] const bool registered_frame = [] {
    for (const Isa isa : kIsas)
        benchmark::RegisterBenchmark(("resolve_frame/" + std::string(simd::isa_name(isa))).c_str(), bench_resolve_frame, isa)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime();
    return true;
}();

}  // namespace
}  // namespace tessera::microbench
