// A peer renderer: the same scene drawn by OpenGL 3.3 core with the ORIGINAL GLSL of
// docs/reference/pbr_lighting.md (with shadows: LearnOpenGL's shadow chapters, gl_shadows.cpp), and for a scene with an [environment] the image-based
// lighting chapters' GLSL and GL set-up of docs/reference/ibl_lighting.md (gl_ibl.cpp), on
// Mesa's llvmpipe (a CPU driver) through an EGL surfaceless context. It checks Tessera's pixels against an independent
// implementation and gives a CPU rasterizer to race. Not part of the pipeline:
// nothing under src/ may include it.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "tessera/renderer.hpp"
#include "tessera/scene.hpp"

namespace tessera::gl_reference {

// Where the image's row 0 lies in GL's window space. bottom_left is plain OpenGL, whose 4×
// sample positions are Tessera's. top_left draws the scene upside down in window space
// (projection y negated) and reads the rows back unflipped: the same image, but with
// the sample pattern mirrored top to bottom (as D3D/Vulkan place the same numbers); the
// MSAA cross-check uses it to show that the unmirrored pattern is the one that matches.
enum class WindowOrigin { bottom_left, top_left };

// How the peer makes the IBL maps. The defaults do what docs/reference/ibl_lighting.md says
// Tessera does where it departs from the chapter ("Where we depart from the GPU's bits"), so
// that a comparison measures implementation differences; each flag restores the chapter's own.
struct IblOptions {
    // The chapter's RGB16F / RG16F textures; false: RGB32F / RG32F (Tessera keeps float).
    bool half_float_storage = false;
    // The chapter's texture() in irradiance_convolution.fs, whose level llvmpipe picks from the
    // derivatives of sampleVec; false: textureLod(..., 4.0), Tessera's kIrradianceLod.
    bool irradiance_lod_from_derivatives = false;
    bool operator==(const IblOptions&) const = default;
};

// How the peer makes shadow maps (gl_shadows.hpp). The default does what Tessera does: float
// depth. The flag restores the chapters' own unsized GL_DEPTH_COMPONENT (the driver's choice).
struct ShadowOptions {
    bool chapter_depth_format = false;
    bool operator==(const ShadowOptions&) const = default;
};

// One shadowed light's depth map as the peer drew it (glGetTexImage): faces (1, or 6 in GL's
// cube order +X −X +Y −Y +Z −Z) of size² floats, rows from the BOTTOM (GL's t = 0 first; Tessera's
// ShadowMap keeps row 0 at the top). Window depth for a directional light, distance / far plane
// for spot and point lights; 1 where nothing was drawn.
struct ShadowMapReadback {
    int light = 0;  // index into scene.lights
    int size = 0, faces = 1;
    int depth_bits = 0;           // GL_TEXTURE_DEPTH_SIZE of the texture the driver made
    bool float_depth = false;     // GL_TEXTURE_DEPTH_TYPE is GL_FLOAT (else normalized integers)
    std::vector<float> depth;  // [face][row from the bottom][column]
};

// One level of a cube map read back: 6 faces (+X, −X, +Y, −Y, +Z, −Z) of size² RGB floats,
// rows t = 0 first (GL's texel addressing, as Tessera's CubeMap::texel(level, face, x, y)).
struct CubeLevelReadback {
    int size = 0;
    std::vector<float> rgb;  // [face][t][s][channel]
};
// The maps the peer computed for a scene's environment (glGetTexImage, as floats).
struct IblMapsReadback {
    std::vector<CubeLevelReadback> environment;  // envCubemap, every level
    CubeLevelReadback irradiance;                // irradianceMap
    std::vector<CubeLevelReadback> prefiltered;  // prefilterMap levels 0..4
    int brdf_size = 0;
    std::vector<float> brdf_rg;                  // brdfLUTTexture, [y][x][A, B], row y = roughness
    double precompute_ms = 0;                    // the capture passes, to glFinish
};

// Owns one EGL display + GL 3.3 core context (current on the constructing thread;
// use the object from that thread only) and an offscreen framebuffer of RGBA8
// colour + 24-bit depth at the last scene's size. A scene with msaa = 4 is drawn into
// a 4-sample framebuffer of the same formats (glRenderbufferStorageMultisample) and
// resolved by glBlitFramebuffer into the single-sample one, which is read back; with
// msaa = 1 nothing multisampled is made or used. Meshes and the shader program are
// rebuilt when the scene (its meshes, or its light count) changes.
// A scene with an environment: its maps are made by the chapter's capture passes on first
// use and kept while the image file and the IblOptions stay the same; a frame draws the
// objects with the IBL pbr.fs and then, with environment.background, the chapter's skybox.
// Directional and spot lights follow docs/reference/pbr_lighting.md ("Other light types"); a
// light with shadows first draws its depth map each frame (gl_shadows.hpp: the shadow
// chapters' depth passes with Tessera's light cameras) and scales its term of Lo by the
// chapters' 1 − shadow.
// Every EGL/GL failure throws std::runtime_error naming what failed, including a
// driver whose GL_MAX_SAMPLES is below 4 when a scene asks for 4× MSAA.
class GlReferenceRenderer {
public:
    GlReferenceRenderer();
    ~GlReferenceRenderer();
    GlReferenceRenderer(const GlReferenceRenderer&) = delete;
    GlReferenceRenderer& operator=(const GlReferenceRenderer&) = delete;

    // One frame (multisampled and resolved if scene.msaa is 4), read back: `display` is
    // RGB8, row 0 at the top (as Tessera's);
    // `radiance` stays empty (the reference shader only writes the tonemapped colour).
    RenderedImage render(const Scene& scene, WindowOrigin origin = WindowOrigin::bottom_left);

    // The object covering each pixel, row 0 at the top: 0 for background, i + 1 for
    // scene.objects[i]. Same geometry and depth test as render(), but always one sample
    // per pixel (ids cannot be averaged), at the pixel centre; for finding silhouettes.
    std::vector<std::uint32_t> render_object_ids(const Scene& scene);

    // Renders `warmup` untimed frames, then `frames` timed ones, and returns each timed
    // frame's wall-clock milliseconds. A frame is clear + every draw (+ with msaa = 4 the
    // resolve blit, as Tessera's frame includes its resolve) + glFinish; the readback is
    // not included (Tessera's frame time does not include writing a file either).
    std::vector<double> time_frames(const Scene& scene, int frames, int warmup);

    // GL_SAMPLE_POSITION of each sample of the 4× multisampled framebuffer, as GL reports
    // it: in pixels from the pixel's bottom-left corner, x right, y UP (window space). In
    // a top-down image the sample sits at (x, 1 - y) from the pixel's top-left corner.
    std::vector<glm::vec2> msaa_sample_positions();

    // Options for the IBL maps of later renders (the maps are computed again when they change).
    void set_ibl_options(const IblOptions& options);
    // The IBL maps for scene.environment (computed now unless the last scene's image and
    // options were the same); throws if the scene has no environment.
    IblMapsReadback read_ibl_maps(const Scene& scene);

    // Options for the shadow maps of later renders.
    void set_shadow_options(const ShadowOptions& options);
    // The shadow maps of scene's shadowed lights, drawn now by the chapters' depth passes.
    std::vector<ShadowMapReadback> read_shadow_maps(const Scene& scene);

    // GLSL `expression` (of a float x, e.g. "asin(x)") evaluated by the driver's fragment
    // shader for each of `inputs`: how far its built-ins are from exact (explains differences).
    std::vector<float> evaluate_glsl(const std::string& expression, const std::vector<float>& inputs);

    // GL_RENDERER and GL_VERSION, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)", "3.3 (Core Profile) Mesa 22.3.6".
    std::string renderer_name() const;
    std::string version() const;

private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace tessera::gl_reference
