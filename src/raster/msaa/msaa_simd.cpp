// The 4× MSAA rasterizer's inner loop over vectors of samples
// (msaa_kernels.hpp), compiled once per ISA. Same arithmetic as the scalar
// loop in msaa.cpp, lane by lane, so both give bit-identical sample buffers.
#include <bit>
#include <cstddef>
#include <cstdint>

#include "simd/kernel_prelude.hpp"
#include "simd/lane_helpers.hpp"

#include "raster/msaa/msaa_bin.hpp"
#include "raster/msaa/msaa_kernels.hpp"
#include "raster/msaa/msaa_pattern.hpp"
#include "raster/raster_limits.hpp"
#include "raster/tiny_triangle_simd.hpp"

namespace tessera::raster {
namespace {

using Arch = TESSERA_SIMD_ARCH;
using Int = xsimd::batch<std::int32_t, Arch>;
using Float = xsimd::batch<float, Arch>;
using IntMask = xsimd::batch_bool<std::int32_t, Arch>;
using Double = xsimd::batch<double, Arch>;
static_assert(Double::size * 2 == Float::size);

constexpr int kPixels = int(Int::size) / kMsaaSamples;  // pixels per vector
static_assert(kPixels * kMsaaSamples == int(Int::size));
static_assert(kMsaaKernelOverreach >= (kPixels - 1) * kMsaaSamples);

// Per lane i (pixel i / 4, sample i % 4): the sample's offset from the first
// pixel's centre in 1/256 pixel, x (pixel · 256 + sample offset) and y.
struct LaneOffsets {
    alignas(64) std::int32_t x[16], y[16], pixel[16];
    alignas(64) double x_double[16], y_double[16];
    constexpr LaneOffsets() : x{}, y{}, pixel{}, x_double{}, y_double{} {
        for (int i = 0; i < 16; ++i) {
            x[i] = 256 * (i / kMsaaSamples) + kSampleOffsetX[i % kMsaaSamples];
            y[i] = kSampleOffsetY[i % kMsaaSamples];
            pixel[i] = i / kMsaaSamples;
            x_double[i] = x[i], y_double[i] = y[i];
        }
    }
};
constexpr LaneOffsets kLane;

using simd::lane_bits;
using simd::round_to_float;


// The barycentric numerators E1, E2 in double where they leave int32
// (WideWeights): per lane the row's value plus the lane's offset, exact
// integers, so float(E) rounds once as the scalar loop's float(int64) does.
struct WideLanes {
    Double offset_lo[2], offset_hi[2];  // the lanes' offsets from the vector's first pixel centre
    double row[2], right[2], down[2];   // at the row's first vector; per vector right; per row down
};

// A triangle's edges over the lanes of a row's first vector, biased by the
// top-left rule (a sample is inside where all three are >= 0), and how they
// change one vector right and one row down.
struct LaneEdges {
    Int row[3], right[3], down[3];
    std::int32_t bias1, bias2;  // removed again for the barycentric numerators
};

// The tile-relative block [x_begin, x_end) × [y_begin, y_end), a row at a
// time, kPixels pixels per vector. The last vector of a row may reach up to 3
// pixels past its end (into the next row or TileSamples' padding): those lanes
// write back what they read.
template <bool kWide>
[[gnu::always_inline]] inline void rasterize_rows(LaneEdges edges, WideLanes wide, int x_begin, int x_end, int y_begin, int y_end,
                                                  float inv_area_value, float d0_value, float d10_value,
                                                  float d20_value, std::uint32_t triangle_id, const SampleView& tile,
                                                  RasterCounters& counters) {
    const Int lane_pixel = Int::load_aligned(kLane.pixel), end(x_end);
    // E >= 0 as E > -1: one compare (AVX2 has no >= for integers).
    const Int bias1(edges.bias1), bias2(edges.bias2), minus_one(-1), id = Int(std::int32_t(triangle_id));
    const Float inv_area(inv_area_value), d0(d0_value), d10(d10_value), d20(d20_value), zero(0.0f);
    unsigned fragments = 0, passed = 0;
    for (int y = y_begin; y < y_end; ++y) {
        Int e0 = edges.row[0], e1 = edges.row[1], e2 = edges.row[2];
        double weight1 = wide.row[0], weight2 = wide.row[1];
        const std::size_t first = std::size_t(kMsaaSamples) * (std::size_t(y) * tile.side + x_begin);
        std::int32_t* depth = reinterpret_cast<std::int32_t*>(tile.depth) + first;
        std::int32_t* triangle = reinterpret_cast<std::int32_t*>(tile.triangle) + first;
        Int column = lane_pixel + Int(x_begin);  // each lane's pixel column
        for (int x = x_begin; x < x_end; x += kPixels, depth += Int::size, triangle += Int::size) {
            const IntMask inside = ((e0 | e1 | e2) > minus_one) & (column < end);
            column += Int(kPixels);
            const Int w1 = e1, w2 = e2;
            const double v1 = weight1, v2 = weight2;
            e0 += edges.right[0], e1 += edges.right[1], e2 += edges.right[2];
            if constexpr (kWide) weight1 += wide.right[0], weight2 += wide.right[1];
            // No branch on whether any lane is inside or passes: at a small
            // triangle's edges that mispredicted ~9 times per triangle.
            fragments += unsigned(std::popcount(lane_bits(inside)));
            // As the scalar loop: barycentrics, then depth linear in screen space, kept >= 0
            // (max(z, 0) gives 0 for -0 too, as the scalar window_depth does).
            Float lambda1, lambda2;
            if constexpr (kWide) {
                lambda1 = round_to_float(Double(v1) + wide.offset_lo[0], Double(v1) + wide.offset_hi[0]) * inv_area;
                lambda2 = round_to_float(Double(v2) + wide.offset_lo[1], Double(v2) + wide.offset_hi[1]) * inv_area;
            } else {
                lambda1 = xsimd::to_float(w1 - bias1) * inv_area;
                lambda2 = xsimd::to_float(w2 - bias2) * inv_area;
            }
            const Int new_depth = xsimd::bitwise_cast<Int>(xsimd::max(d0 + lambda1 * d10 + lambda2 * d20, zero));
            // Depths in [0, 1] order like their bit patterns: LESS as an integer compare.
            const Int old_depth = Int::load_unaligned(depth);
            const IntMask pass = inside & (new_depth < old_depth);
            passed += unsigned(std::popcount(lane_bits(pass)));
#if XSIMD_WITH_AVX512F
            // Masked stores: no read-back of the triangle ids (AVX2's vpmaskmovd is microcoded on AMD).
            _mm512_mask_storeu_epi32(depth, pass.data, new_depth);
            _mm512_mask_storeu_epi32(triangle, pass.data, id);
#else
            xsimd::select(pass, new_depth, old_depth).store_unaligned(depth);
            xsimd::select(pass, id, Int::load_unaligned(triangle)).store_unaligned(triangle);
#endif
        }
        for (int k = 0; k < 3; ++k) edges.row[k] += edges.down[k];
        if constexpr (kWide) wide.row[0] += wide.down[0], wide.row[1] += wide.down[1];
    }
    counters.fragments += fragments;
    counters.depth_passed += passed;
}

}  // namespace

void TESSERA_SIMD_ENTRY(rasterize_msaa_block)(const EdgeBlock32& b, const WideWeights* weights,
                                              const SampleView& tile, RasterCounters& counters) {
    // E is affine: E at a lane's sample = E at the block's first pixel centre
    // + (step_x / 256) · offset x + (step_y / 256) · offset y, exact in int32
    // (the steps are multiples of 256), as the scalar loop's offset[k][s]
    // plus its whole-pixel steps.
    static_assert(kSubpixelScale == 256);
    const Int offset_x = Int::load_aligned(kLane.x), offset_y = Int::load_aligned(kLane.y);
    LaneEdges edges;
    for (int k = 0; k < 3; ++k) {
        edges.row[k] = Int(b.row[k]) + offset_x * Int(b.step_x[k] / 256) + offset_y * Int(b.step_y[k] / 256);
        edges.right[k] = Int(kPixels * b.step_x[k]);
        edges.down[k] = Int(b.step_y[k]);
    }
    edges.bias1 = b.bias[1], edges.bias2 = b.bias[2];
    WideLanes wide{};
    if (!weights)
        return rasterize_rows<false>(edges, wide, b.x_begin, b.x_end, b.y_begin, b.y_end, b.inv_area, b.d0, b.d10,
                                     b.d20, b.triangle_id, tile, counters);
    const Double x_lo = Double::load_aligned(kLane.x_double), x_hi = Double::load_aligned(kLane.x_double + Double::size);
    const Double y_lo = Double::load_aligned(kLane.y_double), y_hi = Double::load_aligned(kLane.y_double + Double::size);
    for (int k = 0; k < 2; ++k) {
        // (step / 256) · offset, as in the int32 case: exact in double.
        const Double per_x(weights->step_x[k] / 256), per_y(weights->step_y[k] / 256);
        wide.offset_lo[k] = x_lo * per_x + y_lo * per_y;
        wide.offset_hi[k] = x_hi * per_x + y_hi * per_y;
        wide.row[k] = weights->row[k];
        wide.right[k] = kPixels * weights->step_x[k];
        wide.down[k] = weights->step_y[k];
    }
    rasterize_rows<true>(edges, wide, b.x_begin, b.x_end, b.y_begin, b.y_end, b.inv_area, b.d0, b.d10, b.d20,
                         b.triangle_id, tile, counters);
}

namespace {

// rasterize_msaa_tiny_<isa>, inlined into the bin loop below too.
[[gnu::always_inline]] inline void rasterize_tiny(const RasterTriangle& t, std::uint32_t triangle_id,
                                                  const TinyBox& box, const SampleView& tile,
                                                  RasterCounters& counters) {
    // The lanes' sample positions in the box's first vector, fixed point.
    const Int x = Int(box.x_begin * 256 + 128) + Int::load_aligned(kLane.x);
    const Int y = Int(box.y_begin * 256 + 128) + Int::load_aligned(kLane.y);
    LaneEdges edges;
    // Edge k from corner a to corner b: E = (bx - ax)(y - ay) - (by - ay)(x - ax), as
    // edge_function(), plus EdgeStepper's top-left bias; exact in int32, every value
    // being below 2^26.
    static_assert(kTinySpan <= (1 << 12));
    constexpr int kCorners[3][2] = {{1, 2}, {2, 0}, {0, 1}};
    std::int32_t bias[3];
    for (int k = 0; k < 3; ++k) {
        const int a = kCorners[k][0], b = kCorners[k][1];
        const std::int32_t dx = t.x[b] - t.x[a], dy = t.y[b] - t.y[a];
        // EdgeStepper's bias, 0 for a top or left edge (dy < 0, or dy == 0 and dx > 0), else -1, without
        // branches: the sign of dy · 2^13 - dx, as |dx| < kTinySpan <= 2^12 (and dx != 0 where dy == 0:
        // set-up triangles have area).
        bias[k] = ~(((dy << 13) - dx) >> 31);
        edges.row[k] = Int(dx) * (y - Int(t.y[a])) - Int(dy) * (x - Int(t.x[a])) + Int(bias[k]);
        edges.right[k] = Int(-dy * (kPixels * 256));
        edges.down[k] = Int(dx * 256);
    }
    edges.bias1 = bias[1], edges.bias2 = bias[2];
    rasterize_rows<false>(edges, WideLanes{}, box.x_begin - box.tile_x0, box.x_end - box.tile_x0, box.y_begin - box.tile_y0,
                   box.y_end - box.tile_y0, t.inv_area, t.depth[0], t.depth[1] - t.depth[0], t.depth[2] - t.depth[0],
                   triangle_id, tile, counters);
}

}  // namespace

void TESSERA_SIMD_ENTRY(rasterize_msaa_tiny)(const RasterTriangle& t, std::uint32_t triangle_id, const TinyBox& box,
                                             const SampleView& tile, RasterCounters& counters) {
    rasterize_tiny(t, triangle_id, box, tile, counters);
}

void TESSERA_SIMD_ENTRY(rasterize_bin_msaa)(const RasterTriangle* records, const std::uint32_t* bin, std::size_t count,
                                            std::uint32_t id_base, const TileRect& tile, TileSamples& samples,
                                            const SampleView& view, RasterCounters& counters, WrittenBox& written,
                                            DrawnCallback drawn, const CornerPrefetch& prefetch) {
    // Copies the compiler may keep in registers: the vector stores into the
    // tile's samples could otherwise change them, as far as it knows, so they
    // would be read back from memory for every triangle and row.
    const SampleView local_view = view;
    const TileRect local_tile = tile;
    RasterCounters local_counters = counters;
    const CornerPrefetch local_prefetch = prefetch;
    int written_x0 = written.x0, written_y0 = written.y0, written_x1 = written.x1, written_y1 = written.y1;
    for (std::size_t i = 0; i < count; ++i) {
        // A tile's triangles lie scattered through the chunk: fetch ahead
        // (records are one aligned cache line each).
        constexpr std::size_t kPrefetchDistance = 8;
        if (i + kPrefetchDistance < count) __builtin_prefetch(&records[bin[i + kPrefetchDistance]]);
        const RasterTriangle& t = records[bin[i]];
        // As rasterize_triangle_msaa(isa, ...): the box in the tile, marked written, then tiny or not.
        const int x_begin = t.px_min > local_tile.x0 ? t.px_min : local_tile.x0;
        const int x_end = t.px_max < local_tile.x1 ? t.px_max + 1 : local_tile.x1;
        const int y_begin = t.py_min > local_tile.y0 ? t.py_min : local_tile.y0;
        const int y_end = t.py_max < local_tile.y1 ? t.py_max + 1 : local_tile.y1;
        if (x_begin >= x_end || y_begin >= y_end) continue;
        const int box_x0 = x_begin - local_tile.x0, box_y0 = y_begin - local_tile.y0;
        const int box_x1 = x_end - local_tile.x0, box_y1 = y_end - local_tile.y0;
        written_x0 = box_x0 < written_x0 ? box_x0 : written_x0, written_y0 = box_y0 < written_y0 ? box_y0 : written_y0;
        written_x1 = box_x1 > written_x1 ? box_x1 : written_x1, written_y1 = box_y1 > written_y1 ? box_y1 : written_y1;
        const std::uint32_t id = id_base | bin[i];
        const std::uint64_t passed = local_counters.depth_passed;
        if (tiny(t)) {
            const TinyBox box{x_begin, x_end, y_begin, y_end, local_tile.x0, local_tile.y0};
            rasterize_tiny(t, id, box, local_view, local_counters);
        } else {
            // Counted apart, so that local_counters' address never escapes and it stays in registers.
            RasterCounters general;
            rasterize_general_msaa(simd::Isa::TESSERA_SIMD_SUFFIX, t, id, local_tile, x_begin, x_end, y_begin, y_end,
                                   local_view, samples, general);
            local_counters.fragments += general.fragments, local_counters.depth_passed += general.depth_passed;
        }
        if (local_counters.depth_passed != passed) {
            if (local_prefetch.vertices) prefetch_corners(t, local_prefetch);
            if (drawn.call) drawn.call(drawn.context, bin[i]);
        }
    }
    counters = local_counters;
    written = {written_x0, written_y0, written_x1, written_y1};
}

}  // namespace tessera::raster
