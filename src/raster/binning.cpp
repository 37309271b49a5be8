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

namespace {

constexpr std::uint32_t kSeveralTiles = ~std::uint32_t{0};

// `tile` if `real` (0 or 1), else `dummy`, without a branch.
inline std::uint32_t real_or(std::uint32_t tile, std::uint32_t real, std::uint32_t dummy) {
    return tile ^ ((tile ^ dummy) & (real - 1));
}

// Whether a chunk's triangles cross tile borders often enough that the
// branch-free pass pays: a count over the first few boxes (at 720p nearly all
// fit one tile and the branchy pass predicts well; at 4K ~30% of the 5–13 px
// boxes cross a border and its branch mispredicts).
bool crossing_often(const TileGrid& grid, std::span<const RasterTriangle> triangles) {
    constexpr std::size_t kSamples = 64;
    const std::size_t stride = std::max<std::size_t>(triangles.size() / kSamples, 1);
    std::size_t crossing = 0, sampled = 0;
    for (std::size_t i = 0; i < triangles.size(); i += stride, ++sampled) {
        const RasterTriangle& t = triangles[i];
        crossing += std::size_t(((t.px_min ^ t.px_max) | (t.py_min ^ t.py_max)) >> grid.tile_shift != 0);
    }
    return crossing * 8 > sampled;  // > 1 in 8
}

}  // namespace

// Most triangles of a finely tessellated mesh lie inside one tile: the first
// pass notes that tile, so the second reads 4 bytes of such a triangle instead
// of its record and goes round no loop. Consecutive triangles mostly share
// their tile: both passes keep the current run's count or cursor in a
// register, since ++count[tile] one triangle after another would wait on
// its own store each time. Only touched tiles are visited after the first
// pass: the per-tile scratch is 0 between builds, so it is not cleared.
//
// Where boxes often cross a tile border (small triangles at 4K), "one tile or
// several?" mispredicts: then a box of at most 2×2 tiles (nearly all, since
// the kernels' boxes are < 64 px and most < 16 px) takes one branch-free
// path. Its top-left tile goes through the run as above; the other three
// tiles are always counted and filled, a missing one (box 1 tile wide or
// tall) sent to a dummy slot past the grid, so counts stay exact. Each
// triangle's note is then its top-left tile and its width and height bits.
void ChunkBins::build(const TileGrid& grid, std::span<const RasterTriangle> triangles) {
    const bool branch_free = crossing_often(grid, triangles);
    const std::size_t tile_count = std::size_t(grid.tile_count());
    const std::uint32_t tiles_x = std::uint32_t(grid.tiles_x);
    // The 2×2 path reads the counts of the 3 tiles right of and below the
    // top-left one even when absent (up to tile_count + tiles_x); past those,
    // the dummy slot.
    const std::uint32_t dummy = std::uint32_t(tile_count) + tiles_x + 1;
    const std::size_t scratch_size = std::size_t(dummy) + 1;
    if (scratch_dirty || tile_scratch.size() != scratch_size) tile_scratch.assign(scratch_size, 0);
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
    // Counts `tile` if `real`, else the dummy, without a branch.
    const auto add_if = [&](std::uint32_t tile, std::uint32_t real) {
        const std::uint32_t n = count[tile];
        touched[touched_count] = tile;
        touched_count += std::size_t(real & std::uint32_t(n == 0));
        count[real_or(tile, real, dummy)] = n + 1;
    };
    triangle_tile.resize(triangles.size());
    std::uint32_t* const tile_of = triangle_tile.data();
    std::uint32_t run_tile = 0, run_length = 0;  // consecutive one-tile triangles counted, not yet in count
    const auto run = [&](std::uint32_t tile) {
        if (tile != run_tile) {
            if (run_length != 0) add(run_tile, run_length);
            run_tile = tile, run_length = 0;
        }
        ++run_length;
    };
    for (std::size_t i = 0; i < triangles.size(); ++i) {
        const RasterTriangle& t = triangles[i];
        const int tx0 = t.px_min >> grid.tile_shift, tx1 = t.px_max >> grid.tile_shift;
        const int ty0 = t.py_min >> grid.tile_shift, ty1 = t.py_max >> grid.tile_shift;
        const std::uint32_t tile = std::uint32_t(ty0) * tiles_x + std::uint32_t(tx0);
        const std::uint32_t dx = std::uint32_t(tx1 - tx0), dy = std::uint32_t(ty1 - ty0);
        if (branch_free && (dx | dy) <= 1) {
            tile_of[i] = tile << 2 | dy << 1 | dx;
            run(tile);
            add_if(tile + 1, dx);
            add_if(tile + tiles_x, dy);
            add_if(tile + tiles_x + 1, dx & dy);
        } else if (!branch_free && (dx | dy) == 0) {
            tile_of[i] = tile << 2;
            run(tile);
        } else {
            tile_of[i] = kSeveralTiles;
            for_each_tile(grid, t, [&](int several) { add(std::uint32_t(several), 1); });
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
    const std::uint32_t trash = starts.back();  // the item slot the dummy's writes go to
    items.resize(std::size_t(trash) + 1);
    std::uint32_t* const item = items.data();
    std::uint32_t* const cursor = tile_scratch.data();
    std::uint32_t cursor_tile = kSeveralTiles, run_cursor = 0;  // the current run's cursor, not yet in `cursor`
    // Writes triangle i into `tile`'s bin if `real`, else into the trash slot.
    const auto put_if = [&](std::uint32_t tile, std::uint32_t real, std::uint32_t i) {
        const std::uint32_t at = real_or(cursor[tile], real, trash);
        item[at] = i;
        cursor[real_or(tile, real, dummy)] = at + 1;
    };
    for (std::uint32_t i = 0; i < triangles.size(); ++i) {
        const std::uint32_t note = tile_of[i];
        if (note == kSeveralTiles) {  // its tiles' cursors must be in `cursor`
            if (cursor_tile != kSeveralTiles) cursor[cursor_tile] = run_cursor, cursor_tile = kSeveralTiles;
            for_each_tile(grid, triangles[i], [&](int several) { item[cursor[several]++] = i; });
            continue;
        }
        const std::uint32_t tile = note >> 2;
        if (tile != cursor_tile) {
            if (cursor_tile != kSeveralTiles) cursor[cursor_tile] = run_cursor;
            cursor_tile = tile, run_cursor = cursor[tile];
        }
        item[run_cursor++] = i;
        if (branch_free) {  // the run's tile is `tile`, never one of these three
            const std::uint32_t dx = note & 1, dy = note >> 1 & 1;
            put_if(tile + 1, dx, i);
            put_if(tile + tiles_x, dy, i);
            put_if(tile + tiles_x + 1, dx & dy, i);
        }
    }
    items.resize(trash);
    for (const std::uint32_t tile : tiles) cursor[tile] = 0;
    cursor[dummy] = 0;
    scratch_dirty = false;
}

}  // namespace tessera::raster
