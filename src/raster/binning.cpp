#include "raster/binning.hpp"

#include <algorithm>
#include <bit>

namespace tessera::raster {

TileGrid::TileGrid(int image_width, int image_height, int tile_side)
    : width(image_width),
      height(image_height),
      tile_size(tile_side),
      tile_shift(std::countr_zero(unsigned(tile_side))),
      tiles_x((image_width + tile_side - 1) / tile_side),
      tiles_y((image_height + tile_side - 1) / tile_side) {}

TileRect TileGrid::rect(int tile) const {
    const int tx = tile % tiles_x, ty = tile / tiles_x;
    return {tx * tile_size, ty * tile_size, std::min((tx + 1) * tile_size, width), std::min((ty + 1) * tile_size, height)};
}

namespace {

// Calls f(tile) for each tile that the triangle's pixel box overlaps.
template <class F>
void for_each_tile(const TileGrid& grid, const RasterTriangle& t, F&& f) {
    const int tx0 = t.px_min >> grid.tile_shift, tx1 = t.px_max >> grid.tile_shift;
    const int ty0 = t.py_min >> grid.tile_shift, ty1 = t.py_max >> grid.tile_shift;
    for (int ty = ty0; ty <= ty1; ++ty)
        for (int tx = tx0; tx <= tx1; ++tx) f(ty * grid.tiles_x + tx);
}

}  // namespace

// Most triangles of a finely tessellated mesh lie inside one tile: the first
// pass notes that tile, so the second reads 4 bytes of such a triangle instead
// of its record and goes round no loop. Consecutive triangles mostly share
// their tile: both passes keep the current run's count or cursor in a
// register, since ++offsets[tile] one triangle after another would wait on
// its own store each time.
void ChunkBins::build(const TileGrid& grid, std::span<const RasterTriangle> triangles) {
    constexpr std::uint32_t kSeveralTiles = ~std::uint32_t{0};
    offsets.assign(std::size_t(grid.tile_count()) + 1, 0);
    triangle_tile.resize(triangles.size());
    std::uint32_t run_tile = 0, run_length = 0;  // consecutive one-tile triangles counted, not yet in offsets
    for (std::size_t i = 0; i < triangles.size(); ++i) {
        const RasterTriangle& t = triangles[i];
        const int tx0 = t.px_min >> grid.tile_shift, tx1 = t.px_max >> grid.tile_shift;
        const int ty0 = t.py_min >> grid.tile_shift, ty1 = t.py_max >> grid.tile_shift;
        if (tx0 == tx1 && ty0 == ty1) {
            const std::uint32_t tile = std::uint32_t(ty0 * grid.tiles_x + tx0);
            triangle_tile[i] = tile;
            if (tile != run_tile) offsets[run_tile + 1] += run_length, run_tile = tile, run_length = 0;
            ++run_length;
        } else {
            triangle_tile[i] = kSeveralTiles;
            for_each_tile(grid, t, [&](int tile) { ++offsets[tile + 1]; });
        }
    }
    offsets[run_tile + 1] += run_length;
    for (std::size_t i = 1; i < offsets.size(); ++i) offsets[i] += offsets[i - 1];
    items.resize(offsets.back());
    // Fill using offsets[t] as a cursor (the current run's held in `cursor`), then shift the cursors back.
    std::uint32_t cursor_tile = kSeveralTiles, cursor = 0;
    for (std::uint32_t i = 0; i < triangles.size(); ++i) {
        const std::uint32_t tile = triangle_tile[i];
        if (tile == kSeveralTiles) {  // its tiles' cursors must be in offsets
            if (cursor_tile != kSeveralTiles) offsets[cursor_tile] = cursor, cursor_tile = kSeveralTiles;
            for_each_tile(grid, triangles[i], [&](int several) { items[offsets[several]++] = i; });
            continue;
        }
        if (tile != cursor_tile) {
            if (cursor_tile != kSeveralTiles) offsets[cursor_tile] = cursor;
            cursor_tile = tile, cursor = offsets[tile];
        }
        items[cursor++] = i;
    }
    if (cursor_tile != kSeveralTiles) offsets[cursor_tile] = cursor;
    for (std::size_t t = offsets.size() - 1; t > 0; --t) offsets[t] = offsets[t - 1];
    offsets[0] = 0;
}

}  // namespace tessera::raster
