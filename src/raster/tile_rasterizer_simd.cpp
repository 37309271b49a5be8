// The rasterizer's inner loop over vectors of pixel centres (raster_kernels.hpp),
// compiled once per ISA. Same arithmetic as the scalar loop in
// tile_rasterizer.cpp, lane by lane, so both give bit-identical buffers.
#include <bit>
#include <cstddef>
#include <cstdint>

#include "simd/kernel_prelude.hpp"
#include "simd/lane_helpers.hpp"

#include "raster/bin_rasterizer.hpp"
#include "raster/raster_kernels.hpp"
#include "raster/raster_limits.hpp"
#include "raster/tiny_triangle_simd.hpp"

namespace tessera::raster {
namespace {

using Arch = TESSERA_SIMD_ARCH;
using Int = xsimd::batch<std::int32_t, Arch>;
using Float = xsimd::batch<float, Arch>;

using Double = xsimd::batch<double, Arch>;
static_assert(Int::size <= kMaxRasterLanes && Double::size * 2 == Float::size);
using simd::lane_bits;
using simd::round_to_float;

alignas(64) constexpr std::int32_t kLaneIndex[16] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
alignas(64) constexpr double kLaneIndexDouble[16] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};

// kCovered: every pixel of the block is inside, only the depth test remains.
// kWideWeights: barycentric numerators in double (see EdgeBlock32).
template <bool kCovered, bool kWideWeights>
void rasterize_block(const EdgeBlock32& b, const WideWeights* wide, const TileView& tile, RasterCounters& counters) {
    constexpr int kLanes = int(Int::size);
    const Int lane = Int::load_aligned(kLaneIndex);
    const Int lane_step0 = lane * Int(b.step_x[0]), lane_step1 = lane * Int(b.step_x[1]),
              lane_step2 = lane * Int(b.step_x[2]);
    const Int x_end(b.x_end);
    const Float inv_area(b.inv_area), d0(b.d0), d10(b.d10), d20(b.d20), zero(0.0f);
    const Int id(std::int32_t(b.triangle_id)), one(1), none(0);
    Int covered_lanes(0), passed_lanes(0);
    // Wide weights: lane offsets of the numerators, exact integers in double.
    const WideWeights ww = kWideWeights ? *wide : WideWeights{};
    const Double lane_lo = Double::load_aligned(kLaneIndexDouble),
                 lane_hi = Double::load_aligned(kLaneIndexDouble + Double::size);
    const Double lane_lo1 = lane_lo * Double(ww.step_x[0]), lane_hi1 = lane_hi * Double(ww.step_x[0]),
                 lane_lo2 = lane_lo * Double(ww.step_x[1]), lane_hi2 = lane_hi * Double(ww.step_x[1]);
    double weight_row1 = ww.row[0], weight_row2 = ww.row[1];

    std::int32_t row0 = b.row[0], row1 = b.row[1], row2 = b.row[2];
    for (int y = b.y_begin; y < b.y_end; ++y) {
        for (int x = b.x_begin; x < b.x_end; x += kLanes) {
            const std::int32_t dx = x - b.x_begin;
            const auto in_block = (Int(x) + lane) < x_end;
            auto inside = in_block;
            Int w1 = Int(row1 + dx * b.step_x[1]) + lane_step1;
            Int w2 = Int(row2 + dx * b.step_x[2]) + lane_step2;
            if constexpr (!kCovered) {
                const Int w0 = Int(row0 + dx * b.step_x[0]) + lane_step0;
                inside = ((w0 | w1 | w2) >= none) & in_block;
                if (xsimd::none(inside)) continue;
            }
            // As the scalar loop: barycentrics, then depth linear in screen space, kept >= 0.
            Float lambda1, lambda2;
            if constexpr (kWideWeights) {
                const Double w1(weight_row1 + double(dx) * ww.step_x[0]);
                const Double w2(weight_row2 + double(dx) * ww.step_x[1]);
                lambda1 = round_to_float(w1 + lane_lo1, w1 + lane_hi1) * inv_area;
                lambda2 = round_to_float(w2 + lane_lo2, w2 + lane_hi2) * inv_area;
            } else {
                lambda1 = xsimd::to_float(w1 - Int(b.bias[1])) * inv_area;
                lambda2 = xsimd::to_float(w2 - Int(b.bias[2])) * inv_area;
            }
            const Float z_raw = d0 + lambda1 * d10 + lambda2 * d20;
            const Float z = xsimd::select(z_raw > zero, z_raw, zero);
            // Depths in [0, 1] order like their bit patterns, so LESS is an integer compare
            // and the whole update stays in one mask type.
            const std::size_t index = std::size_t(y) * tile.side + x;
            std::int32_t* depth_bits = reinterpret_cast<std::int32_t*>(tile.depth + index);
            const Int old_depth = Int::load_unaligned(depth_bits);
            const Int new_depth = xsimd::bitwise_cast<Int>(z);
            const auto pass = inside & (new_depth < old_depth);
            covered_lanes += xsimd::select(inside, one, none);
            if (xsimd::none(pass)) continue;
            passed_lanes += xsimd::select(pass, one, none);
            xsimd::select(pass, new_depth, old_depth).store_unaligned(depth_bits);
            std::int32_t* ids = reinterpret_cast<std::int32_t*>(tile.triangle + index);
            xsimd::select(pass, id, Int::load_unaligned(ids)).store_unaligned(ids);
            std::int32_t* l1 = reinterpret_cast<std::int32_t*>(tile.lambda1 + index);
            xsimd::select(pass, xsimd::bitwise_cast<Int>(lambda1), Int::load_unaligned(l1)).store_unaligned(l1);
            std::int32_t* l2 = reinterpret_cast<std::int32_t*>(tile.lambda2 + index);
            xsimd::select(pass, xsimd::bitwise_cast<Int>(lambda2), Int::load_unaligned(l2)).store_unaligned(l2);
        }
        row0 += b.step_y[0], row1 += b.step_y[1], row2 += b.step_y[2];
        weight_row1 += ww.step_y[0], weight_row2 += ww.step_y[1];
    }
    counters.fragments += std::uint64_t(xsimd::hadd(covered_lanes));
    counters.depth_passed += std::uint64_t(xsimd::hadd(passed_lanes));
}


// A stamp kWidth pixels wide (4, 8 or 16): lane i of a vector is pixel
// (i % kWidth, i / kWidth) of kRows rows when kWidth is below the lane count,
// else one row is kVectors vectors side by side. Boxes take the narrowest
// stamp they fit in, so few lanes are wasted whatever the box's shape.
template <int kWidth>
struct Stamp {
    static constexpr int kLanes = int(Int::size);
    static constexpr int kColumns = kWidth < kLanes ? kWidth : kLanes;  // pixels of one row in a vector
    static constexpr int kRows = kLanes / kColumns;                      // rows in a vector
    static constexpr int kVectors = kWidth / kColumns;                   // vectors across a row
    static_assert(kWidth == 4 || kWidth == 8 || kWidth == 16);
    static_assert(kWidth <= kMaxRasterLanes, "a stamp's loads past a row's end stay in the tile buffers' padding");
};

// kColumns int32 from each of kRows rows (row r at base + offset[r]) into one
// vector, and back. Hand-written: xsimd 8.1 loads and stores whole vectors only.
template <int kColumns>
[[gnu::always_inline]] inline Int load_rows(const std::int32_t* base, const std::size_t* offset) {
    if constexpr (kColumns == int(Int::size)) {
        return Int::load_unaligned(base + offset[0]);
    } else {
#if XSIMD_WITH_AVX512F
        if constexpr (kColumns == 8) {
            const __m512i low = _mm512_castsi256_si512(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(base + offset[0])));
            return _mm512_inserti64x4(low, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(base + offset[1])), 1);
        } else {
            static_assert(kColumns == 4);
            const __m512i low = _mm512_castsi128_si512(_mm_loadu_si128(reinterpret_cast<const __m128i*>(base + offset[0])));
            const __m512i two = _mm512_inserti32x4(low, _mm_loadu_si128(reinterpret_cast<const __m128i*>(base + offset[1])), 1);
            const __m512i three = _mm512_inserti32x4(two, _mm_loadu_si128(reinterpret_cast<const __m128i*>(base + offset[2])), 2);
            return _mm512_inserti32x4(three, _mm_loadu_si128(reinterpret_cast<const __m128i*>(base + offset[3])), 3);
        }
#elif XSIMD_WITH_AVX2
        static_assert(kColumns == 4);
        return _mm256_loadu2_m128i(reinterpret_cast<const __m128i*>(base + offset[1]),
                                   reinterpret_cast<const __m128i*>(base + offset[0]));
#else
        static_assert(kColumns == int(Int::size), "SSE stamps are one row per vector");
#endif
    }
}
// Rows past the box share row 0's offset (their lanes write back what was
// read), so rows are stored last to first: row 0's own values land last.
template <int kColumns>
[[gnu::always_inline]] inline void store_rows(std::int32_t* base, const std::size_t* offset, const Int& v) {
    if constexpr (kColumns == int(Int::size)) {
        v.store_unaligned(base + offset[0]);
    } else {
#if XSIMD_WITH_AVX512F
        if constexpr (kColumns == 8) {
            _mm256_storeu_si256(reinterpret_cast<__m256i*>(base + offset[1]), _mm512_extracti64x4_epi64(v, 1));
            _mm256_storeu_si256(reinterpret_cast<__m256i*>(base + offset[0]), _mm512_castsi512_si256(v));
        } else {
            _mm_storeu_si128(reinterpret_cast<__m128i*>(base + offset[3]), _mm512_extracti32x4_epi32(v, 3));
            _mm_storeu_si128(reinterpret_cast<__m128i*>(base + offset[2]), _mm512_extracti32x4_epi32(v, 2));
            _mm_storeu_si128(reinterpret_cast<__m128i*>(base + offset[1]), _mm512_extracti32x4_epi32(v, 1));
            _mm_storeu_si128(reinterpret_cast<__m128i*>(base + offset[0]), _mm512_castsi512_si128(v));
        }
#elif XSIMD_WITH_AVX2
        // Not _mm256_storeu2_m128i: it stores the low half first.
        _mm_storeu_si128(reinterpret_cast<__m128i*>(base + offset[1]), _mm256_extracti128_si256(v, 1));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(base + offset[0]), _mm256_castsi256_si128(v));
#endif
    }
}
// v into one tile array where `pass` holds: AVX-512 by masked stores, a row
// at a time (rows past the box have no lane set, so they write nothing);
// elsewhere a load + select + store (AVX2's vpmaskmovd stores are microcoded
// on AMD: the stamps took 1.8x as long with them).
// `current`: the array's values there, where the caller has loaded them
// already (AVX-512 does not need them).
template <int kColumns>
[[gnu::always_inline]] inline void update_rows(std::int32_t* base, const std::size_t* offset,
                                               const xsimd::batch_bool<std::int32_t, Arch>& pass, const Int& v,
                                               [[maybe_unused]] const Int& current) {
#if XSIMD_WITH_AVX512F
    const __mmask16 mask = pass;
    if constexpr (kColumns == 16) {
        _mm512_mask_storeu_epi32(base + offset[0], mask, v);
    } else if constexpr (kColumns == 8) {
        _mm256_mask_storeu_epi32(base + offset[0], __mmask8(mask), _mm512_castsi512_si256(v));
        _mm256_mask_storeu_epi32(base + offset[1], __mmask8(mask >> 8), _mm512_extracti64x4_epi64(v, 1));
    } else {
        static_assert(kColumns == 4);
        _mm_mask_storeu_epi32(base + offset[0], __mmask8(mask & 0xF), _mm512_castsi512_si128(v));
        _mm_mask_storeu_epi32(base + offset[1], __mmask8((mask >> 4) & 0xF), _mm512_extracti32x4_epi32(v, 1));
        _mm_mask_storeu_epi32(base + offset[2], __mmask8((mask >> 8) & 0xF), _mm512_extracti32x4_epi32(v, 2));
        _mm_mask_storeu_epi32(base + offset[3], __mmask8(mask >> 12), _mm512_extracti32x4_epi32(v, 3));
    }
#else
    store_rows<kColumns>(base, offset, xsimd::select(pass, v, current));
#endif
}
template <int kColumns>
[[gnu::always_inline]] inline void update_rows(std::int32_t* base, const std::size_t* offset,
                                               const xsimd::batch_bool<std::int32_t, Arch>& pass, const Int& v) {
#if XSIMD_WITH_AVX512F
    update_rows<kColumns>(base, offset, pass, v, v);  // no read-back
#else
    update_rows<kColumns>(base, offset, pass, v, load_rows<kColumns>(base, offset));
#endif
}

// The lanes' column and row within a vector of a kColumns-wide stamp.
template <int kColumns>
[[gnu::always_inline]] inline Int lane_column() {
    return Int::load_aligned(kLaneIndex) & Int(kColumns - 1);
}
template <int kColumns>
[[gnu::always_inline]] inline Int lane_row() {
    return Int::load_aligned(kLaneIndex) >> std::countr_zero(unsigned(kColumns));
}

// A block's three edges over the lanes of its first stamp: the unbiased edge
// values E (the barycentric numerators) in the stamp's first vector, their
// change from one vector to the next across a row (`across`) and from one
// stamp to the next (kRows rows down), and the top-left rule as a threshold:
// a pixel centre is inside edge k when E_k > threshold_k (-1 for top and left
// edges, i.e. E >= 0; 0 for the others, E >= 1), as the scalar loop's E + bias >= 0.
struct StampEdges {
    Int e[3], across[3], down[3], threshold[3];
};

// A box at most kWidth wide (tile-relative pixels [x_begin, x_end) ×
// [y_begin, y_end)), a stamp of kRows rows per step, the same arithmetic per
// lane as the scalar loop. A row's loads reach kWidth - 1 pixels right of the
// box's first column: at most into the start of the next row, left of the
// box's columns there as kWidth <= the tile's side, or into the tile
// buffers' padding. Lanes outside the box write back what they read.
template <int kWidth>
[[gnu::always_inline]] inline void rasterize_stamps(StampEdges edges, int x_begin, int x_end, int y_begin, int y_end,
                                                    float inv_area_value, float d0_value, float d10_value,
                                                    float d20_value, std::uint32_t triangle_id, const TileView& tile,
                                                    RasterCounters& counters) {
    using S = Stamp<kWidth>;
    const Int ox = lane_column<S::kColumns>(), oy = lane_row<S::kColumns>();
    const Float inv_area(inv_area_value), d0(d0_value), d10(d10_value), d20(d20_value), zero(0.0f);
    const Int id = Int(std::int32_t(triangle_id));
    unsigned fragments = 0, passed = 0;
    for (int y = y_begin; y < y_end; y += S::kRows) {
        std::size_t offset[S::kRows];
        for (int r = 0; r < S::kRows; ++r) offset[r] = std::size_t(y + r < y_end ? y + r : y) * tile.side + x_begin;
        Int e[3] = {edges.e[0], edges.e[1], edges.e[2]};
        for (int v = 0; v < S::kVectors; ++v) {
            if (v > 0) {
                for (int k = 0; k < 3; ++k) e[k] += edges.across[k];
                for (int r = 0; r < S::kRows; ++r) offset[r] += S::kLanes;
            }
            auto inside = (e[0] > edges.threshold[0]) & (e[1] > edges.threshold[1]) & (e[2] > edges.threshold[2]) &
                          (ox < Int(x_end - x_begin - v * S::kLanes));
            if constexpr (S::kRows > 1) inside = inside & (oy < Int(y_end - y));
            const unsigned inside_bits = lane_bits(inside);
            // No branch on whether the vector has a lane inside or passing:
            // one with none, at a box's corners, mispredicted one time in
            // five at 4K (callgrind: 522k of a culled frame's mispredicts,
            // 243k without, for +7% instructions; at 720p, where the boxes are
            // one vector that seldom misses, +3% instructions, no gain).
            // As the scalar loop: barycentrics, then depth linear in screen space, kept >= 0
            // (max(z, 0) gives 0 for -0 too, as the scalar z > 0 ? z : 0 does).
            const Float lambda1 = xsimd::to_float(e[1]) * inv_area;
            const Float lambda2 = xsimd::to_float(e[2]) * inv_area;
            const Int new_depth = xsimd::bitwise_cast<Int>(xsimd::max(d0 + lambda1 * d10 + lambda2 * d20, zero));
            std::int32_t* depth = reinterpret_cast<std::int32_t*>(tile.depth);
            const Int old_depth = load_rows<S::kColumns>(depth, offset);
            // Depths in [0, 1] order like their bit patterns: LESS as an integer compare.
            const auto pass = inside & (new_depth < old_depth);
            fragments += unsigned(std::popcount(inside_bits));
            passed += unsigned(std::popcount(lane_bits(pass)));
            update_rows<S::kColumns>(depth, offset, pass, new_depth, old_depth);
            update_rows<S::kColumns>(reinterpret_cast<std::int32_t*>(tile.triangle), offset, pass, id);
            update_rows<S::kColumns>(reinterpret_cast<std::int32_t*>(tile.lambda1), offset, pass,
                                     xsimd::bitwise_cast<Int>(lambda1));
            update_rows<S::kColumns>(reinterpret_cast<std::int32_t*>(tile.lambda2), offset, pass,
                                     xsimd::bitwise_cast<Int>(lambda2));
        }
        for (int k = 0; k < 3; ++k) edges.e[k] += edges.down[k];
    }
    counters.fragments += fragments;
    counters.depth_passed += passed;
}

// A block in EdgeBlock32 form (biased rows and steps), at most kStampWidth wide, as stamps.
[[gnu::always_inline]] inline void rasterize_stamp(const EdgeBlock32& b, const TileView& tile,
                                                   RasterCounters& counters) {
    using S = Stamp<kStampWidth>;
    const Int ox = lane_column<S::kColumns>(), oy = lane_row<S::kColumns>();
    StampEdges edges;
    for (int k = 0; k < 3; ++k) {
        edges.e[k] = Int(b.row[k] - b.bias[k]) + ox * Int(b.step_x[k]) + oy * Int(b.step_y[k]);
        // A 4-wide stamp is one vector across: no step across, whose product
        // (lanes × step_x) stamp_fits_int32 does not bound and could overflow.
        static_assert(S::kVectors == 1);
        edges.across[k] = Int(0);
        edges.down[k] = Int(S::kRows * b.step_y[k]);
        edges.threshold[k] = Int(-1 - b.bias[k]);
    }
    rasterize_stamps<kStampWidth>(edges, b.x_begin, b.x_end, b.y_begin, b.y_end, b.inv_area, b.d0, b.d10, b.d20,
                                  b.triangle_id, tile, counters);
}

// Edge k of a tiny triangle, from corner a to corner b, over the lanes of the
// first vector of its first stamp (pixel centres x, y): E = (bx - ax)(y - ay)
// - (by - ay)(x - ax), as edge_function(); exact in int32, as every value is
// below 2^26 (raster_kernels.hpp).
template <int kWidth>
[[gnu::always_inline]] inline void tiny_edge(const RasterTriangle& t, int k, int a, int b, const Int& x, const Int& y,
                                             StampEdges& edges) {
    using S = Stamp<kWidth>;
    const Int ax(t.x[a]), ay(t.y[a]);
    const Int dx = Int(t.x[b]) - ax, dy = Int(t.y[b]) - ay;
    edges.e[k] = dx * (y - ay) - dy * (x - ax);
    edges.across[k] = dy * Int(-S::kLanes * 256);
    edges.down[k] = dx * Int(S::kRows * 256);
    // Top-left rule (EdgeStepper): a top edge (horizontal, interior below) or
    // a left edge, dy < 0 or (dy == 0 and dx > 0), has threshold -1: the sign
    // of dy · 2^13 - dx, as |dx| < kTinySpan <= 2^12 (and dx != 0 where dy ==
    // 0: set-up triangles have area). Three operations instead of seven.
    static_assert(kTinySpan <= (1 << 12));
    edges.threshold[k] = ((dy << 13) - dx) >> 31;
}

template <int kWidth>
[[gnu::always_inline]] inline void rasterize_tiny(const RasterTriangle& t, std::uint32_t triangle_id,
                                                  const TinyBox& box, const TileView& tile, RasterCounters& counters) {
    static_assert(kSubpixelScale == 256);
    using S = Stamp<kWidth>;
    // The lanes' pixel centres, fixed point.
    const Int x = Int(box.x_begin * 256 + 128) + (lane_column<S::kColumns>() << 8);
    const Int y = Int(box.y_begin * 256 + 128) + (lane_row<S::kColumns>() << 8);
    StampEdges edges;
    tiny_edge<kWidth>(t, 0, 1, 2, x, y, edges);
    tiny_edge<kWidth>(t, 1, 2, 0, x, y, edges);
    tiny_edge<kWidth>(t, 2, 0, 1, x, y, edges);
    rasterize_stamps<kWidth>(edges, box.x_begin - box.tile_x0, box.x_end - box.tile_x0, box.y_begin - box.tile_y0,
                             box.y_end - box.tile_y0, t.inv_area, t.depth[0], t.depth[1] - t.depth[0],
                             t.depth[2] - t.depth[0], triangle_id, tile, counters);
}

// rasterize_triangle_<isa>, inlined into the bin loop below too.
[[gnu::always_inline]] inline void rasterize_one(const RasterTriangle& t, std::uint32_t triangle_id,
                                                 const TileRect& tile, TileBuffers& buffers, const TileView& view,
                                                 RasterCounters& counters) {
    const int x_begin = t.px_min > tile.x0 ? t.px_min : tile.x0, x_end = t.px_max < tile.x1 ? t.px_max + 1 : tile.x1;
    const int y_begin = t.py_min > tile.y0 ? t.py_min : tile.y0, y_end = t.py_max < tile.y1 ? t.py_max + 1 : tile.y1;
    if (x_begin >= x_end || y_begin >= y_end) return;
    const int width = x_end - x_begin;
    if (width <= kMaxTinyWidth && tiny(t)) {
        // The narrowest stamp the box fits in.
        const TinyBox box{x_begin, x_end, y_begin, y_end, tile.x0, tile.y0};
#if XSIMD_WITH_AVX512F
        // AVX-512's 4-wide stamp is 4 rows a vector, 16 row stores a vector;
        // a box of at most 2 rows (most tiny ones) takes the 8-wide stamp,
        // 2 rows a vector: half the stores.
        if (width <= 4 && y_end - y_begin <= 2) return rasterize_tiny<8>(t, triangle_id, box, view, counters);
#endif
        if (width <= 4) return rasterize_tiny<4>(t, triangle_id, box, view, counters);
        if (width <= 8) return rasterize_tiny<8>(t, triangle_id, box, view, counters);
        return rasterize_tiny<16>(t, triangle_id, box, view, counters);
    }
    rasterize_general(simd::Isa::TESSERA_SIMD_SUFFIX, t, triangle_id, tile, buffers, counters);
}

}  // namespace

void TESSERA_SIMD_ENTRY(rasterize_triangle)(const RasterTriangle& t, std::uint32_t triangle_id, const TileRect& tile,
                                            TileBuffers& buffers, const TileView& view, RasterCounters& counters) {
    rasterize_one(t, triangle_id, tile, buffers, view, counters);
}

void TESSERA_SIMD_ENTRY(rasterize_bin)(const RasterTriangle* records, const std::uint32_t* bin, std::size_t count,
                                       std::uint32_t id_base, std::uint32_t* ids, std::uint32_t first_id,
                                       const TileRect& tile, TileBuffers& buffers,
                                       const TileView& view, RasterCounters& counters, DrawnCallback drawn,
                                       const CornerPrefetch& prefetch) {
    // Copies the compiler may keep in registers: the vector stores into the
    // tile (may_alias types) could otherwise change them, as far as it knows,
    // so they were read back from memory for every triangle and stamp row.
    const TileView local_view = view;
    const TileRect local_tile = tile;
    RasterCounters local_counters = counters;
    const CornerPrefetch local_prefetch = prefetch;
    for (std::size_t i = 0; i < count; ++i) {
        // A tile's triangles lie scattered through the chunk: fetch ahead
        // (records are one aligned cache line each).
        constexpr std::size_t kPrefetchDistance = 8;
        if (i + kPrefetchDistance < count) __builtin_prefetch(&records[bin[i + kPrefetchDistance]]);
        const RasterTriangle& t = records[bin[i]];
        ids[i] = id_base | bin[i];
        const std::uint64_t passed = local_counters.depth_passed;
        rasterize_one(t, first_id + std::uint32_t(i), local_tile, buffers, local_view, local_counters);
        if (local_counters.depth_passed != passed) {
            if (local_prefetch.vertices) prefetch_corners(t, local_prefetch);
            if (drawn.call) drawn.call(drawn.context, bin[i]);
        }
    }
    counters = local_counters;
}

void TESSERA_SIMD_ENTRY(rasterize_stamp)(const EdgeBlock32& block, const TileView& tile, RasterCounters& counters) {
    rasterize_stamp(block, tile, counters);
}

void TESSERA_SIMD_ENTRY(rasterize_block)(const EdgeBlock32& block, const WideWeights* wide, const TileView& tile,
                                         RasterCounters& counters) {
    if (wide)
        return block.fully_covered ? rasterize_block<true, true>(block, wide, tile, counters)
                                   : rasterize_block<false, true>(block, wide, tile, counters);
    return block.fully_covered ? rasterize_block<true, false>(block, wide, tile, counters)
                               : rasterize_block<false, false>(block, wide, tile, counters);
}

}  // namespace tessera::raster
