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

std::span<const std::uint32_t> ChunkBins::tile(int t) const {
    const auto found = std::lower_bound(tiles.begin(), tiles.end(), std::uint32_t(t));
    if (found == tiles.end() || *found != std::uint32_t(t)) return {};
    return bin(std::size_t(found - tiles.begin()));
}

// Most triangles of a finely tessellated mesh lie inside one tile: the first
// pass notes that tile, so the second reads 4 bytes of such a triangle instead
// of its record and goes round no loop. Consecutive triangles mostly share
// their tile: both passes keep the current run's count or cursor in a
// register, since ++count[tile] one triangle after another would wait on
// its own store each time. Only touched tiles are visited after the first
// pass: the per-tile scratch is 0 between builds, so it is not cleared.
void ChunkBins::build(const TileGrid& grid, std::span<const RasterTriangle> triangles) {
    constexpr std::uint32_t kSeveralTiles = ~std::uint32_t{0};
    const std::size_t tile_count = std::size_t(grid.tile_count());
    if (scratch_dirty || tile_scratch.size() != tile_count) tile_scratch.assign(tile_count, 0);
    touched_scratch.resize(tile_count + 1);  // + the slot add() writes after the last new tile
    scratch_dirty = true;
    // Plain pointers and no call in the loops (a push_back there made g++
    // reload the loops' state after every tile).
    std::uint32_t* const count = tile_scratch.data();
    std::uint32_t* const touched = touched_scratch.data();
    std::size_t touched_count = 0;
    const auto add = [&](std::uint32_t tile, std::uint32_t n) {
        touched[touched_count] = tile;  // kept if new
        touched_count += std::size_t(count[tile] == 0);
        count[tile] += n;
    };
    triangle_tile.resize(triangles.size());
    std::uint32_t* const tile_of = triangle_tile.data();
    std::uint32_t run_tile = 0, run_length = 0;  // consecutive one-tile triangles counted, not yet in count
    for (std::size_t i = 0; i < triangles.size(); ++i) {
        const RasterTriangle& t = triangles[i];
        const int tx0 = t.px_min >> grid.tile_shift, tx1 = t.px_max >> grid.tile_shift;
        const int ty0 = t.py_min >> grid.tile_shift, ty1 = t.py_max >> grid.tile_shift;
        if (tx0 == tx1 && ty0 == ty1) {
            const std::uint32_t tile = std::uint32_t(ty0 * grid.tiles_x + tx0);
            tile_of[i] = tile;
            if (tile != run_tile) {
                if (run_length != 0) add(run_tile, run_length);
                run_tile = tile, run_length = 0;
            }
            ++run_length;
        } else {
            tile_of[i] = kSeveralTiles;
            for_each_tile(grid, t, [&](int tile) { add(std::uint32_t(tile), 1); });
        }
    }
    if (run_length != 0) add(run_tile, run_length);
    tiles.assign(touched, touched + touched_count);
    std::sort(tiles.begin(), tiles.end());
    // Counts → each touched tile's start, which count then holds as its cursor.
    starts.resize(tiles.size() + 1);
    starts[0] = 0;
    for (std::size_t i = 0; i < tiles.size(); ++i) {
        starts[i + 1] = starts[i] + count[tiles[i]];
        count[tiles[i]] = starts[i];
    }
    items.resize(starts.back());
    std::uint32_t* const item = items.data();
    std::uint32_t* const cursor = tile_scratch.data();
    std::uint32_t cursor_tile = kSeveralTiles, run_cursor = 0;  // the current run's cursor, not yet in `cursor`
    for (std::uint32_t i = 0; i < triangles.size(); ++i) {
        const std::uint32_t tile = tile_of[i];
        if (tile == kSeveralTiles) {  // its tiles' cursors must be in `cursor`
            if (cursor_tile != kSeveralTiles) cursor[cursor_tile] = run_cursor, cursor_tile = kSeveralTiles;
            for_each_tile(grid, triangles[i], [&](int several) { item[cursor[several]++] = i; });
            continue;
        }
        if (tile != cursor_tile) {
            if (cursor_tile != kSeveralTiles) cursor[cursor_tile] = run_cursor;
            cursor_tile = tile, run_cursor = cursor[tile];
        }
        item[run_cursor++] = i;
    }
    for (const std::uint32_t tile : tiles) cursor[tile] = 0;
    scratch_dirty = false;
}

}  // namespace tessera::raster
