#include <doctest/doctest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <span>
#include <vector>

#include "raster/bin_rasterizer.hpp"
#include "raster_test_util.hpp"

using namespace tessera;

namespace {

struct BinResult {
    raster::TileBuffers buffers;
    raster::RasterCounters counters;
    std::vector<std::uint32_t> drawn;  // bin entries reported as having passed the depth test, in order
};

// The vertices the records' corner references (0, 1, 2) name, for the kernels' corner prefetch.
const std::vector<geometry::ShadedVertex> kFrameVertices(3), kClippedVertices(1);
const raster::CornerPrefetch kPrefetch{reinterpret_cast<const std::byte*>(kFrameVertices.data()),
                                       reinterpret_cast<const std::byte*>(kClippedVertices.data()),
                                       sizeof(geometry::ShadedVertex)};

// The reference: the scalar loop, one triangle at a time in bin order, each
// drawn as its position in the tile's list; a triangle is drawn when the
// depth-passed count moved.
BinResult scalar_one_by_one(const std::vector<raster::RasterTriangle>& records, const std::vector<std::uint32_t>& bin,
                            std::uint32_t id_base, const raster::TileRect& tile) {
    BinResult r;
    r.buffers.reset(tile.width());
    for (const std::uint32_t entry : bin) {
        const std::uint64_t before = r.counters.depth_passed;
        raster::rasterize_triangle(records[entry], r.buffers.triangles.add(id_base | entry), tile, r.buffers,
                                   r.counters);
        if (r.counters.depth_passed != before) r.drawn.push_back(entry);
    }
    return r;
}

BinResult whole_bin(simd::Isa isa, const std::vector<raster::RasterTriangle>& records,
                    const std::vector<std::uint32_t>& bin, std::uint32_t id_base, const raster::TileRect& tile) {
    BinResult r;
    r.buffers.reset(tile.width());
    // Garbage where nothing is drawn, as a reused tile has: only depth says what is covered.
    std::fill(r.buffers.triangle.begin(), r.buffers.triangle.end(), 0xdeadbeefu);
    raster::DrawnCallback drawn{[](void* context, std::uint32_t entry) {
                                    static_cast<std::vector<std::uint32_t>*>(context)->push_back(entry);
                                },
                                &r.drawn};
    // In two calls, as the renderer draws a tile's bins of several chunks:
    // the second's triangles follow the first's in the tile's list. With the
    // corner prefetch the renderer asks for: a hint that must change nothing.
    const std::span<const std::uint32_t> all(bin);
    const std::size_t half = bin.size() / 2;
    raster::rasterize_bin(isa, records.data(), all.first(half), id_base, tile, r.buffers, r.counters, drawn, kPrefetch);
    raster::rasterize_bin(isa, records.data(), all.subspan(half), id_base, tile, r.buffers, r.counters, drawn,
                          kPrefetch);
    return r;
}

std::vector<std::uint32_t> listed_ids(const raster::TileBuffers& buffers) {
    return {buffers.triangles.ids.begin(), buffers.triangles.ids.begin() + buffers.triangles.count};
}

// Depth bit for bit everywhere; triangle (position) and both barycentrics bit for bit where covered.
int mismatched_pixels(const raster::TileBuffers& a, const raster::TileBuffers& b, int side) {
    int mismatches = 0;
    for (std::size_t p = 0; p < std::size_t(side) * side; ++p) {
        const bool covered = a.covered(p);
        if (covered != b.covered(p) || std::memcmp(&a.depth[p], &b.depth[p], sizeof(float)) != 0 ||
            (covered && (a.triangle[p] != b.triangle[p] ||
                         std::memcmp(&a.lambda1[p], &b.lambda1[p], sizeof(float)) != 0 ||
                         std::memcmp(&a.lambda2[p], &b.lambda2[p], sizeof(float)) != 0)))
            ++mismatches;
    }
    return mismatches;
}

void check_every_isa(const std::vector<raster::RasterTriangle>& records, const std::vector<std::uint32_t>& bin,
                     std::uint32_t id_base, const raster::TileRect& tile) {
    const BinResult reference = scalar_one_by_one(records, bin, id_base, tile);
    REQUIRE(reference.counters.depth_passed > 0);
    for (simd::Isa isa : {simd::Isa::scalar, simd::Isa::sse4, simd::Isa::avx2, simd::Isa::avx512}) {
        CAPTURE(simd::isa_name(isa));
        if (!simd::isa_supported(isa)) {
            MESSAGE("skipped: " << simd::isa_name(isa) << " is not supported by this CPU");
            continue;
        }
        const BinResult result = whole_bin(isa, records, bin, id_base, tile);
        CHECK(result.counters.fragments == reference.counters.fragments);
        CHECK(result.counters.depth_passed == reference.counters.depth_passed);
        CHECK(mismatched_pixels(reference.buffers, result.buffers, tile.width()) == 0);
        CHECK(result.drawn == reference.drawn);
        CHECK(listed_ids(result.buffers) == listed_ids(reference.buffers));
    }
}

}  // namespace

// Many random small triangles piled on one another in one bin, as a finely
// tessellated mesh seen from both sides puts them: shared edges (fans around
// shared corners), equal depths (later triangles tie with earlier ones: LESS
// keeps the first), corners on pixel centres and corners (top-left rule
// ties), axis-aligned edges, boxes at the kernels' limits (4, 8 and 16 px
// wide; corners kTinySpan - 1 apart) and just past them (general path), boxes
// cut by the tile's sides; the bin a subset of the records, out of record
// order, with the chunk's id bits set. One call must give exactly what drawing
// them one by one with the scalar loop gives, and report the same triangles
// as drawn, in the same order.
TEST_CASE("a bin of many tiny overlapping triangles in one call matches the scalar loop triangle by triangle") {
    std::mt19937 rng(1313);
    std::uniform_int_distribution<int> coin(0, 5);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    constexpr int kSpan = raster::kTinySpan - 1;
    for (int tile_side : {8, 16, 32, 64}) {
        CAPTURE(tile_side);
        const int image = 4 * tile_side, x0 = tile_side, y0 = 2 * tile_side;
        const raster::TileRect tile{x0, y0, x0 + tile_side, y0 + tile_side};
        std::uniform_int_distribution<int> pixel(x0 - 6, x0 + tile_side + 1);
        std::vector<raster::RasterTriangle> records;
        int tiny_boxes = 0, limit_boxes = 0, past_limit = 0;
        glm::ivec2 fan_centre{x0 * 256, y0 * 256};
        for (int kind = 0; records.size() < 5000; ++kind) {
            const glm::ivec2 anchor{pixel(rng) * 256, (pixel(rng) + y0 - x0) * 256};
            // Box sizes: mostly 1-3 px (the spheres' triangles), some at the stamp widths' limits, some past.
            const int reach = kind % 10 < 6 ? 3 * 256 : kind % 10 == 6 ? 4 * 256 - 1 : kind % 10 == 7 ? 8 * 256 - 1
                              : kind % 10 == 8 ? kSpan : kSpan + 600;
            std::uniform_int_distribution<int> offset(0, reach);
            auto corner = [&](glm::ivec2 base) {
                glm::ivec2 p = base + glm::ivec2{offset(rng), offset(rng)};
                if (kind % 3 == 0) p = p / 256 * 256 + 128;  // on pixel centres
                else if (kind % 7 == 0) p = p / 256 * 256;   // on pixel corners
                return p;
            };
            std::array<glm::ivec2, 3> p{corner(anchor), corner(anchor), corner(anchor)};
            if (kind % 8 == 4) p[1].y = p[0].y;  // a horizontal edge
            if (kind % 8 == 5) p[1].x = p[0].x;  // a vertical edge
            if (kind % 4 == 1) {                 // a fan around one corner: every edge shared with the next
                if (coin(rng) == 0) fan_centre = corner(anchor);
                p[0] = fan_centre;
            }
            if (kind % 10 == 8 && coin(rng) < 3) p[1] = p[0] + glm::ivec2{kSpan, 0}, p[2] = p[0] + glm::ivec2{0, kSpan};
            const std::array<float, 3> depth = kind % 3 == 1 ? std::array<float, 3>{0.5f, 0.5f, 0.5f}
                                                             : std::array<float, 3>{unit(rng), unit(rng), unit(rng)};
            const auto t = test::fixed_triangle(p, image, depth);
            if (!t) continue;
            records.push_back(*t);
            const int width = std::min<int>(t->px_max + 1, tile.x1) - std::max<int>(t->px_min, tile.x0);
            tiny_boxes += width >= 1 && width <= 3;
            limit_boxes += width == 4 || width == 8 || width == 16;
            past_limit += t->px_max - t->px_min + 1 > raster::kMaxTinyWidth;
        }
        CHECK(tiny_boxes > 1000);
        CHECK(limit_boxes > 100);
        CHECK(past_limit > 50);
        // The bin: nine records in ten, every seventh pair swapped (bins follow submission order, but
        // nothing in the kernel may assume entries increase).
        std::vector<std::uint32_t> bin;
        for (std::uint32_t i = 0; i < records.size(); ++i)
            if (i % 10 != 3) bin.push_back(i);
        for (std::size_t i = 0; i + 1 < bin.size(); i += 7) std::swap(bin[i], bin[i + 1]);
        check_every_isa(records, bin, 5u << 17, tile);
    }
}

TEST_CASE("a bin of the jittered shared-edge mesh with a second layer crossing it matches the scalar loop") {
    constexpr int kTile = 32, kImage = 128;
    std::mt19937 rng(99);
    for (int pitch : {320, 384, 512, 1280}) {
        CAPTURE(pitch);
        std::size_t first_layer = 0;
        const std::vector<raster::RasterTriangle> records =
            test::jittered_mesh(rng, pitch, 40 * 256 / pitch + 1, kImage, 1, first_layer);
        std::vector<std::uint32_t> bin(records.size());
        for (std::uint32_t i = 0; i < bin.size(); ++i) bin[i] = i;
        check_every_isa(records, bin, 0, {32, 32, 32 + kTile, 32 + kTile});
    }
}

// The kernels set a bin up a vector of entries at a time (4, 8 or 16): bins
// of every length up to past two AVX-512 vectors, each group mixing entries
// whose box misses the tile, big triangles (the general path), tiny ones cut
// by the tile's sides or inside it, 4, 8 and 16 px wide, ties in depth and
// repeated entries (LESS keeps the first), and lanes past the bin's end.
TEST_CASE("bins of every length, groups mixing missed, big and tiny triangles, match the scalar loop") {
    std::mt19937 rng(2024);
    constexpr int kImage = 128;
    const raster::TileRect tile{32, 64, 64, 96};
    std::uniform_int_distribution<int> near_tile(24 * 256, 72 * 256), reach(0, raster::kTinySpan - 1);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<raster::RasterTriangle> records;
    int missed = 0, big = 0, tiny_in_tile = 0;
    while (records.size() < 400) {
        const int kind = int(records.size() % 5);
        glm::ivec2 a{near_tile(rng), near_tile(rng) + 32 * 256};
        std::uniform_int_distribution<int> offset(0, kind == 4 ? 40 * 256 : kind == 3 ? reach.max() : 6 * 256);
        std::array<glm::ivec2, 3> p{a, a + glm::ivec2{offset(rng), offset(rng)}, a + glm::ivec2{offset(rng), offset(rng)}};
        if (kind == 1) p[1].y = p[0].y, p[2] = p[2] / 256 * 256 + 128;  // a horizontal edge, a corner on a centre
        const std::array<float, 3> depth = kind == 2 ? std::array<float, 3>{0.25f, 0.25f, 0.25f}
                                                     : std::array<float, 3>{unit(rng), unit(rng), unit(rng)};
        const auto t = test::fixed_triangle(p, kImage, depth);
        if (!t) continue;
        const bool misses = t->px_max < tile.x0 || t->px_min >= tile.x1 || t->py_max < tile.y0 || t->py_min >= tile.y1;
        const bool wide = t->px_max - t->px_min + 1 > raster::kMaxTinyWidth;
        missed += misses, big += wide && !misses, tiny_in_tile += !misses && !wide;
        records.push_back(*t);
    }
    CHECK(missed > 20);
    CHECK(big > 20);
    CHECK(tiny_in_tile > 100);
    std::uniform_int_distribution<std::uint32_t> entry(0, std::uint32_t(records.size() - 1));
    for (std::size_t length = 1; length <= 40; ++length) {
        CAPTURE(length);
        // The first entry draws something (check_every_isa asks for it); the others anything, repeats included.
        std::vector<std::uint32_t> bin;
        while (bin.empty()) {
            const std::uint32_t first = entry(rng);
            const auto& t = records[first];
            if (t.px_max >= tile.x0 && t.px_min < tile.x1 && t.py_max >= tile.y0 && t.py_min < tile.y1 &&
                t.px_max - t.px_min < 8)
                bin.push_back(first);
        }
        while (bin.size() < length) bin.push_back(entry(rng) % 7 == 0 && bin.size() > 1 ? bin[bin.size() - 2] : entry(rng));
        check_every_isa(records, bin, 3u << 17, tile);
    }
}

TEST_CASE("the corner prefetch finds a reference's vertex in the frame's vertices or the clipped ones") {
    const std::vector<geometry::ShadedVertex> frame(10), clipped(4);
    const raster::CornerPrefetch prefetch{reinterpret_cast<const std::byte*>(frame.data()),
                                          reinterpret_cast<const std::byte*>(clipped.data()),
                                          sizeof(geometry::ShadedVertex)};
    for (std::uint32_t i = 0; i < frame.size(); ++i)
        CHECK(raster::corner_vertex(prefetch, i) == reinterpret_cast<const std::byte*>(&frame[i]));
    for (std::uint32_t i = 0; i < clipped.size(); ++i)
        CHECK(raster::corner_vertex(prefetch, geometry::kClippedVertexBit | i) ==
              reinterpret_cast<const std::byte*>(&clipped[i]));
}

TEST_CASE("an empty bin draws nothing") {
    const std::vector<raster::RasterTriangle> records;
    for (simd::Isa isa : {simd::Isa::scalar, simd::Isa::sse4, simd::Isa::avx2}) {
        if (!simd::isa_supported(isa)) continue;
        const BinResult r = whole_bin(isa, records, {}, 0, {0, 0, 8, 8});
        CHECK(r.counters.fragments == 0);
        CHECK(r.drawn.empty());
        CHECK(std::all_of(r.buffers.depth.begin(), r.buffers.depth.end(), [](float d) { return d == 1.0f; }));
    }
}
