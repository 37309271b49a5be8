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

// One chunk's bins, listing only the tiles its triangles touch (a chunk of a
// finely tessellated mesh touches few of a 4K frame's 8160 tiles): the
// triangles of tile tiles[i] are items[starts[i] .. starts[i + 1]), in
// submission order; tiles ascend.
struct ChunkBins {
    std::vector<std::uint32_t> tiles;
    std::vector<std::uint32_t> starts;  // tiles.size() + 1
    std::vector<std::uint32_t> items;   // indices into the chunk's triangles
    // build()'s scratch: each triangle's tile, if it touches only one; per
    // tile of the grid a count, then a cursor, back to 0 at the end of build().
    std::vector<std::uint32_t> triangle_tile;
    std::vector<std::uint32_t> tile_scratch;
    std::vector<std::uint32_t> touched_scratch;  // the touched tiles, in the order first met
    bool scratch_dirty = false;  // build() stopped part way (an allocation threw)

    // The bin of the i-th touched tile, and that of any tile (empty if untouched).
    std::span<const std::uint32_t> bin(std::size_t i) const {
        return {items.data() + starts[i], items.data() + starts[i + 1]};
    }
    std::span<const std::uint32_t> tile(int t) const;
    // Rebuilds the bins for `triangles` (a counting sort by tile over the
    // touched tiles only; reuses memory).
    void build(const TileGrid& grid, std::span<const RasterTriangle> triangles);
};

// Where each tile's triangles are, over every chunk: tile t's bins are
// entries[starts[t] .. starts[t + 1]), in chunk order (submission order), so a
// tile's worker visits only the chunks that touch its tile instead of asking
// every chunk.
struct TileBinIndex {
    struct Entry {
        std::uint32_t chunk;
        std::uint32_t first, last;  // the bin: the chunk's items[first .. last)
    };
    std::vector<std::uint32_t> starts;  // tile count + 1
    std::vector<Entry> entries;
    std::span<const Entry> tile(int t) const { return {entries.data() + starts[t], entries.data() + starts[t + 1]}; }
    // bins_of(c): chunk c's ChunkBins, for c < chunk_count.
    template <class BinsOf>
    void build(const TileGrid& grid, std::size_t chunk_count, BinsOf&& bins_of) {
        starts.assign(std::size_t(grid.tile_count()) + 1, 0);
        for (std::size_t c = 0; c < chunk_count; ++c)
            for (const std::uint32_t t : bins_of(c).tiles) ++starts[t + 1];
        for (std::size_t t = 1; t < starts.size(); ++t) starts[t] += starts[t - 1];
        entries.resize(starts.back());
        // starts[t] serves as tile t's cursor, then is shifted back.
        for (std::size_t c = 0; c < chunk_count; ++c) {
            const ChunkBins& bins = bins_of(c);
            for (std::size_t i = 0; i < bins.tiles.size(); ++i)
                entries[starts[bins.tiles[i]]++] = {std::uint32_t(c), bins.starts[i], bins.starts[i + 1]};
        }
        for (std::size_t t = starts.size() - 1; t > 0; --t) starts[t] = starts[t - 1];
        starts[0] = 0;
    }
};

}  // namespace tessera::raster
