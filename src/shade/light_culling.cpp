#include "shade/light_culling.hpp"

#include <algorithm>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace tessera::shade {

namespace {

// min and max of v[0, count), count > 0, as glm::min/glm::max fold them one
// by one from v[0]: (x < m) ? x : m, so a NaN after the first is passed over.
// Taken four at a time, it was a sixth of a many-lights frame's shading
// instructions one by one (twice per fragment: tile and cluster). minps and
// maxps are that same select, exact, so the order does not change the result.
void axis_bounds(const float* v, std::size_t count, float& min, float& max) {
    std::size_t i = 1;
    float lo = v[0], hi = v[0];
#if defined(__SSE2__)
    if (count >= 5) {
        __m128 lo4 = _mm_set1_ps(v[0]), hi4 = lo4;
        for (; i + 4 <= count; i += 4) {
            const __m128 x = _mm_loadu_ps(v + i);
            lo4 = _mm_min_ps(x, lo4);
            hi4 = _mm_max_ps(x, hi4);
        }
        alignas(16) float lo_lanes[4], hi_lanes[4];
        _mm_store_ps(lo_lanes, lo4);
        _mm_store_ps(hi_lanes, hi4);
        lo = lo_lanes[0], hi = hi_lanes[0];
        for (int lane = 1; lane < 4; ++lane) {
            lo = lo_lanes[lane] < lo ? lo_lanes[lane] : lo;
            hi = hi_lanes[lane] > hi ? hi_lanes[lane] : hi;
        }
    }
#endif
    for (; i < count; ++i) {
        lo = v[i] < lo ? v[i] : lo;
        hi = v[i] > hi ? v[i] : hi;
    }
    min = lo, max = hi;
}

}  // namespace

WorldBounds fragment_bounds(const FragmentInputs& in) {
    WorldBounds b;
    axis_bounds(in.world_x, in.count, b.min.x, b.max.x);
    axis_bounds(in.world_y, in.count, b.min.y, b.max.y);
    axis_bounds(in.world_z, in.count, b.min.z, b.max.z);
    return b;
}

namespace {

// The gap from `position` to [min, max] along one axis, >= 0. For any p in
// [min, max], rounding being monotonic: gap <= |fl(position - p)|.
float axis_gap(float position, float min, float max) {
    const float below = min - position, above = position - max;  // at most one is > 0
    const float gap = below > above ? below : above;
    return gap > 0.0f ? gap : 0.0f;
}

// The farthest any point of [min, max] can be from `position` along one axis:
// for any p in [min, max], |fl(position - p)| <= this, rounding being monotonic.
float axis_reach(float position, float min, float max) {
    const float from_min = position - min, from_max = max - position;
    return from_min > from_max ? from_min : from_max;
}

}  // namespace

void select_reaching(const ShadingLights&, const LightSelection& from, const WorldBounds& bounds,
                     LightSelection& out) {
    // First every light's verdict, without branches or compaction, so that the
    // compiler vectorizes it: 0 misses the box, 1 reaches part of it, 1 | kReachesAll all of it.
    const std::size_t n = from.count();
    out.verdict.resize(n);
    const float *x = from.x.data(), *y = from.y.data(), *z = from.z.data(), *reach_sq = from.reach_sq.data();
    std::uint32_t* verdict = out.verdict.data();
    for (std::size_t k = 0; k < n; ++k) {
        const float gx = axis_gap(x[k], bounds.min.x, bounds.max.x);
        const float gy = axis_gap(y[k], bounds.min.y, bounds.max.y);
        const float gz = axis_gap(z[k], bounds.min.z, bounds.max.z);
        const float gap_sq = (gx * gx + gy * gy) + gz * gz;  // distance_squared's order
        const float fx = axis_reach(x[k], bounds.min.x, bounds.max.x);
        const float fy = axis_reach(y[k], bounds.min.y, bounds.max.y);
        const float fz = axis_reach(z[k], bounds.min.z, bounds.max.z);
        const float far_sq = (fx * fx + fy * fy) + fz * fz;
        // far_sq >= gap_sq: kReachesAll comes only with 1.
        verdict[k] = std::uint32_t(gap_sq <= reach_sq[k]) | (far_sq <= reach_sq[k] ? kReachesAll : 0u);
    }
    // Then the kept lights, compacted without branches: every entry is written
    // and the count advances only past kept ones (a push_back per light cost
    // ~60 instructions, more than the test).
    for (auto* column : {&out.x, &out.y, &out.z, &out.reach_sq}) column->resize(n);
    out.index.resize(n);
    std::uint32_t* index = out.index.data();
    float *out_x = out.x.data(), *out_y = out.y.data(), *out_z = out.z.data(), *out_reach_sq = out.reach_sq.data();
    std::size_t kept = 0;
    const auto compact = [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            index[kept] = (from.index[k] & kLightIndexMask) | (verdict[k] & kReachesAll);
            out_x[kept] = x[k], out_y[kept] = y[k], out_z[kept] = z[k], out_reach_sq[kept] = reach_sq[k];
            kept += verdict[k] != 0;
        }
    };
    compact(0, from.spot_begin);
    out.spot_begin = kept;
    compact(from.spot_begin, from.directional_begin);
    out.directional_begin = kept;
    compact(from.directional_begin, n);
    for (auto* column : {&out.x, &out.y, &out.z, &out.reach_sq}) column->resize(kept);
    out.index.resize(kept);
}

void LightCullScratch::reserve(std::size_t light_count) {
    for (LightSelection* s : {&tile, &cluster}) {
        s->index.reserve(light_count), s->verdict.reserve(light_count);
        for (auto* column : {&s->x, &s->y, &s->z, &s->reach_sq}) column->reserve(light_count);
    }
}

CulledWork shade_fragments_culled(Isa isa, const FragmentInputs& in, const ShadingLights& lights,
                                  LightCullScratch& scratch, const RadianceOutputs& out) {
    CulledWork work;
    if (in.count == 0) return work;
    select_reaching(lights, lights.every, fragment_bounds(in), scratch.tile);
    work.tile_lights = scratch.tile.count();
    for (std::size_t begin = 0; begin < in.count; begin += kClusterFragments) {
        const std::size_t count = std::min(kClusterFragments, in.count - begin);
        FragmentInputs cluster{count,
                               in.world_x + begin,  in.world_y + begin,  in.world_z + begin,
                               in.normal_x + begin, in.normal_y + begin, in.normal_z + begin,
                               in.albedo_r + begin, in.albedo_g + begin, in.albedo_b + begin,
                               in.metallic + begin, in.roughness + begin, in.ao + begin};
        if (in.visibility != nullptr)
            cluster.visibility = in.visibility + begin, cluster.visibility_stride = in.visibility_stride;
        select_reaching(lights, scratch.tile, fragment_bounds(cluster), scratch.cluster);
        work.fragment_lights += count * scratch.cluster.count();
        shade_fragments_in_range(isa, cluster, lights, scratch.cluster,
                                 {out.r + begin, out.g + begin, out.b + begin});
    }
    return work;
}

}  // namespace tessera::shade
