#include "shade/alpha_mask.hpp"

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
    const glm::vec2 uv0 = c.corner[0]->uv, uv_d1 = c.corner[1]->uv - uv0, uv_d2 = c.corner[2]->uv - uv0;
    const glm::vec2 uv = uv0 + b1 * uv_d1 + b2 * uv_d2;
    // The quad partners, as SurfaceGather::add finds them (tile origins are even,
    // so image and tile pixels have the same parity).
    const float step_x = (x & 1) ? -1.0f : 1.0f, step_y = (y & 1) ? -1.0f : 1.0f;
    const auto [bx1, bx2] =
        raster::perspective_barycentrics(inv_w, lambda1 + step_x * c.lambda1_dx, lambda2 + step_x * c.lambda2_dx);
    const auto [by1, by2] =
        raster::perspective_barycentrics(inv_w, lambda1 + step_y * c.lambda1_dy, lambda2 + step_y * c.lambda2_dy);
    const glm::vec2 duv_dx = step_x * ((bx1 - b1) * uv_d1 + (bx2 - b2) * uv_d2);
    const glm::vec2 duv_dy = -step_y * ((by1 - b1) * uv_d1 + (by2 - b2) * uv_d2);
    const texture::Texture& map = *triangle.textures[std::size_t(material.albedo_map.texture)];
    const float lod = texture::lod_from_derivatives(duv_dx.x, duv_dx.y, duv_dy.x, duv_dy.y, map.width(), map.height());
    const texture::Wrap wrap =
        material.albedo_map.wrap == TextureWrap::clamp_to_edge ? texture::Wrap::clamp_to_edge : texture::Wrap::repeat;
    return alpha * map.sample_trilinear(uv, lod, wrap).a;
}

bool alpha_mask_keep(const void* triangle, int x, int y, float lambda1, float lambda2) {
    const auto& t = *static_cast<const AlphaMaskTriangle*>(triangle);
    return fragment_alpha(t, x, y, lambda1, lambda2) >= t.corners.material->alpha_cutoff;
}

}  // namespace tessera::shade
