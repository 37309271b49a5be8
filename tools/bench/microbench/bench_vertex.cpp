// The vertex stage per ISA: geometry::run_vertex_stage over the demo's sphere
// mesh (the reference's 64×64 UV sphere, 4225 vertices) placed and viewed as
// in scenes/spheres.toml, at 1280×720. Items = vertices.
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "bench_common.hpp"
#include "geometry/vertex_stage.hpp"

namespace tessera::microbench {
namespace {

void bench_vertex_stage(benchmark::State& state, Isa isa) {
    if (skip_if_unsupported(state, isa)) return;
    const Mesh mesh = make_sphere_mesh();
    const glm::mat4 model = glm::translate(glm::mat4(1.0f), glm::vec3(-2.5f, 2.5f, 0.0f));
    const glm::mat4 view_projection =
        glm::perspective(glm::radians(45.0f), 1280.0f / 720.0f, 0.1f, 100.0f) *
        glm::lookAt(glm::vec3(0.0f, 0.0f, 20.0f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    const geometry::Viewport viewport{1280, 720};
    const geometry::GuardBand guard(viewport.width, viewport.height);
    std::vector<geometry::ShadedVertex> vertices(mesh.positions.size());
    std::vector<std::uint32_t> outcodes(vertices.size());
    std::vector<geometry::ScreenVertex> screen(vertices.size());
    for (auto _ : state) {
        geometry::run_vertex_stage(isa, mesh, 0, model, view_projection, guard, viewport,
                                   {vertices, outcodes.data(), screen.data()});
        benchmark::DoNotOptimize(vertices.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(vertices.size()));
    state.counters["ns_per_vertex"] = time_per_unit(double(vertices.size()));
}

[[maybe_unused]] const bool registered = [] {
    for (const Isa isa : kIsas)
        benchmark::RegisterBenchmark(("vertex/" + std::string(simd::isa_name(isa))).c_str(), bench_vertex_stage, isa);
    return true;
}();

}  // namespace
}  // namespace tessera::microbench
