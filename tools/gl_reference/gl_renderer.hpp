// A peer renderer: the same scene drawn by OpenGL 3.3 core with the ORIGINAL GLSL of
// ../shared/reference/pbr_lighting.md, on Mesa's llvmpipe (a CPU driver) through an
// EGL surfaceless context. It checks Tessera's pixels against an independent
// implementation and gives a CPU rasterizer to race. Not part of the pipeline:
// nothing under src/ may include it.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tessera/renderer.hpp"
#include "tessera/scene.hpp"

namespace tessera::gl_reference {

// Owns one EGL display + GL 3.3 core context (current on the constructing thread;
// use the object from that thread only) and an offscreen framebuffer of RGBA8
// colour + 24-bit depth at the last scene's size, without MSAA. Meshes and the
// shader program are rebuilt when the scene (its meshes, or its light count) changes.
// Every EGL/GL failure throws std::runtime_error naming what failed.
class GlReferenceRenderer {
public:
    GlReferenceRenderer();
    ~GlReferenceRenderer();
    GlReferenceRenderer(const GlReferenceRenderer&) = delete;
    GlReferenceRenderer& operator=(const GlReferenceRenderer&) = delete;

    // One frame, read back: `display` is RGB8, row 0 at the top (as Tessera's);
    // `radiance` stays empty (the reference shader only writes the tonemapped colour).
    RenderedImage render(const Scene& scene);

    // The object covering each pixel, row 0 at the top: 0 for background, i + 1 for
    // scene.objects[i]. Same geometry and depth test as render(); for finding silhouettes.
    std::vector<std::uint32_t> render_object_ids(const Scene& scene);

    // Renders `warmup` untimed frames, then `frames` timed ones, and returns each timed
    // frame's wall-clock milliseconds. A frame is clear + every draw + glFinish; the
    // readback is not included (Tessera's frame time does not include writing a file either).
    std::vector<double> time_frames(const Scene& scene, int frames, int warmup);

    // GL_RENDERER and GL_VERSION, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)", "3.3 (Core Profile) Mesa 22.3.6".
    std::string renderer_name() const;
    std::string version() const;

private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace tessera::gl_reference
