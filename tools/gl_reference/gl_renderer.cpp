#include "gl_renderer.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "gl_common.hpp"
#include "gl_ibl.hpp"
#include "gl_pbr_shaders.hpp"
#include "gl_shadows.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace tessera::gl_reference {

namespace {

// The only multisample count Tessera has (src/raster/msaa/msaa.hpp: kMsaaSamples).
constexpr int kMsaaSamples = 4;

std::string egl_error_name(EGLint code) {
    switch (code) {
        case EGL_SUCCESS: return "EGL_SUCCESS";
        case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
        case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
        case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
        case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
        case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
        case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
        case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
        case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
        case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
        default: return "EGL error 0x" + [code] {
            char buf[16];
            std::snprintf(buf, sizeof buf, "%x", unsigned(code));
            return std::string(buf);
        }();
    }
}

[[noreturn]] void fail_egl(const std::string& what) { fail(what + " (" + egl_error_name(eglGetError()) + ")"); }

bool has_extension(const char* list, const char* name) {
    if (list == nullptr) return false;
    const std::size_t n = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

// Uniform locations; -1 where the compiler dropped an unused uniform (glUniform ignores -1).
struct Uniforms {
    GLint projection = -1, view = -1, model = -1, normal_matrix = -1;
    GLint albedo = -1, metallic = -1, roughness = -1, ao = -1, cam_pos = -1;
    GLint light_positions = -1, light_colors = -1, object_id = -1;
    GLint light_types = -1, light_directions = -1, light_cos_inner = -1, light_cos_outer = -1, light_ranges = -1;

    explicit Uniforms(GLuint program) {
        projection = glGetUniformLocation(program, "projection");
        view = glGetUniformLocation(program, "view");
        model = glGetUniformLocation(program, "model");
        normal_matrix = glGetUniformLocation(program, "normalMatrix");
        albedo = glGetUniformLocation(program, "albedo");
        metallic = glGetUniformLocation(program, "metallic");
        roughness = glGetUniformLocation(program, "roughness");
        ao = glGetUniformLocation(program, "ao");
        cam_pos = glGetUniformLocation(program, "camPos");
        light_positions = glGetUniformLocation(program, "lightPositions");
        light_colors = glGetUniformLocation(program, "lightColors");
        object_id = glGetUniformLocation(program, "objectId");
        light_types = glGetUniformLocation(program, "lightTypes");
        light_directions = glGetUniformLocation(program, "lightDirections");
        light_cos_inner = glGetUniformLocation(program, "lightCosInner");
        light_cos_outer = glGetUniformLocation(program, "lightCosOuter");
        light_ranges = glGetUniformLocation(program, "lightRanges");
    }
    Uniforms() = default;
};

struct GpuMesh {
    GLuint vao = 0;
    GLuint buffers[4] = {0, 0, 0, 0};  // positions, uvs, normals, indices
    GLsizei index_count = 0;
};

}  // namespace

struct GlReferenceRenderer::State {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;

    // Single-sample target: drawn into without MSAA, the resolve target with it; read back.
    GLuint fbo = 0, color_rb = 0, depth_rb = 0;
    int fb_width = 0, fb_height = 0;
    // 4× multisampled target (RGBA8 + DEPTH24), created on the first scene with msaa = 4.
    GLuint msaa_fbo = 0, msaa_color_rb = 0, msaa_depth_rb = 0;
    int msaa_width = 0, msaa_height = 0;

    GLuint pbr_program = 0;
    int pbr_light_count = -1;  // the LIGHT_COUNT pbr_program was built for
    bool pbr_environment = false;  // and whether with the IBL ambient
    bool pbr_light_types = false;  // with LIGHT_TYPES
    bool pbr_ranges = false;       // with RANGES
    std::string pbr_shadows;       // the SHADOW_DECLARATIONS it was built with
    Uniforms pbr_uniforms;
    GLuint id_program = 0;
    Uniforms id_uniforms;

    std::vector<GpuMesh> meshes;

    std::unique_ptr<GlIbl> ibl;  // made for the first scene with an environment
    IblOptions ibl_options;
    std::unique_ptr<GlShadows> shadows;  // made for the first scene with a shadowed light
    ShadowOptions shadow_options;

    ~State() {
        if (context != EGL_NO_CONTEXT) {
            ibl.reset();
            shadows.reset();
            free_meshes();
            if (pbr_program) glDeleteProgram(pbr_program);
            if (id_program) glDeleteProgram(id_program);
            if (fbo) glDeleteFramebuffers(1, &fbo);
            if (color_rb) glDeleteRenderbuffers(1, &color_rb);
            if (depth_rb) glDeleteRenderbuffers(1, &depth_rb);
            if (msaa_fbo) glDeleteFramebuffers(1, &msaa_fbo);
            if (msaa_color_rb) glDeleteRenderbuffers(1, &msaa_color_rb);
            if (msaa_depth_rb) glDeleteRenderbuffers(1, &msaa_depth_rb);
            eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            eglDestroyContext(display, context);
        }
        if (display != EGL_NO_DISPLAY) eglTerminate(display);
    }

    void create_context() {
        // Mesa's surfaceless platform picks a GPU render node when one exists; the peer
        // is meant to be llvmpipe, so ask for software unless the caller decided otherwise.
        setenv("LIBGL_ALWAYS_SOFTWARE", "1", 0);

        const char* client_extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
        if (!has_extension(client_extensions, "EGL_MESA_platform_surfaceless"))
            fail("no EGL device/driver: EGL_MESA_platform_surfaceless is missing (install libegl-mesa0 "
                 "libgl1-mesa-dri)");
        display = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (display == EGL_NO_DISPLAY) fail_egl("no EGL device/driver: install libegl-mesa0 libgl1-mesa-dri");
        EGLint major = 0, minor = 0;
        if (!eglInitialize(display, &major, &minor)) {
            display = EGL_NO_DISPLAY;  // nothing to terminate
            fail_egl("no EGL device/driver: eglInitialize failed on the surfaceless platform; install "
                     "libegl-mesa0 libgl1-mesa-dri");
        }
        const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
        if (!has_extension(extensions, "EGL_KHR_surfaceless_context"))
            fail("EGL display lacks EGL_KHR_surfaceless_context");
        if (!eglBindAPI(EGL_OPENGL_API)) fail_egl("eglBindAPI(EGL_OPENGL_API) failed");

        // Rendering goes to our own FBO: a config only matters if the display needs one.
        EGLConfig config = EGL_NO_CONFIG_KHR;
        if (!has_extension(extensions, "EGL_KHR_no_config_context")) {
            const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT,
                                             EGL_NONE};
            EGLint count = 0;
            if (!eglChooseConfig(display, config_attribs, &config, 1, &count) || count < 1)
                fail_egl("no EGL config renders with desktop OpenGL");
        }
        const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                          3,
                                          EGL_CONTEXT_MINOR_VERSION,
                                          3,
                                          EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                          EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                          EGL_NONE};
        context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attribs);
        if (context == EGL_NO_CONTEXT) fail_egl("cannot create an OpenGL 3.3 core context");
        if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
            fail_egl("eglMakeCurrent without a surface failed");
        if (glGetString(GL_VERSION) == nullptr) fail("the context is current but glGetString(GL_VERSION) is null");

        id_program = link_program(kVertexShader, kObjectIdFragmentShader, "object-id fragment shader");
        id_uniforms = Uniforms(id_program);
        check_gl("creating the context");
    }

    void ensure_framebuffer(int width, int height) {
        if (fbo != 0 && fb_width == width && fb_height == height) return;
        GLint max_size = 0;
        glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
        if (width > max_size || height > max_size)
            fail(std::to_string(width) + "x" + std::to_string(height) + " exceeds GL_MAX_RENDERBUFFER_SIZE " +
                 std::to_string(max_size));
        if (fbo == 0) {
            glGenFramebuffers(1, &fbo);
            glGenRenderbuffers(1, &color_rb);
            glGenRenderbuffers(1, &depth_rb);
        }
        glBindRenderbuffer(GL_RENDERBUFFER, color_rb);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
        glBindRenderbuffer(GL_RENDERBUFFER, depth_rb);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_rb);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_rb);
        check_framebuffer_complete("framebuffer");
        check_gl("creating the framebuffer");
        fb_width = width;
        fb_height = height;
    }

    // The 4× multisampled framebuffer beside the single-sample one (which stays the
    // resolve target and what is read back).
    void ensure_msaa_framebuffer(int width, int height) {
        if (msaa_fbo != 0 && msaa_width == width && msaa_height == height) return;
        GLint max_samples = 0;
        glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
        if (max_samples < kMsaaSamples)
            fail("4x MSAA unsupported: GL_MAX_SAMPLES is " + std::to_string(max_samples));
        if (msaa_fbo == 0) {
            glGenFramebuffers(1, &msaa_fbo);
            glGenRenderbuffers(1, &msaa_color_rb);
            glGenRenderbuffers(1, &msaa_depth_rb);
        }
        GLint color_samples = 0, depth_samples = 0;
        glBindRenderbuffer(GL_RENDERBUFFER, msaa_color_rb);
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, kMsaaSamples, GL_RGBA8, width, height);
        glGetRenderbufferParameteriv(GL_RENDERBUFFER, GL_RENDERBUFFER_SAMPLES, &color_samples);
        glBindRenderbuffer(GL_RENDERBUFFER, msaa_depth_rb);
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, kMsaaSamples, GL_DEPTH_COMPONENT24, width, height);
        glGetRenderbufferParameteriv(GL_RENDERBUFFER, GL_RENDERBUFFER_SAMPLES, &depth_samples);
        check_gl("allocating the 4x multisampled renderbuffers");
        // GL may round the count up; anything but 4 would compare against a different resolve.
        if (color_samples != kMsaaSamples || depth_samples != kMsaaSamples)
            fail("asked for 4x MSAA renderbuffers, got " + std::to_string(color_samples) + " colour / " +
                 std::to_string(depth_samples) + " depth samples");
        glBindFramebuffer(GL_FRAMEBUFFER, msaa_fbo);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, msaa_color_rb);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, msaa_depth_rb);
        check_framebuffer_complete("4x multisampled framebuffer");
        check_gl("creating the 4x multisampled framebuffer");
        msaa_width = width;
        msaa_height = height;
    }

    static void check_framebuffer_complete(const char* which) {
        const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE) {
            char buf[16];
            std::snprintf(buf, sizeof buf, "0x%04x", unsigned(status));
            fail(std::string(which) + " incomplete: " + buf);
        }
    }

    void ensure_pbr_program(const Scene& scene, bool environment) {
        const int light_count = int(scene.lights.size());
        bool light_types = false, any_shadows = false, ranges = false;
        for (const Light& light : scene.lights) {
            light_types = light_types || light.type != LightType::point;
            ranges = ranges || (light.type != LightType::directional && light.range > 0.0f);
            any_shadows = any_shadows || light.shadows;
        }
        const std::string shadow_declarations = any_shadows ? shadow_fragment_declarations(scene) : "";
        if (pbr_program != 0 && pbr_light_count == light_count && pbr_environment == environment &&
            pbr_light_types == light_types && pbr_ranges == ranges && pbr_shadows == shadow_declarations)
            return;
        if (pbr_program) glDeleteProgram(pbr_program);
        pbr_program = 0;
        std::string body = kFragmentShaderBody;
        const auto splice = [&body](const std::string& name, const char* text) {
            body.replace(body.find(name), name.size(), text);
        };
        splice("IBL_DECLARATIONS", environment ? kIblFragmentDeclarations : "");
        splice("IBL_AMBIENT", environment ? kIblAmbient : "");
        splice("SHADOW_DECLARATIONS", shadow_declarations.c_str());
        const std::string fragment = "#version 330 core\n#define LIGHT_COUNT " + std::to_string(light_count) +
                                     "\n#define LIGHT_TYPES " + (light_types ? "1" : "0") +
                                     "\n#define RANGES " + (ranges ? "1" : "0") +
                                     "\n#define SHADOWS " + (any_shadows ? "1" : "0") +
                                     "\n#define LIGHT_ARRAY_SIZE " + std::to_string(light_count > 0 ? light_count : 1) +
                                     "\n#define ENVIRONMENT " + (environment ? "1" : "0") + "\n" + body;
        pbr_program = link_program(kVertexShader, fragment, "PBR fragment shader");
        pbr_uniforms = Uniforms(pbr_program);
        pbr_light_count = light_count;
        pbr_environment = environment;
        pbr_light_types = light_types;
        pbr_ranges = ranges;
        pbr_shadows = shadow_declarations;
        check_gl("building the PBR program");
    }

    // The environment's maps (computed unless they are the last scene's).
    void prepare_environment(const Scene& scene) {
        if (!ibl) ibl = std::make_unique<GlIbl>();
        ibl->prepare(scene.environment.file, ibl_options);
    }

    void free_meshes() {
        for (GpuMesh& m : meshes) {
            glDeleteVertexArrays(1, &m.vao);
            glDeleteBuffers(4, m.buffers);
        }
        meshes.clear();
    }

    // Uploads every mesh afresh: simple, and outside the timed frames.
    void upload_meshes(const Scene& scene) {
        free_meshes();
        for (const Mesh& mesh : scene.meshes) {
            GpuMesh& m = meshes.emplace_back();
            glGenVertexArrays(1, &m.vao);
            glGenBuffers(4, m.buffers);
            glBindVertexArray(m.vao);
            const auto attribute = [&](GLuint location, GLuint buffer, GLint components, const void* data,
                                       std::size_t bytes) {
                glBindBuffer(GL_ARRAY_BUFFER, buffer);
                glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(bytes), data, GL_STATIC_DRAW);
                glVertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, 0, nullptr);
                glEnableVertexAttribArray(location);
            };
            attribute(0, m.buffers[0], 3, mesh.positions.data(), mesh.positions.size() * sizeof(glm::vec3));
            if (mesh.uvs.size() == mesh.positions.size()) {
                attribute(1, m.buffers[1], 2, mesh.uvs.data(), mesh.uvs.size() * sizeof(glm::vec2));
            } else {
                glDisableVertexAttribArray(1);  // reads the current value; (0, 0) as Tessera uses
                glVertexAttrib2f(1, 0.0f, 0.0f);
            }
            attribute(2, m.buffers[2], 3, mesh.normals.data(), mesh.normals.size() * sizeof(glm::vec3));
            glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.buffers[3]);  // recorded in the VAO
            glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.indices.size() * sizeof(std::uint32_t)),
                         mesh.indices.data(), GL_STATIC_DRAW);
            m.index_count = GLsizei(mesh.indices.size());
        }
        glBindVertexArray(0);
        check_gl("uploading meshes");
    }

    void prepare(const Scene& scene) {
        if (scene.msaa != 1 && scene.msaa != kMsaaSamples)
            fail("msaa must be 1 or 4, not " + std::to_string(scene.msaa));
        ensure_framebuffer(scene.width, scene.height);
        if (scene.msaa == kMsaaSamples) ensure_msaa_framebuffer(scene.width, scene.height);
        const bool environment = scene.environment.present();
        if (environment) prepare_environment(scene);
        ensure_pbr_program(scene, environment);
        upload_meshes(scene);
    }

    // One frame into the FBO: clear, then every object; with `multisampled`, into the
    // 4x FBO and then resolved into the single-sample one. No glFinish here.
    void draw(const Scene& scene, bool object_ids, bool multisampled, WindowOrigin origin = WindowOrigin::bottom_left) {
        const bool shadowed = !object_ids && render_shadow_maps(scene);
        glBindFramebuffer(GL_FRAMEBUFFER, multisampled ? msaa_fbo : fbo);
        glViewport(0, 0, scene.width, scene.height);
        if (object_ids)
            glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
        else
            glClearColor(scene.clear_color.r, scene.clear_color.g, scene.clear_color.b, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);

        const Uniforms& u = object_ids ? id_uniforms : pbr_uniforms;
        glUseProgram(object_ids ? id_program : pbr_program);
        const glm::mat4 view = view_matrix(scene.camera);
        glm::mat4 projection = projection_matrix(scene.camera, scene.width, scene.height);
        // Upside down in window space, so the image's top row is window row 0.
        if (origin == WindowOrigin::top_left)
            projection = glm::scale(glm::mat4(1.0f), {1.0f, -1.0f, 1.0f}) * projection;
        glUniformMatrix4fv(u.view, 1, GL_FALSE, glm::value_ptr(view));
        glUniformMatrix4fv(u.projection, 1, GL_FALSE, glm::value_ptr(projection));
        glUniform3fv(u.cam_pos, 1, glm::value_ptr(scene.camera.position));
        const bool environment = !object_ids && scene.environment.present();
        const float rotation = glm::radians(scene.environment.rotation_degrees);  // as shade::ibl_lighting
        const float cos_rotation = std::cos(rotation), sin_rotation = std::sin(rotation);
        if (environment) ibl->bind_for_shading(pbr_program, scene.environment.intensity, cos_rotation, sin_rotation);
        if (shadowed) shadows->bind_for_shading(pbr_program);
        if (!object_ids && !scene.lights.empty()) {
            std::vector<glm::vec3> positions, colors, directions;
            std::vector<GLint> types;
            std::vector<float> cos_inner, cos_outer, ranges;
            for (const Light& light : scene.lights) {
                positions.push_back(light.position);
                colors.push_back(light.color);
                directions.push_back(light.direction);
                types.push_back(light.type == LightType::directional ? 1 : light.type == LightType::spot ? 2 : 0);
                // As shade::spot_cone_factor: the cosines in float on the CPU.
                cos_inner.push_back(std::cos(glm::radians(light.inner_cone_degrees)));
                cos_outer.push_back(std::cos(glm::radians(light.outer_cone_degrees)));
                ranges.push_back(light.type == LightType::directional ? 0.0f : light.range);
            }
            const GLsizei n = GLsizei(positions.size());
            glUniform3fv(u.light_positions, n, glm::value_ptr(positions[0]));
            glUniform3fv(u.light_colors, n, glm::value_ptr(colors[0]));
            glUniform1iv(u.light_types, n, types.data());
            glUniform3fv(u.light_directions, n, glm::value_ptr(directions[0]));
            glUniform1fv(u.light_cos_inner, n, cos_inner.data());
            glUniform1fv(u.light_cos_outer, n, cos_outer.data());
            glUniform1fv(u.light_ranges, n, ranges.data());
        }
        for (std::size_t i = 0; i < scene.objects.size(); ++i) {
            const Object& object = scene.objects[i];
            const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(object.model)));
            glUniformMatrix4fv(u.model, 1, GL_FALSE, glm::value_ptr(object.model));
            glUniformMatrix3fv(u.normal_matrix, 1, GL_FALSE, glm::value_ptr(normal_matrix));
            set_face_culling(scene.materials[object.material].double_sided, object.model, origin);
            if (object_ids) {
                glUniform1ui(u.object_id, GLuint(i + 1));
            } else {
                const Material& material = scene.materials[object.material];
                glUniform3fv(u.albedo, 1, glm::value_ptr(material.albedo));
                glUniform1f(u.metallic, material.metallic);
                glUniform1f(u.roughness, material.roughness);
                glUniform1f(u.ao, material.ao);
            }
            const GpuMesh& mesh = meshes[object.mesh];
            glBindVertexArray(mesh.vao);
            glDrawElements(GL_TRIANGLES, mesh.index_count, GL_UNSIGNED_INT, nullptr);
        }
        glBindVertexArray(0);
        if (environment && scene.environment.background)
            ibl->draw_background(view, projection, scene.environment.intensity, cos_rotation, sin_rotation);
        if (multisampled) resolve(scene.width, scene.height);
    }

    // The shadowed lights' depth maps (gl_shadows.cpp), drawn afresh as Tessera draws them every
    // frame. False when no light casts shadows.
    bool render_shadow_maps(const Scene& scene) {
        bool any = false;
        for (const Light& light : scene.lights) any = any || light.shadows;
        if (!any) return false;
        if (!shadows) shadows = std::make_unique<GlShadows>();
        shadows->render_maps(scene, shadow_options, [&](std::size_t o) {
            const GpuMesh& mesh = meshes[scene.objects[o].mesh];
            glBindVertexArray(mesh.vao);
            glDrawElements(GL_TRIANGLES, mesh.index_count, GL_UNSIGNED_INT, nullptr);
        });
        glBindVertexArray(0);
        return true;
    }

    // Material::double_sided = false culls back faces, by Tessera's (and glTF's) rule: front is
    // counter-clockwise in window space, clockwise under a model matrix with a negative
    // determinant. Drawing upside down (top_left) mirrors window space, which swaps them again.
    static void set_face_culling(bool double_sided, const glm::mat4& model, WindowOrigin origin) {
        if (double_sided) {
            glDisable(GL_CULL_FACE);
            return;
        }
        const bool clockwise_front = (glm::determinant(glm::mat3(model)) < 0.0f) != (origin == WindowOrigin::top_left);
        glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
        glFrontFace(clockwise_front ? GL_CW : GL_CCW);
    }

    // The multisample resolve: GL averages each pixel's samples into the single-sample FBO.
    void resolve(int width, int height) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, msaa_fbo);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
        glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }

    // The colour attachment as RGBA8, row 0 at the top (GL's row 0 is the bottom, unless
    // the frame was drawn with WindowOrigin::top_left).
    std::vector<std::uint8_t> read_rgba_top_down(int width, int height,
                                                 WindowOrigin origin = WindowOrigin::bottom_left) {
        std::vector<std::uint8_t> bottom_up(std::size_t(width) * std::size_t(height) * 4);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
        glReadBuffer(GL_COLOR_ATTACHMENT0);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
        check_gl("reading pixels");
        if (origin == WindowOrigin::top_left) return bottom_up;
        std::vector<std::uint8_t> top_down(bottom_up.size());
        const std::size_t row_bytes = std::size_t(width) * 4;
        for (int y = 0; y < height; ++y)
            std::memcpy(&top_down[std::size_t(y) * row_bytes], &bottom_up[std::size_t(height - 1 - y) * row_bytes],
                        row_bytes);
        return top_down;
    }
};

GlReferenceRenderer::GlReferenceRenderer() : state_(std::make_unique<State>()) { state_->create_context(); }

GlReferenceRenderer::~GlReferenceRenderer() = default;

RenderedImage GlReferenceRenderer::render(const Scene& scene, WindowOrigin origin) {
    state_->prepare(scene);
    state_->draw(scene, false, scene.msaa > 1, origin);
    glFinish();
    check_gl("rendering");
    const std::vector<std::uint8_t> rgba = state_->read_rgba_top_down(scene.width, scene.height, origin);
    RenderedImage image;
    image.width = scene.width;
    image.height = scene.height;
    image.display.resize(std::size_t(scene.width) * std::size_t(scene.height) * 3);
    for (std::size_t p = 0, n = image.display.size() / 3; p < n; ++p)
        for (int c = 0; c < 3; ++c) image.display[p * 3 + std::size_t(c)] = rgba[p * 4 + std::size_t(c)];
    return image;
}

std::vector<std::uint32_t> GlReferenceRenderer::render_object_ids(const Scene& scene) {
    state_->prepare(scene);
    state_->draw(scene, true, false);  // ids are not averaged: the single-sample path, whatever scene.msaa
    glFinish();
    check_gl("rendering object ids");
    const std::vector<std::uint8_t> rgba = state_->read_rgba_top_down(scene.width, scene.height);
    std::vector<std::uint32_t> ids(rgba.size() / 4);
    for (std::size_t p = 0; p < ids.size(); ++p)
        ids[p] = std::uint32_t(rgba[p * 4]) | std::uint32_t(rgba[p * 4 + 1]) << 8 |
                 std::uint32_t(rgba[p * 4 + 2]) << 16 | std::uint32_t(rgba[p * 4 + 3]) << 24;
    return ids;
}

std::vector<double> GlReferenceRenderer::time_frames(const Scene& scene, int frames, int warmup) {
    state_->prepare(scene);
    const bool multisampled = scene.msaa > 1;
    for (int i = 0; i < warmup; ++i) {
        state_->draw(scene, false, multisampled);
        glFinish();
    }
    std::vector<double> ms;
    ms.reserve(std::size_t(frames > 0 ? frames : 0));
    for (int i = 0; i < frames; ++i) {
        const auto start = std::chrono::steady_clock::now();
        state_->draw(scene, false, multisampled);  // with MSAA this includes the resolve blit
        glFinish();
        const auto end = std::chrono::steady_clock::now();
        ms.push_back(std::chrono::duration<double, std::milli>(end - start).count());
    }
    check_gl("timing frames");
    return ms;
}

std::vector<glm::vec2> GlReferenceRenderer::msaa_sample_positions() {
    if (state_->msaa_fbo == 0) state_->ensure_msaa_framebuffer(1, 1);
    glBindFramebuffer(GL_FRAMEBUFFER, state_->msaa_fbo);
    GLint samples = 0;
    glGetIntegerv(GL_SAMPLES, &samples);
    std::vector<glm::vec2> positions(std::size_t(samples > 0 ? samples : 0));
    for (GLuint i = 0; i < GLuint(positions.size()); ++i)
        glGetMultisamplefv(GL_SAMPLE_POSITION, i, glm::value_ptr(positions[i]));
    check_gl("querying GL_SAMPLE_POSITION");
    return positions;
}

void GlReferenceRenderer::set_ibl_options(const IblOptions& options) { state_->ibl_options = options; }

void GlReferenceRenderer::set_shadow_options(const ShadowOptions& options) { state_->shadow_options = options; }

std::vector<ShadowMapReadback> GlReferenceRenderer::read_shadow_maps(const Scene& scene) {
    state_->prepare(scene);
    if (!state_->render_shadow_maps(scene)) return {};
    glFinish();
    return state_->shadows->read_maps();
}

IblMapsReadback GlReferenceRenderer::read_ibl_maps(const Scene& scene) {
    if (!scene.environment.present()) fail("read_ibl_maps: the scene has no environment");
    state_->prepare_environment(scene);
    return state_->ibl->read_maps();
}

std::string GlReferenceRenderer::renderer_name() const {
    const GLubyte* s = glGetString(GL_RENDERER);
    return s ? reinterpret_cast<const char*>(s) : "";
}

std::string GlReferenceRenderer::version() const {
    const GLubyte* s = glGetString(GL_VERSION);
    return s ? reinterpret_cast<const char*>(s) : "";
}

}  // namespace tessera::gl_reference
