// The chapters' ShadowCalculation in plain float C++, and the light cameras
// their demos set by hand, fitted to the scene (shadow_maps.hpp).
#include "shade/shadow_maps.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>
#include <tbb/parallel_for.h>

namespace tessera::shade {

const std::array<glm::vec3, 20> kGridSamplingDisk = {{
    {1, 1, 1},  {1, -1, 1},  {-1, -1, 1},  {-1, 1, 1},  {1, 1, -1}, {1, -1, -1}, {-1, -1, -1},
    {-1, 1, -1}, {1, 1, 0},  {1, -1, 0},   {-1, -1, 0}, {-1, 1, 0}, {1, 0, 1},   {-1, 0, 1},
    {1, 0, -1}, {-1, 0, -1}, {0, 1, 1},    {0, -1, 1},  {0, -1, -1}, {0, 1, -1},
}};

bool casts_shadow(const Scene& scene, const Object& object) {
    return scene.materials[object.material].alpha_mode != AlphaMode::blend;
}

SceneBounds scene_bounds(const Scene& scene) {
    SceneBounds bounds;
    bounds.min = glm::vec3(std::numeric_limits<float>::max());
    bounds.max = glm::vec3(-std::numeric_limits<float>::max());
    for (const Object& object : scene.objects) {
        const Mesh& mesh = scene.meshes[object.mesh];
        if (mesh.positions.empty() || !casts_shadow(scene, object)) continue;
        glm::vec3 lo = mesh.positions[0], hi = mesh.positions[0];
        for (const glm::vec3& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
        for (int corner = 0; corner < 8; ++corner) {  // the mesh's box as placed: conservative
            const glm::vec3 p((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y, (corner & 4) ? hi.z : lo.z);
            const glm::vec3 world = glm::vec3(object.model * glm::vec4(p, 1.0f));
            bounds.min = glm::min(bounds.min, world), bounds.max = glm::max(bounds.max, world);
        }
        bounds.empty = false;
    }
    if (bounds.empty) bounds.min = bounds.max = glm::vec3(0.0f);
    return bounds;
}

namespace {

glm::vec3 box_corner(const SceneBounds& b, int corner) {
    return {(corner & 1) ? b.max.x : b.min.x, (corner & 2) ? b.max.y : b.min.y, (corner & 4) ? b.max.z : b.min.z};
}

// An up vector for lookAt along `forward` (unit), never parallel to it.
glm::vec3 up_for(const glm::vec3& forward) {
    return std::abs(forward.y) > 0.99f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
}

// The far plane of a light at `position`: its range, else just past the scene's farthest point.
float far_plane_from(const SceneBounds& bounds, const glm::vec3& position, float range) {
    if (range > 0.0f) return range;
    float farthest = 0.0f;
    for (int c = 0; c < 8; ++c) farthest = std::max(farthest, glm::length(box_corner(bounds, c) - position));
    return std::max(farthest * 1.01f, 1e-3f);
}

struct Interval {
    float lo = std::numeric_limits<float>::max(), hi = -std::numeric_limits<float>::max();
    void add(float v) { lo = std::min(lo, v), hi = std::max(hi, v); }
};

// The directional light's orthographic camera: along the light, its x and y
// around the scene's bounds where the camera sees them, z around every caster.
void plan_directional(const Scene& scene, const SceneBounds& bounds, const Light& light, ShadowMap& map) {
    const glm::vec3 forward = light.direction;
    const glm::vec3 centre = (bounds.min + bounds.max) * 0.5f;
    const glm::mat4 view = glm::lookAt(centre - forward, centre, up_for(forward));
    Interval bx, by, bz;
    for (int c = 0; c < 8; ++c) {
        const glm::vec3 v = glm::vec3(view * glm::vec4(box_corner(bounds, c), 1.0f));
        bx.add(v.x), by.add(v.y), bz.add(v.z);
    }
    // What the camera sees: its frustum, cut at the scene's farthest point ahead of it.
    Camera seen = scene.camera;
    const glm::vec3 camera_forward = glm::normalize(seen.target - seen.position);
    float ahead = 0.0f;
    for (int c = 0; c < 8; ++c) ahead = std::max(ahead, glm::dot(box_corner(bounds, c) - seen.position, camera_forward));
    Interval fx = bx, fy = by;
    if (ahead > seen.near_plane) {
        seen.far_plane = std::min(seen.far_plane, ahead);
        const glm::mat4 to_world =
            glm::inverse(projection_matrix(seen, scene.width, scene.height) * view_matrix(seen));
        Interval cx, cy;
        for (int c = 0; c < 8; ++c) {
            const glm::vec4 ndc((c & 1) ? 1.0f : -1.0f, (c & 2) ? 1.0f : -1.0f, (c & 4) ? 1.0f : -1.0f, 1.0f);
            const glm::vec4 world = to_world * ndc;
            const glm::vec3 v = glm::vec3(view * glm::vec4(glm::vec3(world) / world.w, 1.0f));
            cx.add(v.x), cy.add(v.y);
        }
        fx = {std::max(bx.lo, cx.lo), std::min(bx.hi, cx.hi)};
        fy = {std::max(by.lo, cy.lo), std::min(by.hi, cy.hi)};
        if (!(fx.lo < fx.hi) || !(fy.lo < fy.hi)) fx = bx, fy = by;  // the camera sees none of it
    }
    const float extent = std::max({bx.hi - bx.lo, by.hi - by.lo, bz.hi - bz.lo, 1e-3f});
    const auto pad = [&](Interval& i) {  // two texels beyond, so that the filter at the edge stays inside
        const float width = std::max(i.hi - i.lo, 1e-4f * extent);
        const float margin = width * 2.0f / float(map.size);
        i.lo -= margin, i.hi += margin;
    };
    pad(fx), pad(fy);
    const float depth_margin = 0.01f * extent;
    map.near_plane = -bz.hi - depth_margin, map.far_plane = -bz.lo + depth_margin;
    map.view_projection[0] = glm::ortho(fx.lo, fx.hi, fy.lo, fy.hi, map.near_plane, map.far_plane) * view;
    map.to_light = -light.direction;
}

}  // namespace

void plan_shadow_map(const Scene& scene, const SceneBounds& bounds, const Light& light, ShadowMap& map) {
    map.size = light.shadow_map_size;
    map.filter_radius = light.shadow_filter_radius;
    map.position = light.position;
    switch (light.type) {
    case LightType::directional:
        map.kind = ShadowMapKind::planar_depth, map.faces = 1;
        plan_directional(scene, bounds, light, map);
        break;
    case LightType::spot: {
        map.kind = ShadowMapKind::planar_distance, map.faces = 1;
        map.far_plane = far_plane_from(bounds, light.position, light.range);
        map.near_plane = map.far_plane / 1000.0f;
        // The outer cone and two texels more, so that the filter at its edge stays inside.
        const float half_fov = std::min(light.outer_cone_degrees * (1.0f + 4.0f / float(map.size)), 89.5f);
        map.tan_half_fov = std::tan(glm::radians(half_fov));
        map.view_projection[0] =
            glm::perspective(glm::radians(2.0f * half_fov), 1.0f, map.near_plane, map.far_plane) *
            glm::lookAt(light.position, light.position + light.direction, up_for(light.direction));
        break;
    }
    case LightType::point: {
        map.kind = ShadowMapKind::cube_distance, map.faces = 6;
        map.far_plane = far_plane_from(bounds, light.position, light.range);
        map.near_plane = map.far_plane / 1000.0f;
        map.tan_half_fov = 1.0f;
        map.disk_far_plane = light.range > 0.0f ? light.range : auto_light_range(light.color);
        const glm::mat4 projection = glm::perspective(glm::radians(90.0f), 1.0f, map.near_plane, map.far_plane);
        const glm::vec3 p = light.position;
        // The chapter's shadowTransforms: GL's cube faces and their up vectors.
        const std::array<std::pair<glm::vec3, glm::vec3>, 6> faces = {{{{1, 0, 0}, {0, -1, 0}},
                                                                      {{-1, 0, 0}, {0, -1, 0}},
                                                                      {{0, 1, 0}, {0, 0, 1}},
                                                                      {{0, -1, 0}, {0, 0, -1}},
                                                                      {{0, 0, 1}, {0, -1, 0}},
                                                                      {{0, 0, -1}, {0, -1, 0}}}};
        for (int f = 0; f < 6; ++f)
            map.view_projection[f] = projection * glm::lookAt(p, p + faces[f].first, faces[f].second);
        break;
    }
    }
    map.depth.resize(std::size_t(map.faces) * map.size * map.size);  // every texel written by the depth pass
}

void prepare_cube_summaries(ShadowMap& map) {
    if (map.kind != ShadowMapKind::cube_distance || map.size <= 0 || map.size > kMaxShadowMapSize ||
        map.depth.size() != std::size_t(map.faces) * map.size * map.size) {
        map.block_min.clear(), map.block_max.clear(), map.blocks_per_side = 0;
        return;
    }
    const int n = summary_blocks_per_side(map.size);
    map.blocks_per_side = n;
    map.block_min.resize(std::size_t(map.faces) * n * n), map.block_max.resize(map.block_min.size());
}

void summarize_cube_rect(ShadowMap& map, int face, int x0, int y0, int x1, int y1) {
    if (map.blocks_per_side == 0) return;
    const int size = map.size, n = map.blocks_per_side;
    const auto row = [&](int y) { return map.depth.data() + (std::size_t(face) * size + std::size_t(y)) * size; };
    thread_local std::vector<float> column_min, column_max;
    column_min.resize(std::size_t(size)), column_max.resize(std::size_t(size));
    for (int b0 = y0; b0 < y1; b0 += kShadowBlock) {
        const int b1 = std::min(y1, b0 + kShadowBlock);
        float* lo = map.block_min.data() + (std::size_t(face) * n + std::size_t(b0 / kShadowBlock)) * n;
        float* hi = map.block_max.data() + (std::size_t(face) * n + std::size_t(b0 / kShadowBlock)) * n;
        // Down the rows, then across each block. The column's least texel is
        // NaN once any of its texels is (b != b), so that a block holding a NaN
        // becomes (−inf, +inf).
        std::copy(row(b0) + x0, row(b0) + x1, column_min.data() + x0);
        std::copy(row(b0) + x0, row(b0) + x1, column_max.data() + x0);
        for (int y = b0 + 1; y < b1; ++y) {
            const float* r = row(y);
            for (int x = x0; x < x1; ++x) {
                const float a = column_min[x], b = r[x];
                column_min[x] = b < a || b != b ? b : a, column_max[x] = std::max(column_max[x], b);
            }
        }
        for (int bx = x0 / kShadowBlock; bx * kShadowBlock < x1; ++bx) {
            float mn = INFINITY, mx = -INFINITY;
            bool any_nan = false;
            for (int x = bx * kShadowBlock; x < std::min(x1, (bx + 1) * kShadowBlock); ++x) {
                any_nan |= column_min[x] != column_min[x];
                mn = std::min(mn, column_min[x]), mx = std::max(mx, column_max[x]);
            }
            lo[bx] = any_nan ? -INFINITY : mn, hi[bx] = any_nan ? INFINITY : mx;
        }
    }
}

void finish_cube_summaries(ShadowMap& map) {
    if (map.blocks_per_side == 0) return;
    const int n = map.blocks_per_side;
    const std::size_t per_face = std::size_t(n) * std::size_t(n);
    // Window (bx, by) = blocks bx .. bx + kShadowWindow − 1 by by .. by + kShadowWindow − 1:
    // along rows, then along columns, each in place in increasing index (reading
    // only entries after the one written).
    tbb::parallel_for(0, map.faces, [&](int face) {
        float* lo = map.block_min.data() + std::size_t(face) * per_face;
        float* hi = map.block_max.data() + std::size_t(face) * per_face;
        const auto widen = [&](std::size_t step, bool along_x) {
            for (int by = 0; by < n; ++by)
                for (int bx = 0; bx < n; ++bx) {
                    const std::size_t i = std::size_t(by) * n + std::size_t(bx);
                    const int at = along_x ? bx : by;
                    for (int k = 1; k < kShadowWindow && at + k < n; ++k)
                        lo[i] = std::min(lo[i], lo[i + k * step]), hi[i] = std::max(hi[i], hi[i + k * step]);
                }
        };
        widen(1, true);
        widen(std::size_t(n), false);
    });
}

void summarize_cube_blocks(ShadowMap& map) {
    prepare_cube_summaries(map);
    if (map.blocks_per_side == 0) return;
    tbb::parallel_for(0, map.faces * map.blocks_per_side, [&](int face_row) {
        const int face = face_row / map.blocks_per_side, y0 = (face_row % map.blocks_per_side) * kShadowBlock;
        summarize_cube_rect(map, face, 0, y0, map.size, std::min(map.size, y0 + kShadowBlock));
    });
    finish_cube_summaries(map);
}

float distance_from_window_depth(const ShadowMap& map, float d, int column, int row) {
    const float n = map.near_plane, f = map.far_plane, size = float(map.size);
    const float ndc_x = ((float(column) + 0.5f) / size * 2.0f - 1.0f) * map.tan_half_fov;
    const float ndc_y = (1.0f - (float(row) + 0.5f) / size * 2.0f) * map.tan_half_fov;
    const float z_ndc = d * 2.0f - 1.0f;
    const float view_depth = 2.0f * f * n / ((f + n) - z_ndc * (f - n));
    return view_depth * std::sqrt(1.0f + ndc_x * ndc_x + ndc_y * ndc_y) / f;
}

namespace {

// texture(shadowMap, uv).r with GL_NEAREST and GL_CLAMP_TO_BORDER (border 1.0).
float sample_planar(const ShadowMap& map, float s, float t) {
    const float column = std::floor(s * float(map.size)), row_from_bottom = std::floor(t * float(map.size));
    if (!(column >= 0.0f && column < float(map.size) && row_from_bottom >= 0.0f && row_from_bottom < float(map.size)))
        return 1.0f;
    return map.texel(0, int(column), map.size - 1 - int(row_from_bottom));
}

// texture(depthMap, direction).r with GL_NEAREST and GL_CLAMP_TO_EDGE: the face
// of the major axis, s and t from GL's table of sc, tc and ma. Spelled out
// operation by operation: shadow_kernels_simd.cpp does the same ones.
float sample_cube(const ShadowMap& map, float dx, float dy, float dz) {
    const float ax = std::abs(dx), ay = std::abs(dy), az = std::abs(dz);
    int face;
    float sc, tc, ma;
    if (ax >= ay && ax >= az) face = dx >= 0.0f ? 0 : 1, sc = dx >= 0.0f ? -dz : dz, tc = -dy, ma = ax;
    else if (ay >= az) face = dy >= 0.0f ? 2 : 3, sc = dx, tc = dy >= 0.0f ? dz : -dz, ma = ay;
    else face = dz >= 0.0f ? 4 : 5, sc = dz >= 0.0f ? dx : -dx, tc = -dy, ma = az;
    const float s = (sc / ma + 1.0f) * 0.5f, t = (tc / ma + 1.0f) * 0.5f;
    const float size = float(map.size), last = float(map.size - 1);
    const float column = std::floor(s * size), row_from_bottom = std::floor(t * size);
    // Zero, NaN or infinite directions: nothing to look up (lit).
    if (!(ma > 0.0f) || !(column == column) || !(row_from_bottom == row_from_bottom)) return 1.0f;
    const float c = std::min(std::max(column, 0.0f), last), r = std::min(std::max(row_from_bottom, 0.0f), last);
    return map.texel(face, int(c), map.size - 1 - int(r));
}

// 3.1.3's ShadowCalculation (for a spot: its current depth a distance / far_plane).
float planar_shadow(const ShadowMap& map, const glm::vec3& world_pos, const glm::vec3& normal_in) {
    const glm::vec4 light_space = map.view_projection[0] * glm::vec4(world_pos, 1.0f);
    if (map.kind == ShadowMapKind::planar_distance && !(light_space.w > 0.0f)) return 0.0f;  // behind the spot
    glm::vec3 proj_coords = glm::vec3(light_space) / light_space.w;
    proj_coords = proj_coords * 0.5f + 0.5f;
    const bool distance = map.kind == ShadowMapKind::planar_distance;
    const float current_depth = distance ? glm::length(world_pos - map.position) / map.far_plane : proj_coords.z;
    const glm::vec3 normal = glm::normalize(normal_in);
    const glm::vec3 light_dir = distance ? glm::normalize(map.position - world_pos) : map.to_light;
    const float bias = std::max(0.05f * (1.0f - glm::dot(normal, light_dir)), 0.005f);
    float shadow = 0.0f;
    const float texel_size = 1.0f / float(map.size);
    const int r = map.filter_radius;
    for (int x = -r; x <= r; ++x) {
        for (int y = -r; y <= r; ++y) {
            const float pcf_depth =
                sample_planar(map, proj_coords.x + float(x) * texel_size, proj_coords.y + float(y) * texel_size);
            shadow += current_depth - bias > pcf_depth ? 1.0f : 0.0f;
        }
    }
    shadow /= float((2 * r + 1) * (2 * r + 1));
    if (proj_coords.z > 1.0f) shadow = 0.0f;
    return shadow;
}

// 3.2.2's ShadowCalculation (filter radius 0: its single-sample variant).
// Lengths as (x² + y²) + z², like shadow_kernels_simd.cpp.
float cube_shadow(const ShadowMap& map, const glm::vec3& frag_pos, const glm::vec3& view_pos) {
    const float fx = frag_pos.x - map.position.x, fy = frag_pos.y - map.position.y, fz = frag_pos.z - map.position.z;
    const float current_depth = std::sqrt((fx * fx + fy * fy) + fz * fz);
    const float bias = 0.15f;
    if (map.filter_radius == 0) {
        const float closest_depth = sample_cube(map, fx, fy, fz) * map.far_plane;
        return current_depth - bias > closest_depth ? 1.0f : 0.0f;
    }
    float shadow = 0.0f;
    const float vx = view_pos.x - frag_pos.x, vy = view_pos.y - frag_pos.y, vz = view_pos.z - frag_pos.z;
    const float view_distance = std::sqrt((vx * vx + vy * vy) + vz * vz);
    const float disk_radius = (1.0f + (view_distance / map.disk_far_plane)) / 25.0f * float(map.filter_radius);
    for (const glm::vec3& offset : kGridSamplingDisk) {
        float closest_depth =
            sample_cube(map, fx + offset.x * disk_radius, fy + offset.y * disk_radius, fz + offset.z * disk_radius);
        closest_depth *= map.far_plane;  // undo mapping [0;1]
        if (current_depth - bias > closest_depth) shadow += 1.0f;
    }
    shadow /= float(kGridSamplingDisk.size());
    return shadow;
}

}  // namespace

float shadow_visibility(const ShadowMap& map, const glm::vec3& world_pos, const glm::vec3& normal,
                        const glm::vec3& cam_pos) {
    const float shadow = map.kind == ShadowMapKind::cube_distance ? cube_shadow(map, world_pos, cam_pos)
                                                                  : planar_shadow(map, world_pos, normal);
    return 1.0f - shadow;
}

// Defined in shadow_kernels_simd.cpp, once per ISA: 1 − cube_shadow of
// fragments [0, count) rounded up to whole vectors.
#define TESSERA_DECLARE_SHADOW_ENTRIES(suffix) \
    CubeLookupStats cube_visibility_##suffix(const CubeMapView& map, const CubeLookupInputs& in, float* out);
TESSERA_DECLARE_SHADOW_ENTRIES(sse4)
TESSERA_DECLARE_SHADOW_ENTRIES(avx2)
TESSERA_DECLARE_SHADOW_ENTRIES(avx512)
#undef TESSERA_DECLARE_SHADOW_ENTRIES

CubeLookupStats shadow_visibility_planes(Isa isa, const FragmentInputs& in, const ShadingLights& lights, float* planes,
                                         std::size_t stride, bool every_visibility) {
    simd::require_supported(isa);
    const std::size_t padded = padded_count(in.count);
    CubeLookupStats stats;
    thread_local std::vector<std::uint32_t> pending;  // the kernels' list, kept from call to call
    for (std::size_t slot = 0; slot < lights.shadowed_count(); ++slot) {
        const ShadowMap& map = *lights.shadow_maps[slot];
        float* plane = planes + slot * stride;
        if (map.kind == ShadowMapKind::cube_distance && isa != Isa::scalar) {
            const bool summarized = map.blocks_per_side > 0 &&
                                    map.block_min.size() == std::size_t(map.faces) * map.blocks_per_side * map.blocks_per_side;
            const CubeMapView view{map.depth.data(), map.size, map.filter_radius, map.position.x, map.position.y,
                                   map.position.z, map.far_plane, map.disk_far_plane,
                                   summarized ? map.block_min.data() : nullptr, summarized ? map.block_max.data() : nullptr,
                                   map.blocks_per_side};
            if (pending.size() < kCubeLookupLists * padded) pending.resize(kCubeLookupLists * padded);
            const bool skip = !every_visibility;
            const CubeLookupInputs fragments{in.world_x, in.world_y, in.world_z, skip ? in.normal_x : nullptr,
                                             skip ? in.normal_y : nullptr, skip ? in.normal_z : nullptr,
                                             in.count, lights.cam_pos, pending.data(), padded};
            switch (isa) {
            case Isa::scalar: break;
            case Isa::sse4: stats += cube_visibility_sse4(view, fragments, plane); break;
            case Isa::avx2: stats += cube_visibility_avx2(view, fragments, plane); break;
            case Isa::avx512: stats += cube_visibility_avx512(view, fragments, plane); break;
            }
            for (std::size_t i = in.count; i < padded; ++i) plane[i] = 1.0f;
            continue;
        }
        for (std::size_t i = 0; i < in.count; ++i)
            plane[i] = shadow_visibility(map, {in.world_x[i], in.world_y[i], in.world_z[i]},
                                         {in.normal_x[i], in.normal_y[i], in.normal_z[i]}, lights.cam_pos);
        for (std::size_t i = in.count; i < padded; ++i) plane[i] = 1.0f;
    }
    return stats;
}

}  // namespace tessera::shade
