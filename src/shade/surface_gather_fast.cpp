// Run-time choice of the gather (surface_gather_fast.hpp): the reference for
// Isa::scalar, else the per-ISA fast gather of surface_gather_simd.cpp. Built
// at baseline x86-64, as are the fast gathers' rare paths here.
#include "shade/surface_gather_fast.hpp"

#include <stdexcept>

namespace tessera::shade {

// Defined in surface_gather_simd.cpp, once per ISA.
#define TESSERA_DECLARE_GATHER_ENTRIES(suffix)                                                                     \
    std::size_t gather_tile_##suffix(const raster::TileBuffers& tile, int width, int height,                        \
                                     const GatherCornerLookup& lookup, FragmentBuffer& out,                         \
                                     std::vector<MaterialRun>& runs);                                              \
    std::size_t gather_fragment_list_##suffix(const raster::TileFragments& fragments, const GatherCornerLookup& lookup, \
                                              FragmentBuffer& out, std::vector<MaterialRun>& runs);
TESSERA_DECLARE_GATHER_ENTRIES(sse4)
TESSERA_DECLARE_GATHER_ENTRIES(avx2)
TESSERA_DECLARE_GATHER_ENTRIES(avx512)
#undef TESSERA_DECLARE_GATHER_ENTRIES

std::size_t gather_surface_points(Isa isa, const raster::TileBuffers& tile, int width, int height,
                                  const GatherCornerLookup& lookup, FragmentBuffer& out, std::vector<MaterialRun>& runs) {
    switch (isa) {
    case Isa::scalar:
        return gather_surface_points(tile, width, height, [&](std::uint32_t id) { return lookup.corners(id); }, out,
                                     runs);
    case Isa::sse4: return gather_tile_sse4(tile, width, height, lookup, out, runs);
    case Isa::avx2: return gather_tile_avx2(tile, width, height, lookup, out, runs);
    case Isa::avx512: return gather_tile_avx512(tile, width, height, lookup, out, runs);
    }
    throw std::invalid_argument("gather_surface_points: unknown ISA");
}

std::size_t gather_surface_points(Isa isa, const raster::TileFragments& fragments, const GatherCornerLookup& lookup,
                                  FragmentBuffer& out, std::vector<MaterialRun>& runs) {
    switch (isa) {
    case Isa::scalar:
        return gather_surface_points(fragments, [&](std::uint32_t id) { return lookup.corners(id); }, out, runs);
    case Isa::sse4: return gather_fragment_list_sse4(fragments, lookup, out, runs);
    case Isa::avx2: return gather_fragment_list_avx2(fragments, lookup, out, runs);
    case Isa::avx512: return gather_fragment_list_avx512(fragments, lookup, out, runs);
    }
    throw std::invalid_argument("gather_surface_points: unknown ISA");
}

namespace detail {

void push_run(std::vector<MaterialRun>& runs, const MaterialRun& run) { runs.push_back(run); }

void add_gathered_extras(const GatheredTriangle& t, const GatheredTriangleExtras& e, int x, int y, float lambda1,
                         float lambda2, float b1, float b2, FragmentBuffer& out, std::size_t i) {
    const glm::vec3 world_d1 = vec3_from(t.world_d1), world_d2 = vec3_from(t.world_d2);
    const SurfaceInterpolants interpolants{t.inv_w.lanes, world_d1, world_d2, e.uv0, e.uv_d1, e.uv_d2};
    add_extras(e.corners, interpolants, x, y, lambda1, lambda2, b1, b2, out, i);
}

}  // namespace detail

}  // namespace tessera::shade
