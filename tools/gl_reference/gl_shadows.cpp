#include "gl_shadows.hpp"

#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "shade/shadow_maps.hpp"

namespace tessera::gl_reference {

namespace {

// 3.1.3's shadow_mapping_depth.vs (its fragment shader is empty). The product is taken
// world position first, as Tessera's vertex stage does (model, then the light's matrix).
constexpr const char* kDepthVertexShader = R"(#version 330 core
layout (location = 0) in vec3 aPos;
uniform mat4 lightSpaceMatrix;
uniform mat4 model;
void main() {
    gl_Position = lightSpaceMatrix * (model * vec4(aPos, 1.0));
}
)";
constexpr const char* kDepthFragmentShader = R"(#version 330 core
void main() {}
)";

// 3.2.2's point_shadows_depth.fs: the distance to the light over far_plane as the depth.
constexpr const char* kDistanceFragmentShader = R"(#version 330 core
in vec4 FragPos;
uniform vec3 lightPos;
uniform float far_plane;
void main() {
    float lightDistance = length(FragPos.xyz - lightPos);
    // map to [0;1] range by dividing by far_plane
    lightDistance = lightDistance / far_plane;
    // write this as modified depth
    gl_FragDepth = lightDistance;
}
)";
// For a spot's single view: 3.2.2's depth vertex and geometry shaders folded into one.
constexpr const char* kDistanceVertexShader = R"(#version 330 core
layout (location = 0) in vec3 aPos;
uniform mat4 lightSpaceMatrix;
uniform mat4 model;
out vec4 FragPos;
void main() {
    FragPos = model * vec4(aPos, 1.0);
    gl_Position = lightSpaceMatrix * FragPos;
}
)";
// 3.2.2's point_shadows_depth.vs and .gs: world positions out of the vertex shader, each
// triangle emitted once per cube face (gl_Layer) through shadowMatrices[face].
constexpr const char* kCubeVertexShader = R"(#version 330 core
layout (location = 0) in vec3 aPos;
uniform mat4 model;
void main() {
    gl_Position = model * vec4(aPos, 1.0);
}
)";
constexpr const char* kCubeGeometryShader = R"(#version 330 core
layout (triangles) in;
layout (triangle_strip, max_vertices=18) out;
uniform mat4 shadowMatrices[6];
out vec4 FragPos; // FragPos from GS (output per emitvertex)
void main() {
    for(int face = 0; face < 6; ++face) {
        gl_Layer = face; // built-in variable that specifies to which face we render.
        for(int i = 0; i < 3; ++i) { // for each triangle's vertices
            FragPos = gl_in[i].gl_Position;
            gl_Position = shadowMatrices[face] * FragPos;
            EmitVertex();
        }
        EndPrimitive();
    }
}
)";

// The chapters' ShadowCalculation functions. ShadowCalculation2D is 3.1.3's, with Tessera's
// generalisations (docs/reference/pbr_lighting.md, Shadows): the filter radius, a spot's
// currentDepth as distance / far_plane (and lit behind the spot, where w <= 0), lightDir
// passed in (−direction for a directional light). ShadowCalculationCube is 3.2.2's, the disk
// scaled by the filter radius and its far_plane the light's reach; radius 0 is the chapter's
// single-sample variant.
constexpr const char* kShadowFunctions = R"(
float ShadowCalculation2D(sampler2D shadowMap, mat4 lightSpaceMatrix, vec3 fragPos, vec3 normalIn,
                          vec3 lightDir, bool distanceMap, vec3 lightPos, float far_plane, int radius) {
    vec4 fragPosLightSpace = lightSpaceMatrix * vec4(fragPos, 1.0);
    if (distanceMap && !(fragPosLightSpace.w > 0.0)) return 0.0;
    // perform perspective divide
    vec3 projCoords = fragPosLightSpace.xyz / fragPosLightSpace.w;
    // transform to [0,1] range
    projCoords = projCoords * 0.5 + 0.5;
    float currentDepth = distanceMap ? length(fragPos - lightPos) / far_plane : projCoords.z;
    vec3 normal = normalize(normalIn);
    float bias = max(0.05 * (1.0 - dot(normal, lightDir)), 0.005);
    float shadow = 0.0;
    vec2 texelSize = 1.0 / textureSize(shadowMap, 0);
    for(int x = -radius; x <= radius; ++x) {
        for(int y = -radius; y <= radius; ++y) {
            float pcfDepth = texture(shadowMap, projCoords.xy + vec2(x, y) * texelSize).r;
            shadow += currentDepth - bias > pcfDepth ? 1.0 : 0.0;
        }
    }
    shadow /= float((2 * radius + 1) * (2 * radius + 1));
    // keep the shadow at 0.0 when outside the far_plane region of the light's frustum.
    if(projCoords.z > 1.0)
        shadow = 0.0;
    return shadow;
}
vec3 gridSamplingDisk[20] = vec3[]
(
   vec3(1, 1,  1), vec3( 1, -1,  1), vec3(-1, -1,  1), vec3(-1, 1,  1),
   vec3(1, 1, -1), vec3( 1, -1, -1), vec3(-1, -1, -1), vec3(-1, 1, -1),
   vec3(1, 1,  0), vec3( 1, -1,  0), vec3(-1, -1,  0), vec3(-1, 1,  0),
   vec3(1, 0,  1), vec3(-1,  0,  1), vec3( 1,  0, -1), vec3(-1, 0, -1),
   vec3(0, 1,  1), vec3( 0, -1,  1), vec3( 0, -1, -1), vec3( 0, 1, -1)
);
float ShadowCalculationCube(samplerCube depthMap, vec3 fragPos, vec3 lightPos, vec3 viewPos, float far_plane,
                            float disk_far_plane, int radius) {
    vec3 fragToLight = fragPos - lightPos;
    float currentDepth = length(fragToLight);
    float bias = 0.15;
    if (radius == 0) {
        float closestDepth = texture(depthMap, fragToLight).r * far_plane;
        return currentDepth - bias > closestDepth ? 1.0 : 0.0;
    }
    float shadow = 0.0;
    int samples = 20;
    float viewDistance = length(viewPos - fragPos);
    float diskRadius = (1.0 + (viewDistance / disk_far_plane)) / 25.0 * float(radius);
    for(int i = 0; i < samples; ++i) {
        float closestDepth = texture(depthMap, fragToLight + gridSamplingDisk[i] * diskRadius).r;
        closestDepth *= far_plane;   // undo mapping [0;1]
        if(currentDepth - bias > closestDepth)
            shadow += 1.0;
    }
    shadow /= float(samples);
    return shadow;
}
)";

std::string slot_name(const char* what, std::size_t slot) { return std::string(what) + std::to_string(slot); }

}  // namespace

std::string shadow_fragment_declarations(const Scene& scene) {
    std::string uniforms, calls;
    std::size_t slot = 0;
    for (std::size_t l = 0; l < scene.lights.size(); ++l) {
        const Light& light = scene.lights[l];
        if (!light.shadows) continue;
        const std::string s = std::to_string(slot);
        const std::string i = std::to_string(l);
        if (light.type == LightType::point) {
            uniforms += "uniform samplerCube shadowMap" + s + ";\n";
            calls += "    if (i == " + i + ") return 1.0 - ShadowCalculationCube(shadowMap" + s + ", WorldPos, shadowLightPos" +
                     s + ", camPos, shadowFarPlane" + s + ", shadowDiskFarPlane" + s + ", shadowFilterRadius" + s + ");\n";
        } else {
            uniforms += "uniform sampler2D shadowMap" + s + ";\nuniform mat4 lightSpaceMatrix" + s + ";\n";
            const std::string light_dir = light.type == LightType::directional
                                              ? "shadowToLight" + s
                                              : "normalize(shadowLightPos" + s + " - WorldPos)";
            calls += "    if (i == " + i + ") return 1.0 - ShadowCalculation2D(shadowMap" + s + ", lightSpaceMatrix" + s +
                     ", WorldPos, Normal, " + light_dir + ", " + (light.type == LightType::spot ? "true" : "false") +
                     ", shadowLightPos" + s + ", shadowFarPlane" + s + ", shadowFilterRadius" + s + ");\n";
        }
        uniforms += "uniform vec3 shadowLightPos" + s + "; uniform vec3 shadowToLight" + s + ";\nuniform float shadowFarPlane" +
                    s + "; uniform float shadowDiskFarPlane" + s + "; uniform int shadowFilterRadius" + s + ";\n";
        ++slot;
    }
    if (slot == 0) return "float lightVisibility(int i) { return 1.0; }\n";
    return kShadowFunctions + uniforms + "float lightVisibility(int i) {\n" + calls + "    return 1.0;\n}\n";
}

GlShadows::~GlShadows() {
    free_maps();
    if (fbo_) glDeleteFramebuffers(1, &fbo_);
    for (const GLuint p : {depth_program_, distance_program_, cube_program_})
        if (p) glDeleteProgram(p);
}

void GlShadows::free_maps() {
    for (const Map& m : maps_) glDeleteTextures(1, &m.texture);
    maps_.clear();
}

void GlShadows::build_programs() {
    if (depth_program_) return;
    depth_program_ = link_program(kDepthVertexShader, kDepthFragmentShader, "shadow depth shader");
    distance_program_ = link_program(kDistanceVertexShader, kDistanceFragmentShader, "spot shadow distance shader");
    cube_program_ = link_program(kCubeVertexShader, kCubeGeometryShader, kDistanceFragmentShader, "point shadow cube shader");
    glGenFramebuffers(1, &fbo_);
    check_gl("building the shadow programs");
}

void GlShadows::render_maps(const Scene& scene, const ShadowOptions& options,
                            const std::function<void(std::size_t object)>& draw_object) {
    free_maps();
    bool any = false;
    for (const Light& light : scene.lights) any = any || light.shadows;
    if (!any) return;
    build_programs();
    GLint max_units = 0;
    glGetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &max_units);
    const shade::SceneBounds bounds = shade::scene_bounds(scene);
    const GLenum internal_format = options.chapter_depth_format ? GL_DEPTH_COMPONENT : GL_DEPTH_COMPONENT32F;
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glDrawBuffer(GL_NONE);
    glReadBuffer(GL_NONE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);  // the depth pass culls nothing (as Tessera's)
    for (std::size_t l = 0; l < scene.lights.size(); ++l) {
        const Light& light = scene.lights[l];
        if (!light.shadows) continue;
        if (kFirstShadowTextureUnit + int(maps_.size()) >= max_units)
            fail("more shadowed lights than GL_MAX_TEXTURE_IMAGE_UNITS leaves units for");
        shade::ShadowMap plan;
        shade::plan_shadow_map(scene, bounds, light, plan);  // Tessera's light cameras and planes
        Map& m = maps_.emplace_back();
        m.light = int(l), m.size = plan.size, m.faces = plan.faces;
        m.view_projection.assign(plan.view_projection.begin(), plan.view_projection.begin() + plan.faces);
        m.position = plan.position, m.to_light = plan.to_light;
        m.far_plane = plan.far_plane, m.disk_far_plane = plan.disk_far_plane;
        m.filter_radius = plan.filter_radius;
        m.distance = plan.kind == shade::ShadowMapKind::planar_distance;
        m.target = plan.kind == shade::ShadowMapKind::cube_distance ? GL_TEXTURE_CUBE_MAP : GL_TEXTURE_2D;
        glGenTextures(1, &m.texture);
        glBindTexture(m.target, m.texture);
        if (m.target == GL_TEXTURE_2D) {
            // 3.1.3's depthMap: nearest, clamped to a border of depth 1.
            glTexImage2D(GL_TEXTURE_2D, 0, GLint(internal_format), m.size, m.size, 0, GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
            const float border[] = {1.0f, 1.0f, 1.0f, 1.0f};
            glTexParameterfv(GL_TEXTURE_2D, GL_TEXTURE_BORDER_COLOR, border);
            glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, m.texture, 0);
        } else {
            // 3.2.2's depthCubemap: six faces, nearest, clamped to the edge; attached layered.
            for (int f = 0; f < 6; ++f)
                glTexImage2D(GLenum(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f), 0, GLint(internal_format), m.size, m.size, 0,
                             GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
            glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
            glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
            glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
            glFramebufferTexture(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, m.texture, 0);
        }
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) fail("shadow map framebuffer incomplete");
        glViewport(0, 0, m.size, m.size);
        glClear(GL_DEPTH_BUFFER_BIT);
        const GLuint program = m.target == GL_TEXTURE_CUBE_MAP ? cube_program_ : m.distance ? distance_program_ : depth_program_;
        glUseProgram(program);
        if (m.target == GL_TEXTURE_CUBE_MAP)
            glUniformMatrix4fv(glGetUniformLocation(program, "shadowMatrices"), 6, GL_FALSE,
                               glm::value_ptr(m.view_projection[0]));
        else
            glUniformMatrix4fv(glGetUniformLocation(program, "lightSpaceMatrix"), 1, GL_FALSE,
                               glm::value_ptr(m.view_projection[0]));
        glUniform3fv(glGetUniformLocation(program, "lightPos"), 1, glm::value_ptr(m.position));
        glUniform1f(glGetUniformLocation(program, "far_plane"), m.far_plane);
        const GLint model = glGetUniformLocation(program, "model");
        for (std::size_t o = 0; o < scene.objects.size(); ++o) {
            const Object& object = scene.objects[o];
            if (!shade::casts_shadow(scene, object)) continue;
            glUniformMatrix4fv(model, 1, GL_FALSE, glm::value_ptr(object.model));
            draw_object(o);
        }
        check_gl("rendering a shadow map");
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void GlShadows::bind_for_shading(GLuint program) const {
    for (std::size_t s = 0; s < maps_.size(); ++s) {
        const Map& m = maps_[s];
        glActiveTexture(GLenum(GL_TEXTURE0 + kFirstShadowTextureUnit + int(s)));
        glBindTexture(m.target, m.texture);
        const auto location = [&](const char* name) { return glGetUniformLocation(program, slot_name(name, s).c_str()); };
        glUniform1i(location("shadowMap"), kFirstShadowTextureUnit + int(s));
        if (m.target == GL_TEXTURE_2D)
            glUniformMatrix4fv(location("lightSpaceMatrix"), 1, GL_FALSE, glm::value_ptr(m.view_projection[0]));
        glUniform3fv(location("shadowLightPos"), 1, glm::value_ptr(m.position));
        glUniform3fv(location("shadowToLight"), 1, glm::value_ptr(m.to_light));
        glUniform1f(location("shadowFarPlane"), m.far_plane);
        glUniform1f(location("shadowDiskFarPlane"), m.disk_far_plane);
        glUniform1i(location("shadowFilterRadius"), m.filter_radius);
    }
    glActiveTexture(GL_TEXTURE0);
    check_gl("binding the shadow maps");
}

std::vector<ShadowMapReadback> GlShadows::read_maps() const {
    std::vector<ShadowMapReadback> out;
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    for (const Map& m : maps_) {
        ShadowMapReadback& r = out.emplace_back();
        r.light = m.light, r.size = m.size, r.faces = m.faces;
        r.depth.resize(std::size_t(m.faces) * std::size_t(m.size) * std::size_t(m.size));
        glBindTexture(m.target, m.texture);
        const GLenum level_target = m.target == GL_TEXTURE_2D ? GL_TEXTURE_2D : GL_TEXTURE_CUBE_MAP_POSITIVE_X;
        GLint bits = 0, type = 0;
        glGetTexLevelParameteriv(level_target, 0, GL_TEXTURE_DEPTH_SIZE, &bits);
        glGetTexLevelParameteriv(level_target, 0, GL_TEXTURE_DEPTH_TYPE, &type);
        r.depth_bits = bits, r.float_depth = type == GL_FLOAT;
        for (int f = 0; f < m.faces; ++f)
            glGetTexImage(m.target == GL_TEXTURE_2D ? GL_TEXTURE_2D : GLenum(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f), 0,
                          GL_DEPTH_COMPONENT, GL_FLOAT,
                          r.depth.data() + std::size_t(f) * std::size_t(m.size) * std::size_t(m.size));
    }
    check_gl("reading the shadow maps back");
    return out;
}

}  // namespace tessera::gl_reference
