// The point chapter's ShadowCalculation (shadow_maps.cpp cube_shadow and
// sample_cube) over a vector of fragments at a time: the same float
// operations in the same order (no contraction on either side), the face
// picked per lane by selects and the texels gathered, so that every lane gets
// the scalar lookup's bits. Compiled once per ISA (cmake/SimdTargets.cmake).
#include <cstddef>
#include <cstdint>

#include "simd/kernel_prelude.hpp"

#include "shade/shadow_maps.hpp"
#include "simd/hardware_gather.hpp"

namespace tessera::shade {
namespace {

using Arch = TESSERA_SIMD_ARCH;
using Batch = xsimd::batch<float, Arch>;
using Mask = xsimd::batch_bool<float, Arch>;
using IntBatch = xsimd::batch<std::int32_t, Arch>;

// sample_cube for each lane's direction.
Batch sample_cube(const CubeMapView& map, const Batch& dx, const Batch& dy, const Batch& dz) {
    const Batch zero(0.0f);
    const Batch ax = xsimd::abs(dx), ay = xsimd::abs(dy), az = xsimd::abs(dz);
    const Mask is_x = (ax >= ay) & (ax >= az);
    const Mask is_y = (!is_x) & (ay >= az);
    const Mask pos_x = dx >= zero, pos_y = dy >= zero, pos_z = dz >= zero;
    // Per face, as the scalar branches: X, else Y, else Z.
    const Batch sc = xsimd::select(is_x, xsimd::select(pos_x, -dz, dz), xsimd::select(is_y, dx, xsimd::select(pos_z, dx, -dx)));
    const Batch tc = xsimd::select(is_y, xsimd::select(pos_y, dz, -dz), -dy);
    const Batch ma = xsimd::select(is_x, ax, xsimd::select(is_y, ay, az));
    const Batch face = xsimd::select(is_x, xsimd::select(pos_x, Batch(0.0f), Batch(1.0f)),
                                     xsimd::select(is_y, xsimd::select(pos_y, Batch(2.0f), Batch(3.0f)),
                                                   xsimd::select(pos_z, Batch(4.0f), Batch(5.0f))));
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

}  // namespace

void TESSERA_SIMD_ENTRY(cube_visibility)(const CubeMapView& map, const float* x, const float* y, const float* z,
                                         std::size_t count, const glm::vec3& view_pos, float* out) {
    const std::size_t end = (count + Batch::size - 1) / Batch::size * Batch::size;
    const Batch bias(0.15f), far_plane(map.far_plane), one(1.0f), zero(0.0f);
    for (std::size_t i = 0; i < end; i += Batch::size) {
        const Batch px = xsimd::load_unaligned(x + i), py = xsimd::load_unaligned(y + i), pz = xsimd::load_unaligned(z + i);
        const Batch fx = px - Batch(map.position_x), fy = py - Batch(map.position_y), fz = pz - Batch(map.position_z);
        const Batch current_depth = xsimd::sqrt((fx * fx + fy * fy) + fz * fz);
        Batch shadow(0.0f);
        if (map.filter_radius == 0) {
            const Batch closest_depth = sample_cube(map, fx, fy, fz) * far_plane;
            shadow = xsimd::select(current_depth - bias > closest_depth, one, zero);
        } else {
            const Batch vx = Batch(view_pos.x) - px, vy = Batch(view_pos.y) - py, vz = Batch(view_pos.z) - pz;
            const Batch view_distance = xsimd::sqrt((vx * vx + vy * vy) + vz * vz);
            const Batch disk_radius =
                (one + (view_distance / Batch(map.disk_far_plane))) / Batch(25.0f) * Batch(float(map.filter_radius));
            for (const glm::vec3& offset : kGridSamplingDisk) {
                Batch closest_depth = sample_cube(map, fx + Batch(offset.x) * disk_radius, fy + Batch(offset.y) * disk_radius,
                                                  fz + Batch(offset.z) * disk_radius);
                closest_depth *= far_plane;
                shadow += xsimd::select(current_depth - bias > closest_depth, one, zero);
            }
            shadow /= Batch(float(kGridSamplingDisk.size()));
        }
        (one - shadow).store_unaligned(out + i);
    }
}

}  // namespace tessera::shade
