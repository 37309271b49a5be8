// The frame driver: the only place that knows every stage. A frame is
//   vertex stage -> per chunk of triangles: clip, set up, bin into tiles ->
//   per tile: rasterize, shade the visible pixels, resolve into the images.
// Every pass runs in parallel; none depends on scheduling, so the image is the
// same for any thread count.
#include "tessera/renderer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <optional>
#include <span>
#include <stdexcept>
#include <type_traits>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "geometry/clipper.hpp"
#include "geometry/draw_order.hpp"
#include "geometry/line_expansion.hpp"
#include "geometry/vertex_stage.hpp"
#include "image/blend.hpp"
#include "image/environment_background.hpp"
#include "image/resolve.hpp"
#include "raster/bin_rasterizer.hpp"
#include "raster/blend_raster.hpp"
#include "raster/msaa/msaa.hpp"
#include "raster/msaa/msaa_bin.hpp"
#include "raster/raster_limits.hpp"
#include "raster/triangle_assembly.hpp"
#include "render/frame_memory.hpp"
#include "render/huge_pages.hpp"
#include "render/shadow_pass.hpp"
#include "shade/alpha_mask.hpp"
#include "shade/light_culling.hpp"
#include "shade/material_maps.hpp"
#include "shade/shade_kernels.hpp"
#include "shade/shadow_maps.hpp"
#include "shade/surface_gather_fast.hpp"

namespace tessera {

namespace {

using Clock = std::chrono::steady_clock;
double ms_between(Clock::time_point start, Clock::time_point end) {
    return std::chrono::duration<double, std::milli>(end - start).count();
}

simd::Isa parse_isa(const std::string& name) {
    if (name == "auto") return simd::best_supported_isa();
    for (simd::Isa isa : {simd::Isa::scalar, simd::Isa::sse4, simd::Isa::avx2, simd::Isa::avx512}) {
        if (name != simd::isa_name(isa)) continue;
        if (!simd::isa_supported(isa)) throw std::invalid_argument("this CPU cannot run the '" + name + "' kernels");
        return isa;
    }
    throw std::invalid_argument("unknown ISA '" + name + "' (expected auto, scalar, sse4, avx2 or avx512)");
}

// One worker's memory, reserved once and reused, and its busy time this frame.
struct WorkerScratch {
    raster::TileBuffers raster;
    raster::TileSamples samples;             // 4× MSAA only
    raster::TileFragments sample_fragments;  // 4× MSAA only
    int reserved_msaa = 0;
    shade::FragmentBuffer fragments;
    std::vector<shade::MaterialRun> material_runs;
    shade::MaterialScratch material_scratch;
    shade::LightCullScratch light_culling;
    raster::BlendFragments blend_fragments;  // blended objects only: reserved at the first tile that has them
    image::TileRadiance blend_radiance;
    raster::RasterCounters counters;
    std::uint64_t fragments_shaded = 0;
    std::uint64_t fragment_lights = 0;
    shade::CubeLookupStats shadow_lookups;
    std::uint64_t tile_triangles = 0;  // rasterized in the current tile (profile)
    std::uint32_t tile_light_count = 0;  // lights shaded in the current tile (profile)
    std::vector<ProfileSpan> spans;    // this worker's chunks and tiles, with RenderSettings::profile
    // Zeros for the ao channel of the direct-light kernels when an environment
    // gives the ambient term instead (their 0.03·albedo·0 adds exactly 0).
    std::vector<float> zero_ao;
    std::vector<float> visibility;  // shadowed lights' visibility planes (FragmentInputs::visibility)
    double clip_setup_ms = 0, binning_ms = 0, rasterize_ms = 0, shade_ms = 0, resolve_ms = 0;

    void reserve(int tile_side, int msaa) {
        raster.reset(tile_side);
        // With MSAA a pixel has up to one fragment per sample.
        const std::size_t max_fragments = std::size_t(tile_side) * tile_side * msaa;
        if (msaa > 1) samples.reset(tile_side), sample_fragments.reserve(tile_side);
        reserved_msaa = msaa;
        fragments.reserve(max_fragments);
        material_runs.reserve(max_fragments);
        material_scratch.reserve(max_fragments);
    }
};

// What render() relies on and checks itself, at a cost per object, not per
// vertex: sizes, and the references it indexes with. Index values are checked
// as triangles are assembled (out of range: the triangle is dropped).
// validate_scene() checks everything, with messages for people.
void check_renderable(const Scene& scene) {
    if (scene.width < 1 || scene.height < 1 || scene.width > kMaxImageDimension || scene.height > kMaxImageDimension ||
        std::int64_t(scene.width) * scene.height > kMaxImagePixels)
        throw std::invalid_argument("image size " + std::to_string(scene.width) + "x" + std::to_string(scene.height) +
                                    " is outside 1.." + std::to_string(kMaxImageDimension) + " per side or above " +
                                    std::to_string(kMaxImagePixels) + " pixels");
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        const Object& object = scene.objects[o];
        if (object.mesh >= scene.meshes.size() || object.material >= scene.materials.size())
            throw std::invalid_argument("object " + std::to_string(o) + " refers to a missing mesh or material");
        const Mesh& mesh = scene.meshes[object.mesh];
        if (mesh.topology != Topology::triangles) {
            if (mesh.topology == Topology::lines && mesh.indices.size() % 2 != 0)
                throw std::invalid_argument("mesh '" + mesh.name + "' draws lines from an odd number of indices");
            continue;  // checked again as triangles once expanded
        }
        if (mesh.normals.size() != mesh.positions.size() || mesh.indices.size() % 3 != 0 ||
            (!mesh.colors.empty() && mesh.colors.size() != mesh.positions.size()) ||
            (!mesh.uvs1.empty() && mesh.uvs1.size() != mesh.positions.size()))
            throw std::invalid_argument("mesh '" + mesh.name +
                                        "' needs one normal (and colour and second uv, if any) per position and whole triangles");
    }
    if (scene.msaa != 1 && scene.msaa != raster::kMsaaSamples)
        throw std::invalid_argument("msaa must be 1 or 4, not " + std::to_string(scene.msaa));
    std::uint64_t shadow_texels = 0;  // the frame's shadow maps and cube maps' summaries, 4 bytes each
    for (std::size_t l = 0; l < scene.lights.size(); ++l) {
        const Light& light = scene.lights[l];
        if (!light.shadows) continue;
        const std::uint64_t side = std::uint64_t(std::max(light.shadow_map_size, 0));
        const std::uint64_t blocks = std::uint64_t(shade::summary_blocks_per_side(light.shadow_map_size));
        shadow_texels += light.type == LightType::point ? 6 * (side * side + 2 * blocks * blocks) : side * side;
        if (light.shadow_map_size < kMinShadowMapSize || light.shadow_map_size > kMaxShadowMapSize ||
            light.shadow_filter_radius < 0 || light.shadow_filter_radius > kMaxShadowFilterRadius)
            throw std::invalid_argument("light " + std::to_string(l) + ": shadow map size " +
                                        std::to_string(light.shadow_map_size) + " or filter radius " +
                                        std::to_string(light.shadow_filter_radius) + " outside " +
                                        std::to_string(kMinShadowMapSize) + ".." + std::to_string(kMaxShadowMapSize) +
                                        " and 0.." + std::to_string(kMaxShadowFilterRadius));
    }
    if (shadow_texels * sizeof(float) > kMaxShadowMapBytes)
        throw std::invalid_argument("the lights' shadow maps would take " +
                                    std::to_string(shadow_texels * sizeof(float) >> 20) + " MiB, more than " +
                                    std::to_string(kMaxShadowMapBytes >> 20) +
                                    " MiB: give fewer lights shadows or smaller shadow_map_size");
}

// Sizes the AOV planes the settings ask for (memory kept from frame to
// frame); the others stay empty and never allocate.
void size_aov_planes(AovSet wanted, std::size_t pixels, AovPlanes& aov) {
    const auto size = [&](Aov which, auto& plane, std::size_t per_pixel) {
        if (!wanted.contains(which)) return plane.clear();
        render::reserve_huge(plane, per_pixel * pixels);
        plane.resize(per_pixel * pixels);
    };
    size(Aov::depth, aov.depth, 1);
    size(Aov::normal, aov.normal, 3);
    size(Aov::albedo, aov.albedo, 3);
    size(Aov::roughness, aov.roughness, 1);
    size(Aov::metallic, aov.metallic, 1);
    size(Aov::position, aov.position, 3);
    size(Aov::object_id, aov.object_id, 1);
    size(Aov::material_id, aov.material_id, 1);
    size(Aov::shadow, aov.shadow, 1);
}

// Back faces of single-sided materials. Front faces are counter-clockwise in
// GL window space, negative area in image space (raster::Culling), unless the
// model matrix mirrors: a negative determinant swaps them (glTF's rule; a GL
// renderer flips glFrontFace). The camera's matrices are the same for every
// object, so the model matrix alone decides.
bool mirrors(const Object& object) { return glm::determinant(glm::mat3(object.model)) < 0.0f; }

raster::Culling culling_of(const Scene& scene, const Object& object) {
    if (scene.materials[object.material].double_sided) return raster::Culling::none;
    return mirrors(object) ? raster::Culling::drop_negative_area : raster::Culling::drop_positive_area;
}

}  // namespace

std::string_view aov_name(Aov aov) {
    switch (aov) {
    case Aov::depth: return "depth";
    case Aov::normal: return "normal";
    case Aov::albedo: return "albedo";
    case Aov::roughness: return "roughness";
    case Aov::metallic: return "metallic";
    case Aov::position: return "position";
    case Aov::object_id: return "object_id";
    case Aov::material_id: return "material_id";
    case Aov::shadow: return "shadow";
    }
    return "?";
}

void parse_aov_list(std::string_view list, AovSet& set) {
    for (std::size_t begin = 0;;) {
        const std::size_t comma = list.find(',', begin);
        const std::string_view name = list.substr(begin, comma == std::string_view::npos ? comma : comma - begin);
        const Aov* known = std::find_if(std::begin(kAllAovs), std::end(kAllAovs),
                                        [&](Aov aov) { return name == aov_name(aov); });
        if (known == std::end(kAllAovs)) {
            std::string expected;
            for (Aov aov : kAllAovs) expected += (expected.empty() ? "" : ", ") + std::string(aov_name(aov));
            throw std::invalid_argument("unknown AOV '" + std::string(name) + "' in '" + std::string(list) +
                                        "' (expected a comma-separated list of " + expected + ")");
        }
        set.insert(*known);
        if (comma == std::string_view::npos) return;
        begin = comma + 1;
    }
}

struct Renderer::Frame {
    RenderSettings settings;
    simd::Isa isa;
    // oneTBB runs no more workers than cores unless told: asking for more
    // threads than that must really give more (the determinism tests do).
    std::optional<tbb::global_control> allow_oversubscription;
    tbb::task_arena arena;
    FrameStats stats;
    FrameProfile profile;
    Clock::time_point frame_start;  // the origin of profile spans
    RenderedImage image;

    Scene expanded_scene;  // the scene with its points and lines as triangles (geometry/line_expansion.hpp)
    std::vector<geometry::ShadedVertex> vertices;  // every object's vertices, object after object
    std::vector<glm::vec4> tangents;               // world-space tangents, beside `vertices`; set only for meshes that have them
    std::vector<std::uint32_t> outcodes;           // one per vertex
    std::vector<geometry::ScreenVertex> screen;    // one per vertex; set where the outcode has no clip bit
    std::vector<std::uint32_t> first_vertex;       // per object, into `vertices`
    std::vector<render::Chunk> chunks;             // only the first chunk_count are this frame's
    std::size_t chunk_count = 0;
    std::vector<std::uint32_t> object_first_chunk;  // per object, its first chunk; then chunk_count
    std::vector<std::uint32_t> blend_chunks;       // the blended objects' chunks, in drawing order (geometry/draw_order.hpp)
    bool any_unlit = false;                        // some material is unlit (shade::apply_unlit)
    raster::TileBinIndex tile_bins;                // per tile, the chunks' bins that are not empty
    raster::TileGrid grid;
    shade::ShadingLights lights;
    render::ShadowPass shadow_pass;                       // the shadow maps' depth passes
    std::vector<shade::ShadowMap> shadow_maps;            // this frame's, kept from frame to frame
    std::vector<const shade::ShadowMap*> shadow_by_light;  // per scene light, its map or null
    shade::IblLighting ibl;                    // the scene's environment; ibl.maps null = none
    image::EnvironmentBackground background;   // shown where no surface is, if the scene says so
    float exposure_scale = 1.0f;               // 2^Scene::exposure_ev
    image::ViewDepth view_depth;  // for the depth AOV
    // Per chunk, its object's object_id and material_id AOV values; filled only
    // when those AOVs are asked for (surface_ids points into them).
    std::vector<std::uint32_t> chunk_object_id, chunk_material_id;
    image::SurfaceIds surface_ids;
    tbb::enumerable_thread_specific<WorkerScratch> scratch;

    explicit Frame(const RenderSettings& s)
        : settings(s), isa(parse_isa(s.isa)), arena(s.threads > 0 ? s.threads : tbb::info::default_concurrency()) {
        if (s.threads > tbb::info::default_concurrency())
            allow_oversubscription.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(s.threads));
    }

    void run_vertex_stage(const Scene& scene);
    void cut_into_chunks(const Scene& scene);
    void assemble_and_bin(const Scene& scene);
    void render_tiles(const Scene& scene);
    void render_tile(const Scene& scene, const image::ClearValues& clear, int tile, WorkerScratch& scratch);
    void render_tile_msaa(const Scene& scene, const image::ClearValues& clear, int tile, WorkerScratch& scratch);
    // Whether blended triangles touch the tile; if so, the worker's blend memory is made ready.
    bool has_blended(int tile, int msaa, WorkerScratch& s) const {
        const bool any = std::any_of(blend_chunks.begin(), blend_chunks.end(),
                                     [&](std::uint32_t c) { return !chunks[c].bins.tile(tile).empty(); });
        if (any && (s.blend_radiance.side != grid.tile_size || s.blend_radiance.samples != msaa)) {
            s.blend_radiance.reserve(grid.tile_size, msaa);
            s.blend_fragments.reserve(grid.tile_size, msaa);
        }
        return any;
    }
    void blend_tile(const Scene& scene, const image::ClearValues& clear, int tile, bool opaque_drawn, WorkerScratch& s);
    void record_span(WorkerScratch& s, ProfileSpan span, Clock::time_point start, Clock::time_point end) const {
        span.worker = tbb::this_task_arena::current_thread_index();
        span.start_ms = ms_between(frame_start, start), span.end_ms = ms_between(frame_start, end);
        s.spans.push_back(span);
    }
    void collect_profile(Clock::time_point t1, Clock::time_point t2, Clock::time_point t3);
    template <class Reset, class Rasterize, class RasterizeBin = std::nullptr_t>
    bool rasterize_bins(int tile, WorkerScratch& s, Reset&& reset, Rasterize&& rasterize,
                        RasterizeBin&& rasterize_bin = nullptr) const;
    void rasterize_bin(const render::Chunk& chunk, std::span<const std::uint32_t> bin, std::uint32_t id_base,
                       const raster::TileRect& rect, WorkerScratch& s) const;
    template <class Gather, class Resolve>
    void shade_and_resolve(const Scene& scene, const image::ClearValues& clear, int tile, bool drawn,
                           Clock::time_point raster_start, WorkerScratch& s, Gather&& gather, Resolve&& resolve,
                           bool blended);
    std::size_t shade_tile(const Scene& scene, std::size_t count, WorkerScratch& scratch) const;
    // The inputs with the visibility planes shade_tile left in the worker's scratch (the shadow AOV).
    shade::FragmentInputs with_visibility(shade::FragmentInputs in, const WorkerScratch& s) const {
        if (lights.shadowed_count() == 0) return in;
        in.visibility = s.visibility.data(), in.visibility_stride = shade::padded_count(in.count);
        in.visibility_planes = lights.shadowed_count();
        return in;
    }
    shade::TriangleCorners corners_of(const Scene& scene, std::uint32_t id) const;
    // The gathers' lookup (set by render_tiles): the chunks' triangles, corners
    // and materials as plain arrays, corners_of through `full`.
    std::vector<shade::GatherChunk> gather_chunks;  // per chunk
    const Scene* gathered_scene = nullptr;
    shade::GatherCornerLookup corner_lookup;
    void set_corner_lookup(const Scene& scene) {
        gather_chunks.clear();
        for (std::size_t c = 0; c < chunk_count; ++c)
            gather_chunks.push_back({chunks[c].assembled.triangles.data(), chunks[c].assembled.clipped_vertices.data(),
                                     chunks[c].material, chunks[c].beyond_plain});
        gathered_scene = &scene;
        corner_lookup = {vertices.data(), gather_chunks.data(), render::kChunkIdShift,
                         [](const void* frame, std::uint32_t id) {
                             const Frame& f = *static_cast<const Frame*>(frame);
                             return f.corners_of(*f.gathered_scene, id);
                         },
                         this};
    }
    const raster::RasterTriangle& triangle_of(std::uint32_t id) const {
        return chunks[id >> render::kChunkIdShift].assembled.triangles[id & render::kChunkIndexMask];
    }
    void describe_for_textures(const raster::RasterTriangle& t, const Mesh& mesh, shade::TriangleCorners& corners) const;
    // A triangle that has just won a depth test will likely be gathered: its
    // corners are fetched then, while the rest of the tile rasterizes, instead
    // of stalling the gather (they lie scattered through the frame's vertices,
    // or the chunk's clipped ones: Chunk::vertex).
    raster::CornerPrefetch corner_prefetch(const render::Chunk& chunk) const {
        return {reinterpret_cast<const std::byte*>(vertices.data()),
                reinterpret_cast<const std::byte*>(chunk.assembled.clipped_vertices.data()),
                sizeof(geometry::ShadedVertex)};
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
const FrameProfile& Renderer::last_frame_profile() const { return frame_->profile; }
std::string Renderer::isa_name() const { return std::string(simd::isa_name(frame_->isa)); }
int Renderer::threads() const { return frame_->arena.max_concurrency(); }
void Renderer::swap_image(RenderedImage& other) { std::swap(frame_->image, other); }

const RenderedImage& Renderer::render(const Scene& given) {
    check_renderable(given);
    Frame& f = *frame_;
    // Points and lines become triangles for this camera and size (a copy of the
    // scene, kept for the frame; scenes without them are drawn as they are).
    const bool expand = geometry::has_points_or_lines(given);
    if (expand) geometry::expand_points_and_lines(given, f.expanded_scene);
    const Scene& scene = expand ? f.expanded_scene : given;
    f.stats = {};
    f.profile.spans.clear();
    for (WorkerScratch& s : f.scratch) s.spans.clear();
    f.arena.execute([&] {
        const auto t0 = Clock::now();
        f.frame_start = t0;
        f.run_vertex_stage(scene);
        const auto t1 = Clock::now();
        f.cut_into_chunks(scene);
        f.assemble_and_bin(scene);
        const auto shadow_start = Clock::now();
        f.shadow_pass.render_maps(f.isa, scene, f.shadow_maps, f.shadow_by_light);
        const auto t2 = Clock::now();
        f.stats.shadow_ms = ms_between(shadow_start, t2);
        f.stats.shadow_maps_drawn = std::uint32_t(f.shadow_pass.maps_drawn());
        f.stats.shadow_maps_kept = std::uint32_t(f.shadow_pass.maps_kept());
        f.render_tiles(scene);
        const auto t3 = Clock::now();
        f.stats.vertex_ms = ms_between(t0, t1);
        f.stats.triangles_ms = ms_between(t1, shadow_start);
        f.stats.tiles_ms = ms_between(t2, t3);
        f.stats.total_ms = ms_between(t0, t3);
        if (f.settings.profile) f.collect_profile(t1, t2, t3);
    });
    return f.image;
}

// The passes on the calling thread's track, then every worker's spans.
void Renderer::Frame::collect_profile(Clock::time_point t1, Clock::time_point t2, Clock::time_point t3) {
    profile.threads = arena.max_concurrency();
    profile.width = grid.width, profile.height = grid.height;
    profile.tile_size = grid.tile_size, profile.tiles_x = grid.tiles_x, profile.tiles_y = grid.tiles_y;
    profile.total_ms = stats.total_ms;
    const int caller = tbb::this_task_arena::current_thread_index();
    const auto pass = [&](const char* name, Clock::time_point start, Clock::time_point end) {
        ProfileSpan span;
        span.name = name, span.worker = caller;
        span.start_ms = ms_between(frame_start, start), span.end_ms = ms_between(frame_start, end);
        profile.spans.push_back(span);
    };
    pass("vertex", frame_start, t1);
    pass("triangles", t1, t2);
    pass("tiles", t2, t3);
    const std::size_t passes = profile.spans.size();
    for (const WorkerScratch& s : scratch) profile.spans.insert(profile.spans.end(), s.spans.begin(), s.spans.end());
    std::sort(profile.spans.begin() + std::ptrdiff_t(passes), profile.spans.end(),
              [](const ProfileSpan& a, const ProfileSpan& b) {
                  return a.worker != b.worker ? a.worker < b.worker : a.start_ms < b.start_ms;
              });
}

void Renderer::Frame::run_vertex_stage(const Scene& scene) {
    first_vertex.resize(scene.objects.size());
    std::size_t total = 0;
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        first_vertex[o] = std::uint32_t(total);
        total += scene.meshes[scene.objects[o].mesh].positions.size();
        stats.triangles_in += scene.meshes[scene.objects[o].mesh].indices.size() / 3;
    }
    if (total >= geometry::kClippedVertexBit) throw std::invalid_argument("the scene has too many vertices");
    render::reserve_huge(vertices, total);
    render::reserve_huge(outcodes, total);
    render::reserve_huge(screen, total);
    const bool any_tangents = std::any_of(scene.objects.begin(), scene.objects.end(), [&](const Object& o) {
        return !scene.meshes[o.mesh].tangents.empty();
    });
    if (any_tangents) render::reserve_huge(tangents, total), tangents.resize(total);
    vertices.resize(total);
    outcodes.resize(total);
    screen.resize(total);
    const glm::mat4 view_projection =
        projection_matrix(scene.camera, scene.width, scene.height) * view_matrix(scene.camera);
    const geometry::GuardBand guard(scene.width, scene.height);
    const geometry::Viewport viewport{scene.width, scene.height};
    // In runs of vertices, so that one large mesh spreads over every thread too.
    constexpr std::size_t kRun = 4096;
    tbb::parallel_for(std::size_t(0), scene.objects.size(), [&](std::size_t o) {
        const Object& object = scene.objects[o];
        const Mesh& mesh = scene.meshes[object.mesh];
        tbb::parallel_for(std::size_t(0), mesh.positions.size(), kRun, [&](std::size_t first) {
            const std::size_t count = std::min(kRun, mesh.positions.size() - first);
            const std::size_t base = first_vertex[o] + first;
            // The viewport transform too, once per vertex rather than once per triangle corner.
            geometry::run_vertex_stage(isa, mesh, first, object.model, view_projection, guard, viewport,
                                       {{vertices.data() + base, count}, outcodes.data() + base, screen.data() + base});
            if (!mesh.tangents.empty())
                geometry::transform_tangents(mesh, first, object.model, {tangents.data() + base, count});
        });
    });
}

// Cuts every object's triangles into chunks; the cut depends on the scene only.
void Renderer::Frame::cut_into_chunks(const Scene& scene) {
    chunk_count = 0;
    object_first_chunk.resize(scene.objects.size() + 1);
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        object_first_chunk[o] = std::uint32_t(chunk_count);
        const auto triangles = std::uint32_t(scene.meshes[scene.objects[o].mesh].indices.size() / 3);
        for (std::uint32_t first = 0; first < triangles; first += render::kChunkTriangles) {
            if (chunk_count >= render::kMaxChunks) throw std::invalid_argument("the scene has too many triangles");
            if (chunk_count == chunks.size()) chunks.emplace_back();
            render::Chunk& chunk = chunks[chunk_count++];
            chunk.object = std::uint32_t(o);
            chunk.first_triangle = first;
            chunk.triangle_count = std::min(render::kChunkTriangles, triangles - first);
            chunk.material = &scene.materials[scene.objects[o].material];
            chunk.blended = chunk.material->alpha_mode == AlphaMode::blend;
            const Mesh& mesh = scene.meshes[scene.objects[o].mesh];
            chunk.colors = mesh.colors.empty() ? nullptr : mesh.colors.data();
            chunk.uvs1 = mesh.uvs1.empty() || !chunk.material->has_maps() ? nullptr : mesh.uvs1.data();
            chunk.beyond_plain = chunk.material->has_maps() || chunk.colors != nullptr || chunk.blended;
        }
    }
    object_first_chunk.back() = std::uint32_t(chunk_count);
    any_unlit = std::any_of(scene.materials.begin(), scene.materials.end(), [](const Material& m) { return m.unlit; });
    surface_ids = {};
    if (settings.aovs.contains(Aov::object_id) || settings.aovs.contains(Aov::material_id)) {
        chunk_object_id.resize(chunk_count), chunk_material_id.resize(chunk_count);
        for (std::size_t c = 0; c < chunk_count; ++c) {
            const Object& object = scene.objects[chunks[c].object];
            chunk_object_id[c] = object.id != 0 ? object.id : chunks[c].object + 1;
            chunk_material_id[c] = object.material + 1;
        }
        surface_ids = {chunk_object_id.data(), chunk_material_id.data(), render::kChunkIdShift};
    }
    blend_chunks.clear();
    for (const std::uint32_t o : geometry::blended_objects_back_to_front(scene))
        for (std::uint32_t c = object_first_chunk[o]; c < object_first_chunk[o + 1]; ++c) blend_chunks.push_back(c);
}

// Each chunk is binned right after it is assembled, while its triangles are
// still in this core's cache.
void Renderer::Frame::assemble_and_bin(const Scene& scene) {
    const raster::FrameVertices frame{vertices, outcodes, screen};
    const geometry::Viewport viewport{scene.width, scene.height};
    const geometry::GuardBand guard(scene.width, scene.height);
    grid = raster::TileGrid(scene.width, scene.height, settings.tile_size);
    for (WorkerScratch& s : scratch) s.clip_setup_ms = s.binning_ms = 0;
    tbb::parallel_for(std::size_t(0), chunk_count, [&](std::size_t c) {
        WorkerScratch& s = scratch.local();
        const auto t0 = Clock::now();
        render::Chunk& chunk = chunks[c];
        const Object& object = scene.objects[chunk.object];
        chunk.alpha_tested = scene.materials[object.material].alpha_mode == AlphaMode::mask;
        const std::span<const std::uint32_t> indices(
            scene.meshes[object.mesh].indices.data() + 3 * std::size_t(chunk.first_triangle), 3 * chunk.triangle_count);
        chunk.assembled.clear();
        render::reserve_huge(chunk.assembled.triangles,  // most triangles stay one triangle
                            chunk.triangle_count + raster::kAssemblyRoom);
        raster::assemble_triangles(isa, indices, first_vertex[chunk.object],
                                   std::uint32_t(scene.meshes[object.mesh].positions.size()), frame, viewport, guard,
                                   chunk.assembled, scene.msaa, culling_of(scene, object),
                                   {chunk.colors, chunk.colors ? scene.meshes[object.mesh].colors.size() : 0},
                                   mirrors(object),
                                   {chunk.uvs1, chunk.uvs1 ? scene.meshes[object.mesh].uvs1.size() : 0});
        const auto t1 = Clock::now();
        chunk.bins.build(grid, chunk.assembled.triangles);
        const auto t2 = Clock::now();
        s.clip_setup_ms += ms_between(t0, t1);
        s.binning_ms += ms_between(t1, t2);
        if (settings.profile) {
            ProfileSpan span;
            span.kind = ProfileSpan::Kind::chunk, span.name = "chunk", span.index = int(c);
            span.triangles = chunk.triangle_count;
            record_span(s, span, t0, t2);
        }
    });
    // On one thread (at 4K culled, 8160 tiles and ~3000 entries), counted as
    // binning like the chunks' share.
    const auto index_start = Clock::now();
    tile_bins.build(grid, chunk_count, [&](std::size_t c) -> const raster::ChunkBins& { return chunks[c].bins; });
    const double threads = arena.max_concurrency();
    stats.binning_ms += ms_between(index_start, Clock::now()) / threads;
    for (const WorkerScratch& s : scratch)
        stats.clip_setup_ms += s.clip_setup_ms / threads, stats.binning_ms += s.binning_ms / threads;
    for (std::size_t c = 0; c < chunk_count; ++c) stats.triangles_binned += chunks[c].assembled.triangles.size();
}

void Renderer::Frame::render_tiles(const Scene& scene) {
    image.width = scene.width;
    image.height = scene.height;
    const std::size_t pixels = std::size_t(scene.width) * scene.height;
    if (settings.keep_radiance) {
        render::reserve_huge(image.radiance, 3 * pixels);
        image.radiance.resize(3 * pixels);
    } else {
        image.radiance.clear();
    }
    render::reserve_huge(image.display, 3 * pixels);
    image.display.resize(3 * pixels);
    size_aov_planes(settings.aovs, pixels, image.aov);
    view_depth = image::ViewDepth(view_matrix(scene.camera));
    lights.assign(scene.camera.position, scene.lights);
    lights.assign_shadows(shadow_by_light);
    ibl = scene.environment.present() ? shade::ibl_lighting(scene.environment) : shade::IblLighting{};
    exposure_scale = scene.exposure_ev == 0.0f ? 1.0f : std::exp2(scene.exposure_ev);
    background = image::EnvironmentBackground(scene, exposure_scale);
    for (WorkerScratch& s : scratch) s.light_culling.reserve(lights.count());  // a no-op once large enough
    const image::ClearValues clear = image::clear_values(scene.clear_color);
    for (WorkerScratch& s : scratch) s.counters = {}, s.fragments_shaded = s.fragment_lights = 0, s.shadow_lookups = {}, s.rasterize_ms = s.shade_ms = s.resolve_ms = 0;
    set_corner_lookup(scene);

    tbb::parallel_for(0, grid.tile_count(), [&](int tile) {
        WorkerScratch& s = scratch.local();
        if (s.raster.side != grid.tile_size || s.reserved_msaa < scene.msaa) s.reserve(grid.tile_size, scene.msaa);
        if (scene.msaa > 1) render_tile_msaa(scene, clear, tile, s);
        else render_tile(scene, clear, tile, s);
    });
    const double threads = arena.max_concurrency();
    for (const WorkerScratch& s : scratch) {
        stats.fragments_rasterized += s.counters.fragments;
        stats.fragments_shaded += s.fragments_shaded;
        stats.fragment_lights += s.fragment_lights;
        stats.shadow_lookups_settled += s.shadow_lookups.settled;
        stats.shadow_lookups_facing_away += s.shadow_lookups.facing_away;
        stats.shadow_lookups_tapped += s.shadow_lookups.tapped;
        stats.rasterize_ms += s.rasterize_ms / threads;
        stats.shade_ms += s.shade_ms / threads;
        stats.resolve_ms += s.resolve_ms / threads;
    }
}

// What a textured material's fragments need beyond the corners: how the
// screen-space barycentrics change per pixel, and stored tangents.
void Renderer::Frame::describe_for_textures(const raster::RasterTriangle& t, const Mesh& mesh,
                                            shade::TriangleCorners& corners) const {
    // λ1 = E(corner 2 → corner 0) / area, λ2 = E(corner 0 → corner 1) / area, in
    // fixed point: one pixel is kSubpixelScale units (raster/triangle_setup.hpp).
    const float scale = float(geometry::kSubpixelScale) * t.inv_area;
    corners.lambda1_dx = -float(t.y[0] - t.y[2]) * scale, corners.lambda1_dy = float(t.x[0] - t.x[2]) * scale;
    corners.lambda2_dx = -float(t.y[1] - t.y[0]) * scale, corners.lambda2_dy = float(t.x[1] - t.x[0]) * scale;
    // Tangents are kept for the frame's own vertices; a triangle clipping made
    // derives its tangent frame instead.
    if (mesh.tangents.empty()) return;
    for (int k = 0; k < 3; ++k) {
        if (t.vertex[k] & geometry::kClippedVertexBit) return;
    }
    for (int k = 0; k < 3; ++k) corners.tangent[k] = &tangents[t.vertex[k]];
}

// Rasterizes every chunk's triangles for this tile, in submission order:
// reset() clears the tile's buffers before the first one, rasterize(t, id,
// alpha_tested) draws one (alpha_tested: its material is masked). Returns whether any fragment passed the depth test.
// Given rasterize_bin(chunk, bin, id_base), a chunk's bin that needs no alpha
// test goes to it whole instead (id_base: the chunk's part of the ids).
template <class Reset, class Rasterize, class RasterizeBin>
bool Renderer::Frame::rasterize_bins(int tile, WorkerScratch& s, Reset&& reset, Rasterize&& rasterize,
                                     RasterizeBin&& rasterize_bin) const {
    const std::uint64_t passed_before = s.counters.depth_passed;
    s.tile_triangles = 0;
    bool is_reset = false;
    for (const raster::TileBinIndex::Entry& entry : tile_bins.tile(tile)) {
        const std::uint32_t c = entry.chunk;
        const render::Chunk& chunk = chunks[c];
        const std::span<const std::uint32_t> bin(chunk.bins.items.data() + entry.first, entry.last - entry.first);
        s.tile_triangles += bin.size();
        if (chunk.blended) continue;  // the blend pass draws them
        if constexpr (!std::is_same_v<std::decay_t<RasterizeBin>, std::nullptr_t>) {
            if (!chunk.alpha_tested && !bin.empty()) {
                if (!is_reset) reset(), is_reset = true;
                rasterize_bin(chunk, bin, std::uint32_t(c) << render::kChunkIdShift);
                continue;
            }
        }
        const raster::CornerPrefetch prefetch = corner_prefetch(chunk);
        for (std::size_t i = 0; i < bin.size(); ++i) {
            if (!is_reset) reset(), is_reset = true;
            // A tile's triangles lie scattered through the chunk: fetch ahead
            // (records are one aligned cache line each).
            constexpr std::size_t kPrefetchDistance = 8;
            if (i + kPrefetchDistance < bin.size()) __builtin_prefetch(&chunk.assembled.triangles[bin[i + kPrefetchDistance]]);
            const raster::RasterTriangle& t = chunk.assembled.triangles[bin[i]];
            const std::uint64_t passed = s.counters.depth_passed;
            rasterize(t, (std::uint32_t(c) << render::kChunkIdShift) | bin[i], chunk.alpha_tested);
            if (s.counters.depth_passed != passed) raster::prefetch_corners(t, prefetch);
        }
    }
    return s.counters.depth_passed != passed_before;
}

// One chunk's bin for a one-sample tile (raster/bin_rasterizer.hpp). Out of
// line since it kept render_tile small enough for g++ to inline the gather;
// the gather has since gone out of line itself (it measured faster so), and
// inlining this again was not measured.
[[gnu::noinline]] void Renderer::Frame::rasterize_bin(const render::Chunk& chunk, std::span<const std::uint32_t> bin,
                                                      std::uint32_t id_base, const raster::TileRect& rect,
                                                      WorkerScratch& s) const {
    raster::rasterize_bin(isa, chunk.assembled.triangles.data(), bin, id_base, rect, s.raster, s.counters, {},
                          corner_prefetch(chunk));
}

void Renderer::Frame::render_tile(const Scene& scene, const image::ClearValues& clear, int tile, WorkerScratch& s) {
    const raster::TileRect rect = grid.rect(tile);
    image::prefetch_tile_output(rect, image);
    const auto t0 = Clock::now();
    // A triangle is drawn as its position in the tile's list (TileBuffers::triangles).
    const bool drawn = rasterize_bins(tile, s, [&] { s.raster.reset(grid.tile_size); },
                                      [&](const raster::RasterTriangle& t, std::uint32_t id, bool alpha_tested) {
                                          const std::uint32_t position = s.raster.triangles.add(id);
                                          if (!alpha_tested)
                                              return raster::rasterize_triangle(isa, t, position, rect, s.raster,
                                                                                s.counters);
                                          const shade::AlphaMaskTriangle mask{corners_of(scene, id), scene.textures};
                                          raster::rasterize_triangle(t, position, rect, s.raster, s.counters,
                                                                     {shade::alpha_mask_keep, &mask});
                                      },
                                      [&](const render::Chunk& chunk, std::span<const std::uint32_t> bin,
                                          std::uint32_t id_base) { rasterize_bin(chunk, bin, id_base, rect, s); });
    const bool blended = has_blended(tile, scene.msaa, s);
    shade_and_resolve(
        scene, clear, tile, drawn, t0, s,
        [&] {  // every visible pixel once
            return shade::gather_surface_points(
                isa, s.raster, rect.width(), rect.height(), corner_lookup,
                s.fragments, s.material_runs);
        },
        [&](std::size_t count, const shade::RadianceOutputs& shaded) {
            if (blended) {
                image::fill_opaque(s.raster, rect, shaded, clear, s.blend_radiance);
                if (background.shown()) background.paint(rect, &s.raster, nullptr, s.blend_radiance);
            } else {
                image::resolve_tile(s.raster, rect, count, shaded, clear, isa, image);
                if (background.shown()) background.paint(rect, &s.raster, isa, image);
            }
            if (!image.aov.empty())
                image::resolve_aov_tile(s.raster, rect, with_visibility(s.fragments.inputs(count), s), view_depth,
                                        surface_ids, image);
        },
        blended);
}

// render_tile with 4 samples per pixel: depth and triangle per sample, one
// fragment per pixel and visible triangle, pixels the mean of their samples.
void Renderer::Frame::render_tile_msaa(const Scene& scene, const image::ClearValues& clear, int tile, WorkerScratch& s) {
    const raster::TileRect rect = grid.rect(tile);
    image::prefetch_tile_output(rect, image);
    const auto t0 = Clock::now();
    const bool drawn = rasterize_bins(tile, s, [&] { s.samples.reset(grid.tile_size); },
                                      [&](const raster::RasterTriangle& t, std::uint32_t id, bool alpha_tested) {
                                          if (!alpha_tested)
                                              return raster::rasterize_triangle_msaa(isa, t, id, rect, s.samples, s.counters);
                                          const shade::AlphaMaskTriangle mask{corners_of(scene, id), scene.textures};
                                          const raster::FragmentTest test{shade::alpha_mask_keep, &mask};
                                          raster::rasterize_triangle_msaa(t, id, rect, s.samples, s.counters, &test);
                                      },
                                      [&](const render::Chunk& chunk, std::span<const std::uint32_t> bin,
                                          std::uint32_t id_base) {
                                          raster::rasterize_bin_msaa(isa, chunk.assembled.triangles.data(), bin, id_base,
                                                                     rect, s.samples, s.counters, {},
                                                                     corner_prefetch(chunk));
                                      });
    const bool blended = has_blended(tile, scene.msaa, s);
    shade_and_resolve(
        scene, clear, tile, drawn, t0, s,
        [&] {  // one fragment per pixel and visible triangle
            raster::collect_fragments(isa, rect, s.samples, [&](std::uint32_t id) -> const raster::RasterTriangle& {
                return triangle_of(id);
            }, s.sample_fragments);
            return shade::gather_surface_points(
                isa, s.sample_fragments, corner_lookup, s.fragments,
                s.material_runs);
        },
        [&](std::size_t count, const shade::RadianceOutputs& shaded) {
            if (blended) {
                image::fill_opaque(s.samples, rect, shaded, clear, s.blend_radiance);
                if (background.shown()) background.paint(rect, nullptr, &s.samples, s.blend_radiance);
            } else {
                image::resolve_tile_msaa(s.samples, rect, count, shaded, clear, isa, image);
                if (background.shown()) background.paint(rect, s.samples, isa, image);
            }
            if (!image.aov.empty())
                image::resolve_aov_tile_msaa(s.samples, rect, with_visibility(s.fragments.inputs(count), s), view_depth,
                                             {surface_ids, s.sample_fragments.triangle.data()}, image);
        },
        blended);
}

// The tail both tile paths share, from the end of rasterization (begun at
// raster_start): gather the visible fragments, shade them, resolve them into
// the images, and time each step; a tile nothing was drawn on is only cleared.
// gather() fills s.fragments and returns their count; resolve(count, shaded)
// writes the pixels and AOVs. blended: the tile has blended triangles, drawn
// over the opaque result (blend_tile; its time counts as shading).
template <class Gather, class Resolve>
void Renderer::Frame::shade_and_resolve(const Scene& scene, const image::ClearValues& clear, int tile, bool drawn,
                                        Clock::time_point raster_start, WorkerScratch& s, Gather&& gather,
                                        Resolve&& resolve, bool blended) {
    const auto t1 = Clock::now();
    s.rasterize_ms += ms_between(raster_start, t1);
    std::size_t count = 0;
    s.tile_light_count = 0;
    const std::uint64_t fragment_lights_before = s.fragment_lights;
    auto t2 = t1;
    if (drawn) {
        count = gather();
        const shade::RadianceOutputs shaded = s.fragments.outputs();
        shade_tile(scene, count, s);
        t2 = Clock::now();
        resolve(count, shaded);
    } else {  // background only
        image::clear_tile(grid.rect(tile), clear, image);
        if (background.shown()) background.paint(grid.rect(tile), nullptr, isa, image);
    }
    if (blended) {
        const auto blend_start = Clock::now();
        blend_tile(scene, clear, tile, drawn, s);
        t2 += Clock::now() - blend_start;
    }
    const auto t3 = Clock::now();
    s.shade_ms += ms_between(t1, t2);
    s.resolve_ms += ms_between(t2, t3);
    if (settings.profile) {
        ProfileSpan span;
        span.kind = ProfileSpan::Kind::tile, span.name = "tile", span.index = tile;
        span.rasterize_ms = ms_between(raster_start, t1), span.shade_ms = ms_between(t1, t2);
        span.resolve_ms = ms_between(t2, t3);
        span.triangles = s.tile_triangles, span.fragments = count, span.lights = s.tile_light_count;
        span.fragment_lights = s.fragment_lights - fragment_lights_before;
        record_span(s, span, raster_start, t3);
    }
}

shade::TriangleCorners Renderer::Frame::corners_of(const Scene& scene, std::uint32_t id) const {
    const render::Chunk& chunk = chunks[id >> render::kChunkIdShift];
    const raster::RasterTriangle& t = chunk.assembled.triangles[id & render::kChunkIndexMask];
    const Object& object = scene.objects[chunk.object];
    shade::TriangleCorners corners{{&chunk.vertex(t.vertex[0], vertices), &chunk.vertex(t.vertex[1], vertices),
                                    &chunk.vertex(t.vertex[2], vertices)},
                                   &scene.materials[object.material]};
    corners.back_facing = t.back_facing != 0;
    if (corners.material->has_maps()) describe_for_textures(t, scene.meshes[object.mesh], corners);
    if (chunk.colors) [[unlikely]]
        for (int k = 0; k < 3; ++k) corners.color[k] = &chunk.color(t.vertex[k], first_vertex[chunk.object]);
    if (chunk.uvs1) [[unlikely]]
        for (int k = 0; k < 3; ++k) corners.uv1[k] = &chunk.uv1(t.vertex[k], first_vertex[chunk.object]);
    return corners;
}

// The blend pass of a tile (image/blend.hpp): the blended objects' triangles
// in drawing order, tested against the opaque depth, shaded in batches as
// large as the fragment buffer, composited in order over the opaque radiance,
// which is then written into the images. opaque_drawn: the opaque pass left
// fragments (and filled s.blend_radiance); otherwise the tile is background.
void Renderer::Frame::blend_tile(const Scene& scene, const image::ClearValues& clear, int tile, bool opaque_drawn,
                                 WorkerScratch& s) {
    const raster::TileRect rect = grid.rect(tile);
    if (!opaque_drawn) {  // the opaque depth may be another tile's, or none was cleared
        if (scene.msaa > 1) s.samples.reset(grid.tile_size);
        else s.raster.reset(grid.tile_size);
        image::fill_background(rect, clear, s.blend_radiance);
        if (background.shown()) background.paint(rect, nullptr, nullptr, s.blend_radiance);
    }
    raster::BlendFragments& fragments = s.blend_fragments;
    const auto shade_and_blend = [&] {
        const std::size_t count = shade::gather_surface_points(
            isa, fragments.fragments, corner_lookup, s.fragments, s.material_runs);
        shade_tile(scene, count, s);
        image::blend_over(fragments, count, s.fragments.outputs(), s.fragments.channel(shade::FragmentBuffer::alpha),
                          s.blend_radiance);
        fragments.clear();
    };
    fragments.clear();
    for (const std::uint32_t c : blend_chunks) {
        const render::Chunk& chunk = chunks[c];
        for (const std::uint32_t index : chunk.bins.tile(tile)) {
            const raster::RasterTriangle& t = chunk.assembled.triangles[index];
            if (fragments.count() + raster::max_blend_fragments(t, rect) > fragments.capacity) shade_and_blend();
            const std::uint32_t id = (c << render::kChunkIdShift) | index;
            if (scene.msaa > 1) raster::rasterize_blended(t, id, rect, s.samples, fragments, s.counters);
            else raster::rasterize_blended(t, id, rect, s.raster, fragments, s.counters);
        }
    }
    if (fragments.count() > 0) shade_and_blend();
    image::resolve_blended_tile(s.blend_radiance, rect, isa, image);
}

// Textures, lights and emission for the `count` gathered fragments; their
// radiance goes to s.fragments.outputs().
std::size_t Renderer::Frame::shade_tile(const Scene& scene, std::size_t count, WorkerScratch& s) const {
    if (count > 0) {
        shade::apply_material_maps(isa, scene.textures, s.material_runs, s.fragments, s.material_scratch);
        const shade::FragmentInputs inputs = s.fragments.inputs(count);
        // The fast gather leaves plain runs' material channels unfilled; culled
        // shading, the AOVs, the scalar kernel and the IBL kernels read them.
        const bool culled = settings.light_culling && lights.any_range;
        const bool with_ibl = ibl.maps != nullptr;
        const bool channels_read = culled || !image.aov.empty() || isa == simd::Isa::scalar || with_ibl;
        if (channels_read) s.fragments.fill_plain_runs(s.material_runs, count);
        else s.fragments.fill_plain_run_edges(s.material_runs, count);
        // With an environment the direct-light kernels see ao = 0, so that they
        // give Lo alone; the IBL ambient is added after (ambient + Lo, as pbr.fs).
        shade::FragmentInputs direct = inputs;
        if (lights.shadowed_count() > 0) {  // each shadowed light's visibility, scaling its share of Lo
            const std::size_t stride = shade::padded_count(count);
            if (s.visibility.size() < stride * lights.shadowed_count()) s.visibility.resize(stride * lights.shadowed_count());
            // The shadow AOV reads every fragment's visibility; the picture alone does not.
            s.shadow_lookups += shade::shadow_visibility_planes(isa, inputs, lights, s.visibility.data(), stride, !image.aov.empty());
            direct.visibility = s.visibility.data(), direct.visibility_stride = stride;
            direct.visibility_planes = lights.shadowed_count();
        }
        if (with_ibl) {
            if (s.zero_ao.size() < shade::padded_count(count)) s.zero_ao.assign(shade::padded_count(count), 0.0f);
            direct.ao = s.zero_ao.data();
        }
        if (culled) {
            const shade::CulledWork work =
                shade::shade_fragments_culled(isa, direct, lights, s.light_culling, s.fragments.outputs());
            s.tile_light_count = std::uint32_t(work.tile_lights);
            s.fragment_lights += work.fragment_lights;
        } else {
            if (with_ibl) shade::shade_fragments(isa, direct, lights, s.fragments.outputs());
            else shade::shade_fragment_runs(isa, direct, s.material_runs, lights, s.fragments.outputs());
            s.tile_light_count = std::uint32_t(lights.count());
            s.fragment_lights += count * lights.count();
        }
        if (with_ibl) shade::add_ibl_ambient(isa, inputs, lights.cam_pos, ibl, s.fragments.outputs());
        shade::add_emission(s.material_runs, s.fragments);
        if (exposure_scale != 1.0f) {  // radiance × 2^EV before the tonemap (and in the EXR)
            const shade::RadianceOutputs out = s.fragments.outputs();
            for (std::size_t i = 0; i < count; ++i) out.r[i] *= exposure_scale, out.g[i] *= exposure_scale, out.b[i] *= exposure_scale;
        }
        // Unlit after the exposure: an unlit colour is what the image shows, whatever the exposure.
        if (any_unlit) [[unlikely]]
            shade::apply_unlit(s.material_runs, s.fragments);
    }
    s.fragments_shaded += count;
    return count;
}

}  // namespace tessera
