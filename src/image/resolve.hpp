// Resolve: from shaded HDR radiance to the two images a frame produces.
#pragma once

#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>

#include "image/display_encoding.hpp"
#include "raster/msaa/msaa.hpp"
#include "raster/tile_rasterizer.hpp"
#include "shade/shade_kernels.hpp"
#include "tessera/renderer.hpp"

namespace tessera::image {

// The scene-linear radiance that Reinhard + gamma map back onto a display
// colour (the tonemap's inverse), kept finite: the EXR's background.
glm::vec3 radiance_for_display(const glm::vec3& display);

// The background as each image stores it, worked out once per frame.
struct ClearValues {
    glm::vec3 radiance;           // radiance_for_display(clear colour)
    std::uint8_t display[3];      // the clear colour quantized
};
ClearValues clear_values(const glm::vec3& clear_color);

// Writes one tile of the frame, each pixel once: covered pixels take the next
// of `count` shaded values (row-major order, as gathered), the others the
// clear colour. Radiance goes to the image as it is (if the image keeps
// radiance); then the display image gets each value tonemapped (Reinhard,
// gamma) and quantized, exactly as the scalar reference does, in any ISA
// (encode_display_unorm8, which overwrites shaded.r).
void resolve_tile(const raster::TileBuffers& coverage, const raster::TileRect& rect, std::size_t count,
                  const shade::RadianceOutputs& shaded, const ClearValues& clear, simd::Isa isa,
                  RenderedImage& image);

// Writes the clear colour over a tile no triangle touched, and the background
// value into each AOV plane the image has.
void clear_tile(const raster::TileRect& rect, const ClearValues& clear, RenderedImage& image);

// Asks for the cache lines of the tile's display (and kept radiance) pixels,
// for writing: called as the tile begins, so that the lines arrive while it is
// rasterized and shaded. Written cold at resolve, each line waited for its
// read from memory (the 4K spheres' resolve took 1.3x as long). A hint only;
// nothing is asked for past kPrefetchTileOutputBytes (large tiles).
inline constexpr std::size_t kPrefetchTileOutputBytes = 64 * 1024;
void prefetch_tile_output(const raster::TileRect& rect, const RenderedImage& image);

// Linear view-space depth of a world-space point, from the same view matrix
// the vertex stage uses: -z in view space, i.e. the distance in front of the
// camera along its view axis. Worked out once per frame.
struct ViewDepth {
    glm::vec4 minus_view_row_z{0.0f};  // -(row 2 of the view matrix)
    explicit ViewDepth(const glm::mat4& view = glm::mat4(1.0f))
        : minus_view_row_z(-view[0][2], -view[1][2], -view[2][2], -view[3][2]) {}
    float operator()(float x, float y, float z) const {
        return minus_view_row_z.x * x + minus_view_row_z.y * y + minus_view_row_z.z * z + minus_view_row_z.w;
    }
};

// The object_id and material_id AOVs of a triangle (AovPlanes), from its id:
// the renderer's triangle ids carry their chunk of one object's triangles in
// the bits from chunk_shift up, and the tables hold each chunk's values.
// Empty (null tables) unless one of the two AOVs was asked for.
struct SurfaceIds {
    const std::uint32_t* object_of_chunk = nullptr;
    const std::uint32_t* material_of_chunk = nullptr;
    int chunk_shift = 0;
    std::uint32_t object_id(std::uint32_t triangle) const { return object_of_chunk[triangle >> chunk_shift]; }
    std::uint32_t material_id(std::uint32_t triangle) const { return material_of_chunk[triangle >> chunk_shift]; }
};

// Writes one tile of each AOV plane the image has (RenderedImage::aov), each
// pixel once: covered pixels take the next of `surface.count` fragments (the
// shader's inputs, in the row-major order they were gathered) and the ids of
// their triangle, the others the planes' background values.
void resolve_aov_tile(const raster::TileBuffers& coverage, const raster::TileRect& rect,
                      const shade::FragmentInputs& surface, const ViewDepth& view_depth, const SurfaceIds& ids,
                      RenderedImage& image);

// A 4×-multisampled tile's fragments' ids: fragment k shows triangle `triangle[k]`
// (raster::TileFragments::triangle).
struct FragmentIds {
    SurfaceIds ids;
    const std::uint32_t* triangle = nullptr;
};

// The same for a 4×-multisampled tile: each sample takes its fragment's
// value (TileSamples::fragment) or the background's, and a pixel is the
// average of its samples, as a GL multisampled RGBA8 framebuffer resolves:
// radiance is the mean of the samples' radiance (summed in pairs, so four
// equal samples give exactly that value); display is the mean of the samples'
// 8-bit values, rounded to nearest (halves up).
void resolve_tile_msaa(const raster::TileSamples& samples, const raster::TileRect& rect, std::size_t count,
                       const shade::RadianceOutputs& shaded, const ClearValues& clear, simd::Isa isa,
                       RenderedImage& image);

// AOVs of a 4×-multisampled tile are not averaged (a mean of depths or normals
// is no surface's value): a pixel holds what its sample 0 shows, surface or
// background.
void resolve_aov_tile_msaa(const raster::TileSamples& samples, const raster::TileRect& rect,
                           const shade::FragmentInputs& surface, const ViewDepth& view_depth, const FragmentIds& ids,
                           RenderedImage& image);

}  // namespace tessera::image
