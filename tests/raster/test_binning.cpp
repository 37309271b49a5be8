#include <doctest/doctest.h>

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
