// The depth passes of shadow mapping: the frame's vertex, triangle and tile
// passes (renderer.cpp) with a light's camera, depth only.
#include "render/shadow_pass.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string_view>

#include <tbb/parallel_for.h>

#include "geometry/clipper.hpp"
#include "geometry/vertex_stage.hpp"
#include "geometry/viewport.hpp"
#include "raster/bin_rasterizer.hpp"
#include "raster/triangle_assembly.hpp"
#include "render/huge_pages.hpp"
#include "shade/alpha_mask.hpp"

namespace tessera::render {

namespace {

constexpr int kShadowTileSize = 64;

// Whether the box lies wholly outside one of the view's clip planes (then none
// of its triangles can be drawn): each plane is a half-space of clip space, so
// a box whose eight corners are all beyond one is beyond it everywhere.
bool outside_view(const shade::SceneBounds& box, const glm::mat4& view_projection) {
    std::uint32_t all_outside = 0x3f;
    for (int c = 0; c < 8 && all_outside != 0; ++c) {
        const glm::vec3 p((c & 1) ? box.max.x : box.min.x, (c & 2) ? box.max.y : box.min.y,
                          (c & 4) ? box.max.z : box.min.z);
        const glm::vec4 clip = view_projection * glm::vec4(p, 1.0f);
        const std::uint32_t outside = (clip.x > clip.w ? 1u : 0u) | (clip.x < -clip.w ? 2u : 0u) |
                                      (clip.y > clip.w ? 4u : 0u) | (clip.y < -clip.w ? 8u : 0u) |
                                      (clip.z > clip.w ? 16u : 0u) | (clip.z < -clip.w ? 32u : 0u);
        all_outside &= outside;
    }
    return all_outside != 0;
}

// The cache keys (render_maps): 64-bit hashes of the bytes a depth pass reads,
// the standard library's hash of a byte string, combined in a fixed order.
std::uint64_t combine(std::uint64_t seed, std::uint64_t value) {
    return seed ^ (value + 0x9e3779b97f4a7c15ull + (seed << 12) + (seed >> 4));
}
template <class T>
std::uint64_t hash_bytes(const T* data, std::size_t count) {
    return std::hash<std::string_view>{}(std::string_view(reinterpret_cast<const char*>(data), count * sizeof(T)));
}
template <class T>
std::uint64_t combine_value(std::uint64_t seed, const T& value) {
    return combine(seed, hash_bytes(&value, 1));
}

bool shadow_cache_enabled() {
    const char* off = std::getenv("TESSERA_NO_SHADOW_CACHE");
    return off == nullptr || std::strcmp(off, "1") != 0;
}

}  // namespace

std::uint64_t ShadowPass::casters_key(const Scene& scene) {
    // Which meshes the casters draw, and whether an alpha test reads their uvs and colours.
    constexpr std::uint8_t kDrawn = 1, kMasked = 2;
    std::vector<std::uint8_t>& use = mesh_use_;
    use.assign(scene.meshes.size(), 0);
    for (const Object& object : scene.objects) {
        if (!shade::casts_shadow(scene, object)) continue;
        use[object.mesh] |= kDrawn;
        if (scene.materials[object.material].alpha_mode == AlphaMode::mask) use[object.mesh] |= kMasked;
    }
    mesh_keys_.assign(scene.meshes.size(), 0);
    tbb::parallel_for(std::size_t(0), scene.meshes.size(), [&](std::size_t m) {
        if (!(use[m] & kDrawn)) return;
        const Mesh& mesh = scene.meshes[m];
        std::uint64_t key = combine_value(0, mesh.topology);
        key = combine(key, hash_bytes(mesh.positions.data(), mesh.positions.size()));
        key = combine(key, hash_bytes(mesh.indices.data(), mesh.indices.size()));
        if (use[m] & kMasked) {
            key = combine(key, hash_bytes(mesh.uvs.data(), mesh.uvs.size()));
            key = combine(key, hash_bytes(mesh.uvs1.data(), mesh.uvs1.size()));
            key = combine(key, hash_bytes(mesh.colors.data(), mesh.colors.size()));
        }
        mesh_keys_[m] = key;
    });
    next_textures_.clear();
    std::uint64_t key = combine_value(0, scene.objects.size());
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        const Object& object = scene.objects[o];
        if (!shade::casts_shadow(scene, object)) continue;
        key = combine_value(combine_value(combine_value(key, o), object.mesh), object.model);
        key = combine(key, mesh_keys_[object.mesh]);
        const Material& material = scene.materials[object.material];
        if (material.alpha_mode != AlphaMode::mask) continue;
        const TextureSlot& slot = material.albedo_map;
        key = combine_value(combine_value(key, material.alpha_factor), material.alpha_cutoff);
        key = combine_value(combine_value(combine_value(key, slot.texture), slot.wrap_s), slot.wrap_t);
        key = combine_value(combine_value(combine_value(key, slot.mag_filter), slot.min_filter), slot.uv_set);
        key = combine_value(combine_value(key, slot.uv_transformed), slot.uv_transform);
        if (slot.present()) {
            const auto& texture = scene.textures[std::size_t(slot.texture)];
            key = combine_value(key, static_cast<const void*>(texture.get()));
            next_textures_.push_back(texture);
        }
    }
    return key;
}

void ShadowPass::prepare(const Scene& scene) {
    bounds_ = shade::scene_bounds(scene);
    object_bounds_.resize(scene.objects.size());
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        object_bounds_[o] = {};
        const Object& object = scene.objects[o];
        const Mesh& mesh = scene.meshes[object.mesh];
        if (mesh.positions.empty() || !shade::casts_shadow(scene, object) || mesh.topology != Topology::triangles)
            continue;
        glm::vec3 lo = mesh.positions[0], hi = mesh.positions[0];
        for (const glm::vec3& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
        shade::SceneBounds& b = object_bounds_[o];
        b.min = glm::vec3(INFINITY), b.max = glm::vec3(-INFINITY), b.empty = false;
        for (int c = 0; c < 8; ++c) {
            const glm::vec3 p((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
            const glm::vec3 world = glm::vec3(object.model * glm::vec4(p, 1.0f));
            b.min = glm::min(b.min, world), b.max = glm::max(b.max, world);
        }
    }
    triangles_drawn_ = 0;
}

void ShadowPass::render_depth(simd::Isa isa, const Scene& scene, const glm::mat4& view_projection, int size,
                              std::span<float> depth, const shade::ShadowMap* distances, shade::ShadowMap* summaries,
                              int face) {
    static_assert(kShadowTileSize % shade::kShadowBlock == 0, "tiles hold whole summary blocks");
    if (depth.size() != std::size_t(size) * size) throw std::invalid_argument("shadow map storage of the wrong size");
    // The casters this view can see, in scene order.
    objects_.clear();
    for (std::size_t o = 0; o < scene.objects.size(); ++o)
        if (!object_bounds_[o].empty && !outside_view(object_bounds_[o], view_projection))
            objects_.push_back(std::uint32_t(o));
    if (objects_.empty()) {  // nothing drawn: every texel cleared, in parallel
        tbb::parallel_for(std::size_t(0), std::size_t(size), [&](std::size_t row) {
            std::fill_n(depth.data() + row * std::size_t(size), size, 1.0f);
        });
        if (summaries != nullptr) shade::summarize_cube_rect(*summaries, face, 0, 0, size, size);
        return;
    }

    // The vertex pass.
    first_vertex_.resize(objects_.size());
    std::size_t total = 0;
    for (std::size_t e = 0; e < objects_.size(); ++e) {
        first_vertex_[e] = std::uint32_t(total);
        total += scene.meshes[scene.objects[objects_[e]].mesh].positions.size();
    }
    if (total >= geometry::kClippedVertexBit) throw std::invalid_argument("the scene has too many vertices");
    reserve_huge(vertices_, total), reserve_huge(outcodes_, total), reserve_huge(screen_, total);
    vertices_.resize(total), outcodes_.resize(total), screen_.resize(total);
    const geometry::GuardBand guard(size, size);
    const geometry::Viewport viewport{size, size};
    constexpr std::size_t kRun = 4096;
    tbb::parallel_for(std::size_t(0), objects_.size(), [&](std::size_t e) {
        const Object& object = scene.objects[objects_[e]];
        const Mesh& mesh = scene.meshes[object.mesh];
        tbb::parallel_for(std::size_t(0), mesh.positions.size(), kRun, [&](std::size_t first) {
            const std::size_t count = std::min(kRun, mesh.positions.size() - first);
            const std::size_t base = first_vertex_[e] + first;
            geometry::run_vertex_stage(isa, mesh, first, object.model, view_projection, guard, viewport,
                                       {{vertices_.data() + base, count}, outcodes_.data() + base, screen_.data() + base});
        });
    });

    // The triangle pass: chunks cut as the frame cuts them, clipped, set up and binned.
    chunk_count_ = 0;
    chunk_entry_.clear();
    for (std::size_t e = 0; e < objects_.size(); ++e) {
        const auto triangles = std::uint32_t(scene.meshes[scene.objects[objects_[e]].mesh].indices.size() / 3);
        for (std::uint32_t first = 0; first < triangles; first += kChunkTriangles) {
            if (chunk_count_ >= kMaxChunks) throw std::invalid_argument("the scene has too many triangles");
            if (chunk_count_ == chunks_.size()) chunks_.emplace_back();
            Chunk& chunk = chunks_[chunk_count_++];
            chunk.object = objects_[e];
            chunk.first_triangle = first;
            chunk.triangle_count = std::min(kChunkTriangles, triangles - first);
            // Masked materials take their alpha test here too (what the
            // colours and second uvs are kept for), so that a cut-out casts its shape.
            const Mesh& mesh = scene.meshes[scene.objects[objects_[e]].mesh];
            chunk.material = &scene.materials[scene.objects[objects_[e]].material];
            chunk.alpha_tested = chunk.material->alpha_mode == AlphaMode::mask;
            chunk.colors = chunk.alpha_tested && !mesh.colors.empty() ? mesh.colors.data() : nullptr;
            chunk.uvs1 = chunk.alpha_tested && !mesh.uvs1.empty() && chunk.material->has_maps() ? mesh.uvs1.data() : nullptr;
            chunk_entry_.push_back(std::uint32_t(e));
        }
    }
    grid_ = raster::TileGrid(size, size, kShadowTileSize);
    const raster::FrameVertices frame{vertices_, outcodes_, screen_};
    tbb::parallel_for(std::size_t(0), chunk_count_, [&](std::size_t c) {
        Chunk& chunk = chunks_[c];
        const Mesh& mesh = scene.meshes[scene.objects[chunk.object].mesh];
        const std::span<const std::uint32_t> indices(mesh.indices.data() + 3 * std::size_t(chunk.first_triangle),
                                                     3 * std::size_t(chunk.triangle_count));
        chunk.assembled.clear();
        reserve_huge(chunk.assembled.triangles, chunk.triangle_count + raster::kAssemblyRoom);
        raster::assemble_triangles(isa, indices, first_vertex_[chunk_entry_[c]], std::uint32_t(mesh.positions.size()),
                                   frame, viewport, guard, chunk.assembled, 1, raster::Culling::none,
                                   {chunk.colors, chunk.colors ? mesh.colors.size() : 0}, false,
                                   {chunk.uvs1, chunk.uvs1 ? mesh.uvs1.size() : 0});
        chunk.bins.build(grid_, chunk.assembled.triangles);
    });
    tile_bins_.build(grid_, chunk_count_, [&](std::size_t c) -> const raster::ChunkBins& { return chunks_[c].bins; });

    // The tile pass: nearest depth per texel, copied into the map (each texel
    // written once: an empty tile is cleared to 1 here, not before).
    tbb::parallel_for(0, grid_.tile_count(), [&](int tile) {
        const auto entries = tile_bins_.tile(tile);
        const raster::TileRect rect = grid_.rect(tile);
        if (entries.empty()) {
            for (int y = rect.y0; y < rect.y1; ++y) std::fill_n(depth.data() + std::size_t(y) * size + rect.x0, rect.width(), 1.0f);
            if (summaries != nullptr) shade::summarize_cube_rect(*summaries, face, rect.x0, rect.y0, rect.x1, rect.y1);
            return;
        }
        raster::TileBuffers& buffers = tiles_.local();
        buffers.reset(kShadowTileSize);
        raster::RasterCounters counters;
        for (const raster::TileBinIndex::Entry& entry : entries) {
            const Chunk& chunk = chunks_[entry.chunk];
            const std::span<const std::uint32_t> bin(chunk.bins.items.data() + entry.first, entry.last - entry.first);
            if (!chunk.alpha_tested) {
                raster::rasterize_bin(isa, chunk.assembled.triangles.data(), bin, entry.chunk << kChunkIdShift, rect,
                                      buffers, counters);
                continue;
            }
            for (const std::uint32_t index : bin) {
                const raster::RasterTriangle& t = chunk.assembled.triangles[index];
                const shade::AlphaMaskTriangle mask{corners_of(chunk, t), scene.textures};
                const std::uint32_t position = buffers.triangles.add((entry.chunk << kChunkIdShift) | index);
                raster::rasterize_triangle(t, position, rect, buffers, counters, {shade::alpha_mask_keep, &mask});
            }
        }
        for (int y = rect.y0; y < rect.y1; ++y) {
            const float* from = buffers.depth.data() + std::size_t(y - rect.y0) * kShadowTileSize;
            float* to = depth.data() + std::size_t(y) * size + rect.x0;
            if (distances == nullptr) {
                std::copy_n(from, rect.width(), to);
                continue;
            }
            for (int x = 0; x < rect.width(); ++x)
                to[x] = from[x] < 1.0f ? shade::distance_from_window_depth(*distances, from[x], rect.x0 + x, y) : 1.0f;
        }
        if (summaries != nullptr) shade::summarize_cube_rect(*summaries, face, rect.x0, rect.y0, rect.x1, rect.y1);
    });
    for (std::size_t c = 0; c < chunk_count_; ++c) triangles_drawn_ += chunks_[c].assembled.triangles.size();
}

shade::TriangleCorners ShadowPass::corners_of(const Chunk& chunk, const raster::RasterTriangle& t) const {
    shade::TriangleCorners corners{{&chunk.vertex(t.vertex[0], vertices_), &chunk.vertex(t.vertex[1], vertices_),
                                    &chunk.vertex(t.vertex[2], vertices_)},
                                   chunk.material};
    // As the frame's corners_of: the barycentrics' steps per pixel (the texture's level of detail).
    const float scale = float(geometry::kSubpixelScale) * t.inv_area;
    corners.lambda1_dx = -float(t.y[0] - t.y[2]) * scale, corners.lambda1_dy = float(t.x[0] - t.x[2]) * scale;
    corners.lambda2_dx = -float(t.y[1] - t.y[0]) * scale, corners.lambda2_dy = float(t.x[1] - t.x[0]) * scale;
    const std::uint32_t first = first_vertex_[chunk_entry_[&chunk - chunks_.data()]];
    if (chunk.colors)
        for (int k = 0; k < 3; ++k) corners.color[k] = &chunk.color(t.vertex[k], first);
    if (chunk.uvs1)
        for (int k = 0; k < 3; ++k) corners.uv1[k] = &chunk.uv1(t.vertex[k], first);
    return corners;
}

void ShadowPass::render_maps(simd::Isa isa, const Scene& scene, std::vector<shade::ShadowMap>& maps,
                             std::vector<const shade::ShadowMap*>& by_light) {
    std::size_t shadowed = 0;
    for (const Light& light : scene.lights) shadowed += light.shadows ? 1 : 0;
    if (maps.size() < shadowed) maps.resize(shadowed);  // never shrunk: the maps keep their memory
    by_light.assign(scene.lights.size(), nullptr);
    maps_drawn_ = maps_kept_ = 0;
    if (shadowed == 0) return;
    prepare(scene);
    const bool cache = shadow_cache_enabled();
    const std::uint64_t casters = cache ? combine_value(casters_key(scene), isa) : 0;
    if (map_keys_.size() < maps.size()) map_keys_.resize(maps.size(), 0), map_storage_.resize(maps.size(), nullptr);
    std::size_t next = 0;
    for (std::size_t l = 0; l < scene.lights.size(); ++l) {
        const Light& light = scene.lights[l];
        if (!light.shadows) continue;
        const std::size_t slot = next++;
        shade::ShadowMap& map = maps[slot];
        shade::plan_shadow_map(scene, bounds_, light, map);
        by_light[l] = &map;
        // Everything of the plan the depth pass reads (distance maps: their projection too).
        std::uint64_t key = combine_value(combine_value(combine_value(casters, map.kind), map.size), map.faces);
        for (int face = 0; face < map.faces; ++face) key = combine_value(key, map.view_projection[face]);
        key = combine_value(combine_value(key, map.position), map.to_light);
        key = combine_value(combine_value(combine_value(key, map.near_plane), map.far_plane), map.tan_half_fov);
        key = combine_value(key, map.disk_far_plane) | 1;  // never 0, the key of nothing
        if (cache && map_keys_[slot] == key && map_storage_[slot] == map.depth.data()) {
            ++maps_kept_;
            continue;
        }
        map_keys_[slot] = 0;  // until drawn whole
        const std::size_t face_texels = std::size_t(map.size) * map.size;
        shade::prepare_cube_summaries(map);  // cube maps: what lets the lookups skip their taps
        shade::ShadowMap* summaries = map.blocks_per_side > 0 ? &map : nullptr;
        for (int face = 0; face < map.faces; ++face) {
            render_depth(isa, scene, map.view_projection[face], map.size,
                         {map.depth.data() + face * face_texels, face_texels},
                         map.kind != shade::ShadowMapKind::planar_depth ? &map : nullptr, summaries, face);
        }
        if (summaries != nullptr) shade::finish_cube_summaries(map);
        ++maps_drawn_;
        if (cache) map_keys_[slot] = key, map_storage_[slot] = map.depth.data();
    }
    if (cache) held_textures_.swap(next_textures_);
}

}  // namespace tessera::render
