// Binning: which triangles touch which screen tile. Triangles are binned per
// chunk (a fixed run of the scene's triangles), each chunk into its own lists,
// so chunks can be binned in parallel and a tile still meets its triangles in
// submission order, whatever the thread count.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "raster/tile_rasterizer.hpp"
#include "raster/triangle_setup.hpp"

namespace tessera::raster {

// The screen cut into square tiles of `tile_size` pixels (edge tiles are cut short).
struct TileGrid {
    int width = 0, height = 0;
    int tile_size = 0;
    int tile_shift = 0;  // log2(tile_size)
    int tiles_x = 0, tiles_y = 0;
    TileGrid() = default;
    TileGrid(int image_width, int image_height, int tile_side);
    int tile_count() const { return tiles_x * tiles_y; }
    TileRect rect(int tile) const;
};

// One chunk's bins as a compact list: the triangles of tile t are
// items[offsets[t] .. offsets[t + 1]), in submission order.
struct ChunkBins {
    std::vector<std::uint32_t> offsets;
    std::vector<std::uint32_t> items;  // indices into the chunk's triangles
    std::vector<std::uint32_t> triangle_tile;  // build()'s scratch: each triangle's tile, if it touches only one
    std::span<const std::uint32_t> tile(int t) const {
        return {items.data() + offsets[t], items.data() + offsets[t + 1]};
    }
    // Rebuilds the bins for `triangles` (a counting sort by tile; reuses memory).
    void build(const TileGrid& grid, std::span<const RasterTriangle> triangles);
};

}  // namespace tessera::raster
