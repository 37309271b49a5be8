// The point chapter's ShadowCalculation (shadow_maps.cpp cube_shadow and
// sample_cube) over a vector of fragments at a time: the same float
// operations in the same order (no contraction on either side), the face
// picked per lane by selects and the texels gathered, so that every lane gets
// the scalar lookup's bits. Compiled once per ISA (cmake/SimdTargets.cmake).
#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>

#include "simd/kernel_prelude.hpp"

#include "shade/shadow_maps.hpp"
#include "simd/hardware_gather.hpp"
#include "simd/lane_helpers.hpp"

namespace tessera::shade {
namespace {

using Arch = TESSERA_SIMD_ARCH;
using Batch = xsimd::batch<float, Arch>;
using Mask = xsimd::batch_bool<float, Arch>;
using IntBatch = xsimd::batch<std::int32_t, Arch>;

// The texel of a cube map at face coordinates (sc, tc, ma) per lane, as
// sample_cube computes it from them: 1 where ma is not > 0 or s, t are NaN.
Batch face_texel(const CubeMapView& map, const Batch& face, const Batch& sc, const Batch& tc, const Batch& ma) {
    const Batch zero(0.0f);
    const Batch s = (sc / ma + Batch(1.0f)) * Batch(0.5f), t = (tc / ma + Batch(1.0f)) * Batch(0.5f);
    const Batch size(float(map.size)), last(float(map.size - 1));
    const Batch column = xsimd::floor(s * size), row_from_bottom = xsimd::floor(t * size);
    const Mask valid = (ma > zero) & (column == column) & (row_from_bottom == row_from_bottom);
    // Invalid lanes look up texel 0 (and take 1 below).
    const Batch c = xsimd::select(valid, xsimd::min(xsimd::max(column, zero), last), zero);
    const Batch r = xsimd::select(valid, xsimd::min(xsimd::max(row_from_bottom, zero), last), last);
    // (face · size + size − 1 − row) · size + column, in int32 (< 6 · 8192²)
    const IntBatch row = IntBatch(map.size - 1) - xsimd::batch_cast<std::int32_t>(r);
    const IntBatch index =
        (xsimd::batch_cast<std::int32_t>(xsimd::select(valid, face, zero)) * IntBatch(map.size) + row) *
            IntBatch(map.size) +
        xsimd::batch_cast<std::int32_t>(c);
    const Batch texel = simd::hardware_gather(map.depth, index);
    return xsimd::select(valid, texel, Batch(1.0f));
}

// GL's face of each lane's direction, picked as sample_cube does: X, else Y, else Z.
struct FacePick {
    Batch face, sc, tc, ma;
    Mask is_x, is_y;
};
FacePick pick_face(const Batch& dx, const Batch& dy, const Batch& dz) {
    const Batch zero(0.0f);
    const Batch ax = xsimd::abs(dx), ay = xsimd::abs(dy), az = xsimd::abs(dz);
    const Mask is_x = (ax >= ay) & (ax >= az);
    const Mask is_y = (!is_x) & (ay >= az);
    const Mask pos_x = dx >= zero, pos_y = dy >= zero, pos_z = dz >= zero;
    const Batch sc = xsimd::select(is_x, xsimd::select(pos_x, -dz, dz), xsimd::select(is_y, dx, xsimd::select(pos_z, dx, -dx)));
    const Batch tc = xsimd::select(is_y, xsimd::select(pos_y, dz, -dz), -dy);
    const Batch ma = xsimd::select(is_x, ax, xsimd::select(is_y, ay, az));
    const Batch face = xsimd::select(is_x, xsimd::select(pos_x, Batch(0.0f), Batch(1.0f)),
                                     xsimd::select(is_y, xsimd::select(pos_y, Batch(2.0f), Batch(3.0f)),
                                                   xsimd::select(pos_z, Batch(4.0f), Batch(5.0f))));
    return {face, sc, tc, ma, is_x, is_y};
}

// sample_cube for each lane's direction. Face >= 0: every lane's direction is
// known to pick that face (the scalar code's branch taken in every lane), so
// sc, tc and ma are its row of GL's table, the same values the selects give.
template <int Face>
Batch sample_cube(const CubeMapView& map, const Batch& dx, const Batch& dy, const Batch& dz) {
    if constexpr (Face < 0) {
        const FacePick f = pick_face(dx, dy, dz);
        return face_texel(map, f.face, f.sc, f.tc, f.ma);
    } else {
        const Batch face = Batch(float(Face));
        if constexpr (Face == 0) return face_texel(map, face, -dz, -dy, dx);
        if constexpr (Face == 1) return face_texel(map, face, dz, -dy, -dx);
        if constexpr (Face == 2) return face_texel(map, face, dx, dz, dy);
        if constexpr (Face == 3) return face_texel(map, face, dx, -dz, -dy);
        if constexpr (Face == 4) return face_texel(map, face, dx, -dy, dz);
        if constexpr (Face == 5) return face_texel(map, face, -dx, -dy, -dz);
    }
}

// The chapter's diskRadius for fragments at p.
Batch disk_radius_at(const CubeMapView& map, const Batch& px, const Batch& py, const Batch& pz, const glm::vec3& view_pos) {
    const Batch vx = Batch(view_pos.x) - px, vy = Batch(view_pos.y) - py, vz = Batch(view_pos.z) - pz;
    const Batch view_distance = xsimd::sqrt((vx * vx + vy * vy) + vz * vz);
    return (Batch(1.0f) + (view_distance / Batch(map.disk_far_plane))) / Batch(25.0f) * Batch(float(map.filter_radius));
}

// 1 − the chapter's `shadow` of fragments at (px, py, pz), taking every tap
// (Face as sample_cube's: the face all of them pick, or −1).
template <int Face>
Batch tapped_visibility(const CubeMapView& map, const Batch& px, const Batch& py, const Batch& pz,
                        const glm::vec3& view_pos) {
    const Batch bias(0.15f), far_plane(map.far_plane), one(1.0f), zero(0.0f);
    const Batch fx = px - Batch(map.position_x), fy = py - Batch(map.position_y), fz = pz - Batch(map.position_z);
    const Batch current_depth = xsimd::sqrt((fx * fx + fy * fy) + fz * fz);
    Batch shadow(0.0f);
    if (map.filter_radius == 0) {
        const Batch closest_depth = sample_cube<Face>(map, fx, fy, fz) * far_plane;
        shadow = xsimd::select(current_depth - bias > closest_depth, one, zero);
    } else {
        const Batch disk_radius = disk_radius_at(map, px, py, pz, view_pos);
        for (const glm::vec3& offset : kGridSamplingDisk) {
            Batch closest_depth = sample_cube<Face>(map, fx + Batch(offset.x) * disk_radius,
                                                    fy + Batch(offset.y) * disk_radius, fz + Batch(offset.z) * disk_radius);
            closest_depth *= far_plane;
            shadow += xsimd::select(current_depth - bias > closest_depth, one, zero);
        }
        shadow /= Batch(float(kGridSamplingDisk.size()));
    }
    return one - shadow;
}

// Every offset of kGridSamplingDisk has components −1, 0 or 1, so the 20 tap
// directions lie in the box f ± r·(1, 1, 1), r = disk_radius (widened here
// for the taps' rounding). Where the box keeps clear of the face edges (the
// major axis beats the others by more than 2r), every tap picks the face f
// does, and its sc/ma moves from the centre's u by at most r·(1 + |u|)/(ma − r)
// (tc/ma likewise).
struct DiskOnFace {
    Batch face, u, v, inner, r;
    Mask clear_of_edges;
};
DiskOnFace disk_on_face(const Batch& fx, const Batch& fy, const Batch& fz, const Batch& disk_radius) {
    const FacePick f = pick_face(fx, fy, fz);
    const Batch ax = xsimd::abs(fx), ay = xsimd::abs(fy), az = xsimd::abs(fz);
    const Batch r = disk_radius * Batch(1.001f) + (((ax + ay) + az) + disk_radius) * Batch(1e-6f);
    const Batch other_1 = xsimd::select(f.is_x, ay, ax), other_2 = xsimd::select(f.is_x | f.is_y, az, ay);
    const Batch inner = f.ma - r;
    return {f.face, f.sc / f.ma, f.tc / f.ma, inner, r, (inner > other_1 + r) & (inner > other_2 + r)};
}

// The block summaries' early out (ShadowMap::block_min, block_max): the
// disk's texels lie within size/2 · r·(1 + |u|)/(ma − r) of the centre's (plus
// rounding). If they fit in one window of blocks, its least texel m and
// greatest M bound every tap's: with d = current_depth − bias, none is
// shadowed if !(d > m·far) and all are if d > M·far (the taps' own test,
// t·far rounding monotonically in t). Then `shadow` is 0/20 or 20/20 exactly,
// as the taps would sum it. NaN anywhere fails the tests, and the lane is left
// to the taps. Returns the lanes settled; visibility gets 1 or 0 in them.
Mask settle_by_blocks(const CubeMapView& map, const DiskOnFace& disk, const Batch& current_depth, const Batch& bias,
                      Batch& visibility) {
    const Batch zero(0.0f), one(1.0f);
    const Batch half_size(0.5f * float(map.size)), last(float(map.size - 1));
    // The taps' texel coordinates (u + 1)·size/2 round within ~2^-22·size of
    // the exact ones, as the centre's: a margin of 1/64 texel + 2^-20·size.
    const Batch spread = disk.r / disk.inner * half_size * Batch(1.01f);
    const Batch margin(1.0f / 64.0f + float(map.size) / float(1 << 20));
    const Batch reach_s = spread * (one + xsimd::abs(disk.u)) + margin, reach_t = spread * (one + xsimd::abs(disk.v)) + margin;
    const Batch centre_s = (disk.u + one) * half_size, centre_t = (disk.v + one) * half_size;
    const auto clamp = [&](const Batch& texel) { return xsimd::min(xsimd::max(xsimd::floor(texel), zero), last); };
    const Batch column_lo = clamp(centre_s - reach_s), column_hi = clamp(centre_s + reach_s);
    // Rows as stored: size − 1 − the row from the bottom.
    const Batch row_lo = last - clamp(centre_t + reach_t), row_hi = last - clamp(centre_t - reach_t);
    const Batch per_block(1.0f / float(kShadowBlock)), last_block(float(kShadowWindow - 1));
    const Batch bx = xsimd::floor(column_lo * per_block), by = xsimd::floor(row_lo * per_block);
    const Mask fits = disk.clear_of_edges & (xsimd::floor(column_hi * per_block) <= bx + last_block) &
                      (xsimd::floor(row_hi * per_block) <= by + last_block) & (current_depth == current_depth);
    // (face · blocks + by) · blocks + bx in int32: up to 6 · 2048², beyond float's exact integers.
    const IntBatch blocks(map.blocks_per_side);
    const auto block = [&](const Batch& v) { return xsimd::batch_cast<std::int32_t>(xsimd::select(fits, v, zero)); };
    const IntBatch index = (block(disk.face) * blocks + block(by)) * blocks + block(bx);
    const Batch least = simd::hardware_gather(map.block_min, index), greatest = simd::hardware_gather(map.block_max, index);
    const Batch d = current_depth - bias, far_plane(map.far_plane);
    const Mask lit = fits & !(d > least * far_plane), shadowed = fits & (d > greatest * far_plane);
    visibility = xsimd::select(lit, one, zero);
    return lit | shadowed;
}

// Where light j's share of Lo is 0 whatever its visibility: the shading
// kernels' N·L = max(N·(light − p)·1/|light − p|, 0) is 0 wherever N·(light − p)
// < 0, and the terms are the visibility times ones that hold N·L as a factor.
// Tested on the fragment's own normal, away from 0 by 1e-3 of |n|·|f| (f =
// p − light), far beyond the rounding of the kernels' normalized N.
Mask facing_away(const Batch& nx, const Batch& ny, const Batch& nz, const Batch& fx, const Batch& fy, const Batch& fz,
                 const Batch& current_depth) {
    const Batch n_dot_f = (nx * fx + ny * fy) + nz * fz;
    const Batch n_sq = (nx * nx + ny * ny) + nz * nz;
    return (n_dot_f > Batch(0.0f)) & (n_dot_f * n_dot_f > Batch(1e-6f) * n_sq * (current_depth * current_depth));
}

// The taps of the fragments listed in indices[0, count), a vector at a time.
template <int Face>
void tap_listed(const CubeMapView& map, const CubeLookupInputs& in, const std::uint32_t* indices, std::size_t count,
                float* out) {
    for (std::size_t j = 0; j < count; j += Batch::size) {
        alignas(64) std::int32_t index[Batch::size];
        for (std::size_t k = 0; k < Batch::size; ++k) index[k] = std::int32_t(indices[std::min(j + k, count - 1)]);
        const IntBatch lanes = xsimd::load_aligned(index);
        alignas(64) float result[Batch::size];
        tapped_visibility<Face>(map, simd::hardware_gather(in.x, lanes), simd::hardware_gather(in.y, lanes),
                                simd::hardware_gather(in.z, lanes), in.view_pos)
            .store_aligned(result);
        for (std::size_t k = 0; k < Batch::size && j + k < count; ++k) out[index[k]] = result[k];
    }
}

}  // namespace

// Two passes: the first settles what it can a vector at a time (the fragments
// facing away, the block summaries) and lists the others' indices by the
// face all their taps pick (list 6: several faces); the second takes the
// listed fragments' taps, gathered a vector at a time, so that a vector of
// lookups is spent on fragments that need them, with one face per vector.
CubeLookupStats TESSERA_SIMD_ENTRY(cube_visibility)(const CubeMapView& map, const CubeLookupInputs& in, float* out) {
    const std::size_t end = (in.count + Batch::size - 1) / Batch::size * Batch::size;
    CubeLookupStats stats;
    if (map.filter_radius == 0) {
        for (std::size_t i = 0; i < end; i += Batch::size)
            tapped_visibility<-1>(map, xsimd::load_unaligned(in.x + i), xsimd::load_unaligned(in.y + i),
                                  xsimd::load_unaligned(in.z + i), in.view_pos)
                .store_unaligned(out + i);
        stats.tapped = in.count;
        return stats;
    }
    const Batch bias(0.15f), zero(0.0f);
    std::size_t listed[kCubeLookupLists] = {};
    for (std::size_t i = 0; i < end; i += Batch::size) {
        const Batch px = xsimd::load_unaligned(in.x + i), py = xsimd::load_unaligned(in.y + i),
                    pz = xsimd::load_unaligned(in.z + i);
        const Batch fx = px - Batch(map.position_x), fy = py - Batch(map.position_y), fz = pz - Batch(map.position_z);
        const Batch current_depth = xsimd::sqrt((fx * fx + fy * fy) + fz * fz);
        const unsigned lanes = in.count - i >= Batch::size ? (1u << Batch::size) - 1 : (1u << (in.count - i)) - 1;
        Mask away(false);
        if (in.normal_x != nullptr)
            away = facing_away(xsimd::load_unaligned(in.normal_x + i), xsimd::load_unaligned(in.normal_y + i),
                               xsimd::load_unaligned(in.normal_z + i), fx, fy, fz, current_depth);
        const unsigned away_bits = simd::lane_bits(away) & lanes;
        stats.facing_away += std::size_t(std::popcount(away_bits));
        if (away_bits == lanes) {  // any value in [0, 1] gives the same picture
            zero.store_unaligned(out + i);
            continue;
        }
        const DiskOnFace disk = disk_on_face(fx, fy, fz, disk_radius_at(map, px, py, pz, in.view_pos));
        Batch visibility(0.0f);
        Mask settled(false);
        if (map.block_min != nullptr) settled = settle_by_blocks(map, disk, current_depth, bias, visibility) & !away;
        xsimd::select(away, zero, visibility).store_unaligned(out + i);
        const unsigned settled_bits = simd::lane_bits(settled) & lanes;
        stats.settled += std::size_t(std::popcount(settled_bits));
        alignas(64) std::int32_t list[Batch::size];
        xsimd::batch_cast<std::int32_t>(xsimd::select(disk.clear_of_edges, disk.face, Batch(6.0f))).store_aligned(list);
        for (unsigned todo = lanes & ~(settled_bits | away_bits); todo != 0; todo &= todo - 1) {
            const auto k = std::size_t(std::countr_zero(todo));
            const auto l = std::size_t(list[k]);
            in.pending[l * in.pending_capacity + listed[l]++] = std::uint32_t(i + k);
        }
    }
    const auto pending = [&](std::size_t l) { return in.pending + l * in.pending_capacity; };
    tap_listed<0>(map, in, pending(0), listed[0], out);
    tap_listed<1>(map, in, pending(1), listed[1], out);
    tap_listed<2>(map, in, pending(2), listed[2], out);
    tap_listed<3>(map, in, pending(3), listed[3], out);
    tap_listed<4>(map, in, pending(4), listed[4], out);
    tap_listed<5>(map, in, pending(5), listed[5], out);
    tap_listed<-1>(map, in, pending(6), listed[6], out);
    for (const std::size_t n : listed) stats.tapped += n;
    return stats;
}

}  // namespace tessera::shade
