#include "shade/alpha_mask.hpp"

#include "shade/material_maps.hpp"
#include "texture/texture.hpp"

namespace tessera::shade {

float fragment_alpha(const AlphaMaskTriangle& triangle, int x, int y, float lambda1, float lambda2) {
    const TriangleCorners& c = triangle.corners;
    const Material& material = *c.material;
    float alpha = material.alpha_factor;
    if (!material.albedo_map.present() && !c.color[0]) return alpha;
    const std::array<float, 3> inv_w{1.0f / c.corner[0]->clip_pos.w, 1.0f / c.corner[1]->clip_pos.w,
                                     1.0f / c.corner[2]->clip_pos.w};
    const auto [b1, b2] = raster::perspective_barycentrics(inv_w, lambda1, lambda2);
    if (c.color[0]) {  // as SurfaceGather interpolates it
        const float a0 = c.color[0]->a;
        alpha *= a0 + b1 * (c.color[1]->a - a0) + b2 * (c.color[2]->a - a0);
    }
    if (!material.albedo_map.present()) return alpha;
    const TextureSlot& slot = material.albedo_map;
    const bool second = slot.uv_set == 1 && c.uv1[0] != nullptr;
    const glm::vec2 uv0 = second ? *c.uv1[0] : c.corner[0]->uv;
    const glm::vec2 uv_d1 = (second ? *c.uv1[1] : c.corner[1]->uv) - uv0;
    const glm::vec2 uv_d2 = (second ? *c.uv1[2] : c.corner[2]->uv) - uv0;
    glm::vec2 uv = uv0 + b1 * uv_d1 + b2 * uv_d2;
    // The quad partners, as SurfaceGather::add finds them (tile origins are even,
    // so image and tile pixels have the same parity).
    const float step_x = (x & 1) ? -1.0f : 1.0f, step_y = (y & 1) ? -1.0f : 1.0f;
    const auto [bx1, bx2] =
        raster::perspective_barycentrics(inv_w, lambda1 + step_x * c.lambda1_dx, lambda2 + step_x * c.lambda2_dx);
    const auto [by1, by2] =
        raster::perspective_barycentrics(inv_w, lambda1 + step_y * c.lambda1_dy, lambda2 + step_y * c.lambda2_dy);
    glm::vec2 duv_dx = step_x * ((bx1 - b1) * uv_d1 + (bx2 - b2) * uv_d2);
    glm::vec2 duv_dy = -step_y * ((by1 - b1) * uv_d1 + (by2 - b2) * uv_d2);
    if (slot.uv_transformed) {  // as the material pass transforms them (material_maps.cpp)
        const glm::mat3& m = slot.uv_transform;
        uv = {m[0][0] * uv.x + m[1][0] * uv.y + m[2][0], m[0][1] * uv.x + m[1][1] * uv.y + m[2][1]};
        duv_dx = {m[0][0] * duv_dx.x + m[1][0] * duv_dx.y, m[0][1] * duv_dx.x + m[1][1] * duv_dx.y};
        duv_dy = {m[0][0] * duv_dy.x + m[1][0] * duv_dy.y, m[0][1] * duv_dy.x + m[1][1] * duv_dy.y};
    }
    const texture::Texture& map = *triangle.textures[std::size_t(slot.texture)];
    const float lod = texture::lod_from_derivatives(duv_dx.x, duv_dx.y, duv_dy.x, duv_dy.y, map.width(), map.height());
    return alpha * map.sample(uv, lod, sampler_of(slot)).a;
}

bool alpha_mask_keep(const void* triangle, int x, int y, float lambda1, float lambda2) {
    const auto& t = *static_cast<const AlphaMaskTriangle*>(triangle);
    return fragment_alpha(t, x, y, lambda1, lambda2) >= t.corners.material->alpha_cutoff;
}

}  // namespace tessera::shade
