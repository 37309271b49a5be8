// Face culling in triangle setup (raster::Culling): the winding rule on
// hand-made triangles, and every ISA's setup kernel culling exactly as the
// scalar setup does.
#include <doctest/doctest.h>

#include <cstring>
#include <random>

#include "raster/triangle_assembly.hpp"

using namespace tessera;

namespace {

geometry::ScreenVertex at(float x, float y) { return {std::int32_t(x * 256), std::int32_t(y * 256), 0.5f, 0}; }

}  // namespace

TEST_CASE("culling drops a triangle by the sign of its image-space area, before corners are reordered") {
    const geometry::Viewport viewport{64, 64};
    // Image space has y down: (10,10) → (10,40) → (40,10) goes down, then up to the
    // right: counter-clockwise as seen on screen (and in GL's window space, y up),
    // a front face, with a negative edge-function area in image coordinates.
    const std::array<geometry::ScreenVertex, 3> front{at(10, 10), at(10, 40), at(40, 10)};
    const std::array<geometry::ScreenVertex, 3> back{at(10, 10), at(40, 10), at(10, 40)};
    const std::array<std::uint32_t, 3> refs{0, 1, 2};
    using raster::Culling;
    CHECK(raster::setup_triangle(viewport, front, refs, 1, Culling::none));
    CHECK(raster::setup_triangle(viewport, back, refs, 1, Culling::none));
    CHECK(raster::setup_triangle(viewport, front, refs, 1, Culling::drop_positive_area));
    CHECK_FALSE(raster::setup_triangle(viewport, back, refs, 1, Culling::drop_positive_area));
    CHECK_FALSE(raster::setup_triangle(viewport, front, refs, 1, Culling::drop_negative_area));
    CHECK(raster::setup_triangle(viewport, back, refs, 1, Culling::drop_negative_area));
    // The same with 4× MSAA.
    CHECK(raster::setup_triangle(viewport, front, refs, 4, Culling::drop_positive_area));
    CHECK_FALSE(raster::setup_triangle(viewport, back, refs, 4, Culling::drop_positive_area));
}

TEST_CASE("every ISA's setup kernel culls what the scalar setup culls, the two cullings split the unculled set") {
    const geometry::Viewport viewport{320, 240};
    const geometry::GuardBand guard(viewport.width, viewport.height);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<geometry::ScreenVertex> screen;
    std::vector<std::uint32_t> indices;
    for (int t = 0; t < 6000; ++t) {
        const float spread = std::array<float, 4>{0.8f, 3.0f, 20.0f, 300.0f}[t % 4];  // the last: scalar fallback
        const float cx = 320.0f * unit(rng), cy = 240.0f * unit(rng);
        for (int k = 0; k < 3; ++k) {
            indices.push_back(std::uint32_t(screen.size()));
            screen.push_back(at(cx + spread * (unit(rng) - 0.5f), cy + spread * (unit(rng) - 0.5f)));
        }
    }
    const std::vector<std::uint32_t> outcodes(screen.size(), 0);
    const std::vector<geometry::ShadedVertex> vertices(screen.size());
    const raster::FrameVertices frame{vertices, outcodes, screen};
    const auto assemble = [&](simd::Isa isa, raster::Culling culling) {
        raster::AssembledTriangles out;
        raster::assemble_triangles(isa, indices, 0, std::uint32_t(screen.size()), frame, viewport, guard, out, 1, culling);
        std::vector<std::uint32_t> kept;  // each kept triangle by its first corner (unique per triangle)
        for (const raster::RasterTriangle& t : out.triangles) kept.push_back(t.vertex[0]);
        return kept;
    };
    const std::vector<std::uint32_t> all = assemble(simd::Isa::scalar, raster::Culling::none);
    const std::vector<std::uint32_t> front = assemble(simd::Isa::scalar, raster::Culling::drop_positive_area);
    const std::vector<std::uint32_t> back = assemble(simd::Isa::scalar, raster::Culling::drop_negative_area);
    CHECK(front.size() > all.size() / 3);
    CHECK(back.size() > all.size() / 3);
    CHECK(front.size() + back.size() == all.size());
    for (simd::Isa isa : {simd::Isa::sse4, simd::Isa::avx2, simd::Isa::avx512}) {
        CAPTURE(simd::isa_name(isa));
        if (!simd::isa_supported(isa)) continue;
        CHECK(assemble(isa, raster::Culling::drop_positive_area) == front);
        CHECK(assemble(isa, raster::Culling::drop_negative_area) == back);
    }
}
