// LearnOpenGL's shadow chapters on llvmpipe: "Shadow Mapping" (src/5.advanced_lighting/
// 3.1.3.shadow_mapping: a depth-only pass into a 2D depth texture, ShadowCalculation with 3×3
// PCF and the slope-scaled bias) and "Point Shadows" (3.2.2.point_shadows_soft: one pass through
// the chapter's geometry shader into a cube depth texture of length(FragPos − lightPos) /
// far_plane, the 20 gridSamplingDisk samples). The GLSL is the chapters', term for term, with
// what docs/reference/pbr_lighting.md ("Shadows") and docs/scene-format.md say Tessera does
// where the chapters leave it to their demo: spot lights take the point chapter's distance
// depth shader into a 2D map filtered as 3.1.3's; a directional light's lightDir is
// −direction; the filter radius generalises the 3×3 PCF to (2r + 1)² and scales the disk.
//
// The light cameras, near and far planes and the disk's far plane — what the chapters' demos set
// by hand — are Tessera's: taken from shade::plan_shadow_map (src/shade/shadow_maps.hpp), the
// internal function Renderer uses, so that a comparison measures the depth passes and the
// shadow factor, not two fits. Depth textures are GL_DEPTH_COMPONENT32F (Tessera keeps float
// depth); ShadowOptions::chapter_depth_format gives the chapters' unsized GL_DEPTH_COMPONENT.
// Internal to tools/gl_reference.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl_common.hpp"
#include "gl_renderer.hpp"
#include "tessera/scene.hpp"

namespace tessera::gl_reference {

// The first texture unit of the shadow maps (the IBL maps take 0..2).
inline constexpr int kFirstShadowTextureUnit = 3;

// Spliced into the PBR fragment shader before main: the chapters' ShadowCalculation functions,
// a sampler and a matrix per shadowed light, and lightVisibility(i), 1 − shadow of light i (1
// for a light without shadows). Depends only on which lights of `scene` cast shadows and how.
std::string shadow_fragment_declarations(const Scene& scene);

class GlShadows {
public:
    GlShadows() = default;
    ~GlShadows();  // the context must still be current
    GlShadows(const GlShadows&) = delete;
    GlShadows& operator=(const GlShadows&) = delete;

    // Every shadowed light's map for `scene`: Tessera's light cameras, every caster (every
    // object but blended ones) drawn by draw_object(i) with the chapters' depth shaders bound
    // (this sets their `model` uniform first). Leaves framebuffer 0 bound, the viewport changed.
    void render_maps(const Scene& scene, const ShadowOptions& options,
                     const std::function<void(std::size_t object)>& draw_object);

    // Binds the maps to units kFirstShadowTextureUnit.. and sets the shadow uniforms of
    // `program` (in use; built with shadow_fragment_declarations(scene)).
    void bind_for_shading(GLuint program) const;

    // The maps of the last render_maps, read back (glGetTexImage as floats).
    std::vector<ShadowMapReadback> read_maps() const;

private:
    struct Map {
        GLenum target = 0;  // GL_TEXTURE_2D or GL_TEXTURE_CUBE_MAP
        GLuint texture = 0;
        int light = 0, size = 0, faces = 1;
        std::vector<glm::mat4> view_projection;
        glm::vec3 position{0.0f}, to_light{0.0f};
        float far_plane = 1.0f, disk_far_plane = 1.0f;
        int filter_radius = 1;
        bool distance = false;  // spot: distance / far_plane in a 2D map
    };
    void build_programs();
    void free_maps();

    GLuint fbo_ = 0;
    GLuint depth_program_ = 0;     // 3.1.3's shadow_mapping_depth: lightSpaceMatrix · model
    GLuint distance_program_ = 0;  // 3.2.2's depth fs (distance / far_plane), one view: spot
    GLuint cube_program_ = 0;      // 3.2.2's depth vs + gs + fs: six faces in one pass
    std::vector<Map> maps_;
};

}  // namespace tessera::gl_reference
