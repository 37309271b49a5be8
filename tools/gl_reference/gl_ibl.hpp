// LearnOpenGL's image-based lighting ("Diffuse irradiance", "Specular IBL",
// src/6.pbr/2.2.1.ibl_specular) on llvmpipe: the chapter's capture passes make the
// environment cube, irradiance, pre-filtered and BRDF maps on the GPU side, and its pbr.fs
// ambient and background.fs use them. The GLSL is the one docs/reference/ibl_lighting.md
// specifies (the chapter's, term for term); it departs from the chapter only where that page
// says Tessera does, and IblOptions can undo each departure. Internal to tools/gl_reference.
#pragma once

#include <string>

#include <glm/mat4x4.hpp>

#include "gl_common.hpp"
#include "gl_renderer.hpp"

namespace tessera::gl_reference {

// Spliced into the PBR fragment shader when the scene has an environment: the chapter's
// samplers and fresnelSchlickRoughness (kIblFragmentDeclarations, before main), and its
// ambient term, which sets `color` (kIblAmbient, after the light loop; needs N, V, F0, Lo).
extern const char* const kIblFragmentDeclarations;
extern const char* const kIblAmbient;

class GlIbl {
public:
    GlIbl() = default;
    ~GlIbl();  // the context must still be current
    GlIbl(const GlIbl&) = delete;
    GlIbl& operator=(const GlIbl&) = delete;

    // The maps of the equirectangular image at `image_path`, computed by the capture passes
    // unless the last call had the same path and options. Leaves framebuffer 0 bound.
    void prepare(const std::string& image_path, const IblOptions& options);

    // Binds irradianceMap, prefilterMap and brdfLUT to texture units 0, 1, 2 and sets the IBL
    // uniforms of `program` (which must be in use): the scene's intensity and rotation about +Y.
    void bind_for_shading(GLuint program, float intensity, float cos_rotation, float sin_rotation) const;

    // background.vs / background.fs into the bound framebuffer, after the objects: the unit cube
    // at depth 1 (gl_Position = clip.xyww) with GL_LEQUAL, as the chapter draws its skybox.
    void draw_background(const glm::mat4& view, const glm::mat4& projection, float intensity, float cos_rotation,
                         float sin_rotation);

    IblMapsReadback read_maps() const;

private:
    void build_programs();
    void free_maps();

    std::string image_path_;
    IblOptions options_;
    bool ready_ = false;
    double precompute_ms_ = 0;

    GLuint capture_fbo_ = 0, cube_vao_ = 0, cube_vbo_ = 0, quad_vao_ = 0, quad_vbo_ = 0;
    GLuint equirect_program_ = 0, irradiance_program_ = 0, prefilter_program_ = 0, brdf_program_ = 0,
           background_program_ = 0;
    bool irradiance_program_from_derivatives_ = false;
    GLuint hdr_texture_ = 0, env_cubemap_ = 0, irradiance_map_ = 0, prefilter_map_ = 0, brdf_lut_ = 0;
};

}  // namespace tessera::gl_reference
