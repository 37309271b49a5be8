#include <doctest/doctest.h>

#include <bit>
#include <cstring>
#include <random>

#include "raster/triangle_assembly.hpp"

using namespace tessera;

namespace {

// Field by field (the record's padding bytes are not part of it), floats bit for bit.
bool same(const raster::RasterTriangle& a, const raster::RasterTriangle& b) {
    return a.x == b.x && a.y == b.y && a.px_min == b.px_min && a.px_max == b.px_max && a.py_min == b.py_min &&
           a.py_max == b.py_max && std::memcmp(&a.inv_area, &b.inv_area, sizeof(float)) == 0 &&
           std::memcmp(a.depth.data(), b.depth.data(), sizeof(a.depth)) == 0 && a.vertex == b.vertex &&
           a.back_facing == b.back_facing;
}

// For each SIMD ISA this CPU runs: `assemble(isa, out)` must give `reference`'s
// records, bit for bit and in order; then `also(assembled)` checks the rest.
template <class Assemble, class Also>
void check_every_simd_isa(const raster::AssembledTriangles& reference, Assemble&& assemble, Also&& also) {
    for (simd::Isa isa : {simd::Isa::sse4, simd::Isa::avx2, simd::Isa::avx512}) {
        CAPTURE(simd::isa_name(isa));
        if (!simd::isa_supported(isa)) {
            MESSAGE("skipped: " << simd::isa_name(isa) << " is not supported by this CPU");
            continue;
        }
        raster::AssembledTriangles assembled;
        assemble(isa, assembled);
        REQUIRE(assembled.triangles.size() == reference.triangles.size());
        int different = 0;
        for (std::size_t i = 0; i < assembled.triangles.size(); ++i)
            different += !same(assembled.triangles[i], reference.triangles[i]);
        CHECK(different == 0);
        also(assembled);
    }
}

template <class Assemble>
void check_every_simd_isa(const raster::AssembledTriangles& reference, Assemble&& assemble) {
    check_every_simd_isa(reference, assemble, [](const raster::AssembledTriangles&) {});
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
            screen.push_back({std::int32_t(std::lrint(x * 256)), std::int32_t(std::lrint(y * 256)), depth(rng), 0});
        }
    }
    const std::vector<std::uint32_t> outcodes(screen.size(), 0);  // all inside: every triangle goes to setup
    const std::vector<geometry::ShadedVertex> vertices(screen.size());
    const raster::FrameVertices frame{vertices, outcodes, screen};

    raster::AssembledTriangles reference;
    raster::assemble_triangles(simd::Isa::scalar, indices, 0, std::uint32_t(screen.size()), frame, viewport, guard, reference);
    REQUIRE(reference.triangles.size() > 5000);
    REQUIRE(reference.triangles.size() < 20000);  // some were dropped

    check_every_simd_isa(reference, [&](simd::Isa isa, raster::AssembledTriangles& assembled) {
        raster::assemble_triangles(isa, indices, 0, std::uint32_t(screen.size()), frame, viewport, guard, assembled);
    });
}

// The whole of assembly through the kernels: index checks, the outcode test
// (rejected, accepted, clipped: the kernels hand clipped and large triangles
// back to the scalar code, which must merge them in submission order), face
// culling and 4× MSAA, from a mesh that does not start at vertex 0 and with a
// last batch shorter than the kernels' vectors.
TEST_CASE("assembly through every ISA's kernel equals the scalar path: clipping, bad indices, culling, MSAA") {
    const geometry::Viewport viewport{320, 200};
    const geometry::GuardBand guard(viewport.width, viewport.height);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    constexpr std::uint32_t kFirstVertex = 5;  // vertices of an earlier mesh come first
    std::vector<geometry::ShadedVertex> vertices(kFirstVertex);
    std::vector<std::uint32_t> indices;
    std::vector<glm::vec4> colors;  // per mesh vertex
    std::size_t behind = 0, outside_guard = 0, not_finite = 0;
    for (int t = 0; t < 6001; ++t) {
        // Clusters of every size around a point on or off screen; each corner at its own w.
        const float spread = std::array<float, 4>{0.01f, 0.05f, 0.4f, 3.0f}[t % 4];
        const float cx = -1.3f + 2.6f * unit(rng), cy = -1.3f + 2.6f * unit(rng);
        for (int k = 0; k < 3; ++k) {
            const float w = 0.5f + 4.0f * unit(rng);
            glm::vec4 ndc(cx + spread * (unit(rng) - 0.5f), cy + spread * (unit(rng) - 0.5f), 2.0f * unit(rng) - 1.0f, 1);
            if (t % 13 == 0 && k == 1) ndc.z = -1.5f, ++behind;         // in front of the near plane
            if (t % 17 == 0 && k == 2) ndc.x = 400.0f, ++outside_guard;  // far past the guard band
            geometry::ShadedVertex v{};
            v.clip_pos = glm::vec4(glm::vec3(ndc) * w, w);
            v.world_pos = glm::vec3(unit(rng), unit(rng), unit(rng));
            v.normal = glm::vec3(0, 0, 1);
            if (t % 29 == 0 && k == 0) v.normal.x = std::nanf(""), ++not_finite;
            v.uv = glm::vec2(unit(rng), unit(rng));
            colors.emplace_back(unit(rng), unit(rng), unit(rng), 1.0f);
            std::uint32_t index = std::uint32_t(vertices.size()) - kFirstVertex;
            if (t % 31 == 0 && k == 1) index = std::uint32_t(6001 * 3 + t);  // out of range
            if (t % 37 == 0 && k == 2) index = 0x8000'0000u + std::uint32_t(t);  // negative as int32
            if (t % 5 == 0 && k == 0 && t > 0) index = indices[indices.size() - 2];  // shared with the last triangle
            indices.push_back(index);
            vertices.push_back(v);
        }
    }
    REQUIRE(behind > 100);
    REQUIRE(outside_guard > 100);
    REQUIRE(not_finite > 100);
    const std::uint32_t vertex_count = std::uint32_t(vertices.size()) - kFirstVertex;
    std::vector<std::uint32_t> outcodes(vertices.size());
    std::vector<geometry::ScreenVertex> screen(vertices.size());
    for (std::size_t i = 0; i < vertices.size(); ++i) {
        outcodes[i] = geometry::outcode(vertices[i], guard);
        if (!(outcodes[i] & (geometry::kClipPlaneBits | geometry::kNotFinite)))
            screen[i] = geometry::to_screen(vertices[i].clip_pos, viewport);
        screen[i].outcode = outcodes[i];
    }
    const raster::FrameVertices frame{vertices, outcodes, screen};

    for (const int samples : {1, 4})
        for (const raster::Culling culling :
             {raster::Culling::none, raster::Culling::drop_positive_area, raster::Culling::drop_negative_area})
        for (const bool mirrored : {false, true}) {
            CAPTURE(samples);
            CAPTURE(int(culling));
            CAPTURE(mirrored);
            raster::AssembledTriangles reference;
            raster::assemble_triangles(simd::Isa::scalar, indices, kFirstVertex, vertex_count, frame, viewport, guard,
                                       reference, samples, culling, colors, mirrored);
            std::size_t clipped = 0;
            for (const raster::RasterTriangle& t : reference.triangles)
                clipped += (t.vertex[0] | t.vertex[1] | t.vertex[2]) >= geometry::kClippedVertexBit;
            REQUIRE(reference.triangles.size() > 1000);
            REQUIRE(clipped > 50);  // clipped pieces sit between the kernel's triangles
            // Culling GL's back faces (positive area, unmirrored) keeps only front faces, and the other way round.
            std::size_t back = 0;
            for (const raster::RasterTriangle& t : reference.triangles) back += t.back_facing;
            if (culling == raster::Culling::drop_positive_area) CHECK(back == (mirrored ? reference.triangles.size() : 0));
            if (culling == raster::Culling::drop_negative_area) CHECK(back == (mirrored ? 0 : reference.triangles.size()));
            if (culling == raster::Culling::none) CHECK((back > 100 && back + 100 < reference.triangles.size()));
            check_every_simd_isa(
                reference,
                [&](simd::Isa isa, raster::AssembledTriangles& assembled) {
                    // Two runs, one of them cut into pieces that end off a batch boundary.
                    raster::assemble_triangles(isa, std::span(indices).first(3 * 1001), kFirstVertex, vertex_count,
                                               frame, viewport, guard, assembled, samples, culling, colors, mirrored);
                    raster::assemble_triangles(isa, std::span(indices).subspan(3 * 1001), kFirstVertex, vertex_count,
                                               frame, viewport, guard, assembled, samples, culling, colors, mirrored);
                },
                [&](const raster::AssembledTriangles& assembled) {
                    REQUIRE(assembled.clipped_vertices.size() == reference.clipped_vertices.size());
                    CHECK(std::memcmp(assembled.clipped_vertices.data(), reference.clipped_vertices.data(),
                                      assembled.clipped_vertices.size() * sizeof(geometry::ShadedVertex)) == 0);
                    CHECK(assembled.clipped_colors == reference.clipped_colors);
                });
        }
}

// The kernels store each lane's record at the next kept slot of the output,
// where a dropped lane's is overwritten by the next kept one: every pattern of
// kept and dropped lanes must leave exactly the kept records, in order, after
// what the output already held. Triangle i is kept (a few pixels, covering
// centres) or dropped (no area) by the bits of a pattern; each pattern is one
// batch of 64, assembled after a first mesh already in the output.
TEST_CASE("assembly keeps exactly the kept lanes' records, in order, for any pattern of kept and dropped lanes") {
    const geometry::Viewport viewport{256, 256};
    const geometry::GuardBand guard(viewport.width, viewport.height);
    std::vector<std::uint64_t> patterns = {0, ~std::uint64_t{0}, 0x5555'5555'5555'5555u, 0xaaaa'aaaa'aaaa'aaaau,
                                           0x8181'8181'8181'8181u, 0x7e7e'7e7e'7e7e'7e7eu};
    for (int lane = 0; lane < 64; ++lane) patterns.push_back(std::uint64_t(1) << lane);         // one kept
    for (int lane = 0; lane < 64; ++lane) patterns.push_back(~(std::uint64_t(1) << lane));      // one dropped
    std::mt19937_64 rng(5);
    for (int i = 0; i < 16; ++i) patterns.push_back(rng());
    // Mesh 0: four kept triangles; then 64 triangles per pattern.
    std::vector<geometry::ScreenVertex> screen;
    std::vector<std::uint32_t> first_indices, indices;
    auto add = [&](std::vector<std::uint32_t>& to, int n, bool kept) {
        const std::int32_t x = 256 * (8 + (n % 60) * 4), y = 256 * (8 + (n / 60 % 60) * 4);
        const std::int32_t spread = kept ? 3 * 256 : 0;  // no area: all three corners on one point
        const float depth = float(n % 97) / 97.0f;
        for (const auto& [dx, dy] : {std::pair{0, 0}, std::pair{spread, 0}, std::pair{0, spread}}) {
            to.push_back(std::uint32_t(screen.size()));
            screen.push_back({x + dx + 37, y + dy + 11, depth, 0});
        }
    };
    for (int n = 0; n < 4; ++n) add(first_indices, n, true);
    int n = 0;
    for (const std::uint64_t pattern : patterns)
        for (int lane = 0; lane < 64; ++lane, ++n) add(indices, n, (pattern >> lane) & 1);
    const std::vector<std::uint32_t> outcodes(screen.size(), 0);
    const std::vector<geometry::ShadedVertex> vertices(screen.size());
    const raster::FrameVertices frame{vertices, outcodes, screen};
    const std::uint32_t count = std::uint32_t(screen.size());

    raster::AssembledTriangles reference;
    raster::assemble_triangles(simd::Isa::scalar, first_indices, 0, count, frame, viewport, guard, reference);
    raster::assemble_triangles(simd::Isa::scalar, indices, 0, count, frame, viewport, guard, reference);
    std::size_t kept = 4;
    for (const std::uint64_t pattern : patterns) kept += std::size_t(std::popcount(pattern));
    REQUIRE(reference.triangles.size() == kept);  // the pattern decides, as meant
    check_every_simd_isa(reference, [&](simd::Isa isa, raster::AssembledTriangles& assembled) {
        raster::assemble_triangles(isa, first_indices, 0, count, frame, viewport, guard, assembled);
        raster::assemble_triangles(isa, indices, 0, count, frame, viewport, guard, assembled);
    });
}
