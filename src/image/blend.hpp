// Blending (AlphaMode::blend, glTF's BLEND): the radiance of a tile's samples,
// kept in float while blended fragments are composited over the opaque result,
// then written into the images.
//
// Where the blend happens: in scene-linear radiance, before tonemapping — the
// physically meaningful "over" of light (a 50% veil lets half the light behind
// it through) and what the EXR stores. The PNG is that blended radiance after
// Reinhard and gamma, exactly as for opaque pixels. (A GL renderer of the
// reference shader, which tonemaps in its fragment shader, would blend the
// display values in its RGBA8 framebuffer instead; that is not linear light.)
//
// The operator, per sample a fragment covers, fragments in drawing order:
//   dst = src · alpha + dst · (1 − alpha)
// src the fragment's shaded radiance (lights and emission), alpha its material's.
// With 4× MSAA each sample blends on its own, and the pixel is the mean of its
// samples as for opaque pixels (resolve.hpp). Pixels no blended fragment covers
// come out bit-identical to what resolve_tile / resolve_tile_msaa write.
#pragma once

#include <cstdint>
#include <vector>

#include "image/resolve.hpp"
#include "raster/blend_raster.hpp"

namespace tessera::image {

// Scene-linear radiance per sample of one tile: sample s of tile pixel p at
// [samples · p + s], p row-major with a stride of `side`. A worker's, reused.
struct TileRadiance {
    int side = 0, samples = 1;
    std::vector<float> r, g, b;  // padded for the tonemap kernel
    void reserve(int tile_side, int samples_per_pixel);
};

// The opaque pass's result: each sample takes its fragment's shaded radiance
// (`shaded`, before tonemapping) or the background's.
void fill_opaque(const raster::TileBuffers& coverage, const raster::TileRect& rect, const shade::RadianceOutputs& shaded,
                 const ClearValues& clear, TileRadiance& tile);
void fill_opaque(const raster::TileSamples& samples, const raster::TileRect& rect, const shade::RadianceOutputs& shaded,
                 const ClearValues& clear, TileRadiance& tile);
// A tile without opaque fragments: background everywhere.
void fill_background(const raster::TileRect& rect, const ClearValues& clear, TileRadiance& tile);

// Composites fragments [0, count) of `fragments` in order: fragment k has
// radiance shaded[k] and alpha[k], and covers the samples of its sample mask.
void blend_over(const raster::BlendFragments& fragments, std::size_t count, const shade::RadianceOutputs& shaded,
                const float* alpha, TileRadiance& tile);

// Writes the tile into the image as resolve_tile / resolve_tile_msaa do:
// radiance (the mean of the samples'), display (Reinhard + gamma per sample,
// exactly as encode_display_unorm8; the mean of the 8-bit values). Overwrites `tile`.
void resolve_blended_tile(TileRadiance& tile, const raster::TileRect& rect, simd::Isa isa, RenderedImage& image);

}  // namespace tessera::image
