// Rendering a scene to an image: the whole pipeline behind one call.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tessera/scene.hpp"

namespace tessera {

struct RenderSettings {
    int threads = 0;        // worker threads; 0 = one per hardware thread
    int tile_size = 32;     // screen tile side in pixels, a power of two in [8, 256]
    std::string isa = "auto";  // SIMD kernels: auto | scalar | sse4 | avx2 | avx512
    // Fill RenderedImage::radiance (what EXR output needs). Without it a frame
    // writes only the 8-bit display image, as an OpenGL RGBA8 framebuffer would.
    bool keep_radiance = true;
};

// A rendered frame, row 0 at the top of the picture.
struct RenderedImage {
    int width = 0;
    int height = 0;
    // Scene-linear HDR radiance before tonemapping, RGB interleaved: what EXR
    // stores. Background pixels hold the radiance that tonemaps to the clear
    // colour. Empty when the renderer was told not to keep it.
    std::vector<float> radiance;
    // Display-referred RGB8 after Reinhard and gamma 1/2.2: what PNG stores.
    // Background pixels hold the clear colour, as glClear writes it.
    std::vector<std::uint8_t> display;
};

// What one frame did and where its time went, in milliseconds.
struct FrameStats {
    std::uint64_t triangles_in = 0;          // submitted by the scene's objects
    std::uint64_t triangles_binned = 0;      // left after clipping, culling and setup
    std::uint64_t fragments_rasterized = 0;  // pixel centres covered, over all triangles
    std::uint64_t fragments_shaded = 0;      // visible pixels, each shaded once
    // Wall-clock time of the frame's three passes, one after the other.
    double vertex_ms = 0;       // vertex shader, outcodes, viewport transform
    double triangles_ms = 0;    // the triangle pass: clip+setup, then binning, chunk by chunk
    double tiles_ms = 0;        // the tile pass: rasterize, shade, resolve, tile by tile
    double total_ms = 0;
    // The steps inside the triangle and tile passes: busy time summed over
    // the workers, divided by the thread count, so that they add up to about
    // their pass's time.
    double clip_setup_ms = 0;   // clipping, culling, triangle setup
    double binning_ms = 0;      // sorting triangles into tiles
    double rasterize_ms = 0;    // edge functions, depth test
    double shade_ms = 0;        // interpolation and the PBR shader
    double resolve_ms = 0;      // tonemap, quantize, write the images
};

// Renders scenes, keeping its frame memory from one frame to the next.
class Renderer {
public:
    explicit Renderer(const RenderSettings& settings = {});  // throws std::invalid_argument
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // The returned image stays valid until the next render().
    const RenderedImage& render(const Scene& scene);
    const FrameStats& last_frame_stats() const;
    std::string isa_name() const;  // the shading kernels in use
    int threads() const;

private:
    struct Frame;
    std::unique_ptr<Frame> frame_;
};

}  // namespace tessera
