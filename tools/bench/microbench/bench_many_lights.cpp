// Many lights with ranges, per ISA: one tile of the many-lights scene's floor
// (tools/bench/make_many_lights.py N) shaded with light culling (shade_fragments_culled:
// tile and cluster selections, then the kernel over each cluster's list), and
// the kernel alone over a cluster's list (shade_fragments_in_range). The
// counter is CPU time per fragment·light shaded (the culled lists' lengths).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench_common.hpp"
#include "shade/light_culling.hpp"
#include "shade/shade_kernels.hpp"
#include "shade/surface_gather.hpp"
#include "tessera/scene.hpp"

namespace tessera::microbench {
namespace {

using shade::FragmentBuffer;
using shade::ShadingLights;

constexpr std::size_t kTileSide = 32;  // the renderer's default tile
constexpr std::size_t kFragments = kTileSide * kTileSide;
constexpr float kFloorY = -9.0f;  // as tools/bench/make_many_lights.py

// A 32×32 tile's visible points on the floor in front of the sphere grid, in
// gather order (rows of the tile), about as far apart as the scene's pixels there.
FragmentBuffer make_floor_tile() {
    FragmentBuffer buffer;
    buffer.reserve(kFragments);
    const Material floor{.albedo = glm::vec3(0.6f), .metallic = 0.0f, .roughness = 0.6f, .ao = 1.0f};
    for (std::size_t i = 0; i < kFragments; ++i) {
        const float x = -1.0f + 0.06f * float(i % kTileSide), z = 6.0f + 0.1f * float(i / kTileSide);
        buffer.set(i, {x, kFloorY, z}, {0.0f, 1.0f, 0.0f}, floor);
    }
    buffer.pad(kFragments);
    return buffer;
}

// tools/bench/make_many_lights.py's lights: half on a patch above the floor, half in
// a wall in front of the spheres, weak colours with range "auto".
ShadingLights make_lights(std::size_t n) {
    std::vector<Light> lights;
    const auto add_grid = [&](std::size_t count, std::size_t columns, auto&& position) {
        const std::size_t rows = std::max<std::size_t>(1, (count + columns - 1) / columns);
        for (std::size_t i = 0; i < count; ++i) {
            const float u = (float(i % columns) + 0.5f) / float(columns), v = (float(i / columns) + 0.5f) / float(rows);
            Light light;
            light.position = position(u, v);
            // A hue per light by the golden ratio, as the script's; brightness sum 0.12.
            const float hue = std::fmod(float(lights.size()) * 0.618034f, 1.0f);
            const glm::vec3 rgb = glm::vec3(0.55f) + 0.45f * glm::cos(6.2831853f * (hue + glm::vec3(0.0f, 1.0f, 2.0f) / 3.0f));
            light.color = rgb * (0.12f / (rgb.r + rgb.g + rgb.b));
            light.range = auto_light_range(light.color);
            lights.push_back(light);
        }
    };
    const std::size_t floor_n = n / 2, wall_n = n - floor_n;
    add_grid(floor_n, std::max<std::size_t>(1, std::size_t(std::lround(std::sqrt(double(floor_n) * 2.0)))),
             [](float u, float v) { return glm::vec3(-16.0f + 32.0f * u, kFloorY + 0.35f, 2.0f + 12.0f * v); });
    add_grid(wall_n, std::max<std::size_t>(1, std::size_t(std::lround(std::sqrt(double(wall_n) * 20.0 / 18.0)))),
             [](float u, float v) { return glm::vec3(-10.0f + 20.0f * u, -9.0f + 18.0f * v, 1.35f); });
    ShadingLights soa;
    soa.assign({0.0f, 3.0f, 30.0f}, lights);  // the scene's camera
    return soa;
}

// Culling and shading, as the renderer's tile pass runs them.
void bench_culled(benchmark::State& state, Isa isa) {
    if (skip_if_unsupported(state, isa)) return;
    FragmentBuffer fragments = make_floor_tile();
    const ShadingLights lights = make_lights(std::size_t(state.range(0)));
    shade::LightCullScratch scratch;
    scratch.reserve(lights.count());
    const shade::FragmentInputs in = fragments.inputs(kFragments);
    const shade::RadianceOutputs out = fragments.outputs();
    shade::CulledWork work;
    for (auto _ : state) {
        work = shade::shade_fragments_culled(isa, in, lights, scratch, out);
        benchmark::DoNotOptimize(out.r);
        benchmark::ClobberMemory();
    }
    state.counters["lights_per_fragment"] = double(work.fragment_lights) / double(kFragments);
    state.counters["ns_per_fragment_light"] = time_per_unit(double(work.fragment_lights));
}

// The kernel alone over one list: the lights the tile's first cluster keeps.
void bench_kernel(benchmark::State& state, Isa isa) {
    if (skip_if_unsupported(state, isa)) return;
    FragmentBuffer fragments = make_floor_tile();
    const ShadingLights lights = make_lights(std::size_t(state.range(0)));
    shade::LightCullScratch scratch;
    scratch.reserve(lights.count());
    const shade::FragmentInputs tile = fragments.inputs(kFragments);
    shade::select_reaching(lights, lights.every, shade::fragment_bounds(tile), scratch.tile);
    const shade::FragmentInputs cluster = fragments.inputs(shade::kClusterFragments);
    shade::select_reaching(lights, scratch.tile, shade::fragment_bounds(cluster), scratch.cluster);
    const shade::RadianceOutputs out = fragments.outputs();
    for (auto _ : state) {
        shade::shade_fragments_in_range(isa, cluster, lights, scratch.cluster, out);
        benchmark::DoNotOptimize(out.r);
        benchmark::ClobberMemory();
    }
    const double work = double(shade::kClusterFragments) * double(scratch.cluster.count());
    state.counters["lights_per_fragment"] = double(scratch.cluster.count());
    state.counters["ns_per_fragment_light"] = time_per_unit(work);
}

[[maybe_unused]] const bool registered = [] {
    for (const Isa isa : kIsas) {
        const std::string name(simd::isa_name(isa));
        benchmark::RegisterBenchmark(("many_lights/culled/" + name).c_str(), bench_culled, isa)
            ->ArgName("lights")
            ->Arg(256)
            ->Arg(1024);
        benchmark::RegisterBenchmark(("many_lights/kernel/" + name).c_str(), bench_kernel, isa)
            ->ArgName("lights")
            ->Arg(256)
            ->Arg(1024);
    }
    return true;
}();

}  // namespace
}  // namespace tessera::microbench
