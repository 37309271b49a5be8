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
