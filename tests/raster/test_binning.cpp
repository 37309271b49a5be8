#include <doctest/doctest.h>

#include <algorithm>
#include <random>
#include <tuple>

#include "raster/binning.hpp"
#include "raster_test_util.hpp"

using namespace tessera;

TEST_CASE("binning lists each triangle in exactly the tiles its pixel box touches, in submission order") {
    const raster::TileGrid grid(100, 70, 32);  // 4 × 3 tiles, the last row and column cut short
    CHECK(grid.tiles_x == 4);
    CHECK(grid.tiles_y == 3);
    CHECK(grid.rect(11).x1 == 100);
    CHECK(grid.rect(11).y1 == 70);
    std::vector<raster::RasterTriangle> triangles;
    auto add = [&](glm::vec2 a, glm::vec2 b, glm::vec2 c) {
        auto t = raster::setup_triangle({100, 70},
                                        {test::clip_for_screen(a.x, a.y, 0.5f, 1, 100, 70),
                                         test::clip_for_screen(b.x, b.y, 0.5f, 1, 100, 70),
                                         test::clip_for_screen(c.x, c.y, 0.5f, 1, 100, 70)},
                                        {0, 1, 2});
        REQUIRE(t);
        triangles.push_back(*t);
    };
    add({2, 2}, {10, 2}, {2, 10});     // tile 0 only
    add({20, 20}, {50, 20}, {20, 50});  // tiles 0, 1, 4, 5
    add({5, 5}, {7, 5}, {5, 7});       // tile 0
    raster::ChunkBins bins;
    bins.build(grid, triangles);
    CHECK(std::vector<std::uint32_t>(bins.tile(0).begin(), bins.tile(0).end()) == std::vector<std::uint32_t>{0, 1, 2});
    CHECK(bins.tile(1).size() == 1);
    CHECK(bins.tile(4).size() == 1);
    CHECK(bins.tile(5).size() == 1);
    CHECK(bins.tile(2).empty());
    CHECK(bins.tile(11).empty());
}

// Runs of triangles in one tile, broken by triangles spanning several (whose
// tiles may include the run's), against the plain definition: tile t lists, in
// order, every triangle whose pixel box overlaps it.
TEST_CASE("binning equals the plain definition for runs of one-tile triangles mixed with larger ones") {
    const raster::TileGrid grid(200, 120, 16);
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> run_length(1, 12), x(0, 199), y(0, 119), kind(0, 3), extent(0, 40);
    std::vector<raster::RasterTriangle> triangles;
    while (triangles.size() < 3000) {
        const int length = run_length(rng), x0 = x(rng), y0 = y(rng);
        for (int i = 0; i < length; ++i) {
            raster::RasterTriangle t{};
            const int k = kind(rng);
            // Most stay at the run's pixel (one tile); some grow past tile borders, some sit elsewhere.
            const int bx = k == 3 ? x(rng) : x0, by = k == 3 ? y(rng) : y0;
            const int wide = k == 2 ? extent(rng) : 0, tall = k == 2 ? extent(rng) : 0;
            t.px_min = std::int16_t(bx), t.px_max = std::int16_t(std::min(bx + wide, 199));
            t.py_min = std::int16_t(by), t.py_max = std::int16_t(std::min(by + tall, 119));
            triangles.push_back(t);
        }
    }
    std::vector<std::vector<std::uint32_t>> expected(std::size_t(grid.tile_count()));
    std::size_t several = 0;
    for (std::uint32_t i = 0; i < triangles.size(); ++i) {
        const raster::RasterTriangle& t = triangles[i];
        int touched = 0;
        for (int tile = 0; tile < grid.tile_count(); ++tile) {
            const raster::TileRect r = grid.rect(tile);
            if (t.px_min < r.x1 && t.px_max >= r.x0 && t.py_min < r.y1 && t.py_max >= r.y0)
                expected[std::size_t(tile)].push_back(i), ++touched;
        }
        several += touched > 1;
    }
    REQUIRE(several > 200);
    raster::ChunkBins bins;
    for (int build = 0; build < 2; ++build) {  // memory reused
        bins.build(grid, triangles);
        int different = 0;
        for (int tile = 0; tile < grid.tile_count(); ++tile)
            different += std::vector<std::uint32_t>(bins.tile(tile).begin(), bins.tile(tile).end()) != expected[std::size_t(tile)];
        CHECK(different == 0);
    }
}

// Random boxes over a grid: some triangles in one tile, some spanning several.
static std::vector<raster::RasterTriangle> random_boxes(std::mt19937& rng, int width, int height, int count) {
    std::uniform_int_distribution<int> x(0, width - 1), y(0, height - 1), extent(0, 40), kind(0, 2);
    std::vector<raster::RasterTriangle> triangles;
    for (int i = 0; i < count; ++i) {
        raster::RasterTriangle t{};
        const int bx = x(rng), by = y(rng), grow = kind(rng) == 0 ? extent(rng) : 0;
        t.px_min = std::int16_t(bx), t.px_max = std::int16_t(std::min(bx + grow, width - 1));
        t.py_min = std::int16_t(by), t.py_max = std::int16_t(std::min(by + grow / 2, height - 1));
        triangles.push_back(t);
    }
    return triangles;
}

TEST_CASE("a chunk's bins list only touched tiles, ascending, and stay right when the grid changes") {
    std::mt19937 rng(11);
    raster::ChunkBins bins;
    // A small grid, a larger one, the small one again: the per-tile scratch is resized and must read 0;
    // then 4 tiles, every one touched long before the last triangle.
    for (const auto& [width, height, side] :
         {std::tuple{200, 120, 16}, std::tuple{640, 360, 32}, std::tuple{200, 120, 16}, std::tuple{64, 64, 32}}) {
        const raster::TileGrid grid(width, height, side);
        const std::vector<raster::RasterTriangle> triangles = random_boxes(rng, width, height, 400);
        bins.build(grid, triangles);
        CHECK(std::is_sorted(bins.tiles.begin(), bins.tiles.end()));
        CHECK(std::adjacent_find(bins.tiles.begin(), bins.tiles.end()) == bins.tiles.end());
        std::size_t listed = 0;
        for (int tile = 0; tile < grid.tile_count(); ++tile) {
            std::vector<std::uint32_t> expected;
            const raster::TileRect r = grid.rect(tile);
            for (std::uint32_t i = 0; i < triangles.size(); ++i) {
                const raster::RasterTriangle& t = triangles[i];
                if (t.px_min < r.x1 && t.px_max >= r.x0 && t.py_min < r.y1 && t.py_max >= r.y0) expected.push_back(i);
            }
            CHECK(std::vector<std::uint32_t>(bins.tile(tile).begin(), bins.tile(tile).end()) == expected);
            const bool touched = std::binary_search(bins.tiles.begin(), bins.tiles.end(), std::uint32_t(tile));
            CHECK(touched == !expected.empty());
            listed += expected.size();
        }
        CHECK(bins.items.size() == listed);
        CHECK(std::all_of(bins.tile_scratch.begin(), bins.tile_scratch.end(), [](std::uint32_t v) { return v == 0; }));
    }
}

TEST_CASE("the tile index lists, per tile, every chunk's non-empty bin in chunk order") {
    const raster::TileGrid grid(300, 200, 32);
    std::mt19937 rng(23);
    std::vector<raster::ChunkBins> chunks(7);
    for (std::size_t c = 0; c < chunks.size(); ++c)
        chunks[c].build(grid, random_boxes(rng, 300, 200, c == 3 ? 0 : int(50 + 40 * c)));  // chunk 3 empty
    raster::TileBinIndex index;
    for (int build = 0; build < 2; ++build) {  // memory reused
        index.build(grid, chunks.size(), [&](std::size_t c) -> const raster::ChunkBins& { return chunks[c]; });
        int wrong = 0;
        for (int tile = 0; tile < grid.tile_count(); ++tile) {
            std::vector<std::uint32_t> expected_chunks, listed_chunks;
            for (std::uint32_t c = 0; c < chunks.size(); ++c)
                if (!chunks[c].tile(tile).empty()) expected_chunks.push_back(c);
            for (const raster::TileBinIndex::Entry& e : index.tile(tile)) {
                listed_chunks.push_back(e.chunk);
                const std::span<const std::uint32_t> bin = chunks[e.chunk].tile(tile);
                wrong += e.first != std::uint32_t(bin.data() - chunks[e.chunk].items.data()) ||
                         e.last - e.first != bin.size();
            }
            wrong += listed_chunks != expected_chunks;
        }
        CHECK(wrong == 0);
    }
}

// Every box shape the 2×2 path and the slow path see — 1×1, 2×1, 1×2 and 2×2
// tiles, wider and taller ones, boxes in the last (cut-short) tile row and
// column — against the plain definition, both where boxes crossing tile
// borders come first (the branch-free pass) and behind a long run of one-tile
// boxes (the branchy pass).
TEST_CASE("binning equals the plain definition for every box shape, at the grid's edges too") {
    const raster::TileGrid grid(100, 70, 32);  // 4 × 3 tiles, the last column 4 px wide, the last row 6 px
    std::vector<raster::RasterTriangle> shapes;
    auto box = [&](int x0, int y0, int x1, int y1) {
        if (x0 > 99 || y0 > 69) return;  // past the image: no box
        raster::RasterTriangle t{};
        t.px_min = std::int16_t(x0), t.px_max = std::int16_t(std::min(x1, 99));
        t.py_min = std::int16_t(y0), t.py_max = std::int16_t(std::min(y1, 69));
        shapes.push_back(t);
    };
    for (int tx = 0; tx < grid.tiles_x; ++tx)
        for (int ty = 0; ty < grid.tiles_y; ++ty) {
            const int x = tx * 32, y = ty * 32;
            box(x + 1, y + 1, x + 3, y + 2);     // 1×1
            box(x + 30, y + 4, x + 33, y + 6);   // 2×1 (1×1 where it meets the right edge)
            box(x + 4, y + 30, x + 6, y + 33);   // 1×2
            box(x + 31, y + 31, x + 32, y + 32); // 2×2
            box(x, y, x + 31, y + 31);           // one whole tile
            box(x + 20, y + 2, x + 70, y + 3);   // 3×1
            box(x + 2, y + 20, x + 3, y + 70);   // 1×3
            box(x + 10, y + 10, x + 80, y + 80); // 3×3
        }
    box(96, 64, 99, 69);  // the last tile, 4 × 6 px
    box(0, 0, 99, 69);    // the whole image
    std::vector<raster::RasterTriangle> one_tile_first(70, shapes[0]);
    one_tile_first.insert(one_tile_first.end(), shapes.begin(), shapes.end());
    raster::ChunkBins bins;
    for (const std::vector<raster::RasterTriangle>& triangles : {shapes, one_tile_first, shapes}) {
        bins.build(grid, triangles);
        std::size_t listed = 0;
        int different = 0;
        for (int tile = 0; tile < grid.tile_count(); ++tile) {
            std::vector<std::uint32_t> expected;
            const raster::TileRect r = grid.rect(tile);
            for (std::uint32_t i = 0; i < triangles.size(); ++i) {
                const raster::RasterTriangle& t = triangles[i];
                if (t.px_min < r.x1 && t.px_max >= r.x0 && t.py_min < r.y1 && t.py_max >= r.y0) expected.push_back(i);
            }
            different += std::vector<std::uint32_t>(bins.tile(tile).begin(), bins.tile(tile).end()) != expected;
            listed += expected.size();
        }
        CHECK(different == 0);
        CHECK(bins.items.size() == listed);
        CHECK(std::all_of(bins.tile_scratch.begin(), bins.tile_scratch.end(), [](std::uint32_t v) { return v == 0; }));
    }
}
