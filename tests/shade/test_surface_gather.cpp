// The fast gather (surface_gather_fast.hpp: per-tile triangle table, materials
// per run; its loops compiled per ISA) against the reference gather:
// bit-identical fragments and the same material runs, for every ISA the CPU
// has, on random tiles and fragment lists (4× MSAA, blending) with plain,
// textured, vertex-coloured and blended materials, corners clipping made, and
// triangle ids that collide in the table; the full TriangleCorners asked for
// beyond-plain triangles only.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include <doctest/doctest.h>

#include "shade/surface_gather_fast.hpp"

namespace {

using namespace tessera;
using namespace tessera::shade;

constexpr float kUnwritten = -777.25f;  // every channel starts so in both buffers

// The fast gathers this CPU runs (the others are skipped, and said so).
std::vector<Isa> fast_isas() {
    std::vector<Isa> isas;
    for (const Isa isa : {Isa::sse4, Isa::avx2, Isa::avx512}) {
        if (simd::isa_supported(isa)) isas.push_back(isa);
        else MESSAGE("skipped: this CPU lacks ", simd::isa_name(isa));
    }
    REQUIRE(!isas.empty());
    return isas;
}

// A random mesh's worth of shaded vertices, materials and triangles in chunks
// (one material each, as the renderer's objects), and the lookup the renderer
// would give the gather.
struct RandomScene {
    static constexpr std::uint32_t kChunks = 10, kChunkShift = 17, kChunkTriangles = 1200;
    std::vector<geometry::ShadedVertex> vertices;
    std::vector<glm::vec4> tangents, colors;
    std::vector<Material> materials;
    struct Chunk {
        std::vector<raster::RasterTriangle> triangles;  // only `vertex` is read
        std::vector<geometry::ShadedVertex> clipped_vertices;
        std::uint32_t material;
        bool colors;
    };
    std::vector<Chunk> chunks;
    std::vector<GatherChunk> gather_chunks;
    struct Triangle {
        std::uint32_t id;
        bool tangents;
        float lambda_d[4];
    };
    std::vector<Triangle> triangles;
    mutable std::size_t full_asked = 0, full_asked_for_plain = 0;

    explicit RandomScene(std::mt19937& rng) {
        std::uniform_real_distribution<float> coord(-20.0f, 20.0f), unit(0.0f, 1.0f), w(0.2f, 60.0f);
        const auto random_vertex = [&] {
            geometry::ShadedVertex v;
            v.clip_pos = {coord(rng), coord(rng), coord(rng), w(rng)};
            v.world_pos = {coord(rng), coord(rng), coord(rng)};
            v.normal = {coord(rng), coord(rng), coord(rng)};
            v.uv = {coord(rng), coord(rng)};
            return v;
        };
        for (int i = 0; i < 300; ++i) {
            vertices.push_back(random_vertex());
            tangents.push_back({unit(rng), unit(rng), unit(rng), unit(rng) < 0.5f ? -1.0f : 1.0f});
            colors.push_back({unit(rng), unit(rng), unit(rng), unit(rng)});
        }
        Material plain_a, plain_b{.albedo = {0.2f, 0.7f, 0.1f}, .metallic = 0.9f, .roughness = 0.3f, .ao = 0.5f};
        Material textured = plain_b;
        textured.albedo_map.texture = 0;  // the gather only asks whether a map is there
        Material blended = plain_a;
        blended.alpha_mode = AlphaMode::blend, blended.alpha_factor = 0.625f;
        Material textured_blended = textured;
        textured_blended.alpha_mode = AlphaMode::blend, textured_blended.alpha_factor = 0.25f;
        materials = {plain_a, plain_b, textured, blended, textured_blended};
        // Chunks 0-4: each material without vertex colours; 5-9: with them.
        for (std::uint32_t c = 0; c < kChunks; ++c) {
            Chunk chunk{std::vector<raster::RasterTriangle>(kChunkTriangles), {}, c % 5, c >= 5};
            for (int k = 0; k < 20; ++k) chunk.clipped_vertices.push_back(random_vertex());
            chunks.push_back(std::move(chunk));
        }
        std::uniform_int_distribution<std::uint32_t> vertex(0, std::uint32_t(vertices.size() - 1)), clipped(0, 19);
        std::uniform_real_distribution<float> step(-0.5f, 0.5f);
        for (std::uint32_t i = 0; i < 400; ++i) {
            const std::uint32_t id = id_of(i);
            raster::RasterTriangle& t = chunks[id >> kChunkShift].triangles[id & ((1u << kChunkShift) - 1)];
            for (int k = 0; k < 3; ++k)
                t.vertex[k] = unit(rng) < 0.15f ? (geometry::kClippedVertexBit | clipped(rng)) : vertex(rng);
            triangles.push_back({id, unit(rng) < 0.5f, {step(rng), step(rng), step(rng), step(rng)}});
        }
        for (const Chunk& chunk : chunks) {
            const Material& m = materials[chunk.material];
            gather_chunks.push_back({chunk.triangles.data(), chunk.clipped_vertices.data(), &m,
                                     m.has_maps() || chunk.colors || m.alpha_mode == AlphaMode::blend});
        }
    }

    // Triangle i's id, as the renderer's: chunk << 17 | index, spread so that
    // several ids share a slot of the fast gather's table.
    static std::uint32_t id_of(std::uint32_t i) { return ((i % kChunks) << kChunkShift) | ((i / kChunks) * 29 % kChunkTriangles); }
    const Triangle& triangle(std::uint32_t id) const {
        for (const Triangle& t : triangles)
            if (t.id == id) return t;
        throw std::out_of_range("no triangle " + std::to_string(id));
    }
    const Chunk& chunk_of(std::uint32_t id) const { return chunks.at(id >> kChunkShift); }
    std::uint32_t corner_ref(std::uint32_t id, int k) const {
        return chunk_of(id).triangles.at(id & ((1u << kChunkShift) - 1)).vertex[k];
    }
    const geometry::ShadedVertex* corner(std::uint32_t id, int k) const {
        const std::uint32_t ref = corner_ref(id, k);
        return (ref & geometry::kClippedVertexBit) ? &chunk_of(id).clipped_vertices.at(ref & ~geometry::kClippedVertexBit)
                                                   : &vertices.at(ref);
    }

    TriangleCorners corners(std::uint32_t id) const {
        const Triangle& t = triangle(id);
        const Chunk& chunk = chunk_of(id);
        TriangleCorners c{{corner(id, 0), corner(id, 1), corner(id, 2)}, &materials[chunk.material]};
        const auto attribute_index = [&](int k) { return (corner_ref(id, k) & ~geometry::kClippedVertexBit) % 300; };
        if (c.material->has_maps()) {
            c.lambda1_dx = t.lambda_d[0], c.lambda1_dy = t.lambda_d[1];
            c.lambda2_dx = t.lambda_d[2], c.lambda2_dy = t.lambda_d[3];
            if (t.tangents)
                for (int k = 0; k < 3; ++k) c.tangent[k] = &tangents[attribute_index(k)];
        }
        if (chunk.colors)
            for (int k = 0; k < 3; ++k) c.color[k] = &colors[attribute_index(k)];
        return c;
    }
    bool beyond_plain(std::uint32_t id) const { return gather_chunks.at(id >> kChunkShift).beyond_plain; }

    // The lookup, as the renderer's: counts the full corners it is asked for.
    GatherCornerLookup lookup() const {
        return {vertices.data(), gather_chunks.data(), int(kChunkShift),
                [](const void* context, std::uint32_t id) {
                    const RandomScene& scene = *static_cast<const RandomScene*>(context);
                    ++scene.full_asked;
                    scene.full_asked_for_plain += scene.beyond_plain(id) ? 0 : 1;
                    return scene.corners(id);
                },
                this};
    }
};

// A triangle id per fragment, in runs as a rasterized tile has them: the
// previous triangle again with probability `repeat`, else a random one.
struct IdStream {
    std::mt19937& rng;
    std::uint32_t triangles;
    float repeat;
    std::uint32_t last = 0;
    std::uint32_t next() {
        if (std::uniform_real_distribution<float>(0.0f, 1.0f)(rng) >= repeat)
            last = RandomScene::id_of(std::uniform_int_distribution<std::uint32_t>(0, triangles - 1)(rng));
        return last;
    }
};

// λ1 λ2 as a rasterizer stores them: inside the triangle, or (MSAA, a sample
// away from the pixel centre) a little outside.
std::array<float, 2> random_lambdas(std::mt19937& rng) {
    std::uniform_real_distribution<float> l(-0.05f, 1.0f);
    float l1 = l(rng), l2 = l(rng);
    if (l1 + l2 > 1.05f) l1 = 1.0f - l1, l2 = 1.0f - l2;
    return {l1, l2};
}

void fill_unwritten(FragmentBuffer& buffer) {
    for (int c = 0; c < FragmentBuffer::kChannels; ++c) {
        float* channel = buffer.channel(FragmentBuffer::Channel(c));
        std::fill(channel, channel + padded_count(buffer.capacity()), kUnwritten);
    }
}

// Same count, same runs, every channel of every lane up to the padded count
// equal bit for bit, once the fast gather's plain runs have their material
// channels (which it leaves unwritten) filled.
void check_same_fragments(std::size_t count, const FragmentBuffer& reference, const std::vector<MaterialRun>& reference_runs,
                          std::size_t fast_count, FragmentBuffer& fast, const std::vector<MaterialRun>& fast_runs) {
    REQUIRE(fast_count == count);
    REQUIRE(fast_runs.size() == reference_runs.size());
    std::size_t plain_fragments = 0, plain_written = 0;
    for (std::size_t r = 0; r < reference_runs.size(); ++r) {
        CHECK(fast_runs[r].begin == reference_runs[r].begin);
        CHECK(fast_runs[r].end == reference_runs[r].end);
        CHECK(fast_runs[r].material == reference_runs[r].material);
        CHECK(fast_runs[r].textured == reference_runs[r].textured);
        CHECK(fast_runs[r].plain == reference_runs[r].plain);
        if (!fast_runs[r].plain) continue;
        for (std::uint32_t i = fast_runs[r].begin; i < fast_runs[r].end; ++i, ++plain_fragments)
            for (int c = FragmentBuffer::albedo_r; c <= FragmentBuffer::ao; ++c)
                plain_written += fast.channel(FragmentBuffer::Channel(c))[i] != kUnwritten;
    }
    CHECK(plain_written == 0);
    fast.fill_plain_runs(fast_runs, fast_count);
    std::size_t differing = 0;
    for (int c = 0; c < FragmentBuffer::kChannels; ++c) {
        const float* a = reference.channel(FragmentBuffer::Channel(c));
        const float* b = fast.channel(FragmentBuffer::Channel(c));
        for (std::size_t i = 0; i < padded_count(count); ++i) {
            if (std::memcmp(&a[i], &b[i], sizeof(float)) != 0) {
                if (differing++ < 5) FAIL_CHECK("channel ", c, " fragment ", i, ": reference ", a[i], ", fast ", b[i]);
            }
        }
    }
    CHECK(differing == 0);
}

TEST_CASE("the fast gather of a tile equals the reference gather bit for bit") {
    std::mt19937 rng(20261124);
    const RandomScene scene(rng);
    const GatherCornerLookup lookup = scene.lookup();
    const std::vector<Isa> isas = fast_isas();
    std::size_t full_asked = 0, full_asked_for_plain = 0;
    constexpr int kSide = 32;
    FragmentBuffer reference, fast;
    reference.reserve(kSide * kSide), fast.reserve(kSide * kSide);
    std::vector<MaterialRun> reference_runs, fast_runs;
    std::size_t fragments = 0, extras = 0, materials_seen = 0;
    for (int trial = 0; trial < 60; ++trial) {
        CAPTURE(trial);
        raster::TileBuffers tile;
        tile.reset(kSide);
        // The tile's triangle list (pixels hold positions in it): every
        // triangle once, in a shuffled order, or a few of them.
        std::vector<std::uint32_t> listed(scene.triangles.size());
        for (std::uint32_t i = 0; i < listed.size(); ++i) listed[i] = RandomScene::id_of(i);
        std::shuffle(listed.begin(), listed.end(), rng);
        if (trial % 4 == 3) listed.resize(40);
        std::unordered_map<std::uint32_t, std::uint32_t> position;
        for (const std::uint32_t id : listed) position[id] = tile.triangles.add(id);
        // Partial tiles at the image's edge, empty and full tiles, long and short runs.
        const int width = trial % 5 == 0 ? 1 + trial % kSide : kSide, height = trial % 7 == 0 ? 3 : kSide;
        const float coverage = trial == 0 ? 0.0f : trial == 1 ? 1.0f : std::uniform_real_distribution<float>(0.2f, 1.0f)(rng);
        IdStream ids{rng, std::uint32_t(scene.triangles.size()), trial % 3 == 0 ? 0.0f : 0.85f};
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                if (std::uniform_real_distribution<float>(0.0f, 1.0f)(rng) >= coverage) continue;
                std::uint32_t id = ids.next();
                if (!position.contains(id)) ids.last = id = listed[id % listed.size()];  // a listed one, repeated as well
                const std::size_t pixel = std::size_t(y) * kSide + x;
                const auto [l1, l2] = random_lambdas(rng);
                tile.depth[pixel] = 0.5f, tile.triangle[pixel] = position[id], tile.lambda1[pixel] = l1,
                tile.lambda2[pixel] = l2;
            }
        fill_unwritten(reference);
        const std::size_t count = gather_surface_points(Isa::scalar, tile, width, height, lookup,
                                                        reference, reference_runs);
        fragments += count;
        for (const MaterialRun& run : reference_runs) {
            if (run.textured || run.material->alpha_mode == AlphaMode::blend) extras += run.end - run.begin;
            materials_seen |= std::size_t(1) << (run.material - scene.materials.data());
        }
        for (const Isa isa : isas) {
            CAPTURE(simd::isa_name(isa));
            fill_unwritten(fast);
            scene.full_asked = scene.full_asked_for_plain = 0;
            const std::size_t fast_count = gather_surface_points(isa, tile, width, height, lookup, fast, fast_runs);
            full_asked += scene.full_asked, full_asked_for_plain += scene.full_asked_for_plain;
            check_same_fragments(count, reference, reference_runs, fast_count, fast, fast_runs);
        }
    }
    CHECK(full_asked > 0);
    CHECK(full_asked_for_plain == 0);
    CHECK(extras > 1000);  // the textured and blended paths were exercised
    CHECK(materials_seen == (std::size_t(1) << scene.materials.size()) - 1);
    MESSAGE(fragments, " fragments in 60 tiles, ", extras, " of them textured or blended");
}

TEST_CASE("the fast gather of a fragment list (MSAA, blending) equals the reference gather bit for bit") {
    std::mt19937 rng(4242);
    const RandomScene scene(rng);
    const GatherCornerLookup lookup = scene.lookup();
    const std::vector<Isa> isas = fast_isas();
    constexpr int kSide = 16;
    constexpr std::size_t kMaxFragments = 4 * kSide * kSide;
    FragmentBuffer reference, fast;
    reference.reserve(kMaxFragments), fast.reserve(kMaxFragments);
    std::vector<MaterialRun> reference_runs, fast_runs;
    for (int trial = 0; trial < 40; ++trial) {
        CAPTURE(trial);
        raster::TileFragments list;
        list.reserve(kSide);
        const std::size_t count = trial == 0 ? 0 : std::uniform_int_distribution<std::size_t>(1, kMaxFragments)(rng);
        IdStream ids{rng, std::uint32_t(scene.triangles.size()), 0.7f};
        list.x.resize(kMaxFragments), list.y.resize(kMaxFragments), list.triangle.resize(kMaxFragments);
        list.lambda1.resize(kMaxFragments), list.lambda2.resize(kMaxFragments);
        for (std::size_t k = 0; k < count; ++k) {
            const auto [l1, l2] = random_lambdas(rng);
            list.x[k] = std::uint16_t(rng() % kSide), list.y[k] = std::uint16_t(rng() % kSide);
            list.triangle[k] = ids.next(), list.lambda1[k] = l1, list.lambda2[k] = l2;
        }
        list.count = count;
        fill_unwritten(reference);
        const std::size_t gathered =
            gather_surface_points(Isa::scalar, list, lookup, reference, reference_runs);
        REQUIRE(gathered == count);
        for (const Isa isa : isas) {
            CAPTURE(simd::isa_name(isa));
            fill_unwritten(fast);
            const std::size_t fast_count = gather_surface_points(isa, list, lookup, fast, fast_runs);
            check_same_fragments(gathered, reference, reference_runs, fast_count, fast, fast_runs);
        }
    }
}

// Both gathers: a fragment's WorldPos is the perspective-correct mix of its
// corners (checked in double), and a vertex-coloured, blended fragment gets
// albedo × colour and alpha_factor × colour alpha.
TEST_CASE("the gathers interpolate perspective-correctly and apply vertex colours") {
    std::mt19937 rng(7);
    const RandomScene scene(rng);
    const GatherCornerLookup lookup = scene.lookup();
    std::vector<Isa> isas = fast_isas();
    isas.insert(isas.begin(), Isa::scalar);
    FragmentBuffer out;
    out.reserve(16);
    std::vector<MaterialRun> runs;
    std::size_t colored_blended = 0;
    for (std::uint32_t i = 0; i < 50; ++i) {
        const std::uint32_t id = RandomScene::id_of(i);
        raster::TileFragments list;
        list.reserve(4);
        const auto [l1, l2] = random_lambdas(rng);
        list.x = {1}, list.y = {2}, list.triangle = {id}, list.lambda1 = {l1}, list.lambda2 = {l2}, list.count = 1;
        for (const Isa isa : isas) {
            REQUIRE(gather_surface_points(isa, list, lookup, out, runs) == 1);
            const TriangleCorners c = scene.corners(id);
            const double q[3] = {(1.0 - l1 - l2) / c.corner[0]->clip_pos.w, l1 / c.corner[1]->clip_pos.w,
                                 l2 / c.corner[2]->clip_pos.w};
            const double sum = q[0] + q[1] + q[2];
            for (int k = 0; k < 3; ++k) {
                double expected = 0, magnitude = 0;
                for (int j = 0; j < 3; ++j) {
                    expected += q[j] / sum * c.corner[j]->world_pos[k];
                    magnitude += std::abs(q[j] / sum * c.corner[j]->world_pos[k]) + std::abs(c.corner[j]->world_pos[k]);
                }
                CHECK(std::abs(out.channel(FragmentBuffer::Channel(FragmentBuffer::world_x + k))[0] - expected) <=
                      1e-5 * magnitude + 1e-6);
            }
            if (c.color[0]) {
                double color_r = 0;
                for (int j = 0; j < 3; ++j) color_r += q[j] / sum * c.color[j]->r;
                CHECK(std::abs(out.channel(FragmentBuffer::albedo_r)[0] - c.material->albedo.r * color_r) <= 1e-4);
            }
            if (c.color[0] && c.material->alpha_mode == AlphaMode::blend) {
                ++colored_blended;
                double alpha = 0;
                for (int j = 0; j < 3; ++j) alpha += q[j] / sum * c.color[j]->a;
                CHECK(std::abs(out.channel(FragmentBuffer::alpha)[0] - c.material->alpha_factor * alpha) <= 1e-4);
            }
        }
    }
    CHECK(colored_blended > 0);
}

}  // namespace
