// Triangle assembly's common case over vectors of triangles (raster_kernels.hpp),
// compiled once per ISA. Each lane does for one triangle what
// assemble_triangles()' scalar path does: the index check, the outcode test,
// face culling and setup_triangle() (pixel centres, or 4× MSAA samples), the
// latter in int32: exact for triangles spanning less than 64 pixels, whose
// coordinate deltas stay below 2^14 so that every product stays below 2^30.
// Larger triangles, and those that need clipping, are handed back to the
// scalar code.
#include <bit>
#include <cstddef>
#include <cstdint>

#include "simd/kernel_prelude.hpp"

#include "simd/lane_helpers.hpp"
#include "simd/transpose.hpp"

#include "geometry/clipper.hpp"
#include "raster/msaa/msaa.hpp"
#include "raster/raster_kernels.hpp"
#include "raster/raster_limits.hpp"

namespace tessera::raster {
namespace {

using Arch = TESSERA_SIMD_ARCH;
using Int = xsimd::batch<std::int32_t, Arch>;
using Float = xsimd::batch<float, Arch>;
using Mask = xsimd::batch_bool<std::int32_t, Arch>;
constexpr int kLanes = int(Int::size);
static_assert(kSetupBatch % kLanes == 0 && kSetupBatch <= 64);

constexpr std::int32_t kMaxExtent = 1 << 14;  // fixed-point units: 64 pixels

// Edge a→b at centre p, biased by the top-left rule (as EdgeStepper).
Int biased_edge(const Int& ax, const Int& ay, const Int& bx, const Int& by, const Int& px, const Int& py) {
    const Int dx = bx - ax, dy = by - ay;
    const Mask top_left = (dy < Int(0)) | ((dy == Int(0)) & (dx > Int(0)));
    const Int bias = xsimd::select(top_left, Int(0), Int(-1));
    return dx * (py - ay) - dy * (px - ax) + bias;
}

// Bit `lane` set for each true lane, widened for the batch's 64-bit lane sets.
std::uint64_t lane_bits(const Mask& m) { return simd::lane_bits(m); }

// The corner indices of kLanes triangles (3 per triangle, from `indices`), a vector per corner.
void load_indices(const std::uint32_t* indices, Int (&index)[3]) {
#if defined(__AVX512F__)
    // Corner k of triangle j is word 3j + k of three registers' 48: picked
    // from the first two by one two-register permute, then from the third
    // where 3j + k >= 32.
    const __m512i a = _mm512_loadu_si512(indices), b = _mm512_loadu_si512(indices + 16),
                  c = _mm512_loadu_si512(indices + 32);
    for (int k = 0; k < 3; ++k) {
        const __m512i word = _mm512_add_epi32(
            _mm512_mullo_epi32(_mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15),
                               _mm512_set1_epi32(3)),
            _mm512_set1_epi32(k));
        const __m512i from_ab = _mm512_permutex2var_epi32(a, word, b);  // uses word's low 5 bits
        const __mmask16 in_c = _mm512_cmpge_epi32_mask(word, _mm512_set1_epi32(32));
        index[k] = Int(_mm512_mask_permutexvar_epi32(from_ab, in_c, _mm512_sub_epi32(word, _mm512_set1_epi32(32)), c));
    }
#elif defined(__AVX2__)
    // Corner k of triangle j is word 3j + k of three registers' 24: blend the
    // three so each lane holds a word of its corner, then put them in order.
    const auto* words = reinterpret_cast<const __m256i*>(indices);
    const __m256i a = _mm256_loadu_si256(words), b = _mm256_loadu_si256(words + 1), c = _mm256_loadu_si256(words + 2);
    const __m256i corner0 = _mm256_blend_epi32(_mm256_blend_epi32(a, b, 0b10010010), c, 0b00100100);
    const __m256i corner1 = _mm256_blend_epi32(_mm256_blend_epi32(a, b, 0b00100100), c, 0b01001001);
    const __m256i corner2 = _mm256_blend_epi32(_mm256_blend_epi32(a, b, 0b01001001), c, 0b10010010);
    index[0] = Int(_mm256_permutevar8x32_epi32(corner0, _mm256_setr_epi32(0, 3, 6, 1, 4, 7, 2, 5)));
    index[1] = Int(_mm256_permutevar8x32_epi32(corner1, _mm256_setr_epi32(1, 4, 7, 2, 5, 0, 3, 6)));
    index[2] = Int(_mm256_permutevar8x32_epi32(corner2, _mm256_setr_epi32(2, 5, 0, 3, 6, 1, 4, 7)));
#else
    alignas(64) std::int32_t lanes[3][kLanes];
    for (int j = 0; j < kLanes; ++j)
        for (int k = 0; k < 3; ++k) lanes[k][j] = std::int32_t(indices[3 * j + k]);
    for (int k = 0; k < 3; ++k) index[k] = Int::load_aligned(lanes[k]);
#endif
}

// The ScreenVertex of each lane's corner, as four vectors.
struct Corner {
    Int x, y, depth, outcode;  // depth: the float's bits
};

// Loads the 16-byte ScreenVertex of every lane and transposes them: on this
// project's AMD machines a hardware gather costs ~17 cycles (AVX2, Zen 2/3),
// so 4 of them per corner would cost more than all the rest of setup; on Zen 5
// four 16-lane gathers made the whole triangles pass 1.6x slower than these
// loads. xsimd 8.1 has no transpose, hence the intrinsics.
Corner load_corner(const std::int32_t* screen, const std::int32_t* ref) {
    // Refs are >= 0: as unsigned, a ref's address is one shift and add away.
    [[maybe_unused]] const auto vertex = [screen, ref](int j) {
        return reinterpret_cast<const float*>(screen) + 4 * std::size_t(std::uint32_t(ref[j]));
    };
#if defined(__AVX512F__)
    // Lanes j, j + 4, j + 8 and j + 12 share a register, one per 128-bit quarter.
    __m512 v[4];
    for (int j = 0; j < 4; ++j) {
        const __m256 low = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(vertex(j))),
                                                _mm_loadu_ps(vertex(j + 4)), 1);
        const __m256 high = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(vertex(j + 8))),
                                                 _mm_loadu_ps(vertex(j + 12)), 1);
        v[j] = simd::join_halves(low, high);
    }
    simd::transpose4x4_quarters(v);
    return {Int(_mm512_castps_si512(v[0])), Int(_mm512_castps_si512(v[1])), Int(_mm512_castps_si512(v[2])),
            Int(_mm512_castps_si512(v[3]))};
#elif defined(__AVX2__)
    // Lanes j and j + 4 share a register, one per 128-bit half.
    __m256 v[4];
    for (int j = 0; j < 4; ++j) {
        const __m128 lo = _mm_loadu_ps(vertex(j));
        const __m128 hi = _mm_loadu_ps(vertex(j + 4));
        v[j] = _mm256_insertf128_ps(_mm256_castps128_ps256(lo), hi, 1);
    }
    simd::transpose4x4_halves(v);
    return {Int(_mm256_castps_si256(v[0])), Int(_mm256_castps_si256(v[1])), Int(_mm256_castps_si256(v[2])),
            Int(_mm256_castps_si256(v[3]))};
#else
    __m128 v[4];
    for (int j = 0; j < 4; ++j) v[j] = _mm_loadu_ps(reinterpret_cast<const float*>(screen + 4 * ref[j]));
    _MM_TRANSPOSE4_PS(v[0], v[1], v[2], v[3]);
    return {Int(_mm_castps_si128(v[0])), Int(_mm_castps_si128(v[1])), Int(_mm_castps_si128(v[2])),
            Int(_mm_castps_si128(v[3]))};
#endif
}

// RasterTriangle as 16 int32 words, in the order of its fields.
static_assert(offsetof(RasterTriangle, y) == 12 && offsetof(RasterTriangle, px_min) == 24 &&
                  offsetof(RasterTriangle, py_min) == 28 && offsetof(RasterTriangle, inv_area) == 32 &&
                  offsetof(RasterTriangle, depth) == 36 && offsetof(RasterTriangle, vertex) == 48 &&
                  sizeof(RasterTriangle) == 64,
              "to_records() writes RasterTriangle as x[3], y[3], px_min..py_max, inv_area, depth[3], vertex[3], pad");

// The kept lanes' records (bit j of `kept`: lane j's), one after another
// from `records`, lane j's from word w of words[w] for every w: a transpose of
// 16 × lanes words (intrinsics: xsimd 8.1 has no transpose or scatter); it may
// write up to kLanes records from `records` whatever is kept. AVX2 and SSE
// store each lane's record where the next kept one goes, lanes in order, so a
// dropped lane's is overwritten by the next kept lane's or lies past the
// last: no branch per lane, and no record is copied again.
[[gnu::always_inline]] inline void to_records(const Int (&words)[16], std::uint64_t kept, RasterTriangle* records) {
#if defined(__AVX512F__)
    // The kept lanes first packed to the front of every word (one compress
    // gives the order, a permute per word applies it), then per 8 of them two
    // 8 × 8 transposes as AVX2 does, stored one record after another: rarely
    // more than 8 of 16 lanes are kept, so mostly half the transposes and stores.
    const __m512i order = _mm512_maskz_compress_epi32(
        __mmask16(kept), _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15));
    __m512 packed[16];
    for (int w = 0; w < 16; ++w) packed[w] = _mm512_castsi512_ps(_mm512_permutexvar_epi32(order, words[w]));
    const int halves = std::popcount(kept) > 8 ? 2 : 1;
    for (int half = 0; half < halves; ++half)
        for (int part = 0; part < 2; ++part) {
            __m256 r[8];
            for (int w = 0; w < 8; ++w) r[w] = simd::half_of(packed[8 * part + w], half);
            simd::transpose8x8(r);
            for (int j = 0; j < 8; ++j)
                _mm256_store_ps(reinterpret_cast<float*>(&records[8 * half + j]) + 8 * part, r[j]);
        }
#else
    std::size_t at[kLanes];  // lane j's slot: the kept lanes before it
    for (int j = 0; j < kLanes; ++j) at[j] = std::size_t(std::popcount(kept & ((std::uint64_t(1) << j) - 1)));
#if defined(__AVX2__)
    // Two 8 × 8 transposes: words 0-7 and 8-15, each lane's half of a record.
    for (int part = 0; part < 2; ++part) {
        __m256 r[8];
        for (int w = 0; w < 8; ++w) r[w] = _mm256_castsi256_ps(words[8 * part + w]);
        simd::transpose8x8(r);
        for (int j = 0; j < 8; ++j) _mm256_store_ps(reinterpret_cast<float*>(&records[at[j]]) + 8 * part, r[j]);
    }
#else  // SSE
    // Four 4 × 4 transposes, a quarter of each record each.
    for (int part = 0; part < 4; ++part) {
        __m128 r[4];
        for (int w = 0; w < 4; ++w) r[w] = _mm_castsi128_ps(words[4 * part + w]);
        _MM_TRANSPOSE4_PS(r[0], r[1], r[2], r[3]);
        for (int j = 0; j < 4; ++j) _mm_store_ps(reinterpret_cast<float*>(&records[at[j]]) + 4 * part, r[j]);
    }
#endif
#endif
}

// kMsaa: in.samples is 4. A constant, so that each form keeps only its own
// values in registers (one body for both spilled a quarter of its instructions).
template <bool kMsaa>
void setup_batch(const SetupBatchInput& in, SetupBatchOutput& out) {
    const Int half(kSubpixelScale / 2), round_up(kSubpixelScale - 1), zero(0), one(1);
    const Int last_x(in.width - 1), last_y(in.height - 1);
    const Mask cull_positive(in.culling == Culling::drop_positive_area);
    const Mask cull_negative(in.culling == Culling::drop_negative_area);
    // back_facing as setup_triangle(): swapped (GL's front) unless mirrored. As
    // integers: a mask made from a bool (Mask(true)) misbehaved with AVX-512's mask registers.
    const Int back_if_swapped(in.mirrored ? 1 : 0), back_if_kept(in.mirrored ? 0 : 1);
    // The points a pixel is tested at: its centre, or its 4 samples
    // (raster/msaa/msaa.hpp), which lie 1/8 to 7/8 of a pixel from its corner: the
    // box holds the pixels with a point between the triangle's extremes.
    constexpr bool msaa = kMsaa;
    constexpr int point_count = msaa ? kMsaaSamples : 1;
    const Int first_point(msaa ? 7 * kSubpixelScale / 8 : kSubpixelScale / 2);
    const Int last_point(msaa ? kSubpixelScale / 8 : kSubpixelScale / 2);
    const int padded = (in.count + kLanes - 1) / kLanes * kLanes;
    const Int first_vertex(in.first_vertex), vertex_count(in.vertex_count);
    alignas(64) std::int32_t lane_index[kLanes];
    for (int lane = 0; lane < kLanes; ++lane) lane_index[lane] = lane;
    // Corner references, for the whole batch first: the corner loads below read
    // them lane by lane, which is slow straight after a vector store. An index
    // out of range (as int32 too: vertex_count < 2^31) drops its triangle,
    // whose corners then read vertex 0 of the mesh.
    alignas(64) std::int32_t ref[3][kSetupBatch], valid[kSetupBatch];
    for (int i = 0; i < padded; i += kLanes) {
        Int index[3];
        load_indices(in.indices + 3 * i, index);
        Mask ok = (Int::load_aligned(lane_index) + Int(i)) < Int(in.count);
        for (int k = 0; k < 3; ++k) ok = ok & (index[k] >= zero) & (index[k] < vertex_count);
        for (int k = 0; k < 3; ++k) (first_vertex + xsimd::select(ok, index[k], zero)).store_aligned(ref[k] + i);
        xsimd::select(ok, Int(-1), zero).store_aligned(valid + i);
    }
    out.kept = out.scalar = out.clipped = 0;
    int records = 0;
    for (int i = 0; i < padded; i += kLanes) {
        const Mask valid_lanes = Int::load_aligned(valid + i) != zero;
        const Int refs[3] = {Int::load_aligned(ref[0] + i), Int::load_aligned(ref[1] + i), Int::load_aligned(ref[2] + i)};
        Corner corner[3];
        for (int k = 0; k < 3; ++k) corner[k] = load_corner(in.screen, ref[k] + i);
        // geometry::classify_triangle over the lanes.
        const Int any_outside = corner[0].outcode | corner[1].outcode | corner[2].outcode;
        const Mask rejected = ((any_outside & Int(geometry::kNotFinite)) != zero) |
                              ((corner[0].outcode & corner[1].outcode & corner[2].outcode) != zero);
        const Mask crosses = (any_outside & Int(geometry::kClipPlaneBits)) != zero;
        const Mask live = valid_lanes & !rejected;
        out.clipped |= lane_bits(live & crosses) << i;
        const Mask accepted = live & !crosses;
        // Positions: any values in lanes not accepted, which are masked off below.
        const Int x[3] = {corner[0].x, corner[1].x, corner[2].x}, y[3] = {corner[0].y, corner[1].y, corner[2].y};
        const Int min_x = xsimd::min(x[0], xsimd::min(x[1], x[2])), max_x = xsimd::max(x[0], xsimd::max(x[1], x[2]));
        const Int min_y = xsimd::min(y[0], xsimd::min(y[1], y[2])), max_y = xsimd::max(y[0], xsimd::max(y[1], y[2]));
        // Pixel box of the centres inside the extent (>> is floor division), clamped to the image.
        // With 4× MSAA, the pixels with a sample inside (triangle_setup.cpp).
        const Int px_min = xsimd::max((min_x - first_point + round_up) >> kSubpixelBits, zero);
        const Int px_max = xsimd::min((max_x - last_point) >> kSubpixelBits, last_x);
        const Int py_min = xsimd::max((min_y - first_point + round_up) >> kSubpixelBits, zero);
        const Int py_max = xsimd::min((max_y - last_point) >> kSubpixelBits, last_y);
        const Mask empty = (px_min > px_max) | (py_min > py_max);
        const Mask small_enough = ((max_x - min_x) < Int(kMaxExtent)) & ((max_y - min_y) < Int(kMaxExtent));

        const Int area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
        const Mask swapped = area < zero;
        const Int double_area = xsimd::abs(area);
        // Corners 1 and 2 as setup orders them.
        const Int x1 = xsimd::select(swapped, x[2], x[1]), y1 = xsimd::select(swapped, y[2], y[1]);
        const Int x2 = xsimd::select(swapped, x[1], x[2]), y2 = xsimd::select(swapped, y[1], y[2]);

        // Boxes of at most 2×2 pixels: is any of their centres (samples) covered?
        // Each edge is evaluated at the box's first centre, then stepped.
        const Int ax[3] = {x1, x2, x[0]}, ay[3] = {y1, y2, y[0]}, bx[3] = {x2, x[0], x1}, by[3] = {y2, y[0], y1};
        const Int first_px = px_min * Int(kSubpixelScale) + half, first_py = py_min * Int(kSubpixelScale) + half;
        Int edge[3], edge_dx[3], edge_dy[3];
        for (int k = 0; k < 3; ++k) {
            edge_dx[k] = bx[k] - ax[k], edge_dy[k] = by[k] - ay[k];
            edge[k] = biased_edge(ax[k], ay[k], bx[k], by[k], first_px, first_py);
        }
        const Mask second_column = (px_min + one) <= px_max, second_row = (py_min + one) <= py_max;
        Mask covered(false);
        for (int p = 0; p < point_count; ++p) {
            Int at_point[3];  // E at the point (x offset ox, y offset oy from the centre): E + dx·oy - dy·ox
            for (int k = 0; k < 3; ++k)
                at_point[k] = msaa ? edge[k] + edge_dx[k] * Int(kSampleOffsetY[p]) - edge_dy[k] * Int(kSampleOffsetX[p])
                                   : edge[k];
            for (int row = 0; row < 2; ++row)
                for (int column = 0; column < 2; ++column) {
                    Int e[3];
                    for (int k = 0; k < 3; ++k)  // one pixel right: -dy·256; down: +dx·256
                        e[k] = at_point[k] - Int(column) * (edge_dy[k] << kSubpixelBits) +
                               Int(row) * (edge_dx[k] << kSubpixelBits);
                    Mask inside = ((e[0] | e[1]) | e[2]) >= zero;
                    if (column) inside = inside & second_column;
                    if (row) inside = inside & second_row;
                    covered = covered | inside;
                }
        }
        const Mask small_box = ((px_max - px_min) <= one) & ((py_max - py_min) <= one);
        const Mask culled = (cull_positive & (area > zero)) | (cull_negative & swapped);

        // Every reason setup_triangle() has to drop a triangle; its order does not matter here.
        const Mask dropped = (area == zero) | culled | empty | (small_box & !covered);
        const Mask kept = accepted & small_enough & !dropped;
        out.scalar |= lane_bits(accepted & !small_enough & !empty) << i;
        const std::uint64_t kept_bits = lane_bits(kept);
        if (kept_bits == 0) continue;
        out.kept |= kept_bits << i;

        // The kept lanes' records, as setup_triangle() fills them: their 16
        // int32 words (RecordWords) a vector each, turned into one record per lane.
        const Int depth1 = xsimd::select(swapped, corner[2].depth, corner[1].depth);
        const Int depth2 = xsimd::select(swapped, corner[1].depth, corner[2].depth);
        // Division is correctly rounded in every ISA, as the scalar 1.0f / float(area) is.
        const Int inv_area = xsimd::bitwise_cast<Int>(Float(1.0f) / xsimd::to_float(double_area));
        const Int words[16] = {x[0], x1, x2, y[0], y1, y2,
                               px_min | (px_max << 16), py_min | (py_max << 16),  // int16 pairs, low half first
                               inv_area, corner[0].depth, depth1, depth2,
                               refs[0], xsimd::select(swapped, refs[2], refs[1]),
                               xsimd::select(swapped, refs[1], refs[2]),
                               xsimd::select(swapped, back_if_swapped, back_if_kept)};
        to_records(words, kept_bits, out.records + records);
        records += std::popcount(kept_bits);
    }
}

}  // namespace

void TESSERA_SIMD_ENTRY(setup_batch)(const SetupBatchInput& in, SetupBatchOutput& out) {
    if (in.samples == 1) setup_batch<false>(in, out);
    else setup_batch<true>(in, out);
}

}  // namespace tessera::raster
