// The raster stage's kernels: rasterizing set-up triangles into one 64×64 tile
// (per ISA, and the scalar reference loop), and triangle setup itself.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench_common.hpp"
#include "raster/bin_rasterizer.hpp"
#include "raster/tile_rasterizer.hpp"
#include "raster/triangle_setup.hpp"

namespace tessera::microbench {
namespace {

using raster::RasterTriangle;
using raster::ScreenVertex;
using raster::TileRect;
using raster::Viewport;

// Triangles of one size class: areas drawn uniformly from [min_area, max_area]
// px², `batch` of them rasterized per iteration.
struct SizeClass {
    const char* name;
    float min_area, max_area;
    std::size_t batch;
};
// small: a finely tessellated mesh (the demo's spheres at 1280×720); medium:
// a coarse one; large: about half a tile; huge: a wall, bigger than the tile.
// Batches keep an iteration well above the cost of the tile reset it includes.
constexpr SizeClass kSmall{"small", 1.0f, 2.0f, 2048};
constexpr SizeClass kMedium{"medium", 20.0f, 40.0f, 512};
constexpr SizeClass kLarge{"large", 1600.0f, 2400.0f, 32};
constexpr SizeClass kHuge{"huge", 10000.0f, 14000.0f, 8};
// Iterations cycle through this many batches of different triangles.
constexpr std::size_t kBatchesInPool = 4;

// The tile: 64×64 pixels in the middle of a 192×192 image, so that large
// triangles can reach past its sides as they do in a real frame.
constexpr int kTileSide = 64;
constexpr Viewport kTileImage{192, 192};
constexpr TileRect kTile{64, 64, 128, 128};

// A triangle of the given area in px², centred near the origin, with no
// sliver corners: corners 120° ± 30° apart around the centre, at 0.6-1 of
// the same radius.
std::array<glm::vec2, 3> random_shape(std::mt19937& rng, float area) {
    constexpr float kTwoPi = 6.28318531f;
    std::uniform_real_distribution<float> angle(0.0f, kTwoPi), jitter(-0.5f, 0.5f), radius(0.6f, 1.0f);
    const float a0 = angle(rng);
    std::array<glm::vec2, 3> p;
    for (int k = 0; k < 3; ++k) {
        const float a = a0 + float(k) * kTwoPi / 3.0f + (k > 0 ? jitter(rng) : 0.0f);
        p[k] = radius(rng) * glm::vec2(std::cos(a), std::sin(a));
    }
    const glm::vec2 d1 = p[1] - p[0], d2 = p[2] - p[0];
    const float scale = std::sqrt(area / (0.5f * std::abs(d1.x * d2.y - d1.y * d2.x)));
    for (glm::vec2& q : p) q *= scale;
    return p;
}

// An offset along one axis for a shape spanning [lo, hi] into [begin, end):
// wholly inside when it fits, otherwise covering all of it.
float random_offset(std::mt19937& rng, float lo, float hi, float begin, float end) {
    float a = begin - lo, b = end - hi;
    if (a > b) std::swap(a, b);
    return std::uniform_real_distribution<float>(a, b)(rng);
}

// Random screen triangles of a size class placed over `region` (image
// pixels), with depths around a random plane. With `visible_only`, only those
// that triangle setup keeps (that cover a pixel centre).
std::vector<std::array<ScreenVertex, 3>> random_triangles(std::mt19937& rng, const SizeClass& size, std::size_t count,
                                                          const Viewport& viewport, const TileRect& region,
                                                          bool visible_only) {
    std::uniform_real_distribution<float> area(size.min_area, size.max_area), base_depth(0.1f, 0.9f),
        depth_slope(-0.05f, 0.05f);
    std::vector<std::array<ScreenVertex, 3>> triangles;
    triangles.reserve(count);
    while (triangles.size() < count) {
        const std::array<glm::vec2, 3> p = random_shape(rng, area(rng));
        const auto [x_lo, x_hi] = std::minmax({p[0].x, p[1].x, p[2].x});
        const auto [y_lo, y_hi] = std::minmax({p[0].y, p[1].y, p[2].y});
        const glm::vec2 offset{random_offset(rng, x_lo, x_hi, float(region.x0), float(region.x1)),
                               random_offset(rng, y_lo, y_hi, float(region.y0), float(region.y1))};
        const float depth = base_depth(rng);
        std::array<ScreenVertex, 3> corners;
        for (int k = 0; k < 3; ++k) {
            const glm::vec2 q = (p[k] + offset) * float(geometry::kSubpixelScale);
            corners[k] = {std::int32_t(std::lrintf(q.x)), std::int32_t(std::lrintf(q.y)), depth + depth_slope(rng), 0};
        }
        if (visible_only && !raster::setup_triangle(viewport, corners, {0, 1, 2})) continue;
        triangles.push_back(corners);
    }
    return triangles;
}

std::vector<RasterTriangle> tile_triangles(const SizeClass& size) {
    std::mt19937 rng(kSeed);
    std::vector<RasterTriangle> triangles;
    for (const auto& corners : random_triangles(rng, size, size.batch * kBatchesInPool, kTileImage, kTile, true))
        triangles.push_back(*raster::setup_triangle(kTileImage, corners, {0, 1, 2}));
    return triangles;
}

// Triangles per second of `state`'s iterations of `batch` triangles, and the
// fragments they covered.
void report_rasterized(benchmark::State& state, std::size_t batch, const raster::RasterCounters& counters) {
    const auto rasterized = double(state.iterations()) * double(batch);
    state.SetItemsProcessed(std::int64_t(rasterized));
    // Covered pixel centres, whether or not they pass the depth test.
    state.counters["fragments"] = benchmark::Counter(double(counters.fragments), benchmark::Counter::kIsRate);
    state.counters["frags_per_tri"] = double(counters.fragments) / rasterized;
}

// Rasterizes a batch of triangles into a freshly reset tile per iteration:
// draw(triangles, first, buffers, counters) draws triangles [first, first + batch).
// The reset (depth back to 1: 16 KB of stores) is timed too, as the renderer
// pays it once per tile; raster/tile_reset is its cost alone.
template <class Draw>
raster::RasterCounters rasterize_batches(benchmark::State& state, const SizeClass& size, Draw&& draw) {
    const std::vector<RasterTriangle> triangles = tile_triangles(size);
    raster::TileBuffers buffers;
    buffers.reset(kTileSide);
    raster::RasterCounters counters;
    std::size_t first = 0;
    for (auto _ : state) {
        buffers.reset(kTileSide);
        draw(triangles, first, buffers, counters);
        first = (first + size.batch) % triangles.size();
        benchmark::DoNotOptimize(buffers.depth.data());
        benchmark::ClobberMemory();
    }
    report_rasterized(state, size.batch, counters);
    return counters;
}

// A call per triangle. isa = nullopt: the scalar reference overload.
void bench_rasterize(benchmark::State& state, const SizeClass& size, std::optional<Isa> isa) {
    if (isa && skip_if_unsupported(state, *isa)) return;
    const raster::RasterCounters counters = rasterize_batches(
        state, size, [&](const std::vector<RasterTriangle>& triangles, std::size_t first, raster::TileBuffers& buffers,
                         raster::RasterCounters& counters) {
            for (std::size_t i = first; i < first + size.batch; ++i) {
                if (isa)
                    raster::rasterize_triangle(*isa, triangles[i], std::uint32_t(i), kTile, buffers, counters);
                else
                    raster::rasterize_triangle(triangles[i], std::uint32_t(i), kTile, buffers, counters);
            }
        });
    state.counters["depth_pass"] = double(counters.depth_passed) / double(std::max<std::uint64_t>(counters.fragments, 1));
}

// The same batches through raster::rasterize_bin, as the renderer draws a
// chunk's bin: one call for all (raster/bin_rasterizer.hpp).
void bench_rasterize_bin(benchmark::State& state, const SizeClass& size, Isa isa) {
    if (skip_if_unsupported(state, isa)) return;
    std::vector<std::uint32_t> bin(size.batch * kBatchesInPool);
    for (std::size_t i = 0; i < bin.size(); ++i) bin[i] = std::uint32_t(i);
    rasterize_batches(state, size, [&](const std::vector<RasterTriangle>& triangles, std::size_t first,
                                       raster::TileBuffers& buffers, raster::RasterCounters& counters) {
        raster::rasterize_bin(isa, triangles.data(), std::span(bin).subspan(first, size.batch), 0, kTile, buffers,
                              counters);
    });
}

void bench_tile_reset(benchmark::State& state) {
    raster::TileBuffers buffers;
    buffers.reset(kTileSide);
    for (auto _ : state) {
        buffers.reset(kTileSide);
        benchmark::DoNotOptimize(buffers.depth.data());
        benchmark::ClobberMemory();
    }
}

// setup_triangle over screen vertices of a 1280×720 frame, placed anywhere in
// it; like a real mesh's, some cover no pixel centre and are dropped (share
// kept: "accepted").
void bench_setup(benchmark::State& state, const SizeClass& size) {
    constexpr Viewport kFrame{1280, 720};
    constexpr std::size_t kTriangles = 4096;
    std::mt19937 rng(kSeed);
    const std::vector<std::array<ScreenVertex, 3>> triangles =
        random_triangles(rng, size, kTriangles, kFrame, {0, 0, kFrame.width, kFrame.height}, false);
    std::size_t accepted = 0;
    for (auto _ : state) {
        for (std::uint32_t i = 0; i < kTriangles; ++i) {
            std::optional<RasterTriangle> t = raster::setup_triangle(kFrame, triangles[i], {3 * i, 3 * i + 1, 3 * i + 2});
            accepted += t.has_value();
            benchmark::DoNotOptimize(t);
        }
    }
    const auto set_up = double(state.iterations()) * double(kTriangles);
    state.SetItemsProcessed(std::int64_t(set_up));
    state.counters["accepted"] = double(accepted) / set_up;
}

[[maybe_unused]] const bool registered = [] {
    for (const SizeClass* size : {&kSmall, &kMedium, &kLarge, &kHuge}) {
        benchmark::RegisterBenchmark(("raster/scalar/" + std::string(size->name)).c_str(), bench_rasterize, *size,
                                     std::optional<Isa>());
        for (const Isa isa : kIsas) {
            if (isa == Isa::scalar) continue;  // rasterize_triangle(Isa::scalar, ...) is the overload above
            benchmark::RegisterBenchmark(
                ("raster/" + std::string(simd::isa_name(isa)) + "/" + size->name).c_str(), bench_rasterize, *size,
                std::optional<Isa>(isa));
        }
    }
    for (const SizeClass* size : {&kSmall, &kMedium})
        for (const Isa isa : kIsas) {
            if (isa == Isa::scalar) continue;
            benchmark::RegisterBenchmark(("raster_bin/" + std::string(simd::isa_name(isa)) + "/" + size->name).c_str(),
                                         bench_rasterize_bin, *size, isa);
        }
    benchmark::RegisterBenchmark("raster/tile_reset", bench_tile_reset);
    for (const SizeClass* size : {&kSmall, &kMedium, &kLarge})
        benchmark::RegisterBenchmark(("setup/" + std::string(size->name)).c_str(), bench_setup, *size);
    return true;
}();

}  // namespace
}  // namespace tessera::microbench
