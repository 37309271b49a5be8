#include "shade/light_culling.hpp"

#include <algorithm>

namespace tessera::shade {

WorldBounds fragment_bounds(const FragmentInputs& in) {
    WorldBounds b{{in.world_x[0], in.world_y[0], in.world_z[0]}, {in.world_x[0], in.world_y[0], in.world_z[0]}};
    for (std::size_t i = 1; i < in.count; ++i) {
        const glm::vec3 p(in.world_x[i], in.world_y[i], in.world_z[i]);
        b.min = glm::min(b.min, p);
        b.max = glm::max(b.max, p);
    }
    return b;
}

namespace {

// The gap from `position` to [min, max] along one axis, >= 0. For any p in
// [min, max], rounding being monotonic: gap <= |fl(position - p)|.
float axis_gap(float position, float min, float max) {
    return std::max(std::max(min - position, position - max), 0.0f);
}

// The farthest any point of [min, max] can be from `position` along one axis:
// for any p in [min, max], |fl(position - p)| <= this, rounding being monotonic.
float axis_reach(float position, float min, float max) { return std::max(position - min, max - position); }

}  // namespace

void select_reaching(const ShadingLights& lights, const LightSelection& from, const WorldBounds& bounds,
                     LightSelection& out) {
    out.index.clear();
    for (std::size_t k = 0; k < from.count(); ++k) {
        if (k == from.spot_begin) out.spot_begin = out.count();
        if (k == from.directional_begin) out.directional_begin = out.count();
        const std::uint32_t j = from.index[k] & kLightIndexMask;
        std::uint32_t reaches_all = kReachesAll;
        if (lights.range[j] > 0.0f) {
            const float x = lights.pos_x[j], y = lights.pos_y[j], z = lights.pos_z[j];
            const float gx = axis_gap(x, bounds.min.x, bounds.max.x);
            const float gy = axis_gap(y, bounds.min.y, bounds.max.y);
            const float gz = axis_gap(z, bounds.min.z, bounds.max.z);
            if ((gx * gx + gy * gy) + gz * gz > lights.range_sq[j]) continue;  // distance_squared's order
            const float fx = axis_reach(x, bounds.min.x, bounds.max.x);
            const float fy = axis_reach(y, bounds.min.y, bounds.max.y);
            const float fz = axis_reach(z, bounds.min.z, bounds.max.z);
            if ((fx * fx + fy * fy) + fz * fz > lights.range_sq[j]) reaches_all = 0;
        }
        out.index.push_back(j | reaches_all);
    }
    // Groups that begin at the very end were never reached in the loop.
    if (from.spot_begin == from.count()) out.spot_begin = out.count();
    if (from.directional_begin == from.count()) out.directional_begin = out.count();
}

void LightCullScratch::reserve(std::size_t light_count) {
    for (LightSelection* s : {&all, &tile, &cluster}) s->index.reserve(light_count);
}

CulledWork shade_fragments_culled(Isa isa, const FragmentInputs& in, const ShadingLights& lights,
                                  LightCullScratch& scratch, const RadianceOutputs& out) {
    CulledWork work;
    if (in.count == 0) return work;
    if (scratch.all.count() != lights.count() || scratch.all.spot_begin != lights.spot_begin ||
        scratch.all.directional_begin != lights.directional_begin)
        scratch.all.assign_all(lights);  // 0 .. count in order: nothing else can change
    select_reaching(lights, scratch.all, fragment_bounds(in), scratch.tile);
    work.tile_lights = scratch.tile.count();
    for (std::size_t begin = 0; begin < in.count; begin += kClusterFragments) {
        const std::size_t count = std::min(kClusterFragments, in.count - begin);
        const FragmentInputs cluster{count,
                                     in.world_x + begin,  in.world_y + begin,  in.world_z + begin,
                                     in.normal_x + begin, in.normal_y + begin, in.normal_z + begin,
                                     in.albedo_r + begin, in.albedo_g + begin, in.albedo_b + begin,
                                     in.metallic + begin, in.roughness + begin, in.ao + begin};
        select_reaching(lights, scratch.tile, fragment_bounds(cluster), scratch.cluster);
        work.fragment_lights += count * scratch.cluster.count();
        shade_fragments_in_range(isa, cluster, lights, scratch.cluster,
                                 {out.r + begin, out.g + begin, out.b + begin});
    }
    return work;
}

}  // namespace tessera::shade
