// The material pass's per-fragment math (material_kernels.hpp) over xsimd
// batches, one fragment per lane; compiled once per ISA like
// shade_kernels_simd.cpp. Same formulas as the scalar reference in
// material_maps.cpp; where the reference branches per fragment (stored
// tangent or not, degenerate frame) the lanes compute both and select.
#include <algorithm>
#include <cstddef>

#include "simd/kernel_prelude.hpp"

#include "shade/material_kernels.hpp"
#include "shade/vec3_batch.hpp"
#include "simd/lane_padding.hpp"

namespace tessera::shade {
namespace {

static_assert(simd::kLanePadding % Batch::size == 0, "padding must hold whole vectors");

// Lanes where v has a usable direction (as normalize_if_usable in material_maps.cpp), and v normalized there.
Mask normalize_if_usable(Vec3& v) {
    const Batch length2 = dot(v, v);
    const Mask usable = (length2 > Batch(0.0f)) & (length2 < Batch(INFINITY));
    v = v * (Batch(1.0f) / xsimd::sqrt(length2));
    return usable;
}

Vec3 load3(const float* const a[3], std::size_t i) { return load3(a[0], a[1], a[2], i); }

Vec3 apply_frame(const Vec3& t, const Vec3& b, const Vec3& n, const Vec3& tangent_normal) {
    return normalize(t * tangent_normal.x + b * tangent_normal.y + n * tangent_normal.z);
}

// Uses only the v derivatives: T = Q1·st2.t − Q2·st1.t.
Vec3 frame_learnopengl(const Vec3& tangent_normal, const Vec3& n, const Vec3& dp_dx, const Vec3& dp_dy,
                       const Batch& dv_dx, const Batch& dv_dy) {
    Vec3 t = dp_dx * dv_dy - dp_dy * dv_dx;
    const Mask t_ok = normalize_if_usable(t);
    Vec3 b = cross(n, t);
    const Mask b_ok = normalize_if_usable(b);
    return select(t_ok & b_ok, apply_frame(t, -b, n, tangent_normal), n);
}

Vec3 frame_gltf(const Vec3& tangent_normal, const Vec3& n, const Vec3& dp_dx, const Vec3& dp_dy, const Batch& du_dx,
                const Batch& dv_dx, const Batch& du_dy, const Batch& dv_dy) {
    const Batch det = du_dx * dv_dy - du_dy * dv_dx;
    const Batch sign = xsimd::select(det < Batch(0.0f), Batch(-1.0f), Batch(1.0f));
    const Vec3 dp_du = (dp_dx * dv_dy - dp_dy * dv_dx) * sign;
    const Vec3 dp_dv = (dp_dy * du_dx - dp_dx * du_dy) * sign;
    Vec3 t = dp_du - n * dot(n, dp_du);
    const Mask t_ok = normalize_if_usable(t);
    Vec3 b = cross(n, t);
    const Mask b_ok = normalize_if_usable(b);
    b = select(dot(b, dp_dv) > Batch(0.0f), -b, b);
    return select(t_ok & b_ok, apply_frame(t, b, n, tangent_normal), n);
}

Vec3 frame_tangent(const Vec3& tangent_normal, const Vec3& n, const Vec3& stored, const Batch& w) {
    Vec3 t = stored - n * dot(n, stored);
    const Mask t_ok = normalize_if_usable(t);
    const Vec3 b = cross(n, t) * w;
    return select(t_ok, apply_frame(t, b, n, tangent_normal), n);
}

}  // namespace

// Entry points, declared in material_maps.cpp.
void TESSERA_SIMD_ENTRY(pow_2_2)(std::size_t count, float* r, float* g, float* b) {
    const std::size_t end = simd::padded_count(count);
    for (float* channel : {r, g, b}) {
        for (std::size_t i = 0; i < end; i += Batch::size) {
            const Batch c = xsimd::load_unaligned(channel + i);
            // pow(0, 2.2) = 0, where log would give -inf.
            xsimd::select(c > Batch(0.0f), xsimd::exp(xsimd::log(c) * Batch(2.2f)), Batch(0.0f)).store_unaligned(channel + i);
        }
    }
}

void TESSERA_SIMD_ENTRY(perturb_normals)(const NormalMapBatch& in, DerivedTangentFrame frame) {
    const auto shading_normals = [&](std::size_t i) {
        Vec3 tangent_normal = load3(in.map, i) * Batch(2.0f) - Vec3{Batch(1.0f), Batch(1.0f), Batch(1.0f)};
        tangent_normal.x *= Batch(in.scale), tangent_normal.y *= Batch(in.scale);
        const Vec3 n = normalize(load3(in.normal, i));
        const Batch w = xsimd::load_unaligned(in.tangent[3] + i);
        const Vec3 stored = load3(in.tangent, i);  // the first three of x, y, z, w
        const Batch du_dx = xsimd::load_unaligned(in.duv_dx[0] + i), dv_dx = xsimd::load_unaligned(in.duv_dx[1] + i);
        const Batch du_dy = xsimd::load_unaligned(in.duv_dy[0] + i), dv_dy = xsimd::load_unaligned(in.duv_dy[1] + i);
        const Vec3 dp_dx = load3(in.dp_dx, i), dp_dy = load3(in.dp_dy, i);
        const Vec3 derived = frame == DerivedTangentFrame::gltf
                                 ? frame_gltf(tangent_normal, n, dp_dx, dp_dy, du_dx, dv_dx, du_dy, dv_dy)
                                 : frame_learnopengl(tangent_normal, n, dp_dx, dp_dy, dv_dx, dv_dy);
        return select(w != Batch(0.0f), frame_tangent(tangent_normal, n, stored, w), derived);
    };
    // In place, so only the batch's own fragments are written: a run's normals
    // are followed by the next run's, which whole vectors past the end
    // overwrote with normals perturbed by this run's map (the next run, if
    // textured too, then perturbed them twice), so that a pixel depended on
    // where the tile's runs met, i.e. on the tile size. Inputs are read whole
    // vectors past the end (the channels are padded).
    std::size_t i = 0;
    for (; i + Batch::size <= in.count; i += Batch::size) {
        const Vec3 result = shading_normals(i);
        result.x.store_unaligned(in.normal[0] + i);
        result.y.store_unaligned(in.normal[1] + i);
        result.z.store_unaligned(in.normal[2] + i);
    }
    if (i < in.count) {
        const Vec3 result = shading_normals(i);
        alignas(64) float lanes[3][Batch::size];
        result.x.store_aligned(lanes[0]), result.y.store_aligned(lanes[1]), result.z.store_aligned(lanes[2]);
        for (int k = 0; k < 3; ++k) std::copy(lanes[k], lanes[k] + (in.count - i), in.normal[k] + i);
    }
}

}  // namespace tessera::shade
