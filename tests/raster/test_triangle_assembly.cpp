#include <doctest/doctest.h>

#include <cstring>
#include <random>

#include "raster/triangle_assembly.hpp"

using namespace tessera;

namespace {

// Field by field (the record's padding bytes are not part of it), floats bit for bit.
bool same(const raster::RasterTriangle& a, const raster::RasterTriangle& b) {
    return a.x == b.x && a.y == b.y && a.px_min == b.px_min && a.px_max == b.px_max && a.py_min == b.py_min &&
           a.py_max == b.py_max && std::memcmp(&a.inv_area, &b.inv_area, sizeof(float)) == 0 &&
           std::memcmp(a.depth.data(), b.depth.data(), sizeof(a.depth)) == 0 && a.vertex == b.vertex;
}

}  // namespace

// The setup kernels decide, a vector of triangles at a time, what the scalar
// setup_triangle() decides one by one: the assembled triangles must be the same,
// in the same order, for every ISA.
TEST_CASE("assembling triangles with every ISA's setup kernel gives the scalar result exactly") {
    const geometry::Viewport viewport{640, 480};
    const geometry::GuardBand guard(viewport.width, viewport.height);
    std::mt19937 rng(99);
    std::uniform_real_distribution<float> depth(0.0f, 1.0f), unit(0.0f, 1.0f);
    // Screen vertices spread over and around the viewport, in clusters of every size:
    // sub-pixel (most), a few pixels, and hundreds of pixels (past the kernels' int32 range).
    std::vector<geometry::ScreenVertex> screen;
    std::vector<std::uint32_t> indices;
    for (int t = 0; t < 20000; ++t) {
        const float spread = std::array<float, 5>{0.7f, 1.5f, 3.0f, 20.0f, 400.0f}[t % 5];
        const float cx = -50.0f + 740.0f * unit(rng), cy = -50.0f + 580.0f * unit(rng);
        for (int k = 0; k < 3; ++k) {
            float x = cx + spread * (unit(rng) - 0.5f), y = cy + spread * (unit(rng) - 0.5f);
            if (t % 7 == 0) x = std::floor(x) + 0.5f, y = std::floor(y) + 0.5f;  // corners on pixel centres: ties
            if (t % 11 == 0 && k == 2) x = screen[screen.size() - 1].x / 256.0f, y = screen[screen.size() - 1].y / 256.0f;  // no area
            indices.push_back(std::uint32_t(screen.size()));
            screen.push_back({std::int32_t(std::lrint(x * 256)), std::int32_t(std::lrint(y * 256)), depth(rng), 1.0f + unit(rng)});
        }
    }
    const std::vector<std::uint32_t> outcodes(screen.size(), 0);  // all inside: every triangle goes to setup
    const std::vector<geometry::ShadedVertex> vertices(screen.size());
    const raster::FrameVertices frame{vertices, outcodes, screen};

    raster::AssembledTriangles reference;
    raster::assemble_triangles(simd::Isa::scalar, indices, 0, std::uint32_t(screen.size()), frame, viewport, guard, reference);
    REQUIRE(reference.triangles.size() > 5000);
    REQUIRE(reference.triangles.size() < 20000);  // some were dropped

    for (simd::Isa isa : {simd::Isa::sse4, simd::Isa::avx2, simd::Isa::avx512}) {
        CAPTURE(simd::isa_name(isa));
        if (!simd::isa_supported(isa)) {
            MESSAGE("skipped: " << simd::isa_name(isa) << " is not supported by this CPU");
            continue;
        }
        raster::AssembledTriangles assembled;
        raster::assemble_triangles(isa, indices, 0, std::uint32_t(screen.size()), frame, viewport, guard, assembled);
        REQUIRE(assembled.triangles.size() == reference.triangles.size());
        int different = 0;
        for (std::size_t i = 0; i < assembled.triangles.size(); ++i)
            different += !same(assembled.triangles[i], reference.triangles[i]);
        CHECK(different == 0);
    }
}
