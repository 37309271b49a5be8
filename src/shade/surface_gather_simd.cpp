// The fast gather's loops (surface_gather_fast.hpp), compiled once per ISA
// (cmake/SimdTargets.cmake) with -ffp-contract=off: every multiply and add is
// the reference's (surface_gather.hpp), lane by lane, never fused. The
// packing of covered pixels and the moves between records and channels need
// lane permutes and transposes that xsimd 8.1 lacks, hence the intrinsics;
// with AVX2, 8 fragments' barycentrics go as one vector and a fragment's
// WorldPos and Normal as another.
#include "simd/kernel_prelude.hpp"

#include <immintrin.h>

#include <array>
#include <cstring>

#include "shade/surface_gather_fast.hpp"
#include "simd/transpose.hpp"

namespace tessera::shade {
namespace {

// A vertex's WorldPos or Normal (at byte Offset) as (x, y, z, 0): one 16-byte
// load (the vec3 and the vertex's next float), the fourth lane cleared.
template <std::size_t Offset>
Float4 load_vec3(const geometry::ShadedVertex& v) {
    using Int4 = std::int32_t __attribute__((vector_size(16)));
    static_assert(Offset + sizeof(Float4) <= sizeof(geometry::ShadedVertex));
    Float4 x;
    std::memcpy(&x, reinterpret_cast<const char*>(&v) + Offset, sizeof x);
    return Float4(Int4(x) & Int4{-1, -1, -1, 0});
}
constexpr std::size_t kWorldPosOffset = offsetof(geometry::ShadedVertex, world_pos);
constexpr std::size_t kNormalOffset = offsetof(geometry::ShadedVertex, normal);
// Fragments per batch of the fast gather. Each of a batch's loops reads back
// what the loop before stored, in other widths; 256 rather than 64 measured
// 1.05-1.15x on the gather microbenchmark and 1.05x on the 4K spheres' shade
// step (Zen 5), perhaps as longer loops let those stores complete first.
constexpr std::size_t kBatch = 256;
static_assert(offsetof(GatheredTriangle, normal0) == offsetof(GatheredTriangle, world0) + 16 &&
                  offsetof(GatheredTriangle, normal_d1) == offsetof(GatheredTriangle, world_d1) + 16 &&
                  offsetof(GatheredTriangle, normal_d2) == offsetof(GatheredTriangle, world_d2) + 16,
              "a WorldPos and its Normal side by side, one 32-byte load");

// For each mask of Lanes bits, the indices of its set lanes packed to the front (the rest 0).
template <int Lanes>
constexpr std::array<std::array<std::uint32_t, Lanes>, (1 << Lanes)> packed_lanes() {
    std::array<std::array<std::uint32_t, Lanes>, (1 << Lanes)> table{};
    for (int mask = 0; mask < (1 << Lanes); ++mask) {
        int packed = 0;
        for (int lane = 0; lane < Lanes; ++lane)
            if (mask & (1 << lane)) table[mask][packed++] = std::uint32_t(lane);
    }
    return table;
}
// Lanes 0..3 as 32-bit integers, packed the same way: the pixel offsets.
constexpr auto kPackLanes4 = packed_lanes<4>();
alignas(16) constexpr auto kPackLanes4Aligned = kPackLanes4;
// The same as pshufb's byte indices: lane l's four bytes 4l..4l+3.
constexpr auto kPackBytes4 = [] {
    std::array<std::array<std::uint8_t, 16>, 16> table{};
    for (int mask = 0; mask < 16; ++mask)
        for (int k = 0; k < 4; ++k)
            for (int b = 0; b < 4; ++b) table[mask][4 * k + b] = std::uint8_t(4 * kPackLanes4[mask][k] + b);
    return table;
}();
alignas(16) constexpr auto kPackBytes4Aligned = kPackBytes4;

#if defined(__AVX2__)
// For each 8-bit mask, vpermd's lane indices that pack its set lanes to the front.
constexpr auto kPackLanes8 = packed_lanes<8>();
alignas(32) constexpr auto kPackLanes8Aligned = kPackLanes8;
// For each 8-bit mask, per lane the count of set bits up to and including it.
constexpr auto kInclusiveCounts8 = [] {
    std::array<std::array<std::uint32_t, 8>, 256> table{};
    for (int mask = 0; mask < 256; ++mask)
        for (int lane = 0, count = 0; lane < 8; ++lane) table[mask][lane] = std::uint32_t(count += (mask >> lane) & 1);
    return table;
}();
alignas(32) constexpr auto kInclusiveCounts8Aligned = kInclusiveCounts8;
#endif

// Packs a tile's covered pixels in the reference's order (rows, then x) into
// the table's lists: pixel, triangle id, λ1, λ2. No branch per pixel: a
// vector of pixels at a time, its covered lanes packed to the front by a table
// on the compare's mask and stored whole (the spare lanes land where the next
// ones go, or in the lists' slack). Returns the count.
std::size_t pack_covered_pixels(const raster::TileBuffers& tile, int width, int height, TriangleTable& table) {
    std::uint32_t* const pixels = table.pixels.data();
    std::uint32_t* const ids = table.ids.data();
    float* const lambda1 = table.lambda1.data();
    float* const lambda2 = table.lambda2.data();
    const float* const depth = tile.depth.data();
    const std::uint32_t* const triangle = tile.triangle.data();
    const float* const tile_lambda1 = tile.lambda1.data();
    const float* const tile_lambda2 = tile.lambda2.data();
    std::size_t count = 0;
    for (int y = 0; y < height; ++y) {
        const std::uint32_t row = std::uint32_t(y * tile.side);
        int x = 0;
        // covered(p) is depth < 1, false for NaN, as the ordered compares here.
#if defined(__AVX2__)
        for (; x + 8 <= width; x += 8) {
            const std::size_t p = row + std::uint32_t(x);
            const int mask =
                _mm256_movemask_ps(_mm256_cmp_ps(_mm256_loadu_ps(depth + p), _mm256_set1_ps(1.0f), _CMP_LT_OQ));
            const __m256i lanes = _mm256_load_si256(reinterpret_cast<const __m256i*>(kPackLanes8Aligned[mask].data()));
            _mm256_storeu_si256(reinterpret_cast<__m256i*>(pixels + count),
                                _mm256_add_epi32(lanes, _mm256_set1_epi32(int(p))));
            _mm256_storeu_si256(
                reinterpret_cast<__m256i*>(ids + count),
                _mm256_permutevar8x32_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(triangle + p)), lanes));
            _mm256_storeu_ps(lambda1 + count, _mm256_permutevar8x32_ps(_mm256_loadu_ps(tile_lambda1 + p), lanes));
            _mm256_storeu_ps(lambda2 + count, _mm256_permutevar8x32_ps(_mm256_loadu_ps(tile_lambda2 + p), lanes));
            count += std::size_t(__builtin_popcount(unsigned(mask)));
        }
#endif
        for (; x + 4 <= width; x += 4) {
            const std::size_t p = row + std::uint32_t(x);
            const int mask = _mm_movemask_ps(_mm_cmplt_ps(_mm_loadu_ps(depth + p), _mm_set1_ps(1.0f)));
            const __m128i bytes = _mm_load_si128(reinterpret_cast<const __m128i*>(kPackBytes4Aligned[mask].data()));
            const __m128i lanes = _mm_load_si128(reinterpret_cast<const __m128i*>(kPackLanes4Aligned[mask].data()));
            _mm_storeu_si128(reinterpret_cast<__m128i*>(pixels + count), _mm_add_epi32(lanes, _mm_set1_epi32(int(p))));
            const auto pack = [&](const void* from, void* to) {
                _mm_storeu_si128(static_cast<__m128i*>(to),
                                 _mm_shuffle_epi8(_mm_loadu_si128(static_cast<const __m128i*>(from)), bytes));
            };
            pack(triangle + p, ids + count), pack(tile_lambda1 + p, lambda1 + count);
            pack(tile_lambda2 + p, lambda2 + count);
            count += std::size_t(__builtin_popcount(unsigned(mask)));
        }
        for (; x < width; ++x) {
            const std::size_t p = row + std::uint32_t(x);
            pixels[count] = std::uint32_t(p), ids[count] = triangle[p];
            lambda1[count] = tile_lambda1[p], lambda2[count] = tile_lambda2[p];
            count += tile.covered(p) ? 1 : 0;
        }
    }
    return count;
}

// Four (x, y, z, ·) vectors into x[0..3], y[0..3], z[0..3].
inline void store_transposed(const Float4 (&v)[4], float* x, float* y, float* z) {
    __m128 r0 = __m128(v[0]), r1 = __m128(v[1]), r2 = __m128(v[2]), r3 = __m128(v[3]);
    _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
    _mm_storeu_ps(x, r0), _mm_storeu_ps(y, r1), _mm_storeu_ps(z, r2);
}

// raster::perspective_barycentrics of four fragments, lane k of triangle t[k]:
// the same IEEE operations, lane by lane.
inline void perspective_barycentrics4(const GatheredTriangle* const (&t)[4], const float* lambda1_of,
                                      const float* lambda2_of, float* b1_out, float* b2_out) {
    __m128 w0 = _mm_load_ps(t[0]->inv_w.lanes.data()), w1 = _mm_load_ps(t[1]->inv_w.lanes.data());
    __m128 w2 = _mm_load_ps(t[2]->inv_w.lanes.data()), w3 = _mm_load_ps(t[3]->inv_w.lanes.data());
    _MM_TRANSPOSE4_PS(w0, w1, w2, w3);  // w0, w1, w2: 1/w of corners 0, 1, 2 of the four triangles
    const __m128 lambda1 = _mm_loadu_ps(lambda1_of), lambda2 = _mm_loadu_ps(lambda2_of);
    const __m128 q0 = _mm_mul_ps(_mm_sub_ps(_mm_sub_ps(_mm_set1_ps(1.0f), lambda1), lambda2), w0);
    const __m128 q1 = _mm_mul_ps(lambda1, w1), q2 = _mm_mul_ps(lambda2, w2);
    const __m128 inv_sum = _mm_div_ps(_mm_set1_ps(1.0f), _mm_add_ps(_mm_add_ps(q0, q1), q2));
    _mm_store_ps(b1_out, _mm_mul_ps(q1, inv_sum)), _mm_store_ps(b2_out, _mm_mul_ps(q2, inv_sum));
}

#if defined(__AVX2__)
// The same for eight fragments.
inline void perspective_barycentrics8(const GatheredTriangle* const (&t)[8], const float* lambda1_of,
                                      const float* lambda2_of, float* b1_out, float* b2_out) {
    __m256 w[4];
    for (int k = 0; k < 4; ++k)
        w[k] = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_load_ps(t[k]->inv_w.lanes.data())),
                                    _mm_load_ps(t[k + 4]->inv_w.lanes.data()), 1);
    simd::transpose4x4_halves(w);  // w[0], w[1], w[2]: 1/w of corners 0, 1, 2 of the eight triangles
    const __m256 lambda1 = _mm256_loadu_ps(lambda1_of), lambda2 = _mm256_loadu_ps(lambda2_of);
    const __m256 q0 = _mm256_mul_ps(_mm256_sub_ps(_mm256_sub_ps(_mm256_set1_ps(1.0f), lambda1), lambda2), w[0]);
    const __m256 q1 = _mm256_mul_ps(lambda1, w[1]), q2 = _mm256_mul_ps(lambda2, w[2]);
    const __m256 inv_sum = _mm256_div_ps(_mm256_set1_ps(1.0f), _mm256_add_ps(_mm256_add_ps(q0, q1), q2));
    _mm256_store_ps(b1_out, _mm256_mul_ps(q1, inv_sum)), _mm256_store_ps(b2_out, _mm256_mul_ps(q2, inv_sum));
}
#endif

// The fast gather's state between fragments; the loop over fragments keeps
// its own in locals, and calls out of line only at a triangle the tile has
// not met yet, a change of material, and extras. XyOf(i): fragment i's tile pixel.
template <class XyOf>
class FastSurfaceGather {
public:
    FastSurfaceGather(const GatherCornerLookup& lookup, FragmentBuffer& out, std::vector<MaterialRun>& runs,
                      const float* lambda1, const float* lambda2, XyOf xy_of)
        : lookup_(lookup), out_(out), runs_(runs), table_(out.triangle_table()), lambda1_(lambda1),
          lambda2_(lambda2), xy_of_(xy_of) {
        runs_.clear();
    }

    // Gathers fragments k < count: fragment k is triangle ids[k], at screen-space λ1 λ2 lambda1[k], lambda2[k].
    std::size_t gather(std::size_t count, const std::uint32_t* ids) {
        table_.start_tile();
        return gather_fragments(count, ids, false);
    }
    // The same where ids[k] is a position in the tile's triangle list `triangles` (n long).
    std::size_t gather_positions(std::size_t count, const std::uint32_t* ids, const std::uint32_t* triangles,
                                 std::size_t n) {
        set_up(0, index_positions(table_, ids, count, triangles, n));
        return gather_fragments(count, ids, true);
    }

private:
    // indexed: every fragment has its entry (index_positions), and every entry is set up.
    std::size_t gather_fragments(std::size_t count, const std::uint32_t* ids, bool indexed) {
        using C = FragmentBuffer;
        float* const world_x = out_.channel(C::world_x);
        float* const world_y = out_.channel(C::world_y);
        float* const world_z = out_.channel(C::world_z);
        float* const normal_x = out_.channel(C::normal_x);
        float* const normal_y = out_.channel(C::normal_y);
        float* const normal_z = out_.channel(C::normal_z);
        const float* const lambda1 = lambda1_;
        const float* const lambda2 = lambda2_;
        std::uint32_t* const entry_of_fragment = table_.entry_of_fragment.data();
        // Entries by their offset in bytes: no multiply per fragment.
        const char* const entries = reinterpret_cast<const char*>(table_.entry.data());
        const auto entry_at = [entries](std::uint32_t offset) {
            return reinterpret_cast<const GatheredTriangle*>(entries + offset);
        };
        std::uintptr_t run_key = 0;  // the current run's material (no run yet: none)
        alignas(32) float batch_b1[kBatch], batch_b2[kBatch];  // perspective barycentrics of a batch's vectors
        // In batches. Not indexed, each in three loops, so that no branch depends
        // on whether a fragment's triangle is new (at 720p that was one miss per
        // ~2 fragments): which fragments meet a new triangle, without a branch;
        // the new triangles' set-ups; the fragments. An entry is indexed by
        // set-up, not by slot, so a later triangle in the same slot does not
        // overwrite it.
        std::size_t entry_count = 0;
        for (std::size_t begin = 0; begin < count; begin += kBatch) {
            const std::size_t end = std::min(count, begin + kBatch);
            if (!indexed) {
                const std::size_t first_new = entry_count;
                entry_count = probe(table_, ids, begin, end, entry_count);
                set_up(first_new, entry_count);
            }
            // First the batch's barycentrics as vectors (the reference's
            // operations lane by lane), in a loop of their own so that the
            // divisions of several vectors overlap; then, four fragments at a
            // time, their WorldPos and Normal, transposed into the channels.
            const std::size_t fours_end = begin + (end - begin) / 4 * 4;
            std::size_t i = begin;
#if defined(__AVX2__)
            for (; i + 8 <= fours_end; i += 8) {
                const GatheredTriangle* const t[8] = {
                    entry_at(entry_of_fragment[i]),     entry_at(entry_of_fragment[i + 1]),
                    entry_at(entry_of_fragment[i + 2]), entry_at(entry_of_fragment[i + 3]),
                    entry_at(entry_of_fragment[i + 4]), entry_at(entry_of_fragment[i + 5]),
                    entry_at(entry_of_fragment[i + 6]), entry_at(entry_of_fragment[i + 7])};
                perspective_barycentrics8(t, lambda1 + i, lambda2 + i, &batch_b1[i - begin], &batch_b2[i - begin]);
            }
#endif
            for (; i < fours_end; i += 4) {
                const GatheredTriangle* const t[4] = {entry_at(entry_of_fragment[i]), entry_at(entry_of_fragment[i + 1]),
                                                      entry_at(entry_of_fragment[i + 2]), entry_at(entry_of_fragment[i + 3])};
                perspective_barycentrics4(t, lambda1 + i, lambda2 + i, &batch_b1[i - begin], &batch_b2[i - begin]);
            }
            i = begin;
#if defined(__AVX512F__)
            // Eight fragments at a time, two to a vector: lanes 0-7 hold
            // fragment k's WorldPos and Normal, lanes 8-15 fragment k + 4's,
            // each b1 and b2 permuted out of one vector rather than broadcast
            // from memory; the same operations per lane as below.
            for (; i + 8 <= fours_end; i += 8) {
                const GatheredTriangle* t[8];
                for (int k = 0; k < 8; ++k) t[k] = entry_at(entry_of_fragment[i + k]);
                const float* const b1 = &batch_b1[i - begin];
                const float* const b2 = &batch_b2[i - begin];
                const __m512 b1s = _mm512_castps256_ps512(_mm256_load_ps(b1));
                const __m512 b2s = _mm512_castps256_ps512(_mm256_load_ps(b2));
                // A WorldPos and its Normal (8 floats from `field`) of t[k], then of t[k + 4].
                const auto pair = [&](int k, Float4 GatheredTriangle::*field) {
                    const auto at = [field](const GatheredTriangle* e) { return reinterpret_cast<const float*>(&(e->*field)); };
                    return simd::join_halves(_mm256_load_ps(at(t[k])), _mm256_load_ps(at(t[k + 4])));
                };
                __m512 point[4];
                for (int k = 0; k < 4; ++k) {
                    const __m512i pick = simd::join_halves(_mm256_set1_epi32(k), _mm256_set1_epi32(k + 4));
                    const __m512 corner0 = pair(k, &GatheredTriangle::world0), d1 = pair(k, &GatheredTriangle::world_d1),
                                 d2 = pair(k, &GatheredTriangle::world_d2);
                    point[k] = _mm512_add_ps(_mm512_add_ps(corner0, _mm512_mul_ps(_mm512_permutexvar_ps(pick, b1s), d1)),
                                             _mm512_mul_ps(_mm512_permutexvar_ps(pick, b2s), d2));
                }
                // point[c]: component c of the WorldPos of fragments 0-3, of their Normals,
                // of the WorldPos of 4-7, of their Normals; then the WorldPos quarters side by side.
                simd::transpose4x4_quarters(point);
                float* const world[3] = {world_x + i, world_y + i, world_z + i};
                float* const normal[3] = {normal_x + i, normal_y + i, normal_z + i};
                const __m512i quarters_0213 = _mm512_setr_epi32(0, 1, 2, 3, 8, 9, 10, 11, 4, 5, 6, 7, 12, 13, 14, 15);
                for (int c = 0; c < 3; ++c) {
                    const __m512 halves = _mm512_permutexvar_ps(quarters_0213, point[c]);
                    _mm256_storeu_ps(world[c], _mm512_castps512_ps256(halves));
                    _mm256_storeu_ps(normal[c], _mm512_extractf32x8_ps(halves, 1));
                }
                for (int k = 0; k < 8; ++k)
                    if (t[k]->run_key != run_key) [[unlikely]]
                        run_key = change_run_or_add_extras(i + k, *t[k], b1[k], b2[k]);
            }
#endif
            for (; i < fours_end; i += 4) {
                const GatheredTriangle* const t[4] = {entry_at(entry_of_fragment[i]), entry_at(entry_of_fragment[i + 1]),
                                                      entry_at(entry_of_fragment[i + 2]), entry_at(entry_of_fragment[i + 3])};
                const float* const b1 = &batch_b1[i - begin];
                const float* const b2 = &batch_b2[i - begin];
#if defined(__AVX2__)
                // A fragment's WorldPos and Normal as one vector: as the
                // reference's glm, (corner 0 + b1·d1) + b2·d2 per component.
                __m256 point[4];
                for (int k = 0; k < 4; ++k) {
                    const __m256 corner0 = _mm256_load_ps(reinterpret_cast<const float*>(&t[k]->world0));
                    const __m256 d1 = _mm256_load_ps(reinterpret_cast<const float*>(&t[k]->world_d1));
                    const __m256 d2 = _mm256_load_ps(reinterpret_cast<const float*>(&t[k]->world_d2));
                    point[k] = _mm256_add_ps(_mm256_add_ps(corner0, _mm256_mul_ps(_mm256_broadcast_ss(&b1[k]), d1)),
                                             _mm256_mul_ps(_mm256_broadcast_ss(&b2[k]), d2));
                }
                simd::transpose4x4_halves(point);  // point[c]: component c of the four WorldPos, then of the Normals
                float* const world[3] = {world_x + i, world_y + i, world_z + i};
                float* const normal[3] = {normal_x + i, normal_y + i, normal_z + i};
                for (int c = 0; c < 3; ++c) {
                    _mm_storeu_ps(world[c], _mm256_castps256_ps128(point[c]));
                    _mm_storeu_ps(normal[c], _mm256_extractf128_ps(point[c], 1));
                }
#else
                Float4 world[4], normal[4];
                for (int k = 0; k < 4; ++k) {
                    // As the reference's glm: (corner 0 + b1·d1) + b2·d2, per component.
                    world[k] = t[k]->world0 + b1[k] * t[k]->world_d1 + b2[k] * t[k]->world_d2;
                    normal[k] = t[k]->normal0 + b1[k] * t[k]->normal_d1 + b2[k] * t[k]->normal_d2;
                }
                store_transposed(world, world_x + i, world_y + i, world_z + i);
                store_transposed(normal, normal_x + i, normal_y + i, normal_z + i);
#endif
                for (int k = 0; k < 4; ++k)
                    if (t[k]->run_key != run_key) [[unlikely]]
                        run_key = change_run_or_add_extras(i + k, *t[k], b1[k], b2[k]);
            }
            for (; i < end; ++i) {
                const GatheredTriangle& t = *entry_at(entry_of_fragment[i]);
                const auto [b1, b2] = raster::perspective_barycentrics(t.inv_w.lanes, lambda1[i], lambda2[i]);
                const Float4 world = t.world0 + b1 * t.world_d1 + b2 * t.world_d2;
                const Float4 normal = t.normal0 + b1 * t.normal_d1 + b2 * t.normal_d2;
                world_x[i] = world[0], world_y[i] = world[1], world_z[i] = world[2];
                normal_x[i] = normal[0], normal_y[i] = normal[1], normal_z[i] = normal[2];
                if (t.run_key != run_key) [[unlikely]]
                    run_key = change_run_or_add_extras(i, t, b1, b2);
            }
        }
        if (!runs_.empty()) end_run(count);
        out_.pad(count);
        return count;
    }

    // Which of fragments [begin, end) meet a triangle the table lacks: each gets
    // its triangle's entry (in bytes: entry_of_fragment), new triangles a new
    // one, listed in new_id. Returns the new entry count. Out of line, so that
    // the loops have the registers to themselves.
    //
    // Fragments in a row mostly share a triangle: only the first of such a run
    // (its head) probes the table, so that consecutive probes seldom meet the
    // same slot. A probe right after one that wrote the same slot waits for
    // that store (~6 cycles of store forwarding, on the spheres at 4K most
    // fragments), where probes of different slots overlap.
    [[gnu::noinline]] static std::size_t probe(TriangleTable& table, const std::uint32_t* ids, std::size_t begin,
                                               std::size_t end, std::size_t entry_count) {
        constexpr std::uint32_t kEntryBytes = sizeof(GatheredTriangle);
        TriangleTable::Slot* const slots = table.slots.data();
        std::uint32_t* const new_ids = table.new_id.data();
        const std::uint32_t* const head_id = table.head_id.data();
        std::uint32_t* const head_slot = table.head_slot.data();
        std::uint32_t* const head_entry = table.head_entry.data();
        const std::size_t heads = find_heads(table, ids, begin, end);
        std::size_t h = 0;
#if defined(__AVX2__)
        // Their table slots, 8 at a time (TriangleTable::slot).
        for (; h + 8 <= heads; h += 8) {
            const __m256i id = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(head_id + h));
            const __m256i hash = _mm256_xor_si256(_mm256_xor_si256(id, _mm256_srli_epi32(id, 11)), _mm256_srli_epi32(id, 17));
            _mm256_storeu_si256(reinterpret_cast<__m256i*>(head_slot + h),
                                _mm256_and_si256(hash, _mm256_set1_epi32(int(TriangleTable::kSize - 1))));
        }
#endif
        for (; h < heads; ++h) head_slot[h] = std::uint32_t(TriangleTable::slot(head_id[h]));
        for (h = 0; h < heads; ++h) {
            const std::uint32_t id = head_id[h];
            TriangleTable::Slot& slot = slots[head_slot[h]];
            new_ids[entry_count] = id;  // kept where new
            // entry = slot.triangle != id ? the next entry : slot.entry, without
            // a branch (which would mispredict once per triangle): g++ makes a
            // branch of every C++ form of this select, hence the asm.
            std::uint32_t entry = slot.entry;
            bool is_new;
            asm("cmpl %[id], %[triangle]\n\tcmovne %[next], %[entry]"
                : [entry] "+r"(entry), "=@ccne"(is_new)
                : [id] "r"(id), [triangle] "m"(slot.triangle), [next] "r"(std::uint32_t(entry_count) * kEntryBytes));
            slot.triangle = id, slot.entry = entry;
            head_entry[h] = entry;
            entry_count += std::size_t(is_new);
        }
        spread_head_entries(table, begin, end);
        return entry_count;
    }

    // A tile whose fragments' ids are positions in its triangle list
    // (`triangles`, n long; raster::TileBuffers::triangles): every position a fragment
    // shows gets an entry, in the list's order, and each fragment its entry,
    // with no table to probe. One pass marks the positions the heads show,
    // one numbers them (listing their triangles in new_id), one gives each
    // head its entry: no load waits for a store just made, as a probe's of a
    // slot the probe before wrote does. Returns the entry count.
    [[gnu::noinline]] static std::size_t index_positions(TriangleTable& table, const std::uint32_t* ids,
                                                         std::size_t count, const std::uint32_t* triangles,
                                                         std::size_t n) {
        constexpr std::uint32_t kEntryBytes = sizeof(GatheredTriangle);
        if (count == 0) return 0;
        if (table.shown.size() < n) table.shown.resize(n), table.entry_of_position.resize(n);  // grows, not per tile
        std::uint8_t* const shown = table.shown.data();  // all 0 between tiles
        std::uint32_t* const entry_of_position = table.entry_of_position.data();
        std::uint32_t* const new_ids = table.new_id.data();
        const std::uint32_t* const head_id = table.head_id.data();
        std::uint32_t* const head_entry = table.head_entry.data();
        const std::size_t heads = find_heads(table, ids, 0, count);
        for (std::size_t h = 0; h < heads; ++h) shown[head_id[h]] = 1;
        std::uint32_t entries = 0;
        std::size_t p = 0;
#if defined(__AVX2__)
        static_assert(kEntryBytes == 1u << 7, "an entry's offset is its index << 7");
        // Eight positions at a time: their shown bytes (0 or 1) as a mask, the
        // shown ones' triangles packed to the front (new_id has kPackSlack
        // spare lanes), their entries from the counts up to each (the lanes
        // not shown get values no fragment reads).
        for (; p + 8 <= n; p += 8) {
            std::uint64_t bytes;
            std::memcpy(&bytes, shown + p, sizeof bytes);
            std::memset(shown + p, 0, sizeof bytes);
            const unsigned mask = unsigned(_pext_u64(bytes, 0x0101010101010101u));
            const __m256i counts =
                _mm256_load_si256(reinterpret_cast<const __m256i*>(kInclusiveCounts8Aligned[mask].data()));
            _mm256_storeu_si256(reinterpret_cast<__m256i*>(entry_of_position + p),
                                _mm256_slli_epi32(_mm256_add_epi32(counts, _mm256_set1_epi32(int(entries) - 1)), 7));
            const __m256i lanes = _mm256_load_si256(reinterpret_cast<const __m256i*>(kPackLanes8Aligned[mask].data()));
            _mm256_storeu_si256(
                reinterpret_cast<__m256i*>(new_ids + entries),
                _mm256_permutevar8x32_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(triangles + p)), lanes));
            entries += std::uint32_t(__builtin_popcount(mask));
        }
#endif
        for (; p < n; ++p) {
            entry_of_position[p] = entries * kEntryBytes;
            new_ids[entries] = triangles[p];  // kept where shown (new_id has a spare element)
            entries += shown[p];
            shown[p] = 0;
        }
        for (std::size_t h = 0; h < heads; ++h) head_entry[h] = entry_of_position[head_id[h]];
        spread_head_entries(table, 0, count);
        return entries;
    }

    // The heads of fragments [begin, end) (the first of each run of fragments
    // of one triangle): their ids in head_id, and for each fragment its head's
    // index in head_of_fragment. Returns the head count.
    static std::size_t find_heads(TriangleTable& table, const std::uint32_t* ids, std::size_t begin, std::size_t end) {
        std::uint32_t* const head_of_fragment = table.head_of_fragment.data();
        std::uint32_t* const head_id = table.head_id.data();
        // Without a branch.
        std::size_t heads = 0, i = begin;
        std::uint32_t previous = ~ids[begin];
#if defined(__AVX2__)
        // Eight fragments at a time: those whose id differs from the one
        // before, their ids packed to the front (a table on the compare's mask).
        if (end - begin > 8) {
            head_id[0] = ids[begin], head_of_fragment[begin] = 0, heads = 1;
            for (i = begin + 1; i + 8 <= end; i += 8) {
                const __m256i id = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(ids + i));
                const __m256i before = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(ids + i - 1));
                const int mask = ~_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(id, before))) & 0xff;
                const __m256i lanes =
                    _mm256_load_si256(reinterpret_cast<const __m256i*>(kPackLanes8Aligned[mask].data()));
                _mm256_storeu_si256(reinterpret_cast<__m256i*>(head_id + heads), _mm256_permutevar8x32_epi32(id, lanes));
                const __m256i counts =
                    _mm256_load_si256(reinterpret_cast<const __m256i*>(kInclusiveCounts8Aligned[mask].data()));
                _mm256_storeu_si256(reinterpret_cast<__m256i*>(head_of_fragment + i),
                                    _mm256_add_epi32(counts, _mm256_set1_epi32(int(heads) - 1)));
                heads += std::size_t(__builtin_popcount(unsigned(mask)));
            }
            previous = ids[i - 1];
        }
#endif
        for (; i < end; ++i) {
            const std::uint32_t id = ids[i];
            head_id[heads] = id;  // kept where a head
            heads += std::size_t(id != previous);
            head_of_fragment[i] = std::uint32_t(heads - 1);
            previous = id;
        }
        return heads;
    }

    // Each of fragments [begin, end) gets its head's entry (head_entry) in entry_of_fragment.
    static void spread_head_entries(TriangleTable& table, std::size_t begin, std::size_t end) {
        std::uint32_t* const entry_of_fragment = table.entry_of_fragment.data();
        const std::uint32_t* const head_of_fragment = table.head_of_fragment.data();
        const std::uint32_t* const head_entry = table.head_entry.data();
        std::size_t i = begin;
#if defined(__AVX2__)
        // Eight fragments' heads are at most eight consecutive ones (each
        // fragment's is its predecessor's or the next): one load from the
        // first lane's and a permute, rather than a gather (~17 cycles on
        // this project's AMD VMs). head_entry has kPackSlack spare lanes.
        for (; i + 8 <= end; i += 8) {
            const __m256i head = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(head_of_fragment + i));
            const std::uint32_t first = std::uint32_t(_mm256_cvtsi256_si32(head));
            const __m256i entries = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(head_entry + first));
            _mm256_storeu_si256(reinterpret_cast<__m256i*>(entry_of_fragment + i),
                                _mm256_permutevar8x32_epi32(entries, _mm256_sub_epi32(head, _mm256_set1_epi32(int(first)))));
        }
#endif
        for (; i < end; ++i) entry_of_fragment[i] = head_entry[head_of_fragment[i]];
    }

    // Sets up entries [begin, end), their triangles listed in new_id: one loop
    // out of line rather than a call per entry, so that the set-ups, each
    // waiting on its record and corners, overlap (shade 1.06× at 720p).
    [[gnu::noinline]] void set_up(std::size_t begin, std::size_t end) {
        const std::uint32_t* const new_ids = table_.new_id.data();
        for (std::size_t e = begin; e < end; ++e) set_up_one(e, new_ids[e]);
    }

    // Sets up triangle `id` in table entry `entry`, as SurfaceGather::add sets up
    // its cached triangle, operation for operation: from its chunk's plain
    // arrays, the full TriangleCorners only beyond plain.
    [[gnu::always_inline]] void set_up_one(std::size_t entry, std::uint32_t id) {
        GatheredTriangle& t = table_.entry[entry];
        const GatherChunk& chunk = lookup_.chunk_of(id);
        const raster::RasterTriangle& triangle = lookup_.triangle_of(id);
        const geometry::ShadedVertex* const corner[3] = {&lookup_.vertex(chunk, triangle.vertex[0]),
                                                         &lookup_.vertex(chunk, triangle.vertex[1]),
                                                         &lookup_.vertex(chunk, triangle.vertex[2])};
        set_up_geometry(t, corner);
        if (triangle.back_facing) [[unlikely]]  // as SurfaceGather::add: the normal negated (exactly)
            t.normal0 = -t.normal0, t.normal_d1 = -t.normal_d1, t.normal_d2 = -t.normal_d2;
        t.beyond_plain = chunk.beyond_plain;
        t.textured = false;
        t.run_key = reinterpret_cast<std::uintptr_t>(chunk.material) | std::uintptr_t(chunk.beyond_plain);
        if (chunk.beyond_plain) [[unlikely]]
            set_up_extras(entry, t, id);
    }

    // 1/w and the corner differences: lane-wise IEEE operations, the same
    // bits per component as the reference's scalar ones.
    static void set_up_geometry(GatheredTriangle& t, const geometry::ShadedVertex* const (&corner)[3]) {
        const Float4 w = {corner[0]->clip_pos.w, corner[1]->clip_pos.w, corner[2]->clip_pos.w, 1.0f};
        const Float4 inv_w = Float4{1.0f, 1.0f, 1.0f, 1.0f} / w;
        static_assert(sizeof t.inv_w == sizeof inv_w);
        std::memcpy(&t.inv_w, &inv_w, sizeof inv_w);
        const Float4 world0 = load_vec3<kWorldPosOffset>(*corner[0]);
        const Float4 normal0 = load_vec3<kNormalOffset>(*corner[0]);
        t.world0 = world0;
        t.world_d1 = load_vec3<kWorldPosOffset>(*corner[1]) - world0;
        t.world_d2 = load_vec3<kWorldPosOffset>(*corner[2]) - world0;
        t.normal0 = normal0;
        t.normal_d1 = load_vec3<kNormalOffset>(*corner[1]) - normal0;
        t.normal_d2 = load_vec3<kNormalOffset>(*corner[2]) - normal0;
    }

    // A beyond-plain triangle: its whole corners and texture coordinates for the extras.
    [[gnu::noinline]] void set_up_extras(std::size_t entry, GatheredTriangle& t, std::uint32_t id) {
        const TriangleCorners c = lookup_.corners(id);
        t.textured = c.material->has_maps();
        GatheredTriangleExtras& e = table_.extras[entry];
        e.corners = c;
        e.uv0 = c.corner[0]->uv;
        e.uv_d1 = c.corner[1]->uv - e.uv0, e.uv_d2 = c.corner[2]->uv - e.uv0;
    }

    // The last run ends before fragment i. A plain run's material channels stay
    // unfilled (the kernels take its material from the run); in a run that is
    // not, the plain fragments after the last beyond-plain one get theirs.
    void end_run(std::size_t i) {
        MaterialRun& run = runs_.back();
        run.end = std::uint32_t(i);
        if (!run.plain) out_.set_material(material_filled_, i, *run.material);
    }

    // Fragment i (at perspective-correct b1 b2) is of another material than
    // the run's, or beyond plain: a new run begins at it, or it gets its
    // extras, or both. Returns the run's key (its material's address).
    [[gnu::noinline]] std::uintptr_t change_run_or_add_extras(std::size_t i, const GatheredTriangle& t, float b1,
                                                              float b2) {
        if (runs_.empty() || runs_.back().material != t.material()) {
            if (!runs_.empty()) end_run(i);
            material_filled_ = i;
            detail::push_run(runs_, {std::uint32_t(i), 0, t.material(), t.textured, true});
        }
        if (t.beyond_plain) add_extras_at(i, std::size_t(&t - table_.entry.data()), b1, b2);
        return reinterpret_cast<std::uintptr_t>(t.material());
    }

    // Fragment i is textured, vertex-coloured or blended: its run is not plain;
    // its material channels now, and those of the run's fragments before it
    // (the colours multiply them), then the reference's extras.
    void add_extras_at(std::size_t i, std::size_t entry, float b1, float b2) {
        runs_.back().plain = false;
        out_.set_material(material_filled_, i + 1, *runs_.back().material);
        material_filled_ = i + 1;
        const auto [x, y] = xy_of_(i);
        detail::add_gathered_extras(table_.entry[entry], table_.extras[entry], x, y, lambda1_[i], lambda2_[i], b1, b2,
                                    out_, i);
    }

    const GatherCornerLookup& lookup_;
    FragmentBuffer& out_;
    std::vector<MaterialRun>& runs_;
    TriangleTable& table_;
    const float* const lambda1_;
    const float* const lambda2_;
    const XyOf xy_of_;
    std::size_t material_filled_ = 0;  // fragments from here to the current one are plain, of the run's material, unfilled
};

}  // namespace

std::size_t TESSERA_SIMD_ENTRY(gather_tile)(const raster::TileBuffers& tile, int width, int height,
                                            const GatherCornerLookup& lookup, FragmentBuffer& out,
                                            std::vector<MaterialRun>& runs) {
    TriangleTable& table = out.triangle_table();
    const std::size_t count = pack_covered_pixels(tile, width, height, table);
    const std::uint32_t* const pixels = table.pixels.data();
    const int side = tile.side;
    const auto xy_of = [pixels, side](std::size_t i) {
        return std::pair<int, int>(int(pixels[i]) % side, int(pixels[i]) / side);
    };
    FastSurfaceGather gather(lookup, out, runs, table.lambda1.data(), table.lambda2.data(), xy_of);
    return gather.gather_positions(count, table.ids.data(), tile.triangles.ids.data(), tile.triangles.count);
}

std::size_t TESSERA_SIMD_ENTRY(gather_fragment_list)(const raster::TileFragments& fragments,
                                                     const GatherCornerLookup& lookup, FragmentBuffer& out,
                                                     std::vector<MaterialRun>& runs) {
    const std::uint16_t* const x = fragments.x.data();
    const std::uint16_t* const y = fragments.y.data();
    const auto xy_of = [x, y](std::size_t i) { return std::pair<int, int>(x[i], y[i]); };
    FastSurfaceGather gather(lookup, out, runs, fragments.lambda1.data(), fragments.lambda2.data(), xy_of);
    return gather.gather(fragments.count, fragments.triangle.data());
}

}  // namespace tessera::shade
