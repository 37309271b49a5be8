// The fragment stage's inputs: for each visible pixel of a tile, the
// interpolated varyings (WorldPos, Normal) and its material, gathered into the
// structure-of-arrays batch the shading kernels take.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

#include "geometry/shaded_vertex.hpp"
#include "raster/msaa/msaa.hpp"
#include "raster/tile_rasterizer.hpp"
#include "shade/shade_kernels.hpp"
#include "tessera/scene.hpp"

namespace tessera::shade {

// A visible triangle as the gather needs it.
struct TriangleCorners {
    const geometry::ShadedVertex* corner[3];
    const Material* material;
    // Textured materials only. Screen-space barycentrics are affine in the
    // pixel position: their change per pixel right and per pixel down.
    float lambda1_dx = 0, lambda1_dy = 0, lambda2_dx = 0, lambda2_dy = 0;
    const glm::vec4* tangent[3] = {nullptr, nullptr, nullptr};  // world-space tangents where the mesh has them
    // Linear RGBA vertex colours (Mesh::colors) where the mesh has them; they
    // multiply the albedo (and alpha), interpolated perspective-correctly.
    const glm::vec4* color[3] = {nullptr, nullptr, nullptr};
    // The second uv set's corners (Mesh::uvs1) where the mesh has one and the material's maps read it.
    const glm::vec2* uv1[3] = {nullptr, nullptr, nullptr};
    // The triangle shows its back (raster::RasterTriangle::back_facing; only a
    // double-sided material's can, single-sided ones are culled): glTF's rule,
    // for TOML materials too, flips the normal and the tangent frame there, so
    // that the side seen is lit from its own side.
    bool back_facing = false;
};

// The fast gather's per-tile table of the triangles it has met: each set up
// once per tile (its corners looked up, 1/w and the differences worked out),
// though the tile's rows meet it several times. A one-sample tile's entries
// are numbered by its triangle list (raster::TileBuffers::triangles); a
// fragment list's are found through `slots`, direct-mapped on the id, which
// start with no valid entry (every slot's triangle kNoTriangle, 4 KB to clear).
//
// A vec3 is kept as (x, y, z, 0) in a 4-float vector (GCC's vector extension,
// one SSE register): its lane-wise IEEE operations give glm's bits per
// component, in a third of the instructions.
using Float4 = float __attribute__((vector_size(16)));
inline Float4 float4_from(const glm::vec3& v) { return Float4{v.x, v.y, v.z, 0.0f}; }
inline glm::vec3 vec3_from(const Float4& v) { return {v[0], v[1], v[2]}; }
struct alignas(64) GatheredTriangle {
    // WorldPos and Normal side by side, so that AVX2 takes a pair as one 8-float vector.
    Float4 world0, normal0, world_d1, normal_d1, world_d2, normal_d2;
    // 1/w of the corners, and a spare float: the set-up stores the four lanes of a vector.
    struct alignas(16) InvW {
        std::array<float, 3> lanes;
        float spare;
    } inv_w;
    // The material's address, its lowest bit set where beyond_plain: a fragment
    // needs the out-of-line path (new run, extras) unless this equals its run's material.
    std::uintptr_t run_key;
    bool textured, beyond_plain;  // beyond_plain: textured, vertex-coloured or blended (scalar extras per fragment)
    const Material* material() const { return reinterpret_cast<const Material*>(run_key & ~std::uintptr_t(1)); }
};
static_assert(sizeof(GatheredTriangle) == 128, "two cache lines; entries are addressed by a shift");
struct GatheredTriangleExtras {
    TriangleCorners corners;
    glm::vec2 uv0, uv_d1, uv_d2;
};
struct TriangleTable {
    static constexpr std::size_t kSize = 512;
    struct Slot {
        std::uint32_t triangle;  // its id, or raster::kNoTriangle
        std::uint32_t entry;     // the triangle's entry, in bytes from the first
    };
    std::vector<Slot> slots;
    // Per set-up of a gather (at most one per fragment):
    std::vector<GatheredTriangle> entry;
    std::vector<GatheredTriangleExtras> extras;  // where beyond_plain
    std::vector<std::uint32_t> new_id;  // the triangle (kPackSlack spare)
    std::vector<std::uint32_t> entry_of_fragment;  // in bytes from the first entry (as Slot::entry)
    // Per fragment of a batch (a fragment list) or of the tile (a one-sample tile): the first
    // fragment of each row of fragments of one triangle (a head).
    std::vector<std::uint32_t> head_of_fragment;  // its head's index among the batch's (tile's) heads
    std::vector<std::uint32_t> head_id, head_slot, head_entry;  // per head
    // A one-sample tile's covered pixels, and their triangles (list positions) and λ1 λ2, packed
    // (kPackSlack: packing stores whole vectors, whose spare lanes land past the end).
    static constexpr std::size_t kPackSlack = 16;
    std::vector<std::uint32_t> pixels, ids;
    std::vector<float> lambda1, lambda2;
    // Per position in a tile's triangle list (raster::TileBuffers::triangles), grown
    // to the longest list met: whether a fragment shows it (0 between tiles), its entry.
    std::vector<std::uint8_t> shown;
    std::vector<std::uint32_t> entry_of_position;

    void reserve(std::size_t max_fragments) {
        entry.resize(max_fragments), extras.resize(max_fragments), new_id.resize(max_fragments + kPackSlack);
        entry_of_fragment.resize(max_fragments + kPackSlack), head_of_fragment.resize(max_fragments + kPackSlack);
        for (auto* v : {&head_id, &head_slot, &head_entry}) v->resize(max_fragments + kPackSlack);
        for (auto* v : {&pixels, &ids}) v->resize(max_fragments + kPackSlack);
        for (auto* v : {&lambda1, &lambda2}) v->resize(max_fragments + kPackSlack);
    }
    // Forgets every entry (no triangle is kNoTriangle).
    void start_tile() {
        slots.assign(kSize, {raster::kNoTriangle, 0});
    }
    static std::size_t slot(std::uint32_t id) { return (id ^ (id >> 11) ^ (id >> 17)) & (kSize - 1); }
};

// Storage for one tile's fragments: shade_fragments' inputs and outputs, and
// for textured materials their texture coordinates with screen-space
// derivatives. Reserved once per worker; nothing is allocated per tile.
class FragmentBuffer {
public:
    enum Channel {
        world_x, world_y, world_z, normal_x, normal_y, normal_z, albedo_r, albedo_g, albedo_b, metallic, roughness, ao,
        out_r, out_g, out_b,
        // Textured materials only (MaterialRun::textured):
        u, v,                          // TexCoords
        dudx, dvdx, dudy, dvdy,        // dFdx(TexCoords), dFdy(TexCoords): y up, as GL's window y
        dpdx_x, dpdx_y, dpdx_z,        // dFdx(WorldPos)
        dpdy_x, dpdy_y, dpdy_z,        // dFdy(WorldPos)
        tangent_x, tangent_y, tangent_z, tangent_w,  // stored world-space tangent; w = 0: none, derive from derivatives
        emissive_r, emissive_g, emissive_b,
        // Meshes with a second uv set (Mesh::uvs1) only: its TexCoords and derivatives, as u..dvdy.
        u1, v1, du1dx, dv1dx, du1dy, dv1dy,
        // Blended materials only (AlphaMode::blend): alpha_factor × vertex colour alpha,
        // × the albedo map's alpha after the material pass.
        alpha,
        kChannels
    };

    void reserve(std::size_t max_fragments);
    std::size_t capacity() const { return capacity_; }
    void set(std::size_t i, const glm::vec3& world_pos, const glm::vec3& normal, const Material& m) {
        channels_[world_x][i] = world_pos.x, channels_[world_y][i] = world_pos.y, channels_[world_z][i] = world_pos.z;
        channels_[normal_x][i] = normal.x, channels_[normal_y][i] = normal.y, channels_[normal_z][i] = normal.z;
        channels_[albedo_r][i] = m.albedo.r, channels_[albedo_g][i] = m.albedo.g, channels_[albedo_b][i] = m.albedo.b;
        channels_[metallic][i] = m.metallic, channels_[roughness][i] = m.roughness, channels_[ao][i] = m.ao;
    }
    // Material channels of fragments [begin, end), all of material m.
    void set_material(std::size_t begin, std::size_t end, const Material& m) {
        const float values[] = {m.albedo.r, m.albedo.g, m.albedo.b, m.metallic, m.roughness, m.ao};
        for (int k = 0; k < 6; ++k) std::fill(channels_[albedo_r + k].data() + begin, channels_[albedo_r + k].data() + end, values[k]);
    }
    float* channel(Channel c) { return channels_[c].data(); }
    const float* channel(Channel c) const { return channels_[c].data(); }
    // Fills the lanes from count to padded_count(count) with copies of a real
    // fragment, so that the kernels' spare lanes compute sane values.
    void pad(std::size_t count);
    // The fast gather leaves the material channels of plain runs (MaterialRun::plain)
    // unfilled: the kernels take such a run's material from the run. These fill
    // them for the readers of channels: all of them, padding included (AOVs, light
    // culling, the scalar kernel), or only the lanes a run shares a SIMD batch of
    // any ISA with another run or with the padding (shade_fragment_runs).
    void fill_plain_runs(std::span<const MaterialRun> runs, std::size_t count);
    void fill_plain_run_edges(std::span<const MaterialRun> runs, std::size_t count);
    FragmentInputs inputs(std::size_t count) const;
    RadianceOutputs outputs();

    TriangleTable& triangle_table() { return triangles_; }

private:
    std::size_t capacity_ = 0;
    std::vector<float> channels_[kChannels];
    TriangleTable triangles_;  // the fast gather's (surface_gather_fast.hpp)
};

// Gathers the covered pixels of a width × height tile, row by row, into `out`,
// records the runs of fragments that share a material, and returns the
// fragment count. A pixel's triangle id is tile.triangles.ids[tile.triangle[pixel]];
// lookup(triangle_id) gives TriangleCorners. Neighbouring
// pixels mostly show the same triangle, so its corners are fetched once per
// run of pixels.
//
// Textured materials also get dFdx/dFdy of TexCoords and WorldPos the way a
// GPU computes them: pixels form 2×2 quads (even x and y at the top-left, tile
// origins being even), and a derivative is the difference between the two
// pixels of the quad's row (x) or column (y), y pointing up as in GL. The
// quad's other pixels need not be covered: like a GPU's helper lanes they
// evaluate this triangle's interpolants there.
template <class Lookup>
std::size_t gather_surface_points(const raster::TileBuffers& tile, int width, int height, Lookup&& lookup,
                                  FragmentBuffer& out, std::vector<MaterialRun>& runs);

// The same for a 4×-multisampled tile: one fragment per entry of `fragments`
// (raster/msaa/msaa.hpp), at its own λ1 λ2; derivatives as above, from its pixel.
template <class Lookup>
std::size_t gather_surface_points(const raster::TileFragments& fragments, Lookup&& lookup, FragmentBuffer& out,
                                  std::vector<MaterialRun>& runs);

namespace detail {

// What the extras of a fragment need of its triangle beyond TriangleCorners.
struct SurfaceInterpolants {
    const std::array<float, 3>& inv_w;
    const glm::vec3 &world_d1, &world_d2;
    const glm::vec2 &uv0, &uv_d1, &uv_d2;
};

// Vertex colours multiply the gathered albedo (fragment i's material channels
// must be written); blended materials get their alpha.
inline void add_color_and_alpha(const TriangleCorners& c, float b1, float b2, FragmentBuffer& out, std::size_t i) {
    using C = FragmentBuffer;
    float alpha = c.material->alpha_factor;
    if (c.color[0]) {
        const glm::vec4 color0 = *c.color[0];
        const glm::vec4 color = color0 + b1 * (*c.color[1] - color0) + b2 * (*c.color[2] - color0);
        for (int k = 0; k < 3; ++k) out.channel(C::Channel(C::albedo_r + k))[i] *= color[k];
        alpha *= color.a;
    }
    if (c.material->alpha_mode == AlphaMode::blend) out.channel(C::alpha)[i] = alpha;
}

// The textured materials' inputs, vertex colours, blended alpha of fragment i,
// at tile pixel (x, y), screen-space λ1 λ2, perspective-correct b1 b2.
inline void add_extras(const TriangleCorners& c, const SurfaceInterpolants& t, int x, int y, float lambda1,
                       float lambda2, float b1, float b2, FragmentBuffer& out, std::size_t i) {
    using C = FragmentBuffer;
    if (c.color[0] != nullptr || c.material->alpha_mode == AlphaMode::blend) add_color_and_alpha(c, b1, b2, out, i);
    if (!c.material->has_maps()) return;
    const glm::vec2 uv = t.uv0 + b1 * t.uv_d1 + b2 * t.uv_d2;
    // The quad partners: the pixel beside this one in the quad's row and in its column.
    const float step_x = (x & 1) ? -1.0f : 1.0f, step_y = (y & 1) ? -1.0f : 1.0f;
    const auto [bx1, bx2] =
        raster::perspective_barycentrics(t.inv_w, lambda1 + step_x * c.lambda1_dx, lambda2 + step_x * c.lambda2_dx);
    const auto [by1, by2] =
        raster::perspective_barycentrics(t.inv_w, lambda1 + step_y * c.lambda1_dy, lambda2 + step_y * c.lambda2_dy);
    // dFdx = right − left pixel; dFdy = upper − lower row (rows run down the image).
    const glm::vec2 duv_dx = step_x * ((bx1 - b1) * t.uv_d1 + (bx2 - b2) * t.uv_d2);
    const glm::vec2 duv_dy = -step_y * ((by1 - b1) * t.uv_d1 + (by2 - b2) * t.uv_d2);
    // A back face's tangent frame is negated whole, T, B and N (the glTF sample
    // viewer's rule): the normal arrives negated; negating dFdx(WorldPos) and
    // dFdy(WorldPos) too makes the derived frames' T and B (material_maps.hpp)
    // come out negated, and the stored tangent's xyz and w below do the same.
    const float facing = c.back_facing ? -1.0f : 1.0f;
    const glm::vec3 dp_dx = (facing * step_x) * ((bx1 - b1) * t.world_d1 + (bx2 - b2) * t.world_d2);
    const glm::vec3 dp_dy = (facing * -step_y) * ((by1 - b1) * t.world_d1 + (by2 - b2) * t.world_d2);
    const float values[] = {uv.x,    uv.y,    duv_dx.x, duv_dx.y, duv_dy.x, duv_dy.y,
                            dp_dx.x, dp_dx.y, dp_dx.z,  dp_dy.x,  dp_dy.y,  dp_dy.z};
    for (int k = 0; k < 12; ++k) out.channel(C::Channel(C::u + k))[i] = values[k];
    if (c.uv1[0] != nullptr) {  // the second set, interpolated and differentiated alike
        const glm::vec2 s0 = *c.uv1[0], s_d1 = *c.uv1[1] - s0, s_d2 = *c.uv1[2] - s0;
        const glm::vec2 uv1 = s0 + b1 * s_d1 + b2 * s_d2;
        const glm::vec2 duv1_dx = step_x * ((bx1 - b1) * s_d1 + (bx2 - b2) * s_d2);
        const glm::vec2 duv1_dy = -step_y * ((by1 - b1) * s_d1 + (by2 - b2) * s_d2);
        const float second[] = {uv1.x, uv1.y, duv1_dx.x, duv1_dx.y, duv1_dy.x, duv1_dy.y};
        for (int k = 0; k < 6; ++k) out.channel(C::Channel(C::u1 + k))[i] = second[k];
    }
    glm::vec4 tangent(0.0f);  // w = 0: derive the tangent frame
    if (c.tangent[0] && c.tangent[1] && c.tangent[2]) {
        const float b0 = 1.0f - b1 - b2;
        tangent = glm::vec4(
            facing * (glm::vec3(*c.tangent[0]) * b0 + glm::vec3(*c.tangent[1]) * b1 + glm::vec3(*c.tangent[2]) * b2),
            facing * (c.tangent[0]->w < 0.0f ? -1.0f : 1.0f));
    }
    for (int k = 0; k < 4; ++k) out.channel(C::Channel(C::tangent_x + k))[i] = tangent[k];
}

// The gather's state: the cached triangle, the fragments and runs written so far.
template <class Lookup>
class SurfaceGather {
public:
    SurfaceGather(Lookup& lookup, FragmentBuffer& out, std::vector<MaterialRun>& runs)
        : lookup_(lookup), out_(out), runs_(runs) {
        runs_.clear();
    }

    // Gathers one fragment of triangle `id` at tile pixel (x, y) with screen-space barycentrics λ1 λ2.
    [[gnu::always_inline]] void add(int x, int y, std::uint32_t id, float lambda1, float lambda2) {
        if (id != cached_id_) {
            cached_id_ = id;
            c_ = lookup_(id);
            textured_ = c_.material->has_maps();
            // Vertex colours and blended alpha ride on the textured branch: other
            // triangles keep exactly one test per fragment.
            beyond_plain_ = textured_ || c_.color[0] != nullptr || c_.material->alpha_mode == AlphaMode::blend;
            // 1 / clip w, as the viewport transform computes it (geometry/viewport.hpp).
            for (int k = 0; k < 3; ++k) inv_w_[k] = 1.0f / c_.corner[k]->clip_pos.w;
            world0_ = c_.corner[0]->world_pos;
            world_d1_ = c_.corner[1]->world_pos - world0_, world_d2_ = c_.corner[2]->world_pos - world0_;
            normal0_ = c_.corner[0]->normal;
            normal_d1_ = c_.corner[1]->normal - normal0_, normal_d2_ = c_.corner[2]->normal - normal0_;
            if (c_.back_facing) normal0_ = -normal0_, normal_d1_ = -normal_d1_, normal_d2_ = -normal_d2_;
            uv0_ = c_.corner[0]->uv;
            uv_d1_ = c_.corner[1]->uv - uv0_, uv_d2_ = c_.corner[2]->uv - uv0_;
        }
        if (runs_.empty() || runs_.back().material != c_.material) {
            if (!runs_.empty()) runs_.back().end = std::uint32_t(count_);
            runs_.push_back({std::uint32_t(count_), 0, c_.material, textured_, true});
        }
        if (beyond_plain_) runs_.back().plain = false;
        const auto [b1, b2] = raster::perspective_barycentrics(inv_w_, lambda1, lambda2);
        const glm::vec3 world = world0_ + b1 * world_d1_ + b2 * world_d2_;
        out_.set(count_, world, normal0_ + b1 * normal_d1_ + b2 * normal_d2_, *c_.material);
        if (beyond_plain_)
            add_extras(c_, {inv_w_, world_d1_, world_d2_, uv0_, uv_d1_, uv_d2_}, x, y, lambda1, lambda2, b1, b2, out_,
                       count_);
        ++count_;
    }

    std::size_t finish() {
        if (!runs_.empty()) runs_.back().end = std::uint32_t(count_);
        out_.pad(count_);
        return count_;
    }

private:
    Lookup& lookup_;
    FragmentBuffer& out_;
    std::vector<MaterialRun>& runs_;
    std::size_t count_ = 0;
    std::uint32_t cached_id_ = raster::kNoTriangle;
    TriangleCorners c_{};
    bool textured_ = false, beyond_plain_ = false;
    std::array<float, 3> inv_w_{};
    glm::vec3 world0_{}, world_d1_{}, world_d2_{}, normal0_{}, normal_d1_{}, normal_d2_{};
    glm::vec2 uv0_{}, uv_d1_{}, uv_d2_{};
};

}  // namespace detail

template <class Lookup>
std::size_t gather_surface_points(const raster::TileBuffers& tile, int width, int height, Lookup&& lookup,
                                  FragmentBuffer& out, std::vector<MaterialRun>& runs) {
    detail::SurfaceGather<std::remove_reference_t<Lookup>> gather(lookup, out, runs);
    for (int y = 0; y < height; ++y) {
        const std::size_t row = std::size_t(y) * tile.side;
        for (int x = 0; x < width; ++x) {
            if (!tile.covered(row + x)) continue;
            gather.add(x, y, tile.triangles.ids[tile.triangle[row + x]], tile.lambda1[row + x], tile.lambda2[row + x]);
        }
    }
    return gather.finish();
}

template <class Lookup>
std::size_t gather_surface_points(const raster::TileFragments& fragments, Lookup&& lookup, FragmentBuffer& out,
                                  std::vector<MaterialRun>& runs) {
    detail::SurfaceGather<std::remove_reference_t<Lookup>> gather(lookup, out, runs);
    for (std::size_t k = 0; k < fragments.count; ++k)
        gather.add(fragments.x[k], fragments.y[k], fragments.triangle[k], fragments.lambda1[k], fragments.lambda2[k]);
    return gather.finish();
}

}  // namespace tessera::shade
