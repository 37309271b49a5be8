// The environment behind the scene (background.fs of LearnOpenGL's IBL chapters):
// where no surface covers a pixel, the environment cube's level 0 along the
// pixel's view ray, times the intensity and the exposure, tonemapped and
// quantized exactly as shaded pixels are (encode_display_unorm8). Painted over
// the clear colour after a tile is resolved.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "image/blend.hpp"
#include "raster/msaa/msaa.hpp"
#include "raster/tile_rasterizer.hpp"
#include "shade/ibl_reference.hpp"
#include "tessera/renderer.hpp"

namespace tessera::image {

class EnvironmentBackground {
public:
    EnvironmentBackground() = default;
    // For the scene's camera and image size; shown() is false unless the
    // scene has an environment shown as its background.
    EnvironmentBackground(const Scene& scene, float exposure_scale);
    bool shown() const { return ibl_.maps != nullptr; }
    // HDR radiance (exposed) seen through the centre of pixel (x, y), y down.
    glm::vec3 radiance(int x, int y) const;

    // Pixels of a resolved one-sample tile that no triangle covers (coverage
    // null: every pixel), in the radiance and display images.
    void paint(const raster::TileRect& rect, const raster::TileBuffers* coverage, simd::Isa isa,
               RenderedImage& image) const;
    // A 4×-multisampled tile: pixels none of whose samples is covered (a
    // pixel the edge of a surface crosses keeps the clear colour in its
    // uncovered samples: a limit of this version).
    void paint(const raster::TileRect& rect, const raster::TileSamples& samples, simd::Isa isa,
               RenderedImage& image) const;
    // The blend pass's opaque radiance: every sample not covered (coverage
    // null, samples null: all of them).
    void paint(const raster::TileRect& rect, const raster::TileBuffers* coverage, const raster::TileSamples* samples,
               TileRadiance& tile) const;

private:
    shade::IblLighting ibl_;
    float exposure_scale_ = 1.0f;
    int width_ = 0, height_ = 0;
    glm::vec3 forward_{0.0f}, right_{0.0f}, up_{0.0f};  // world space; right and up scaled to the image's half extent
    glm::vec3 direction(int x, float ndc_y) const;  // world space, not unit
    template <class Covered>
    void paint_pixels(const raster::TileRect& rect, Covered&& covered, simd::Isa isa, RenderedImage& image) const;
};

}  // namespace tessera::image
