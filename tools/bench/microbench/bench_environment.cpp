// Environment lighting's pre-computation and its caches (src/environment):
//   environment/precompute/<isa>  every map of a 1024x512 EXR (studio.exr from
//       ../shared/assets, else the shipped 256x128 image: the work is the same,
//       the cube being 512² either way) without the BRDF table, wall time;
//   environment/brdf_lut/<isa>    the 512² BRDF table (once per process, or read from the disk cache);
//   environment/acquire/memory    acquire_environment when the maps are in memory;
//   environment/acquire/disk      when they come from the disk cache (memory cache dropped).
#include <filesystem>

#include "bench_common.hpp"
#include "environment/environment_cache.hpp"

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

void register_environment() {
    for (const Isa isa : {Isa::scalar, Isa::avx2, Isa::avx512}) {
        const std::string name(simd::isa_name(isa));
        benchmark::RegisterBenchmark(("environment/precompute/" + name).c_str(), precompute, isa)
            ->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(isa == Isa::scalar ? 1 : 3);
        benchmark::RegisterBenchmark(("environment/brdf_lut/" + name).c_str(), brdf_lut, isa)
            ->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(isa == Isa::scalar ? 1 : 3);
    }
    benchmark::RegisterBenchmark("environment/acquire/memory", acquire, false)->Unit(benchmark::kMillisecond)->UseRealTime();
    benchmark::RegisterBenchmark("environment/acquire/disk", acquire, true)->Unit(benchmark::kMillisecond)->UseRealTime();
}

const int registered = (register_environment(), 0);

}  // namespace
}  // namespace tessera::microbench
