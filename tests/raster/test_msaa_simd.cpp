#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "raster/msaa/msaa.hpp"
#include "raster_test_util.hpp"

using namespace tessera;

namespace {

// Triangle setup for 4× MSAA straight from fixed-point corners (24.8, image y down).
std::optional<raster::RasterTriangle> msaa_fixed_triangle(std::array<glm::ivec2, 3> p, int image,
                                                          const std::array<float, 3>& depth) {
    return test::fixed_triangle(p, image, depth, raster::kMsaaSamples);
}

struct MsaaResult {
    raster::TileSamples samples;
    raster::RasterCounters counters;
};

// Rasterizes the triangles into `tile` (a side × side tile buffer; the rect
// may be smaller, as at the image's edge) with the scalar int64 loop and
// with every ISA's kernel, and checks that every sample's depth (bits) and
// triangle id where covered, and the counters, are identical, also outside
// the rect (nothing written there). Returns the scalar loop's result.
MsaaResult check_msaa_isas_match_scalar(const std::vector<raster::RasterTriangle>& triangles,
                                        const raster::TileRect& tile, int side) {
    MsaaResult reference;
    reference.samples.reset(side);
    for (std::uint32_t i = 0; i < triangles.size(); ++i)
        raster::rasterize_triangle_msaa(triangles[i], i, tile, reference.samples, reference.counters);
    const std::size_t n = std::size_t(raster::kMsaaSamples) * side * side;
    for (simd::Isa isa : {simd::Isa::scalar, simd::Isa::sse4, simd::Isa::avx2, simd::Isa::avx512}) {
        CAPTURE(simd::isa_name(isa));
        if (!simd::isa_supported(isa)) {
            MESSAGE("skipped: " << simd::isa_name(isa) << " is not supported by this CPU");
            continue;
        }
        MsaaResult result;
        result.samples.reset(side);
        for (std::uint32_t i = 0; i < triangles.size(); ++i)
            raster::rasterize_triangle_msaa(isa, triangles[i], i, tile, result.samples, result.counters);
        CHECK(result.counters.fragments == reference.counters.fragments);
        CHECK(result.counters.depth_passed == reference.counters.depth_passed);
        int mismatches = 0;
        for (std::size_t s = 0; s < n; ++s) {
            const bool covered = reference.samples.depth[s] < 1.0f;
            if (std::memcmp(&reference.samples.depth[s], &result.samples.depth[s], sizeof(float)) != 0 ||
                (covered && reference.samples.triangle[s] != result.samples.triangle[s]))
                ++mismatches;
        }
        CHECK(mismatches == 0);
    }
    return reference;
}

int covered_samples(const MsaaResult& r, const raster::TileRect& tile, int side) {
    int covered = 0;
    for (int y = 0; y < tile.height(); ++y)
        for (int x = 0; x < tile.width(); ++x)
            for (int s = 0; s < raster::kMsaaSamples; ++s)
                covered += r.samples.depth[std::size_t(raster::kMsaaSamples) * (std::size_t(y) * side + x) + s] < 1.0f;
    return covered;
}

}  // namespace

// Random triangles from sub-pixel slivers to several tiles across, some with
// corners on pixel centres or on sample positions (so that the top-left rule
// decides samples on edges), many at one shared depth (LESS ties), in tiles of
// every size the renderer allows, whole or cut by the image's right and
// bottom edges: the kernels' lanes past a box's end must leave samples as
// they were.
TEST_CASE("4x MSAA: every ISA's rasterizer gives bit-identical samples to the scalar loop") {
    std::mt19937 rng(2024);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int side = raster::kMinTileSize; side <= raster::kMaxTileSize; side *= 2) {
        for (const bool cut : {false, true}) {
            CAPTURE(side);
            CAPTURE(cut);
            // The tile sits at (side, side); cut: the image ends 3 and 5 pixels inside it.
            const int x0 = side, y0 = side;
            const int image_w = cut ? x0 + side - 3 : 3 * side, image_h = cut ? y0 + side - 5 : 3 * side;
            const raster::TileRect tile{x0, y0, std::min(x0 + side, image_w), std::min(y0 + side, image_h)};
            const int image = std::max(image_w, image_h);
            std::vector<raster::RasterTriangle> triangles;
            for (int kind = 0; triangles.size() < 2000; ++kind) {
                const float size = std::array<float, 5>{1.5f, 3.0f, 8.0f, 0.5f * side, 2.5f * side}[kind % 5];
                const glm::vec2 centre{x0 - 4 + unit(rng) * (side + 8), y0 - 4 + unit(rng) * (side + 8)};
                std::array<glm::ivec2, 3> p;
                for (glm::ivec2& c : p) {
                    const glm::vec2 f = centre + size * glm::vec2{unit(rng) * 2 - 1, unit(rng) * 2 - 1};
                    c = glm::ivec2(glm::round(f * 256.0f));
                    if (kind % 3 == 0) c = c / 256 * 256 + 128;                        // pixel centres
                    if (kind % 7 == 1) c = c / 256 * 256 + glm::ivec2{96, 224};        // sample 0's position
                    if (kind % 7 == 2) c = c / 256 * 256 + glm::ivec2{32 + 64 * (kind % 4), 32};  // sample grid lines
                }
                if (kind % 6 == 4) p[1].y = p[0].y;  // horizontal edge
                if (kind % 6 == 5) p[1].x = p[0].x;  // vertical edge
                const std::array<float, 3> depth = kind % 4 == 3 ? std::array<float, 3>{0.5f, 0.5f, 0.5f}
                                                                 : std::array<float, 3>{unit(rng), unit(rng), unit(rng)};
                // Clamped to the image as setup clamps boxes: the image is a square of `image` px here,
                // and the cut tile's rect ends inside it, as the renderer's grid does.
                if (auto t = msaa_fixed_triangle(p, image, depth)) {
                    t->px_max = std::int16_t(std::min<int>(t->px_max, image_w - 1));
                    t->py_max = std::int16_t(std::min<int>(t->py_max, image_h - 1));
                    if (t->px_min <= t->px_max && t->py_min <= t->py_max) triangles.push_back(*t);
                }
            }
            const MsaaResult reference = check_msaa_isas_match_scalar(triangles, tile, side);
            CHECK(covered_samples(reference, tile, side) > tile.width() * tile.height() * 2);
        }
    }
}

// A mesh of tiny triangles as the spheres make them (~1.3 px²), every edge
// shared: each sample on an edge belongs to exactly one of its two
// triangles, so the mesh covers every sample once; a second layer ties it in
// depth in places.
TEST_CASE("4x MSAA: a mesh of tiny triangles sharing edges gives bit-identical samples in every ISA") {
    constexpr int kTile = 32, kImage = 128;
    std::mt19937 rng(91);
    for (int pitch : {192, 320, 512}) {  // grid step in fixed point: 0.75, 1.25, 2 px
        CAPTURE(pitch);
        const int n = 40 * 256 / pitch;
        std::size_t layer = 0;
        const std::vector<raster::RasterTriangle> triangles =
            test::jittered_mesh(rng, pitch, n, kImage, raster::kMsaaSamples, layer);
        const raster::TileRect tile{32, 32, 32 + kTile, 32 + kTile};
        MsaaResult reference = check_msaa_isas_match_scalar(triangles, tile, kTile);
        CHECK(covered_samples(reference, tile, kTile) == raster::kMsaaSamples * kTile * kTile);  // watertight
        // The first layer alone covers each sample exactly once.
        raster::TileSamples first;
        first.reset(kTile);
        raster::RasterCounters counters;
        for (std::uint32_t i = 0; i < layer; ++i)
            raster::rasterize_triangle_msaa(simd::best_supported_isa(), triangles[i], i, tile, first, counters);
        CHECK(counters.fragments == std::uint64_t(raster::kMsaaSamples) * kTile * kTile);
    }
}

// Triangles whose edge values leave int32 over the tile (hundreds to
// thousands of pixels across) take the scalar loop inside the ISA path: still
// identical, mixed with small ones that take the kernel.
TEST_CASE("4x MSAA: huge triangles next to small ones match the scalar loop in every ISA") {
    constexpr int kImage = 16384, kSide = 64;
    std::mt19937 rng(5150);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const int x0 = 8192, y0 = 8192;
    const raster::TileRect tile{x0, y0, x0 + kSide, y0 + kSide};
    std::vector<raster::RasterTriangle> triangles;
    for (int kind = 0; triangles.size() < 600; ++kind) {
        const float radius = std::array<float, 4>{4.0f, 60.0f, 700.0f, 5000.0f}[kind % 4];
        const glm::vec2 p{x0 + unit(rng) * kSide, y0 + unit(rng) * kSide};
        std::array<glm::ivec2, 3> c;
        for (glm::ivec2& q : c)
            q = glm::ivec2(glm::round((p + radius * glm::vec2{unit(rng) * 2 - 1, unit(rng) * 2 - 1}) * 256.0f));
        if (auto t = msaa_fixed_triangle(c, kImage, {unit(rng), unit(rng), unit(rng)})) triangles.push_back(*t);
    }
    const MsaaResult reference = check_msaa_isas_match_scalar(triangles, tile, kSide);
    CHECK(covered_samples(reference, tile, kSide) == raster::kMsaaSamples * kSide * kSide);
}

namespace {

// collect_fragments with every ISA the CPU has and the plain loop it
// replaces, on the same samples: samples.fragment over the rect, the
// fragments' pixels, triangles and barycentrics (bits).
void check_collect_matches_reference(const raster::TileRect& rect, raster::TileSamples& samples,
                                     const std::vector<raster::RasterTriangle>& triangles) {
    const int side = samples.side;
    auto triangle_of = [&](std::uint32_t id) -> const raster::RasterTriangle& { return triangles[id]; };
    raster::TileFragments expected;
    expected.reserve(side);
    raster::collect_fragments_reference(rect, samples, triangle_of, expected);
    const std::vector<std::int32_t> expected_fragment = samples.fragment;
    for (simd::Isa isa : {simd::Isa::scalar, simd::Isa::sse4, simd::Isa::avx2, simd::Isa::avx512}) {
        CAPTURE(simd::isa_name(isa));
        if (!simd::isa_supported(isa)) {
            MESSAGE("skipped: " << simd::isa_name(isa) << " is not supported by this CPU");
            continue;
        }
        raster::TileFragments actual;
        actual.reserve(side);
        std::fill(samples.fragment.begin(), samples.fragment.end(), 12345);
        raster::collect_fragments(isa, rect, samples, triangle_of, actual);
        REQUIRE(actual.count == expected.count);
        int wrong = 0;
        for (int y = 0; y < rect.height(); ++y)
            for (int x = 0; x < rect.width(); ++x)
                for (int s = 0; s < raster::kMsaaSamples; ++s) {
                    const std::size_t i = std::size_t(raster::kMsaaSamples) * (std::size_t(y) * side + x) + s;
                    wrong += samples.fragment[i] != expected_fragment[i];
                }
        for (std::size_t k = 0; k < expected.count; ++k)
            wrong += actual.x[k] != expected.x[k] || actual.y[k] != expected.y[k] ||
                     actual.triangle[k] != expected.triangle[k] ||
                     std::memcmp(&actual.lambda1[k], &expected.lambda1[k], 4) != 0 ||
                     std::memcmp(&actual.lambda2[k], &expected.lambda2[k], 4) != 0;
        CHECK(wrong == 0);
    }
}

}  // namespace

// collect_fragments works a pixel at a time from a table of coverage and
// id-equality patterns: every pattern (1-4 triangles among covered samples,
// stale ids on uncovered ones) gives the reference loop's fragments, in
// order, on random samples and on a rasterized mesh.
TEST_CASE("4x MSAA: collect_fragments lists the reference loop's fragments for every sample pattern") {
    std::mt19937 rng(31);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<raster::RasterTriangle> triangles;
    for (int i = 0; triangles.size() < 8; ++i) {
        const glm::ivec2 o{(i % 4) * 2000, (i / 4) * 2000};
        if (auto t = msaa_fixed_triangle({o + glm::ivec2{100, 50}, o + glm::ivec2{9000, 700}, o + glm::ivec2{3000, 8000}},
                                         64, {0.5f, 0.6f, 0.7f}))
            triangles.push_back(*t);
    }
    for (int side : {8, 32}) {
        const raster::TileRect rect{side, 0, 2 * side - (side == 32 ? 5 : 0), side};
        raster::TileSamples samples;
        samples.reset(side);
        std::uniform_int_distribution<std::uint32_t> few(0, 3), any(0, 7);
        for (std::size_t i = 0; i < samples.depth.size(); ++i) {
            samples.depth[i] = unit(rng) < 0.3f ? 1.0f : unit(rng) * 0.99f;
            samples.triangle[i] = i % 3 ? few(rng) : any(rng);  // stale where depth is 1
        }
        samples.mark_written(0, 0, side, side);
        check_collect_matches_reference(rect, samples, triangles);
    }
    // A rasterized mesh of tiny triangles: real edges between 2-4 triangles per pixel.
    const raster::TileRect rect{32, 32, 64, 64};
    std::vector<raster::RasterTriangle> mesh;
    for (int j = 0; j < 40; ++j)
        for (int i = 0; i < 40; ++i) {
            const glm::ivec2 a{28 * 256 + i * 230, 28 * 256 + j * 230}, b = a + glm::ivec2{230, 0},
                c = a + glm::ivec2{0, 230}, d = a + glm::ivec2{230, 230};
            if (auto t = msaa_fixed_triangle({a, b, d}, 128, {0.5f, 0.5f, 0.5f})) mesh.push_back(*t);
            if (auto t = msaa_fixed_triangle({a, d, c}, 128, {0.5f, 0.5f, 0.5f})) mesh.push_back(*t);
        }
    raster::TileSamples samples;
    samples.reset(32);
    raster::RasterCounters counters;
    for (std::uint32_t i = 0; i < mesh.size(); ++i) raster::rasterize_triangle_msaa(mesh[i], i, rect, samples, counters);
    check_collect_matches_reference(rect, samples, mesh);
}

// Tiles as the renderer meets them: random triangles from slivers to far
// larger than the tile (edge values far past int32 at the pixel centres),
// rasterized into a tile buffer reused from tile to tile (reset() clears only
// the box written before), whole tiles and tiles cut by the image's right and
// bottom edges, and tiles no triangle reaches: every ISA's collect_fragments
// matches the plain loop, and the cleared samples match a fresh buffer's.
TEST_CASE("4x MSAA: collect_fragments matches the reference loop on reused, partial, empty and large-triangle tiles") {
    constexpr int kImage = 16000;  // not a multiple of the tile sides: partial tiles at the right and bottom
    std::mt19937 rng(977);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int side : {8, 32, 64}) {
        CAPTURE(side);
        raster::TileSamples samples;  // reused, as a worker's
        for (int round = 0; round < 24; ++round) {
            CAPTURE(round);
            const int last = kImage / side;  // the last, partial tile's index
            const int tx = round % 3 == 0 ? last : int(unit(rng) * last), ty = round % 4 == 1 ? last : int(unit(rng) * last);
            const raster::TileRect rect{tx * side, ty * side, std::min((tx + 1) * side, kImage), std::min((ty + 1) * side, kImage)};
            std::vector<raster::RasterTriangle> triangles;
            const int wanted = round % 6 == 5 ? 0 : 1 + int(unit(rng) * 40);  // some tiles empty
            for (int kind = 0; int(triangles.size()) < wanted; ++kind) {
                const float radius = std::array<float, 5>{0.7f, 5.0f, 30.0f, 900.0f, 6000.0f}[kind % 5];
                const glm::vec2 p{rect.x0 + unit(rng) * rect.width(), rect.y0 + unit(rng) * rect.height()};
                std::array<glm::ivec2, 3> c;
                for (glm::ivec2& q : c)
                    q = glm::clamp(glm::ivec2(glm::round((p + radius * glm::vec2{unit(rng) * 2 - 1, unit(rng) * 2 - 1}) * 256.0f)),
                                   glm::ivec2(-8000 * 256), glm::ivec2((kImage + 8000) * 256));
                if (auto t = msaa_fixed_triangle(c, kImage, {unit(rng), unit(rng), unit(rng)})) triangles.push_back(*t);
            }
            samples.reset(side);
            raster::TileSamples fresh;
            fresh.reset(side);
            CHECK(std::memcmp(samples.depth.data(), fresh.depth.data(), samples.depth.size() * sizeof(float)) == 0);
            raster::RasterCounters counters;
            const simd::Isa isa = simd::best_supported_isa();
            for (std::uint32_t i = 0; i < triangles.size(); ++i)
                raster::rasterize_triangle_msaa(isa, triangles[i], i, rect, samples, counters);
            check_collect_matches_reference(rect, samples, triangles);
        }
    }
}
