// The fragment stage's kernels per ISA: shade_fragments (the PBR shader) over
// one batch of fragments, and tonemap_gamma (Reinhard + gamma) over its output.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench_common.hpp"
#include "shade/shade_kernels.hpp"
#include "shade/surface_gather.hpp"
#include "tessera/scene.hpp"

namespace tessera::microbench {
namespace {

using shade::FragmentBuffer;
using shade::ShadingLights;

// One batch: as many fragments as a 64×64 tile has pixels.
constexpr std::size_t kFragments = 4096;
const glm::vec3 kCameraPosition{0.0f, 0.0f, 22.0f};  // as scenes/spheres.toml

// Points on the camera-facing halves of the spheres of scenes/spheres.toml (a
// 7×7 grid, radius 1, 2.5 apart), with random materials: what the gather
// hands the shader for that scene, in a random order.
FragmentBuffer make_fragments(std::mt19937& rng) {
    std::uniform_int_distribution<int> cell(0, 6);
    std::normal_distribution<float> gauss(0.0f, 1.0f);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    FragmentBuffer buffer;
    buffer.reserve(kFragments);
    for (std::size_t i = 0; i < kFragments; ++i) {
        const glm::vec3 centre{float(cell(rng) - 3) * 2.5f, float(cell(rng) - 3) * 2.5f, 0.0f};
        glm::vec3 n;
        do n = {gauss(rng), gauss(rng), gauss(rng)};
        while (glm::dot(n, n) < 1e-6f);
        n = glm::normalize(n);
        if (glm::dot(n, kCameraPosition - centre) < 0.0f) n = -n;
        Material m;
        m.albedo = {unit(rng), unit(rng), unit(rng)};
        m.metallic = unit(rng);
        m.roughness = std::max(unit(rng), 0.05f);
        m.ao = 0.5f + 0.5f * unit(rng);
        // Interpolated normals are a little off unit length; the shader normalizes.
        buffer.set(i, centre + n, n * (0.95f + 0.1f * unit(rng)), m);
    }
    buffer.pad(kFragments);
    return buffer;
}

// The four lights of scenes/spheres.toml, then more at random in front of the grid.
ShadingLights make_lights(std::size_t count, std::mt19937& rng) {
    std::vector<Light> lights = {{{-10, 10, 10}, {300, 300, 300}},
                                      {{10, 10, 10}, {300, 300, 300}},
                                      {{-10, -10, 10}, {300, 300, 300}},
                                      {{10, -10, 10}, {300, 300, 300}}};
    std::uniform_real_distribution<float> across(-15.0f, 15.0f), depth(5.0f, 15.0f), power(150.0f, 450.0f);
    while (lights.size() < count) {
        const float p = power(rng);
        lights.push_back({{across(rng), across(rng), depth(rng)}, {p, p, p}});
    }
    lights.resize(count);
    ShadingLights soa;
    soa.assign(kCameraPosition, lights);
    return soa;
}

void bench_shade(benchmark::State& state, Isa isa) {
    if (skip_if_unsupported(state, isa)) return;
    const auto light_count = std::size_t(state.range(0));
    std::mt19937 rng(kSeed);
    FragmentBuffer fragments = make_fragments(rng);
    const ShadingLights lights = make_lights(light_count, rng);
    const shade::FragmentInputs in = fragments.inputs(kFragments);
    const shade::RadianceOutputs out = fragments.outputs();
    for (auto _ : state) {
        shade::shade_fragments(isa, in, lights, out);
        // The kernel lives in another translation unit, but say it anyway:
        // its stores are the result and must happen every iteration.
        benchmark::DoNotOptimize(out.r);
        benchmark::ClobberMemory();
    }
    const double work = double(kFragments) * double(light_count);
    state.SetItemsProcessed(state.iterations() * std::int64_t(work));
    state.counters["ns_per_fragment_light"] = time_per_unit(work);
}

// shade_fragment_runs over one plain run (the race's untextured spheres: the
// gather leaves the material channels unfilled and the kernel broadcasts the
// run's material), the fragments as above.
void bench_shade_plain_run(benchmark::State& state, Isa isa) {
    if (skip_if_unsupported(state, isa)) return;
    const auto light_count = std::size_t(state.range(0));
    std::mt19937 rng(kSeed);
    FragmentBuffer fragments = make_fragments(rng);
    const ShadingLights lights = make_lights(light_count, rng);
    const Material material{.albedo = {0.5f, 0.0f, 0.0f}, .metallic = 0.25f, .roughness = 0.4f, .ao = 1.0f};
    fragments.set_material(0, kFragments, material);
    const shade::MaterialRun run{0, std::uint32_t(kFragments), &material, false, true};
    const shade::FragmentInputs in = fragments.inputs(kFragments);
    const shade::RadianceOutputs out = fragments.outputs();
    for (auto _ : state) {
        shade::shade_fragment_runs(isa, in, {&run, 1}, lights, out);
        benchmark::DoNotOptimize(out.r);
        benchmark::ClobberMemory();
    }
    const double work = double(kFragments) * double(light_count);
    state.SetItemsProcessed(state.iterations() * std::int64_t(work));
    state.counters["ns_per_fragment_light"] = time_per_unit(work);
    state.counters["ns_per_fragment"] = time_per_unit(double(kFragments));
}

// tonemap_gamma works in place, so each iteration first restores its input
// (the HDR radiance of the fragments above under the demo's four lights): that
// copy of 3 × 16 KB, within L2, is timed too; tonemap/restore_only is its cost.
struct TonemapInput {
    std::vector<float> r, g, b;
};

TonemapInput make_radiance() {
    std::mt19937 rng(kSeed);
    FragmentBuffer fragments = make_fragments(rng);
    const ShadingLights lights = make_lights(4, rng);
    const shade::RadianceOutputs out = fragments.outputs();
    shade::shade_fragments(Isa::scalar, fragments.inputs(kFragments), lights, out);
    const std::size_t n = shade::padded_count(kFragments);
    return {{out.r, out.r + n}, {out.g, out.g + n}, {out.b, out.b + n}};
}

void bench_tonemap(benchmark::State& state, Isa isa, bool restore_only) {
    if (!restore_only && skip_if_unsupported(state, isa)) return;
    const TonemapInput hdr = make_radiance();
    TonemapInput work = hdr;
    for (auto _ : state) {
        std::copy(hdr.r.begin(), hdr.r.end(), work.r.begin());
        std::copy(hdr.g.begin(), hdr.g.end(), work.g.begin());
        std::copy(hdr.b.begin(), hdr.b.end(), work.b.begin());
        if (!restore_only) shade::tonemap_gamma(isa, kFragments, work.r.data(), work.g.data(), work.b.data());
        benchmark::DoNotOptimize(work.r.data());
        benchmark::DoNotOptimize(work.g.data());
        benchmark::DoNotOptimize(work.b.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(state.iterations() * std::int64_t(kFragments));
    state.counters["ns_per_fragment"] = time_per_unit(double(kFragments));
}

[[maybe_unused]] const bool registered = [] {
    for (const Isa isa : kIsas) {
        const std::string name(simd::isa_name(isa));
        benchmark::RegisterBenchmark(("shade/" + name).c_str(), bench_shade, isa)
            ->ArgName("lights")
            ->Arg(1)
            ->Arg(4)
            ->Arg(16);
        benchmark::RegisterBenchmark(("shade_plain_run/" + name).c_str(), bench_shade_plain_run, isa)
            ->ArgName("lights")
            ->Arg(1)
            ->Arg(2)
            ->Arg(4)
            ->Arg(8);
    }
    for (const Isa isa : kIsas)
        benchmark::RegisterBenchmark(("tonemap/" + std::string(simd::isa_name(isa))).c_str(), bench_tonemap, isa, false);
    benchmark::RegisterBenchmark("tonemap/restore_only", bench_tonemap, Isa::scalar, true);
    return true;
}();

}  // namespace
}  // namespace tessera::microbench
