#include <doctest/doctest.h>

#include <algorithm>
#include <random>

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
