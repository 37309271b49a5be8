// The fragment stage's inputs: for each visible pixel of a tile, the
// interpolated varyings (WorldPos, Normal) and its material, gathered into the
// structure-of-arrays batch the shading kernels take.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "geometry/shaded_vertex.hpp"
#include "raster/tile_rasterizer.hpp"
#include "shade/shade_kernels.hpp"
#include "tessera/scene.hpp"

namespace tessera::shade {

// Storage for one tile's fragments: shade_fragments' inputs and outputs.
// Reserved once per worker; nothing is allocated per tile.
class FragmentBuffer {
public:
    void reserve(std::size_t max_fragments);
    std::size_t capacity() const { return channels_[0].size(); }
    void set(std::size_t i, const glm::vec3& world_pos, const glm::vec3& normal, const Material& m) {
        channels_[world_x][i] = world_pos.x, channels_[world_y][i] = world_pos.y, channels_[world_z][i] = world_pos.z;
        channels_[normal_x][i] = normal.x, channels_[normal_y][i] = normal.y, channels_[normal_z][i] = normal.z;
        channels_[albedo_r][i] = m.albedo.r, channels_[albedo_g][i] = m.albedo.g, channels_[albedo_b][i] = m.albedo.b;
        channels_[metallic][i] = m.metallic, channels_[roughness][i] = m.roughness, channels_[ao][i] = m.ao;
    }
    // Fills the lanes from count to padded_count(count) with copies of a real
    // fragment, so that the kernels' spare lanes compute sane values.
    void pad(std::size_t count);
    FragmentInputs inputs(std::size_t count) const;
    RadianceOutputs outputs();

private:
    enum Channel { world_x, world_y, world_z, normal_x, normal_y, normal_z, albedo_r, albedo_g, albedo_b, metallic,
                   roughness, ao, out_r, out_g, out_b, kChannels };
    std::vector<float> channels_[kChannels];
};

// A visible triangle as the gather needs it.
struct TriangleCorners {
    const geometry::ShadedVertex* corner[3];
    const Material* material;
};

// Gathers the covered pixels of a width × height tile, row by row, into `out`
// and returns how many there are. lookup(triangle_id) gives TriangleCorners.
// Neighbouring pixels mostly show the same triangle, so its corners are
// fetched once per run of pixels.
template <class Lookup>
std::size_t gather_surface_points(const raster::TileBuffers& tile, int width, int height, Lookup&& lookup,
                                  FragmentBuffer& out) {
    std::size_t count = 0;
    std::uint32_t cached_id = raster::kNoTriangle;
    const Material* m = nullptr;
    std::array<float, 3> inv_w{};
    glm::vec3 world0{}, world_d1{}, world_d2{}, normal0{}, normal_d1{}, normal_d2{};
    for (int y = 0; y < height; ++y) {
        const std::size_t row = std::size_t(y) * tile.side;
        for (int x = 0; x < width; ++x) {
            if (!tile.covered(row + x)) continue;
            const std::uint32_t id = tile.triangle[row + x];
            if (id != cached_id) {
                cached_id = id;
                const TriangleCorners c = lookup(id);
                m = c.material;
                // As the viewport transform computed it (ScreenVertex::inv_w).
                for (int k = 0; k < 3; ++k) inv_w[k] = 1.0f / c.corner[k]->clip_pos.w;
                world0 = c.corner[0]->world_pos;
                world_d1 = c.corner[1]->world_pos - world0, world_d2 = c.corner[2]->world_pos - world0;
                normal0 = c.corner[0]->normal;
                normal_d1 = c.corner[1]->normal - normal0, normal_d2 = c.corner[2]->normal - normal0;
            }
            const auto [b1, b2] = raster::perspective_barycentrics(inv_w, tile.lambda1[row + x], tile.lambda2[row + x]);
            out.set(count++, world0 + b1 * world_d1 + b2 * world_d2, normal0 + b1 * normal_d1 + b2 * normal_d2, *m);
        }
    }
    out.pad(count);
    return count;
}

}  // namespace tessera::shade
