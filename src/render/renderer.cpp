// The frame driver: the only place that knows every stage. A frame is
//   vertex stage -> clip, set up and bin (per chunk) -> per tile: rasterize,
//   shade the visible pixels, resolve.
#include "tessera/renderer.hpp"

#include <chrono>
#include <cstring>
#include <stdexcept>

#include <optional>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "geometry/clipper.hpp"
#include "geometry/vertex_stage.hpp"
#include "image/resolve.hpp"
#include "raster/raster_limits.hpp"
#include "render/frame_memory.hpp"
#include "shade/shade_kernels.hpp"

namespace tessera {

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

shade::Isa parse_isa(const std::string& name) {
    if (name == "auto") return shade::best_supported_isa();
    for (shade::Isa isa : {shade::Isa::scalar, shade::Isa::sse4, shade::Isa::avx2, shade::Isa::avx512}) {
        if (name != shade::isa_name(isa)) continue;
        if (!shade::isa_supported(isa)) throw std::invalid_argument("this CPU cannot run the '" + name + "' kernels");
        return isa;
    }
    throw std::invalid_argument("unknown ISA '" + name + "' (expected auto, scalar, sse4, avx2 or avx512)");
}

// Per-worker scratch for a tile: its raster buffers and the visible pixels'
// shading inputs and outputs in structure-of-arrays form.
struct TileScratch {
    raster::TileBuffers raster;
    raster::RasterCounters counters;
    std::uint64_t fragments_shaded = 0;
    // world xyz, normal xyz, albedo rgb, metallic, roughness, ao, radiance rgb
    enum Channel { wx, wy, wz, nx, ny, nz, ar, ag, ab, metal, rough, occl, out_r, out_g, out_b, kChannels };
    std::vector<float> channels[kChannels];

    void reserve(int tile_side) {
        raster.reset(tile_side);
        const std::size_t n = shade::padded_count(std::size_t(tile_side) * tile_side);
        for (auto& c : channels) c.resize(n);
    }
};

}  // namespace

struct Renderer::Frame {
    RenderSettings settings;
    shade::Isa isa;
    // oneTBB runs no more workers than cores unless told: asking for more
    // threads than that must really give more (the determinism tests do).
    std::optional<tbb::global_control> allow_oversubscription;
    tbb::task_arena arena;
    FrameStats stats;
    RenderedImage image;

    std::vector<geometry::ShadedVertex> vertices;  // every object's vertices, object after object
    std::vector<std::uint32_t> outcodes;           // one per vertex
    std::vector<geometry::ScreenVertex> screen;    // one per vertex; set where the outcode has no clip bit
    std::vector<std::uint32_t> first_vertex;       // per object, into `vertices`
    std::vector<render::Chunk> chunks;
    std::size_t chunk_count = 0;
    raster::TileGrid grid;
    shade::ShadingLights lights;
    tbb::enumerable_thread_specific<TileScratch> scratch;

    explicit Frame(const RenderSettings& s)
        : settings(s), isa(parse_isa(s.isa)), arena(s.threads > 0 ? s.threads : tbb::info::default_concurrency()) {
        if (s.threads > tbb::info::default_concurrency())
            allow_oversubscription.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(s.threads));
    }

    void run_vertex_stage(const Scene& scene, const glm::mat4& view_projection);
    void setup_and_bin(const Scene& scene);
    void render_tiles(const Scene& scene);
    void render_tile(const Scene& scene, int tile, TileScratch& scratch);
    const geometry::ShadedVertex& vertex(const render::Chunk& chunk, std::uint32_t ref) const {
        return (ref & geometry::kClippedVertexBit) ? chunk.clipped_vertices[ref & ~geometry::kClippedVertexBit]
                                                   : vertices[ref];
    }
};

Renderer::Renderer(const RenderSettings& settings) {
    if (settings.threads < 0) throw std::invalid_argument("thread count must be >= 0");
    const int t = settings.tile_size;
    if (t < raster::kMinTileSize || t > raster::kMaxTileSize || (t & (t - 1)) != 0)
        throw std::invalid_argument("tile size must be a power of two from " + std::to_string(raster::kMinTileSize) +
                                    " to " + std::to_string(raster::kMaxTileSize));
    frame_ = std::make_unique<Frame>(settings);
}

Renderer::~Renderer() = default;

const FrameStats& Renderer::last_frame_stats() const { return frame_->stats; }
std::string Renderer::isa_name() const { return std::string(shade::isa_name(frame_->isa)); }
int Renderer::threads() const { return frame_->arena.max_concurrency(); }

const RenderedImage& Renderer::render(const Scene& scene) {
    if (scene.width < 1 || scene.height < 1 || scene.width > kMaxImageDimension || scene.height > kMaxImageDimension)
        throw std::invalid_argument("image size must be from 1 to " + std::to_string(kMaxImageDimension) +
                                    " pixels per side");
    Frame& f = *frame_;
    f.stats = {};
    const auto frame_start = Clock::now();
    f.arena.execute([&] {
        const glm::mat4 view_projection =
            projection_matrix(scene.camera, scene.width, scene.height) * view_matrix(scene.camera);
        auto start = Clock::now();
        f.run_vertex_stage(scene, view_projection);
        f.stats.vertex_ms = ms_since(start);

        start = Clock::now();
        f.setup_and_bin(scene);
        f.stats.setup_and_binning_ms = ms_since(start);

        start = Clock::now();
        f.render_tiles(scene);
        f.stats.tiles_ms = ms_since(start);
    });
    f.stats.total_ms = ms_since(frame_start);
    return f.image;
}

void Renderer::Frame::run_vertex_stage(const Scene& scene, const glm::mat4& view_projection) {
    first_vertex.resize(scene.objects.size());
    std::size_t total = 0;
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        first_vertex[o] = std::uint32_t(total);
        total += scene.meshes[scene.objects[o].mesh].positions.size();
        stats.triangles_in += scene.meshes[scene.objects[o].mesh].indices.size() / 3;
    }
    if (total >= geometry::kClippedVertexBit) throw std::invalid_argument("the scene has too many vertices");
    vertices.resize(total);
    outcodes.resize(total);
    screen.resize(total);
    const geometry::GuardBand guard(scene.width, scene.height);
    const geometry::Viewport viewport{scene.width, scene.height};
    tbb::parallel_for(std::size_t(0), scene.objects.size(), [&](std::size_t o) {
        const Object& object = scene.objects[o];
        const Mesh& mesh = scene.meshes[object.mesh];
        const std::span<geometry::ShadedVertex> out(vertices.data() + first_vertex[o], mesh.positions.size());
        geometry::shade_vertices(mesh, object.model, view_projection, out);
        for (std::size_t i = 0, v = first_vertex[o]; i < out.size(); ++i, ++v) {
            outcodes[v] = geometry::outcode(out[i].clip_pos, guard);
            // The viewport transform, once per vertex rather than once per triangle corner.
            if (!(outcodes[v] & geometry::kClipPlaneBits)) screen[v] = geometry::to_screen(out[i].clip_pos, viewport);
        }
    });
}

void Renderer::Frame::setup_and_bin(const Scene& scene) {
    // Cut every object's triangles into chunks; the cut depends on the scene only.
    chunk_count = 0;
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        const auto triangles = std::uint32_t(scene.meshes[scene.objects[o].mesh].indices.size() / 3);
        for (std::uint32_t first = 0; first < triangles; first += render::kChunkTriangles) {
            if (chunk_count >= render::kMaxChunks) throw std::invalid_argument("the scene has too many triangles");
            if (chunk_count == chunks.size()) chunks.emplace_back();
            render::Chunk& chunk = chunks[chunk_count++];
            chunk.object = std::uint32_t(o);
            chunk.first_triangle = first;
            chunk.triangle_count = std::min(render::kChunkTriangles, triangles - first);
        }
    }
    grid = raster::TileGrid(scene.width, scene.height, settings.tile_size);
    const geometry::Viewport viewport{scene.width, scene.height};
    const geometry::GuardBand guard(scene.width, scene.height);

    tbb::parallel_for(std::size_t(0), chunk_count, [&](std::size_t c) {
        render::Chunk& chunk = chunks[c];
        chunk.triangles.clear();
        chunk.triangles.reserve(chunk.triangle_count);  // most triangles stay one triangle
        chunk.clipped_vertices.clear();
        const Object& object = scene.objects[chunk.object];
        const std::uint32_t* indices = scene.meshes[object.mesh].indices.data() + 3 * std::size_t(chunk.first_triangle);
        const std::uint32_t base = first_vertex[chunk.object];
        geometry::ClippedPolygon polygon;
        for (std::uint32_t t = 0; t < chunk.triangle_count; ++t) {
            const std::array<std::uint32_t, 3> ref{base + indices[3 * t], base + indices[3 * t + 1], base + indices[3 * t + 2]};
            const std::uint32_t oc0 = outcodes[ref[0]], oc1 = outcodes[ref[1]], oc2 = outcodes[ref[2]];
            const geometry::ClipResult kind = geometry::classify_triangle(oc0, oc1, oc2);
            if (kind == geometry::ClipResult::rejected) continue;
            if (kind == geometry::ClipResult::accepted) {
                const auto set_up =
                    raster::setup_triangle(viewport, {screen[ref[0]], screen[ref[1]], screen[ref[2]]}, ref, object.material);
                if (set_up) chunk.triangles.push_back(*set_up);
                continue;
            }
            geometry::clip_triangle(vertices[ref[0]], vertices[ref[1]], vertices[ref[2]],
                                    (oc0 | oc1 | oc2) & geometry::kClipPlaneBits, guard, polygon);
            // Give every new corner a reference into the chunk's clipped vertices.
            std::array<std::uint32_t, geometry::ClippedPolygon::kMaxCorners> corner_ref;
            for (int i = 0; i < polygon.count; ++i) {
                if (polygon.source[i] >= 0) {
                    corner_ref[i] = ref[polygon.source[i]];
                } else {
                    corner_ref[i] = geometry::kClippedVertexBit | std::uint32_t(chunk.clipped_vertices.size());
                    chunk.clipped_vertices.push_back(polygon.corners[i]);
                }
            }
            for (int i = 1; i + 1 < polygon.count; ++i) {  // a fan around corner 0
                const auto set_up = raster::setup_triangle(
                    viewport, {polygon.corners[0].clip_pos, polygon.corners[i].clip_pos, polygon.corners[i + 1].clip_pos},
                    {corner_ref[0], corner_ref[i], corner_ref[i + 1]}, object.material);
                if (set_up) chunk.triangles.push_back(*set_up);
            }
        }
        chunk.bins.build(grid, chunk.triangles);
    });
    for (std::size_t c = 0; c < chunk_count; ++c) stats.triangles_binned += chunks[c].triangles.size();
}

void Renderer::Frame::render_tiles(const Scene& scene) {
    image.width = scene.width;
    image.height = scene.height;
    const std::size_t pixels = std::size_t(scene.width) * scene.height;
    image.radiance.resize(3 * pixels);
    image.display.resize(3 * pixels);
    lights.assign(scene.camera.position, scene.lights);
    for (TileScratch& s : scratch) s.counters = {}, s.fragments_shaded = 0;

    tbb::parallel_for(0, grid.tile_count(), [&](int tile) {
        TileScratch& s = scratch.local();
        if (s.raster.side != grid.tile_size) s.reserve(grid.tile_size);
        render_tile(scene, tile, s);
    });
    for (const TileScratch& s : scratch) {
        stats.fragments_rasterized += s.counters.fragments;
        stats.fragments_shaded += s.fragments_shaded;
    }
}

void Renderer::Frame::render_tile(const Scene& scene, int tile, TileScratch& s) {
    const raster::TileRect rect = grid.rect(tile);
    s.raster.reset(grid.tile_size);

    // Rasterize: every chunk's triangles for this tile, in submission order.
    for (std::size_t c = 0; c < chunk_count; ++c) {
        const render::Chunk& chunk = chunks[c];
        for (std::uint32_t index : chunk.bins.tile(tile)) {
            const std::uint32_t id = (std::uint32_t(c) << render::kChunkIdShift) | index;
            raster::rasterize_triangle(isa, chunk.triangles[index], id, rect, s.raster, s.counters);
        }
    }

    // Gather the visible pixels' surface points, row by row. Neighbouring
    // pixels mostly show the same triangle, so its corners are fetched once per run.
    auto& ch = s.channels;
    std::size_t count = 0;
    std::uint32_t cached_id = raster::kNoTriangle;
    const raster::RasterTriangle* t = nullptr;
    const Material* m = nullptr;
    glm::vec3 world0{}, world_d1{}, world_d2{}, normal0{}, normal_d1{}, normal_d2{};
    for (int y = 0; y < rect.height(); ++y) {
        const std::size_t row = std::size_t(y) * s.raster.side;
        for (int x = 0; x < rect.width(); ++x) {
            if (!s.raster.covered(row + x)) continue;
            const std::uint32_t id = s.raster.triangle[row + x];
            if (id != cached_id) {
                cached_id = id;
                const render::Chunk& chunk = chunks[id >> render::kChunkIdShift];
                t = &chunk.triangles[id & ((1u << render::kChunkIdShift) - 1)];
                m = &scene.materials[t->material];
                const geometry::ShadedVertex& v0 = vertex(chunk, t->vertex[0]);
                const geometry::ShadedVertex& v1 = vertex(chunk, t->vertex[1]);
                const geometry::ShadedVertex& v2 = vertex(chunk, t->vertex[2]);
                world0 = v0.world_pos, world_d1 = v1.world_pos - v0.world_pos, world_d2 = v2.world_pos - v0.world_pos;
                normal0 = v0.normal, normal_d1 = v1.normal - v0.normal, normal_d2 = v2.normal - v0.normal;
            }
            const auto [b1, b2] = raster::perspective_barycentrics(*t, s.raster.lambda1[row + x], s.raster.lambda2[row + x]);
            const glm::vec3 world = world0 + b1 * world_d1 + b2 * world_d2;
            const glm::vec3 normal = normal0 + b1 * normal_d1 + b2 * normal_d2;
            ch[TileScratch::wx][count] = world.x, ch[TileScratch::wy][count] = world.y, ch[TileScratch::wz][count] = world.z;
            ch[TileScratch::nx][count] = normal.x, ch[TileScratch::ny][count] = normal.y, ch[TileScratch::nz][count] = normal.z;
            ch[TileScratch::ar][count] = m->albedo.r, ch[TileScratch::ag][count] = m->albedo.g, ch[TileScratch::ab][count] = m->albedo.b;
            ch[TileScratch::metal][count] = m->metallic, ch[TileScratch::rough][count] = m->roughness;
            ch[TileScratch::occl][count] = m->ao;
            ++count;
        }
    }
    // Padding lanes get copies of a real fragment so the kernels see sane values.
    for (std::size_t i = count; i < shade::padded_count(count); ++i)
        for (auto& c : ch) c[i] = count > 0 ? c[0] : 0.5f;

    // Shade.
    const shade::FragmentInputs in{count, ch[TileScratch::wx].data(), ch[TileScratch::wy].data(),
                                   ch[TileScratch::wz].data(), ch[TileScratch::nx].data(), ch[TileScratch::ny].data(),
                                   ch[TileScratch::nz].data(), ch[TileScratch::ar].data(), ch[TileScratch::ag].data(),
                                   ch[TileScratch::ab].data(), ch[TileScratch::metal].data(),
                                   ch[TileScratch::rough].data(), ch[TileScratch::occl].data()};
    const shade::RadianceOutputs out{ch[TileScratch::out_r].data(), ch[TileScratch::out_g].data(),
                                     ch[TileScratch::out_b].data()};
    if (count > 0) shade::shade_fragments(isa, in, lights, out);

    // Resolve: every pixel of the tile written once, shaded pixels in the order
    // they were gathered, the rest with the clear colour. Radiance first, since
    // the tonemap works in place.
    const glm::vec3 clear_radiance = image::radiance_for_display(scene.clear_color);
    const std::uint8_t clear_display[3] = {image::quantize_unorm8(scene.clear_color.r),
                                           image::quantize_unorm8(scene.clear_color.g),
                                           image::quantize_unorm8(scene.clear_color.b)};
    auto for_each_pixel = [&](auto&& write) {
        std::size_t k = 0;
        for (int y = 0; y < rect.height(); ++y) {
            const float* depth = &s.raster.depth[std::size_t(y) * s.raster.side];
            const std::size_t first = 3 * (std::size_t(rect.y0 + y) * image.width + rect.x0);
            for (int x = 0; x < rect.width(); ++x) {
                const bool shaded = depth[x] < 1.0f;  // TileBuffers::covered
                write(first + 3 * std::size_t(x), shaded, k);
                k += shaded;
            }
        }
    };
    for_each_pixel([&](std::size_t i, bool shaded, std::size_t k) {
        float* radiance = &image.radiance[i];
        if (shaded) radiance[0] = out.r[k], radiance[1] = out.g[k], radiance[2] = out.b[k];
        else radiance[0] = clear_radiance.r, radiance[1] = clear_radiance.g, radiance[2] = clear_radiance.b;
    });
    if (count > 0) shade::tonemap_gamma(isa, count, out.r, out.g, out.b);
    for_each_pixel([&](std::size_t i, bool shaded, std::size_t k) {
        std::uint8_t* display = &image.display[i];
        if (shaded) {
            display[0] = image::quantize_unorm8(out.r[k]);
            display[1] = image::quantize_unorm8(out.g[k]);
            display[2] = image::quantize_unorm8(out.b[k]);
        } else {
            display[0] = clear_display[0], display[1] = clear_display[1], display[2] = clear_display[2];
        }
    });
    s.fragments_shaded += count;
}

}  // namespace tessera
