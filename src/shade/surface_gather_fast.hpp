// The gather the SIMD ISAs run: the same fragments, runs and bits as the
// reference gather (surface_gather.hpp), which `--isa scalar` runs, with less
// work per triangle and per fragment:
//  - a triangle is set up (looked up, 1/w and the corner differences worked
//    out) once per tile, in a per-tile table (TriangleTable), where the
//    reference does it at every change of triangle along a row — on the
//    spheres at 4K ~3.7 times per visible triangle;
//  - given a SplitCornerLookup, a plain triangle's set-up looks up only its
//    corners and material (the full TriangleCorners only beyond plain): at
//    720p, with ~1.3 px triangles, there is a set-up per ~2 fragments;
//  - plain fragments (untextured, no vertex colours, not blended) get no
//    material channels: a run of them is marked plain (MaterialRun::plain),
//    and the kernels (shade_fragment_runs) take its material from the run;
//    FragmentBuffer::fill_plain_runs fills them where channels are read;
//  - the covered pixels are listed without a branch per pixel;
//  - fragments go four at a time: their barycentrics as one vector (a
//    batch's first, in a loop of their own), WorldPos and Normal as 4-float
//    vectors (Float4) transposed into the channels; the same IEEE operations
//    per lane and component as the reference's glm;
//  - the table is probed for a batch of fragments without a branch, then the
//    batch's new triangles are set up, then its fragments gathered: the
//    probe's miss (once per triangle of the tile) is no mispredicted branch;
//  - the set-up, the run changes and the extras stay out of line, so the
//    per-fragment loop keeps its state in registers.
// Textured, vertex-coloured and blended fragments get the reference's scalar
// extras (detail::add_extras, which the reference gather calls too).
#pragma once

#include <cstddef>
#include <cstring>
#include <utility>

#include <xmmintrin.h>
#include <emmintrin.h>

#include "shade/surface_gather.hpp"

namespace tessera::shade {

// What the fast gather's set-up needs of a triangle before it knows whether
// the triangle is plain: its corners and material, and whether it is beyond
// plain (textured, vertex-coloured or blended), which a renderer knows per
// chunk of one object rather than per triangle.
struct PlainCorners {
    const geometry::ShadedVertex* corner[3];
    const Material* material;
    bool beyond_plain;
};

// A lookup in two forms: plain(id) gives PlainCorners, full(id) the whole
// TriangleCorners (asked by the fast gather only where beyond_plain). Called
// as a function it is full(id), the lookup the reference gather takes.
template <class Plain, class Full>
struct SplitCornerLookup {
    Plain plain;
    Full full;
    TriangleCorners operator()(std::uint32_t id) const { return full(id); }
};
template <class Plain, class Full>
SplitCornerLookup(Plain, Full) -> SplitCornerLookup<Plain, Full>;

namespace detail {

// A vertex's WorldPos or Normal (at byte Offset) as (x, y, z, 0): one 16-byte
// load (the vec3 and the vertex's next float), the fourth lane cleared.
template <std::size_t Offset>
inline Float4 load_vec3(const geometry::ShadedVertex& v) {
    using Int4 = std::int32_t __attribute__((vector_size(16)));
    static_assert(Offset + sizeof(Float4) <= sizeof(geometry::ShadedVertex));
    Float4 x;
    std::memcpy(&x, reinterpret_cast<const char*>(&v) + Offset, sizeof x);
    return Float4(Int4(x) & Int4{-1, -1, -1, 0});
}
inline constexpr std::size_t kWorldPosOffset = offsetof(geometry::ShadedVertex, world_pos);
inline constexpr std::size_t kNormalOffset = offsetof(geometry::ShadedVertex, normal);
inline constexpr std::size_t kBatch = 64;  // fragments per batch of the fast gather

// For each 4-bit mask, the indices of its set bits packed to the front (the rest 0).
alignas(16) inline constexpr std::uint32_t kPackedLanes[16][4] = {
    {0, 0, 0, 0}, {0, 0, 0, 0}, {1, 0, 0, 0}, {0, 1, 0, 0}, {2, 0, 0, 0}, {0, 2, 0, 0}, {1, 2, 0, 0}, {0, 1, 2, 0},
    {3, 0, 0, 0}, {0, 3, 0, 0}, {1, 3, 0, 0}, {0, 1, 3, 0}, {2, 3, 0, 0}, {0, 2, 3, 0}, {1, 2, 3, 0}, {0, 1, 2, 3}};
// Set bits of each 4-bit mask (x86-64's baseline has no popcnt).
inline constexpr std::uint8_t kSetBits[16] = {0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4};

// raster::perspective_barycentrics of four fragments, lane k of triangle t[k]:
// the same IEEE operations, lane by lane.
inline std::pair<Float4, Float4> perspective_barycentrics4(const GatheredTriangle* const (&t)[4], const Float4& lambda1,
                                                           const Float4& lambda2) {
    __m128 w0 = _mm_load_ps(t[0]->inv_w.lanes.data()), w1 = _mm_load_ps(t[1]->inv_w.lanes.data());
    __m128 w2 = _mm_load_ps(t[2]->inv_w.lanes.data()), w3 = _mm_load_ps(t[3]->inv_w.lanes.data());
    _MM_TRANSPOSE4_PS(w0, w1, w2, w3);  // w0, w1, w2: 1/w of corners 0, 1, 2 of the four triangles
    const Float4 q0 = (1.0f - lambda1 - lambda2) * Float4(w0), q1 = lambda1 * Float4(w1), q2 = lambda2 * Float4(w2);
    const Float4 inv_sum = 1.0f / (q0 + q1 + q2);
    return {q1 * inv_sum, q2 * inv_sum};
}

// Four (x, y, z, ·) vectors into x[0..3], y[0..3], z[0..3].
inline void store_transposed(const Float4 (&v)[4], float* x, float* y, float* z) {
    __m128 r0 = __m128(v[0]), r1 = __m128(v[1]), r2 = __m128(v[2]), r3 = __m128(v[3]);
    _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
    _mm_storeu_ps(x, r0), _mm_storeu_ps(y, r1), _mm_storeu_ps(z, r2);
}

// The fast gather's state between fragments; the loop over fragments
// (gather_fragments) keeps its own in locals, and calls out of line only at a
// triangle the tile has not met yet, a change of material, and extras.
template <class Lookup>
class FastSurfaceGather {
public:
    FastSurfaceGather(Lookup& lookup, FragmentBuffer& out, std::vector<MaterialRun>& runs)
        : lookup_(lookup), out_(out), runs_(runs), table_(out.triangle_table()) {
        runs_.clear();
        table_.start_tile();
    }

    // Gathers fragments k < count: fragment k is triangle id(k) at tile pixel
    // xy(k) = (x, y) (asked only for extras), screen-space λ1 λ2 lambda1(k), lambda2(k).
    template <class Id, class Lambda1, class Lambda2, class Xy>
    std::size_t gather(std::size_t count, Id&& id_of, Lambda1&& lambda1_of, Lambda2&& lambda2_of, Xy&& xy_of) {
        using C = FragmentBuffer;
        float* const world_x = out_.channel(C::world_x);
        float* const world_y = out_.channel(C::world_y);
        float* const world_z = out_.channel(C::world_z);
        float* const normal_x = out_.channel(C::normal_x);
        float* const normal_y = out_.channel(C::normal_y);
        float* const normal_z = out_.channel(C::normal_z);
        const std::uint64_t key_base = std::uint64_t(table_.epoch) << 32;
        std::uint64_t* const tags = table_.tag.data();
        std::uint32_t* const entry_of_slot = table_.entry_of_slot.data();
        std::uint32_t* const entry_of_fragment = table_.entry_of_fragment.data();
        std::uint32_t* const new_ids = table_.new_id.data();
        const GatheredTriangle* const entries = table_.entry.data();
        const Material* run_material = nullptr;
        std::size_t entry_count = 0;
        alignas(16) float batch_b1[kBatch], batch_b2[kBatch];  // perspective barycentrics of a batch's fours
        // In batches, each in three loops, so that no branch depends on whether
        // a fragment's triangle is new (at 720p that was one miss per ~2 fragments):
        // which fragments meet a new triangle, without a branch; the new
        // triangles' set-ups; the fragments. An entry is indexed by set-up, not
        // by slot, so a later triangle in the same slot does not overwrite it.
        for (std::size_t begin = 0; begin < count; begin += kBatch) {
            const std::size_t end = std::min(count, begin + kBatch), first_new = entry_count;
            for (std::size_t i = begin; i < end; ++i) {
                const std::uint32_t id = id_of(i);
                const std::size_t slot = TriangleTable::slot(id);
                const bool is_new = tags[slot] != (key_base | id);
                tags[slot] = key_base | id;
                new_ids[entry_count] = id;  // kept where is_new
                // A mask, not ?:, which g++ compiles to a branch here.
                const std::uint32_t new_mask = 0u - std::uint32_t(is_new);
                const std::uint32_t entry = (std::uint32_t(entry_count) & new_mask) | (entry_of_slot[slot] & ~new_mask);
                entry_of_slot[slot] = entry;
                entry_of_fragment[i] = entry;
                entry_count += std::size_t(is_new);
            }
            for (std::size_t e = first_new; e < entry_count; ++e) set_up(e, new_ids[e]);
            // Four fragments at a time: first the batch's barycentrics as
            // vectors (the reference's operations lane by lane), in a loop of
            // its own so that the divisions of several fours overlap; then
            // their WorldPos and Normal as 4-float vectors each, transposed
            // into the channels.
            const std::size_t fours_end = begin + (end - begin) / 4 * 4;
            for (std::size_t i = begin; i < fours_end; i += 4) {
                const GatheredTriangle* const t[4] = {&entries[entry_of_fragment[i]], &entries[entry_of_fragment[i + 1]],
                                                      &entries[entry_of_fragment[i + 2]],
                                                      &entries[entry_of_fragment[i + 3]]};
                const Float4 lambda1 = {lambda1_of(i), lambda1_of(i + 1), lambda1_of(i + 2), lambda1_of(i + 3)};
                const Float4 lambda2 = {lambda2_of(i), lambda2_of(i + 1), lambda2_of(i + 2), lambda2_of(i + 3)};
                const auto [b1, b2] = perspective_barycentrics4(t, lambda1, lambda2);
                std::memcpy(&batch_b1[i - begin], &b1, sizeof b1);
                std::memcpy(&batch_b2[i - begin], &b2, sizeof b2);
            }
            std::size_t i = begin;
            for (; i < fours_end; i += 4) {
                const std::uint32_t entry[4] = {entry_of_fragment[i], entry_of_fragment[i + 1],
                                                entry_of_fragment[i + 2], entry_of_fragment[i + 3]};
                const GatheredTriangle* const t[4] = {&entries[entry[0]], &entries[entry[1]], &entries[entry[2]],
                                                      &entries[entry[3]]};
                Float4 b1, b2;
                std::memcpy(&b1, &batch_b1[i - begin], sizeof b1);
                std::memcpy(&b2, &batch_b2[i - begin], sizeof b2);
                Float4 world[4], normal[4];
                for (int k = 0; k < 4; ++k) {
                    // As the reference's glm: (corner 0 + b1·d1) + b2·d2, per component.
                    world[k] = t[k]->world0 + b1[k] * t[k]->world_d1 + b2[k] * t[k]->world_d2;
                    normal[k] = t[k]->normal0 + b1[k] * t[k]->normal_d1 + b2[k] * t[k]->normal_d2;
                }
                store_transposed(world, world_x + i, world_y + i, world_z + i);
                store_transposed(normal, normal_x + i, normal_y + i, normal_z + i);
                for (int k = 0; k < 4; ++k) {
                    if (t[k]->material != run_material) [[unlikely]]
                        run_material = start_run(*t[k], i + k);
                    if (t[k]->beyond_plain) [[unlikely]] {
                        const auto [x, y] = xy_of(i + k);
                        add_extras_at(i + k, entry[k], x, y, lambda1_of(i + k), lambda2_of(i + k), b1[k], b2[k]);
                    }
                }
            }
            for (; i < end; ++i) {
                const float lambda1 = lambda1_of(i), lambda2 = lambda2_of(i);
                const std::size_t entry = entry_of_fragment[i];
                const GatheredTriangle& t = entries[entry];
                if (t.material != run_material) [[unlikely]]
                    run_material = start_run(t, i);
                const auto [b1, b2] = raster::perspective_barycentrics(t.inv_w.lanes, lambda1, lambda2);
                const Float4 world = t.world0 + b1 * t.world_d1 + b2 * t.world_d2;
                const Float4 normal = t.normal0 + b1 * t.normal_d1 + b2 * t.normal_d2;
                world_x[i] = world[0], world_y[i] = world[1], world_z[i] = world[2];
                normal_x[i] = normal[0], normal_y[i] = normal[1], normal_z[i] = normal[2];
                if (t.beyond_plain) [[unlikely]] {
                    const auto [x, y] = xy_of(i);
                    add_extras_at(i, entry, x, y, lambda1, lambda2, b1, b2);
                }
            }
        }
        if (!runs_.empty()) end_run(count);
        out_.pad(count);
        return count;
    }

private:
    // Sets up triangle `id` in table entry `entry`, as SurfaceGather::add sets up
    // its cached triangle, operation for operation. A SplitCornerLookup's plain
    // form serves plain triangles; the full TriangleCorners only the others.
    [[gnu::noinline]] void set_up(std::size_t entry, std::uint32_t id) {
        GatheredTriangle& t = table_.entry[entry];
        if constexpr (requires { lookup_.plain(id); }) {
            const PlainCorners p = lookup_.plain(id);
            set_up_geometry(t, p.corner, p.material);
            t.beyond_plain = p.beyond_plain;
            t.textured = false;
            if (p.beyond_plain) [[unlikely]]
                set_up_extras_of(entry, t, id);
        } else {
            const TriangleCorners c = lookup_(id);
            set_up_geometry(t, c.corner, c.material);
            t.beyond_plain = c.material->has_maps() || c.color[0] != nullptr || c.material->alpha_mode == AlphaMode::blend;
            t.textured = false;
            if (t.beyond_plain) set_up_extras(entry, t, c);
        }
    }

    // 1/w and the corner differences: lane-wise IEEE operations, the same
    // bits per component as the reference's scalar ones.
    static void set_up_geometry(GatheredTriangle& t, const geometry::ShadedVertex* const (&corner)[3],
                                const Material* material) {
        t.material = material;
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

    // Out of line, so that the plain set-up keeps no TriangleCorners on its stack.
    [[gnu::noinline]] void set_up_extras_of(std::size_t entry, GatheredTriangle& t, std::uint32_t id) {
        set_up_extras(entry, t, lookup_.full(id));
    }

    // A beyond-plain triangle: its whole corners and texture coordinates for the extras.
    [[gnu::noinline]] void set_up_extras(std::size_t entry, GatheredTriangle& t, const TriangleCorners& c) {
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

    // A run of material t.material begins at fragment i. Returns its material.
    [[gnu::noinline]] const Material* start_run(const GatheredTriangle& t, std::size_t i) {
        if (!runs_.empty()) end_run(i);
        material_filled_ = i;
        runs_.push_back({std::uint32_t(i), 0, t.material, t.textured, true});
        return t.material;
    }

    // Fragment i is textured, vertex-coloured or blended: its run is not plain;
    // its material channels now, and those of the run's fragments before it
    // (the colours multiply them), then the reference's extras.
    [[gnu::noinline]] void add_extras_at(std::size_t i, std::size_t entry, int x, int y, float lambda1, float lambda2,
                                         float b1, float b2) {
        runs_.back().plain = false;
        out_.set_material(material_filled_, i + 1, *runs_.back().material);
        material_filled_ = i + 1;
        const GatheredTriangle& t = table_.entry[entry];
        const GatheredTriangleExtras& e = table_.extras[entry];
        const glm::vec3 world_d1 = vec3_from(t.world_d1), world_d2 = vec3_from(t.world_d2);
        const SurfaceInterpolants interpolants{t.inv_w.lanes, world_d1, world_d2, e.uv0, e.uv_d1, e.uv_d2};
        add_extras(e.corners, interpolants, x, y, lambda1, lambda2, b1, b2, out_, i);
    }

    Lookup& lookup_;
    FragmentBuffer& out_;
    std::vector<MaterialRun>& runs_;
    TriangleTable& table_;
    std::size_t material_filled_ = 0;  // fragments from here to the current one are plain, of the run's material, unfilled
};

}  // namespace detail

// gather_surface_points (surface_gather.hpp) with `isa`'s gather: the
// reference for Isa::scalar, the fast one above for the others; the same
// fragments, runs and bits either way.
template <class Lookup>
std::size_t gather_surface_points(Isa isa, const raster::TileBuffers& tile, int width, int height, Lookup&& lookup,
                                  FragmentBuffer& out, std::vector<MaterialRun>& runs) {
    if (isa == Isa::scalar) return gather_surface_points(tile, width, height, lookup, out, runs);
    // The covered pixels, in the reference's order, without a branch per pixel:
    // four at a time (SSE2, every x86-64), each four's covered ones packed to
    // the front by a table on the compare's mask and stored as one vector (the
    // spare lanes land where the next four go, within the tile's pixel count).
    std::uint32_t* const pixels = out.triangle_table().pixels.data();
    std::size_t count = 0;
    const float* const depth = tile.depth.data();
    for (int y = 0; y < height; ++y) {
        const std::uint32_t row = std::uint32_t(y * tile.side);
        int x = 0;
        for (; x + 4 <= width; x += 4) {
            // covered(p) is depth < 1, false for NaN, as the ordered compare here.
            const int mask = _mm_movemask_ps(_mm_cmplt_ps(_mm_loadu_ps(depth + row + x), _mm_set1_ps(1.0f)));
            const __m128i offsets = _mm_load_si128(reinterpret_cast<const __m128i*>(detail::kPackedLanes[mask]));
            _mm_storeu_si128(reinterpret_cast<__m128i*>(pixels + count),
                             _mm_add_epi32(offsets, _mm_set1_epi32(int(row) + x)));
            count += detail::kSetBits[mask];
        }
        for (; x < width; ++x) {
            pixels[count] = row + std::uint32_t(x);
            count += tile.covered(row + x) ? 1 : 0;
        }
    }
    const int side = tile.side;
    detail::FastSurfaceGather<std::remove_reference_t<Lookup>> gather(lookup, out, runs);
    return gather.gather(
        count, [&](std::size_t i) { return tile.triangle[pixels[i]]; },
        [&](std::size_t i) { return tile.lambda1[pixels[i]]; }, [&](std::size_t i) { return tile.lambda2[pixels[i]]; },
        [&](std::size_t i) { return std::pair<int, int>(int(pixels[i]) % side, int(pixels[i]) / side); });
}

// The same for a fragment list (4× MSAA, blending).
template <class Lookup>
std::size_t gather_surface_points(Isa isa, const raster::TileFragments& fragments, Lookup&& lookup,
                                  FragmentBuffer& out, std::vector<MaterialRun>& runs) {
    if (isa == Isa::scalar) return gather_surface_points(fragments, lookup, out, runs);
    detail::FastSurfaceGather<std::remove_reference_t<Lookup>> gather(lookup, out, runs);
    return gather.gather(
        fragments.count, [&](std::size_t i) { return fragments.triangle[i]; },
        [&](std::size_t i) { return fragments.lambda1[i]; }, [&](std::size_t i) { return fragments.lambda2[i]; },
        [&](std::size_t i) { return std::pair<int, int>(fragments.x[i], fragments.y[i]); });
}

}  // namespace tessera::shade
