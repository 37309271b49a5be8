// The alpha test of masked materials (AlphaMode::mask, glTF's alphaMode MASK):
// run by the rasterizer on each fragment that passes the depth test
// (raster::FragmentTest), so a discarded fragment never reaches the depth
// buffer and the surface behind it shows, as a GPU's `discard` does.
// Alpha is Material::alpha_factor × the vertex colour's alpha (where the mesh
// has colours) × the albedo map's alpha, sampled as the
// material pass samples the map: at the perspective-correct uv, trilinear,
// level of detail from the 2×2 quad's derivatives (surface_gather.hpp).
#pragma once

#include <memory>
#include <span>

#include "shade/surface_gather.hpp"

namespace tessera::shade {

// One triangle's alpha test: its corners (with the barycentrics' per-pixel
// steps, which corners_of fills for materials with maps) and the textures
// its material's slots index.
struct AlphaMaskTriangle {
    TriangleCorners corners;
    std::span<const std::shared_ptr<const texture::Texture>> textures;
};

// Alpha at image pixel (x, y) of the triangle, whose screen-space barycentrics there are λ1 λ2.
float fragment_alpha(const AlphaMaskTriangle& triangle, int x, int y, float lambda1, float lambda2);

// raster::FragmentTest::keep for a context pointing at an AlphaMaskTriangle:
// glTF's rule, alpha >= cutoff is drawn, below it discarded.
bool alpha_mask_keep(const void* triangle, int x, int y, float lambda1, float lambda2);

}  // namespace tessera::shade
