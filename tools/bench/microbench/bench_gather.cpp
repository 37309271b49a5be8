// The gather: a fully covered 32×32 tile of plain (untextured) triangles into a
// FragmentBuffer, the reference gather (scalar) against the fast one (every
// other ISA runs surface_gather_fast.hpp's, compiled for it). A triangle covers a
// block of w × h pixels, so that the tile's rows meet it h times, as a
// rasterized triangle's rows do; its corners lie scattered through 30 000
// vertices. Reported per fragment.
#include <array>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench_common.hpp"
#include "shade/surface_gather_fast.hpp"
#include "tessera/scene.hpp"

namespace tessera::microbench {
namespace {

constexpr int kSide = 32;

struct GatherInputs {
    std::vector<geometry::ShadedVertex> vertices;
    std::vector<raster::RasterTriangle> triangles;  // only the corners' vertex references are read
    Material material;
    shade::GatherChunk chunk{};
    raster::TileBuffers tile;

    GatherInputs(int block_width, int block_height, std::mt19937& rng) {
        std::uniform_real_distribution<float> coord(-10.0f, 10.0f), w(15.0f, 30.0f), unit(0.0f, 1.0f);
        vertices.resize(30000);
        for (auto& v : vertices) {
            v.clip_pos = {coord(rng), coord(rng), coord(rng), w(rng)};
            v.world_pos = {coord(rng), coord(rng), coord(rng)};
            v.normal = {coord(rng), coord(rng), coord(rng)};
        }
        std::uniform_int_distribution<std::uint32_t> vertex(0, std::uint32_t(vertices.size() - 3));
        const int blocks_per_row = (kSide + block_width - 1) / block_width;
        for (int b = 0; b < blocks_per_row * ((kSide + block_height - 1) / block_height); ++b) {
            const std::uint32_t v = vertex(rng);
            raster::RasterTriangle t{};
            t.vertex = {v, v + 1, v + 2};
            triangles.push_back(t);
        }
        chunk = {triangles.data(), nullptr, &material, false};
        tile.reset(kSide);
        for (std::uint32_t id = 0; id < triangles.size(); ++id) tile.triangles.add(id);  // position = id
        for (int y = 0; y < kSide; ++y)
            for (int x = 0; x < kSide; ++x) {
                const int pixel = y * kSide + x;
                const float l1 = unit(rng), l2 = unit(rng) * (1.0f - l1);
                tile.depth[pixel] = 0.5f;
                tile.triangle[pixel] = std::uint32_t((y / block_height) * blocks_per_row + x / block_width);
                tile.lambda1[pixel] = l1, tile.lambda2[pixel] = l2;
            }
    }
    shade::TriangleCorners corners(std::uint32_t id) const {
        const auto& v = triangles[id].vertex;
        return {{&vertices[v[0]], &vertices[v[1]], &vertices[v[2]]}, &material};
    }
    // One chunk, as the renderer's lookup has them (ids below 2^17).
    shade::GatherCornerLookup lookup() const {
        return {vertices.data(), &chunk, 17,
                [](const void* inputs, std::uint32_t id) { return static_cast<const GatherInputs*>(inputs)->corners(id); },
                this};
    }
};

void BM_gather(benchmark::State& state, Isa isa, int block_width, int block_height) {
    if (skip_if_unsupported(state, isa)) return;
    std::mt19937 rng(kSeed);
    const GatherInputs in(block_width, block_height, rng);
    const shade::GatherCornerLookup lookup = in.lookup();
    shade::FragmentBuffer out;
    out.reserve(kSide * kSide);
    std::vector<shade::MaterialRun> runs;
    runs.reserve(kSide * kSide);
    for (auto _ : state) {
        const std::size_t count = shade::gather_surface_points(
            isa, in.tile, kSide, kSide, lookup, out, runs);
        benchmark::DoNotOptimize(count);
        benchmark::DoNotOptimize(out.channel(shade::FragmentBuffer::world_x));
    }
    state.counters["per_fragment"] = time_per_unit(kSide * kSide);
    state.counters["triangles"] = double(in.triangles.size());
}

[[maybe_unused]] const bool registered = [] {
    // 2×1: spheres.toml's ~2-pixel triangles at 720p; 4×3: its ~12-pixel ones at 4K; 16×16: large ones.
    for (const std::array<int, 2> block : {std::array{2, 1}, std::array{4, 3}, std::array{16, 16}})
        for (const Isa isa : kIsas)
            benchmark::RegisterBenchmark(("gather/" + std::string(simd::isa_name(isa)) + "/block:" +
                                          std::to_string(block[0]) + "x" + std::to_string(block[1]))
                                             .c_str(),
                                         BM_gather, isa, block[0], block[1]);
    return true;
}();

}  // namespace
}  // namespace tessera::microbench
