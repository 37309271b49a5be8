#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <random>
#include <vector>

#include "raster/msaa/msaa_bin.hpp"
#include "raster_test_util.hpp"

using namespace tessera;

namespace {

const std::array<simd::Isa, 4> kIsas{simd::Isa::scalar, simd::Isa::sse4, simd::Isa::avx2, simd::Isa::avx512};

// The vertices the records' corner references (0, 1, 2) name, for the kernels' corner prefetch.
const std::vector<geometry::ShadedVertex> kFrameVertices(3), kClippedVertices(1);
const raster::CornerPrefetch kPrefetch{reinterpret_cast<const std::byte*>(kFrameVertices.data()),
                                       reinterpret_cast<const std::byte*>(kClippedVertices.data()),
                                       sizeof(geometry::ShadedVertex)};

struct Drawn {
    raster::TileSamples samples;
    raster::RasterCounters counters;
    std::vector<std::uint32_t> drawn;  // bin entries that passed the depth test at some sample, in order
};

// A tile's samples as a worker leaves them: a first tile's bin drawn, then
// reset for this one (depth 1 again only in the old written box; stale ids
// everywhere), or fresh, with garbage ids where nothing is drawn.
void prepare(Drawn& d, int side, bool reused, const std::vector<raster::RasterTriangle>& records) {
    d.samples.reset(side);
    std::fill(d.samples.triangle.begin(), d.samples.triangle.end(), 0xdeadbeefu);
    if (!reused) return;
    raster::RasterCounters scratch;
    for (std::uint32_t i = 0; i < records.size(); i += 3)
        raster::rasterize_triangle_msaa(records[i], 7u << 20 | i, {0, 0, side, side}, d.samples, scratch);
    d.samples.reset(side);
}

// The reference: rasterize_triangle_msaa(isa, ...) one triangle at a time in
// bin order, bin after bin into the same samples (one tile's chunks); a
// triangle is drawn when the depth-passed count moved.
void one_by_one(simd::Isa isa, const std::vector<raster::RasterTriangle>& records,
                const std::vector<std::vector<std::uint32_t>>& bins, const raster::TileRect& tile, Drawn& d) {
    for (std::size_t b = 0; b < bins.size(); ++b)
        for (const std::uint32_t entry : bins[b]) {
            const std::uint64_t before = d.counters.depth_passed;
            raster::rasterize_triangle_msaa(isa, records[entry], std::uint32_t(b + 1) << 17 | entry, tile, d.samples,
                                            d.counters);
            if (d.counters.depth_passed != before) d.drawn.push_back(entry);
        }
}

void whole_bins(simd::Isa isa, const std::vector<raster::RasterTriangle>& records,
                const std::vector<std::vector<std::uint32_t>>& bins, const raster::TileRect& tile, Drawn& d) {
    const raster::DrawnCallback drawn{[](void* context, std::uint32_t entry) {
                                          static_cast<std::vector<std::uint32_t>*>(context)->push_back(entry);
                                      },
                                      &d.drawn};
    for (std::size_t b = 0; b < bins.size(); ++b)
        // With the corner prefetch the renderer asks for: a hint that must change nothing.
        raster::rasterize_bin_msaa(isa, records.data(), bins[b], std::uint32_t(b + 1) << 17, tile, d.samples,
                                   d.counters, drawn, kPrefetch);
}

// Samples whose depth bits or triangle id differ, over the whole buffer
// (padding included: lanes past a box write back what they read).
int mismatched_samples(const raster::TileSamples& a, const raster::TileSamples& b) {
    REQUIRE(a.depth.size() == b.depth.size());
    int mismatches = 0;
    for (std::size_t s = 0; s < a.depth.size(); ++s)
        mismatches += std::memcmp(&a.depth[s], &b.depth[s], sizeof(float)) != 0 || a.triangle[s] != b.triangle[s];
    return mismatches;
}

// For every ISA the CPU has, fresh and reused samples: the bins in one call
// each give what the triangles one by one give (samples, written box,
// counters, the drawn triangles in order). Returns how many samples the
// reference covered, for the caller to check the case draws something.
int check_bins_match(const std::vector<raster::RasterTriangle>& records,
                     const std::vector<std::vector<std::uint32_t>>& bins, const raster::TileRect& tile, int side) {
    int covered = 0;
    for (const simd::Isa isa : kIsas) {
        CAPTURE(simd::isa_name(isa));
        if (!simd::isa_supported(isa)) {
            MESSAGE("skipped: " << simd::isa_name(isa) << " is not supported by this CPU");
            continue;
        }
        for (const bool reused : {false, true}) {
            CAPTURE(reused);
            Drawn expected, actual;
            prepare(expected, side, reused, records);
            prepare(actual, side, reused, records);
            one_by_one(isa, records, bins, tile, expected);
            whole_bins(isa, records, bins, tile, actual);
            CHECK(mismatched_samples(expected.samples, actual.samples) == 0);
            CHECK(actual.samples.written_x0 == expected.samples.written_x0);
            CHECK(actual.samples.written_y0 == expected.samples.written_y0);
            CHECK(actual.samples.written_x1 == expected.samples.written_x1);
            CHECK(actual.samples.written_y1 == expected.samples.written_y1);
            CHECK(actual.counters.fragments == expected.counters.fragments);
            CHECK(actual.counters.depth_passed == expected.counters.depth_passed);
            CHECK(actual.drawn == expected.drawn);
            covered = int(std::count_if(expected.samples.depth.begin(), expected.samples.depth.end(),
                                        [](float z) { return z < 1.0f; }));
        }
    }
    return covered;
}

std::optional<raster::RasterTriangle> msaa_triangle(const std::array<glm::ivec2, 3>& p, int image,
                                                    const std::array<float, 3>& depth) {
    return test::fixed_triangle(p, image, depth, raster::kMsaaSamples);
}

}  // namespace

// Bins of every length up to past two AVX-512 vectors' worth, mixing boxes
// that miss the tile, tiny triangles inside it or cut by its sides (the
// kernel's inline path), big ones (the general block kernel), triangles tied
// in depth with others at one shared depth (LESS keeps the first: a reordered
// bin changes ids), copies of a triangle under another entry (the first of
// the two keeps every sample), repeated entries (a repeat never passes again)
// and triangles whose corners sit on sample positions (top-left rule ties).
TEST_CASE("4x MSAA: bins of every length, mixing missed, tiny, big and tied triangles, match one by one") {
    std::mt19937 rng(4113);
    constexpr int kImage = 128, kSide = 32;
    const raster::TileRect tile{32, 64, 64, 96};
    std::uniform_int_distribution<int> near_tile(24 * 256, 72 * 256);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<raster::RasterTriangle> records;
    int missed = 0, big = 0, tiny_in_tile = 0, cut = 0;
    while (records.size() < 500) {
        const int kind = int(records.size() % 6);
        if (kind == 5) {  // a copy of the last one: whichever comes first in the bin keeps every sample
            records.push_back(records.back());
            continue;
        }
        const glm::ivec2 a{near_tile(rng), near_tile(rng) + 32 * 256};
        std::uniform_int_distribution<int> offset(0, kind == 4   ? 40 * 256
                                                     : kind == 3 ? raster::kTinySpan - 1
                                                                 : 3 * 256);
        std::array<glm::ivec2, 3> p{a, a + glm::ivec2{offset(rng), offset(rng)}, a + glm::ivec2{offset(rng), offset(rng)}};
        // A horizontal edge, a corner on a sample position.
        if (kind == 1)
            p[1].y = p[0].y,
            p[2] = p[2] / 256 * 256 + 128 + glm::ivec2{raster::kSampleOffsetX[0], raster::kSampleOffsetY[0]};
        const std::array<float, 3> depth = kind == 2 || kind == 0 ? std::array<float, 3>{0.25f, 0.25f, 0.25f}
                                                                  : std::array<float, 3>{unit(rng), unit(rng), unit(rng)};
        const auto t = msaa_triangle(p, kImage, depth);
        if (!t) continue;
        const bool misses = t->px_max < tile.x0 || t->px_min >= tile.x1 || t->py_max < tile.y0 || t->py_min >= tile.y1;
        const bool wide = t->px_max - t->px_min + 1 > 17;
        const bool crosses = !misses && (t->px_min < tile.x0 || t->px_max >= tile.x1 || t->py_min < tile.y0 ||
                                         t->py_max >= tile.y1);
        missed += misses, big += wide && !misses, tiny_in_tile += !misses && !wide, cut += crosses && !wide;
        records.push_back(*t);
    }
    CHECK(missed > 20);
    CHECK(big > 20);
    CHECK(tiny_in_tile > 100);
    CHECK(cut > 20);
    std::uniform_int_distribution<std::uint32_t> entry(0, std::uint32_t(records.size() - 1));
    for (std::size_t length = 1; length <= 40; ++length) {
        CAPTURE(length);
        std::vector<std::uint32_t> bin;
        while (bin.size() < length) bin.push_back(entry(rng) % 7 == 0 && bin.size() > 1 ? bin[bin.size() - 2] : entry(rng));
        check_bins_match(records, {bin}, tile, kSide);
    }
    // Long bins, two chunks' bins in a row into the same samples.
    std::vector<std::uint32_t> all(records.size());
    for (std::uint32_t i = 0; i < all.size(); ++i) all[i] = i;
    std::vector<std::uint32_t> reversed(all.rbegin(), all.rend());
    CHECK(check_bins_match(records, {all, reversed}, tile, kSide) > 1000);
}

// A mesh of tiny triangles sharing edges (the spheres' ~1.3 px² triangles)
// and a second layer crossing it at depth ties: each sample on an edge goes
// to exactly one triangle, the first layer covers the tile once, and the
// second's ties keep the first layer's ids, so a dropped or reordered
// triangle shows.
TEST_CASE("4x MSAA: a bin of a tiny shared-edge mesh with a crossing layer matches one by one") {
    constexpr int kTile = 32, kImage = 128;
    std::mt19937 rng(77);
    for (int pitch : {192, 320, 512, 1280}) {
        CAPTURE(pitch);
        std::size_t first_layer = 0;
        const std::vector<raster::RasterTriangle> records =
            test::jittered_mesh(rng, pitch, 40 * 256 / pitch + 1, kImage, raster::kMsaaSamples, first_layer);
        std::vector<std::uint32_t> bin(records.size());
        for (std::uint32_t i = 0; i < bin.size(); ++i) bin[i] = i;
        // Every seventh pair swapped: nothing in the kernel may assume entries increase.
        for (std::size_t i = 0; i + 1 < bin.size(); i += 7) std::swap(bin[i], bin[i + 1]);
        CHECK(check_bins_match(records, {bin}, {32, 32, 32 + kTile, 32 + kTile}, kTile) ==
              raster::kMsaaSamples * kTile * kTile);
    }
}

// Huge triangles (edge values past int32 over the tile: the wide-weight block
// kernel and the scalar loop inside the ISA path) between tiny ones, in a
// tile cut short by the image's edge (the rect smaller than the buffer).
TEST_CASE("4x MSAA: a bin mixing huge triangles with tiny ones, in a tile cut by the image's edge, matches one by one") {
    constexpr int kImage = 16384 - 40, kSide = 64;
    std::mt19937 rng(909);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const raster::TileRect tile{16384 - 64, 8192, kImage, 8192 + kSide};
    std::vector<raster::RasterTriangle> records;
    for (int kind = 0; records.size() < 400; ++kind) {
        const float radius = std::array<float, 5>{1.5f, 4.0f, 60.0f, 700.0f, 5000.0f}[kind % 5];
        const glm::vec2 p{tile.x0 + unit(rng) * tile.width(), tile.y0 + unit(rng) * kSide};
        std::array<glm::ivec2, 3> c;
        for (glm::ivec2& q : c)
            q = glm::ivec2(glm::round((p + radius * glm::vec2{unit(rng) * 2 - 1, unit(rng) * 2 - 1}) * 256.0f));
        if (auto t = msaa_triangle(c, kImage, {unit(rng), unit(rng), unit(rng)})) records.push_back(*t);
    }
    std::vector<std::uint32_t> bin(records.size());
    for (std::uint32_t i = 0; i < bin.size(); ++i) bin[i] = i;
    CHECK(check_bins_match(records, {bin}, tile, kSide) == raster::kMsaaSamples * tile.width() * kSide);
}

TEST_CASE("4x MSAA: an empty bin draws nothing and leaves the written box empty") {
    const std::vector<raster::RasterTriangle> records;
    for (const simd::Isa isa : kIsas) {
        if (!simd::isa_supported(isa)) continue;
        Drawn d;
        prepare(d, 16, false, records);
        whole_bins(isa, records, {{}}, {0, 0, 16, 16}, d);
        CHECK(d.counters.fragments == 0);
        CHECK(d.drawn.empty());
        CHECK(d.samples.written_x0 > d.samples.written_x1);
        CHECK(std::all_of(d.samples.depth.begin(), d.samples.depth.end(), [](float z) { return z == 1.0f; }));
    }
}
