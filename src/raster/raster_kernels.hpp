// The rasterizer's SIMD inner loop, compiled once per ISA
// (tile_rasterizer_simd.cpp) and called by rasterize_triangle() for a block of
// pixels whose edge tests fit in 32-bit integers: then a vector of int32 lanes
// tests that many pixel centres at once, exactly as the scalar int64 loop would.
#pragma once

#include <cstdint>

#include "raster/tile_rasterizer.hpp"

namespace tessera::raster {

// Lanes in the widest vector any kernel uses; tile buffers are padded by this
// much so a vector load at the end of a row never leaves the allocation.
inline constexpr int kMaxRasterLanes = 16;

// One triangle over a block of one tile, edge tests in int32 (plain data: the
// per-ISA code must not touch std::vector).
struct EdgeBlock32 {
    std::int32_t row[3];     // biased edge values at the block's first pixel centre
    std::int32_t step_x[3];  // per pixel to the right
    std::int32_t step_y[3];  // per pixel down
    std::int32_t bias[3];    // 0 or -1 (top-left rule), removed again for barycentrics
    int x_begin, x_end;      // tile-relative pixel columns [x_begin, x_end)
    int y_begin, y_end;      // tile-relative pixel rows
    float inv_area;          // 1 / double_area
    float d0, d10, d20;      // depth at corner 0, and corners 1, 2 minus corner 0
    std::uint32_t triangle_id;
    // Every pixel centre of the block is inside (hierarchical acceptance): no edge test.
    bool fully_covered = false;
};

// Barycentric numerators of a block where they leave int32, given to the
// kernel instead of taking them from EdgeBlock32::row[1], row[2]; row/step
// then only test coverage, with edges known to be >= 0 over the block given
// as 0. double holds every edge value exactly (|E| < 2^49 < 2^53), so
// float(double(E)) rounds once, like the scalar loop's float(int64 E).
struct WideWeights {
    double row[2];     // unbiased edge values 1 and 2 at the block's first pixel centre
    double step_x[2];  // their steps per pixel right
    double step_y[2];  // and down
};

struct TileView {
    float* depth;
    std::uint32_t* triangle;
    float* lambda1;
    float* lambda2;
    int side;
};

// Boxes at most this many pixels wide take the stamp kernel: a vector covers
// kStampWidth × (lanes / kStampWidth) pixels of the box, several rows at once.
inline constexpr int kStampWidth = 4;

// A tiny triangle: every corner within kTinySpan of the others in x and in y
// (16 px). Its edge values at the pixel centres the kernel's lanes reach (up
// to 16 px right of the box's first column, 8 rows below it) are below 2^26,
// so the kernel sets it up in int32 by itself, from the record, with no int64
// edge steppers: what most triangles of a finely tessellated mesh need. Its
// box is at most kMaxTinyWidth wide.
inline constexpr std::int32_t kTinySpan = 16 * 256;
inline constexpr int kMaxTinyWidth = 16;

// The part of a tile a tiny triangle's box covers, in image pixels, and the tile's origin.
struct TinyBox {
    int x_begin, x_end, y_begin, y_end;
    int tile_x0, tile_y0;
};

// rasterize_block: one EdgeBlock32 a row of pixels at a time (vectors along the row).
// rasterize_stamp: a block at most kStampWidth pixels wide (any height), every
// edge value in int32 (down to a stamp's height below the block), as 4-wide
// stamps of rows: 1 row per SSE vector, 2 per AVX2, 4 per AVX-512 (a 4×4 box
// in one operation). Not fully_covered, no wide weights.
// rasterize_triangle: a whole triangle into the tile (the same result as
// rasterize_triangle() of tile_rasterizer.hpp; `view` is `buffers`' arrays).
// A tiny triangle's box up to kMaxTinyWidth wide is set up in int32 in the
// kernel, and rasterized as stamps of the narrowest width of 4, 8 and 16
// pixels it fits in: 4 wide as above; 8 wide 1 row per AVX2 vector, 2 per
// AVX-512, 2 SSE vectors across; 16 wide one row in 1 AVX-512, 2 AVX2 or 4 SSE
// vectors. Any other triangle goes to rasterize_general().
#define TESSERA_DECLARE_RASTER_KERNEL(suffix) \
    void rasterize_block_##suffix(const EdgeBlock32& block, const WideWeights* wide, const TileView& tile, \
                                  RasterCounters& counters); \
    void rasterize_stamp_##suffix(const EdgeBlock32& block, const TileView& tile, RasterCounters& counters); \
    void rasterize_triangle_##suffix(const RasterTriangle& t, std::uint32_t triangle_id, const TileRect& tile, \
                                     TileBuffers& buffers, const TileView& view, RasterCounters& counters);
TESSERA_DECLARE_RASTER_KERNEL(sse4)
TESSERA_DECLARE_RASTER_KERNEL(avx2)
TESSERA_DECLARE_RASTER_KERNEL(avx512)
#undef TESSERA_DECLARE_RASTER_KERNEL

// Every triangle but tiny ones, with the ISA's block and stamp kernels
// (tile_rasterizer.cpp); the kernels' rasterize_triangle hands them over.
void rasterize_general(simd::Isa isa, const RasterTriangle& t, std::uint32_t triangle_id, const TileRect& tile,
                       TileBuffers& buffers, RasterCounters& counters);

}  // namespace tessera::raster

namespace tessera::raster {

// Triangle assembly over a batch of a mesh's indexed triangles
// (triangle_setup_simd.cpp), a vector of triangles at a time: the index check,
// the outcode test (reject / accept / clip), face culling and the integer part
// of setup_triangle(), and the records of the triangles it keeps. Triangles
// that need clipping, or are too large for its int32 arithmetic, are left to
// the scalar code, by bit; the caller merges them in submission order.
inline constexpr int kSetupBatch = 64;  // triangles per call; a multiple of every lane count

struct SetupBatchInput {
    const std::uint32_t* indices;   // 3 per triangle (count triangles), relative to first_vertex
    const std::uint32_t* outcodes;  // the frame's, per vertex (geometry::outcode)
    const std::int32_t* screen;     // the frame's ScreenVertex array seen as 4 int32 per vertex: x, y, depth, outcode
    int count;                      // triangles, 1..kSetupBatch
    std::int32_t first_vertex;      // the mesh's first frame vertex
    std::int32_t vertex_count;      // > 0: an index at or past it drops its triangle
    int width, height;              // viewport
    int samples;                    // 1, or 4: pixel boxes and coverage by the 4× MSAA sample positions
    Culling culling;
    bool mirrored;                  // the model matrix mirrors: RasterTriangle::back_facing
};

struct SetupBatchOutput {
    std::uint64_t kept;     // bit i: triangle i was set up here; its record is the next in `records`
    std::uint64_t scalar;   // bit i: inside the guard band but to be set up one by one (setup_triangle)
    std::uint64_t clipped;  // bit i: crosses a clip plane (geometry::clip_triangle)
    // Triangles neither kept, scalar nor clipped were dropped: a bad index, outside
    // one plane or not finite, no area, culled, or covering no pixel centre.
    // Set by the caller: room for kSetupBatch records, where the kept
    // triangles' records go in order (popcount(kept) of them; the kernel may
    // write anything into the rest of the room).
    RasterTriangle* records;
};

#define TESSERA_DECLARE_SETUP_KERNEL(suffix) \
    void setup_batch_##suffix(const SetupBatchInput& in, SetupBatchOutput& out);
TESSERA_DECLARE_SETUP_KERNEL(sse4)
TESSERA_DECLARE_SETUP_KERNEL(avx2)
TESSERA_DECLARE_SETUP_KERNEL(avx512)
#undef TESSERA_DECLARE_SETUP_KERNEL

}  // namespace tessera::raster
