// Environment lighting's pre-computation and its caches (src/environment):
//   environment/precompute/<isa>  every map of a 1024x512 EXR (studio.exr from
//       ../shared/assets, else the shipped 256x128 image: the work is the same,
//       the cube being 512² either way) without the BRDF table, wall time;
//   environment/brdf_lut/<isa>    the 512² BRDF table (once per process, or read from the disk cache);
//   environment/acquire/memory    acquire_environment when the maps are in memory;
//   environment/acquire/disk      when they come from the disk cache (memory cache dropped).
//   environment/background_row/<isa>  background.fs over a 1280x720 view of the
//       shipped environment, row by row in 64-pixel spans as the resolve paints it;
//       time per pixel.
#include <cmath>
#include <filesystem>

#include <glm/gtc/constants.hpp>

#include "bench_common.hpp"
#include "environment/environment_cache.hpp"
#include "shade/ibl_reference.hpp"
#include "simd/lane_padding.hpp"

namespace tessera::microbench {
namespace {

namespace fs = std::filesystem;

fs::path environment_image() {
    const fs::path source = TESSERA_MICROBENCH_SOURCE_DIR;
    const fs::path big = source.parent_path() / "shared" / "assets" / "environments" / "studio.exr";
    if (fs::exists(big)) return big;
    return source / "scenes" / "environments" / "studio_256.exr";
}

void precompute(benchmark::State& state, Isa isa) {
    if (skip_if_unsupported(state, isa)) return;
    const environment::EquirectImage image = environment::load_equirect_image(environment_image());
    const auto brdf = std::make_shared<const environment::BrdfLut>(1);
    for (auto _ : state) benchmark::DoNotOptimize(environment::precompute_environment(image, brdf, isa));
    state.SetLabel(std::to_string(image.width) + "x" + std::to_string(image.height));
}

void brdf_lut(benchmark::State& state, Isa isa) {
    if (skip_if_unsupported(state, isa)) return;
    for (auto _ : state) benchmark::DoNotOptimize(environment::integrate_brdf(environment::kBrdfLutSize, isa));
}

void acquire(benchmark::State& state, bool from_disk) {
    const fs::path cache = fs::temp_directory_path() / "tessera_microbench_environment_cache";
    ::setenv("TESSERA_CACHE_DIR", cache.c_str(), 1);
    environment::set_disk_cache_enabled(true);
    environment::acquire_environment(environment_image());  // fills both caches
    for (auto _ : state) {
        if (from_disk) environment::clear_memory_cache();
        benchmark::DoNotOptimize(environment::acquire_environment(environment_image()));
    }
    const environment::AcquireStats stats = environment::last_acquire_stats();
    state.SetLabel(stats.source == environment::CacheSource::disk ? "disk" : stats.source == environment::CacheSource::memory ? "memory" : "computed");
}

void background_row(benchmark::State& state, Isa isa) {
    if (skip_if_unsupported(state, isa)) return;
    const fs::path source = TESSERA_MICROBENCH_SOURCE_DIR;
    const auto maps = environment::acquire_environment(source / "scenes" / "environments" / "studio_256.exr");
    const shade::IblLighting ibl{maps.get(), 1.0f, 1.0f, 0.0f};
    constexpr int kWidth = 1280, kHeight = 720, kSpan = 64;
    // spheres_environment.toml's camera: looking down -Z, fov_y 45 degrees.
    const float tan_half = std::tan(glm::radians(45.0f) * 0.5f), aspect = float(kWidth) / float(kHeight);
    shade::BackgroundRays rays{{0.0f, 0.0f, -1.0f}, {tan_half * aspect, 0.0f, 0.0f}, {0.0f, tan_half, 0.0f}, float(kWidth), 0.0f};
    alignas(64) float column[simd::padded_count(kSpan)], r[simd::padded_count(kSpan)], g[simd::padded_count(kSpan)],
        b[simd::padded_count(kSpan)];
    for (auto _ : state)
        for (int y = 0; y < kHeight; ++y) {
            rays.ndc_y = 1.0f - 2.0f * (float(y) + 0.5f) / float(kHeight);
            for (int x0 = 0; x0 < kWidth; x0 += kSpan) {
                for (int k = 0; k < kSpan; ++k) column[k] = float(x0 + k);
                shade::sample_environment_background_row(isa, kSpan, column, rays, ibl, 1.0f, {r, g, b});
                benchmark::DoNotOptimize(r[0]);
            }
        }
    state.counters["per_pixel"] = time_per_unit(double(kWidth) * kHeight);
}

void register_environment() {
    for (const Isa isa : {Isa::scalar, Isa::avx2, Isa::avx512}) {
        const std::string name(simd::isa_name(isa));
        benchmark::RegisterBenchmark(("environment/precompute/" + name).c_str(), precompute, isa)
            ->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(isa == Isa::scalar ? 1 : 3);
        benchmark::RegisterBenchmark(("environment/brdf_lut/" + name).c_str(), brdf_lut, isa)
            ->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(isa == Isa::scalar ? 1 : 3);
    }
    for (const Isa isa : kIsas)
        benchmark::RegisterBenchmark(("environment/background_row/" + std::string(simd::isa_name(isa))).c_str(),
                                     background_row, isa)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("environment/acquire/memory", acquire, false)->Unit(benchmark::kMillisecond)->UseRealTime();
    benchmark::RegisterBenchmark("environment/acquire/disk", acquire, true)->Unit(benchmark::kMillisecond)->UseRealTime();
}

const int registered = (register_environment(), 0);

}  // namespace
}  // namespace tessera::microbench
