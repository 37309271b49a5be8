#include "gl_ibl.hpp"

#include <chrono>
#include <cmath>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "environment/equirect_image.hpp"

namespace tessera::gl_reference {

namespace {

// The map sizes of ibl_specular.cpp (Tessera's are the same: environment/precompute.hpp).
constexpr int kEnvironmentSize = 512;
constexpr int kIrradianceSize = 32;
constexpr int kPrefilterSize = 128;
constexpr int kPrefilterLevels = 5;  // maxMipLevels
constexpr int kBrdfSize = 512;

// cubemap.vs: the capture passes' vertex shader.
constexpr const char* kCaptureVertexShader = R"(#version 330 core
layout (location = 0) in vec3 aPos;
out vec3 WorldPos;
uniform mat4 projection;
uniform mat4 view;
void main() {
    WorldPos = aPos;
    gl_Position = projection * view * vec4(WorldPos, 1.0);
}
)";

// equirectangular_to_cubemap.fs.
constexpr const char* kEquirectToCubemapShader = R"(#version 330 core
out vec4 FragColor;
in vec3 WorldPos;
uniform sampler2D equirectangularMap;
const vec2 invAtan = vec2(0.1591, 0.3183);
vec2 SampleSphericalMap(vec3 v) {
    vec2 uv = vec2(atan(v.z, v.x), asin(v.y));
    uv *= invAtan;
    uv += 0.5;
    return uv;
}
void main() {
    vec2 uv = SampleSphericalMap(normalize(WorldPos));
    vec3 color = texture(equirectangularMap, uv).rgb;
    FragColor = vec4(color, 1.0);
}
)";

// irradiance_convolution.fs. ENVIRONMENT_LOOKUP is the chapter's texture(environmentMap,
// sampleVec), or with the documented departure textureLod(environmentMap, sampleVec, 4.0).
constexpr const char* kIrradianceShaderBody = R"(
out vec4 FragColor;
in vec3 WorldPos;
uniform samplerCube environmentMap;
const float PI = 3.14159265359;
void main() {
    vec3 N = normalize(WorldPos);
    vec3 irradiance = vec3(0.0);
    vec3 up    = vec3(0.0, 1.0, 0.0);
    vec3 right = cross(up, N);
    up         = cross(N, right);
    float sampleDelta = 0.025;
    float nrSamples = 0.0;
    for (float phi = 0.0; phi < 2.0 * PI; phi += sampleDelta) {
        for (float theta = 0.0; theta < 0.5 * PI; theta += sampleDelta) {
            vec3 tangentSample = vec3(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));
            vec3 sampleVec = tangentSample.x * right + tangentSample.y * up + tangentSample.z * N;
            irradiance += ENVIRONMENT_LOOKUP.rgb * cos(theta) * sin(theta);
            nrSamples++;
        }
    }
    irradiance = PI * irradiance * (1.0 / float(nrSamples));
    FragColor = vec4(irradiance, 1.0);
}
)";

// What prefilter.fs and brdf.fs share: the Hammersley sequence and GGX importance sampling.
constexpr const char* kSamplingFunctions = R"(
const float PI = 3.14159265359;
float RadicalInverse_VdC(uint bits) {
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return float(bits) * 2.3283064365386963e-10; // / 0x100000000
}
vec2 Hammersley(uint i, uint N) {
    return vec2(float(i)/float(N), RadicalInverse_VdC(i));
}
vec3 ImportanceSampleGGX(vec2 Xi, vec3 N, float roughness) {
    float a = roughness*roughness;
    float phi = 2.0 * PI * Xi.x;
    float cosTheta = sqrt((1.0 - Xi.y) / (1.0 + (a*a - 1.0) * Xi.y));
    float sinTheta = sqrt(1.0 - cosTheta*cosTheta);
    vec3 H;
    H.x = cos(phi) * sinTheta;
    H.y = sin(phi) * sinTheta;
    H.z = cosTheta;
    vec3 up        = abs(N.z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
    vec3 tangent   = normalize(cross(up, N));
    vec3 bitangent = cross(N, tangent);
    vec3 sampleVec = tangent * H.x + bitangent * H.y + N * H.z;
    return normalize(sampleVec);
}
)";

// prefilter.fs (after kSamplingFunctions).
constexpr const char* kPrefilterShaderBody = R"(
out vec4 FragColor;
in vec3 WorldPos;
uniform samplerCube environmentMap;
uniform float roughness;
float DistributionGGX(vec3 N, vec3 H, float roughness) {
    float a = roughness*roughness;
    float a2 = a*a;
    float NdotH = max(dot(N, H), 0.0);
    float NdotH2 = NdotH*NdotH;
    float nom   = a2;
    float denom = (NdotH2 * (a2 - 1.0) + 1.0);
    denom = PI * denom * denom;
    return nom / denom;
}
void main() {
    vec3 N = normalize(WorldPos);
    vec3 R = N;
    vec3 V = R;
    const uint SAMPLE_COUNT = 1024u;
    vec3 prefilteredColor = vec3(0.0);
    float totalWeight = 0.0;
    for (uint i = 0u; i < SAMPLE_COUNT; ++i) {
        vec2 Xi = Hammersley(i, SAMPLE_COUNT);
        vec3 H = ImportanceSampleGGX(Xi, N, roughness);
        vec3 L  = normalize(2.0 * dot(V, H) * H - V);
        float NdotL = max(dot(N, L), 0.0);
        if (NdotL > 0.0) {
            float D   = DistributionGGX(N, H, roughness);
            float NdotH = max(dot(N, H), 0.0);
            float HdotV = max(dot(H, V), 0.0);
            float pdf = D * NdotH / (4.0 * HdotV) + 0.0001;
            float resolution = 512.0;
            float saTexel  = 4.0 * PI / (6.0 * resolution * resolution);
            float saSample = 1.0 / (float(SAMPLE_COUNT) * pdf + 0.0001);
            float mipLevel = roughness == 0.0 ? 0.0 : 0.5 * log2(saSample / saTexel);
            prefilteredColor += textureLod(environmentMap, L, mipLevel).rgb * NdotL;
            totalWeight      += NdotL;
        }
    }
    prefilteredColor = prefilteredColor / totalWeight;
    FragColor = vec4(prefilteredColor, 1.0);
}
)";

// brdf.vs and brdf.fs (after kSamplingFunctions).
constexpr const char* kBrdfVertexShader = R"(#version 330 core
layout (location = 0) in vec3 aPos;
layout (location = 1) in vec2 aTexCoords;
out vec2 TexCoords;
void main() {
    TexCoords = aTexCoords;
    gl_Position = vec4(aPos, 1.0);
}
)";
constexpr const char* kBrdfShaderBody = R"(
out vec2 FragColor;
in vec2 TexCoords;
float GeometrySchlickGGX(float NdotV, float roughness) {
    float a = roughness;
    float k = (a * a) / 2.0;  // k for IBL
    float nom   = NdotV;
    float denom = NdotV * (1.0 - k) + k;
    return nom / denom;
}
float GeometrySmith(vec3 N, vec3 V, vec3 L, float roughness) {
    float NdotV = max(dot(N, V), 0.0);
    float NdotL = max(dot(N, L), 0.0);
    float ggx2 = GeometrySchlickGGX(NdotV, roughness);
    float ggx1 = GeometrySchlickGGX(NdotL, roughness);
    return ggx1 * ggx2;
}
vec2 IntegrateBRDF(float NdotV, float roughness) {
    vec3 V;
    V.x = sqrt(1.0 - NdotV*NdotV);
    V.y = 0.0;
    V.z = NdotV;
    float A = 0.0;
    float B = 0.0;
    vec3 N = vec3(0.0, 0.0, 1.0);
    const uint SAMPLE_COUNT = 1024u;
    for (uint i = 0u; i < SAMPLE_COUNT; ++i) {
        vec2 Xi = Hammersley(i, SAMPLE_COUNT);
        vec3 H = ImportanceSampleGGX(Xi, N, roughness);
        vec3 L = normalize(2.0 * dot(V, H) * H - V);
        float NdotL = max(L.z, 0.0);
        float NdotH = max(H.z, 0.0);
        float VdotH = max(dot(V, H), 0.0);
        if (NdotL > 0.0) {
            float G = GeometrySmith(N, V, L, roughness);
            float G_Vis = (G * VdotH) / (NdotH * NdotV);
            float Fc = pow(1.0 - VdotH, 5.0);
            A += (1.0 - Fc) * G_Vis;
            B += Fc * G_Vis;
        }
    }
    A /= float(SAMPLE_COUNT);
    B /= float(SAMPLE_COUNT);
    return vec2(A, B);
}
void main() {
    FragColor = IntegrateBRDF(TexCoords.x, TexCoords.y);
}
)";

// background.vs and background.fs (the specular chapter's: level 0). Departures, as Tessera's
// [environment] keys: the direction turned about +Y by `rotation` and the radiance scaled by
// `intensity` before the tonemap (both 1 and 0 leave the chapter's value bit for bit).
constexpr const char* kBackgroundVertexShader = R"(#version 330 core
layout (location = 0) in vec3 aPos;
uniform mat4 projection;
uniform mat4 view;
out vec3 WorldPos;
void main() {
    WorldPos = aPos;
    mat4 rotView = mat4(mat3(view));
    vec4 clipPos = projection * rotView * vec4(WorldPos, 1.0);
    gl_Position = clipPos.xyww;
}
)";
constexpr const char* kBackgroundFragmentShader = R"(#version 330 core
out vec4 FragColor;
in vec3 WorldPos;
uniform samplerCube environmentMap;
uniform float environmentIntensity;
uniform vec2 environmentRotation;  // (cos, sin) of the angle about +Y
void main() {
    vec3 d = WorldPos;
    vec3 turned = vec3(environmentRotation.x * d.x - environmentRotation.y * d.z, d.y,
                       environmentRotation.y * d.x + environmentRotation.x * d.z);
    vec3 envColor = textureLod(environmentMap, turned, 0.0).rgb * environmentIntensity;
    envColor = envColor / (envColor + vec3(1.0));
    envColor = pow(envColor, vec3(1.0/2.2));
    FragColor = vec4(envColor, 1.0);
}
)";

// The unit cube's 12 triangles (renderCube; no culling, so the winding does not matter).
std::vector<float> cube_positions() {
    std::vector<float> v;
    for (int axis = 0; axis < 3; ++axis)
        for (const float side : {-1.0f, 1.0f}) {
            const int u = (axis + 1) % 3, w = (axis + 2) % 3;
            const float corners[6][2] = {{-1, -1}, {1, -1}, {1, 1}, {1, 1}, {-1, 1}, {-1, -1}};
            for (const auto& c : corners) {
                float p[3];
                p[axis] = side, p[u] = c[0], p[w] = c[1];
                v.insert(v.end(), p, p + 3);
            }
        }
    return v;
}

void set_cube_parameters(GLenum min_filter) {
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GLint(min_filter));
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
}

GLuint make_cube_texture(GLenum internal_format, int size) {
    GLuint texture = 0;
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_CUBE_MAP, texture);
    for (GLenum i = 0; i < 6; ++i)
        glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + i, 0, GLint(internal_format), size, size, 0, GL_RGB, GL_FLOAT,
                     nullptr);
    return texture;
}

void check_capture_framebuffer(const char* what) {
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        fail(std::string(what) + ": the capture framebuffer is incomplete (status " + std::to_string(status) + ")");
}

CubeLevelReadback read_cube_level(GLuint texture, int level) {
    glBindTexture(GL_TEXTURE_CUBE_MAP, texture);
    GLint size = 0;
    glGetTexLevelParameteriv(GL_TEXTURE_CUBE_MAP_POSITIVE_X, level, GL_TEXTURE_WIDTH, &size);
    CubeLevelReadback out;
    out.size = size;
    const std::size_t face_floats = std::size_t(size) * std::size_t(size) * 3;
    out.rgb.resize(6 * face_floats);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    for (GLenum f = 0; f < 6; ++f)
        glGetTexImage(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f, level, GL_RGB, GL_FLOAT, &out.rgb[f * face_floats]);
    return out;
}

}  // namespace

// pbr.fs's IBL uniforms and fresnelSchlickRoughness. environmentIntensity and
// environmentRotation are Tessera's [environment] keys (docs/reference/ibl_lighting.md, pbr.fs).
const char* const kIblFragmentDeclarations = R"(
uniform samplerCube irradianceMap;
uniform samplerCube prefilterMap;
uniform sampler2D brdfLUT;
uniform float environmentIntensity;
uniform vec2 environmentRotation;  // (cos, sin) of the angle about +Y
vec3 fresnelSchlickRoughness(float cosTheta, vec3 F0, float roughness) {
    return F0 + (max(vec3(1.0 - roughness), F0) - F0) * pow(clamp(1.0 - cosTheta, 0.0, 1.0), 5.0);
}
vec3 environmentDirection(vec3 d) {
    return vec3(environmentRotation.x * d.x - environmentRotation.y * d.z, d.y,
                environmentRotation.y * d.x + environmentRotation.x * d.z);
}
)";

// pbr.fs after the light loop.
const char* const kIblAmbient = R"(
    vec3 R = reflect(-V, N);
    vec3 F = fresnelSchlickRoughness(max(dot(N, V), 0.0), F0, roughness);
    vec3 kS = F;
    vec3 kD = 1.0 - kS;
    kD *= 1.0 - metallic;
    vec3 irradiance = texture(irradianceMap, environmentDirection(N)).rgb * environmentIntensity;
    vec3 diffuse    = irradiance * albedo;
    const float MAX_REFLECTION_LOD = 4.0;
    vec3 prefilteredColor = textureLod(prefilterMap, environmentDirection(R), roughness * MAX_REFLECTION_LOD).rgb *
                            environmentIntensity;
    vec2 brdf = texture(brdfLUT, vec2(max(dot(N, V), 0.0), roughness)).rg;
    vec3 specular = prefilteredColor * (F * brdf.x + brdf.y);
    vec3 ambient = (kD * diffuse + specular) * ao;
    vec3 color = ambient + Lo;
)";

GlIbl::~GlIbl() {
    free_maps();
    for (const GLuint program : {equirect_program_, irradiance_program_, prefilter_program_, brdf_program_,
                                 background_program_})
        if (program) glDeleteProgram(program);
    if (capture_fbo_) glDeleteFramebuffers(1, &capture_fbo_);
    if (cube_vao_) glDeleteVertexArrays(1, &cube_vao_);
    if (quad_vao_) glDeleteVertexArrays(1, &quad_vao_);
    if (cube_vbo_) glDeleteBuffers(1, &cube_vbo_);
    if (quad_vbo_) glDeleteBuffers(1, &quad_vbo_);
}

void GlIbl::free_maps() {
    for (GLuint* texture : {&hdr_texture_, &env_cubemap_, &irradiance_map_, &prefilter_map_, &brdf_lut_})
        if (*texture) glDeleteTextures(1, texture), *texture = 0;
    ready_ = false;
}

void GlIbl::build_programs() {
    if (cube_vao_ == 0) {
        const std::vector<float> cube = cube_positions();
        glGenVertexArrays(1, &cube_vao_);
        glGenBuffers(1, &cube_vbo_);
        glBindVertexArray(cube_vao_);
        glBindBuffer(GL_ARRAY_BUFFER, cube_vbo_);
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(cube.size() * sizeof(float)), cube.data(), GL_STATIC_DRAW);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
        glEnableVertexAttribArray(0);
        // renderQuad: the NDC square, texture coordinates 0..1.
        const float quad[] = {-1, 1, 0, 0, 1, -1, -1, 0, 0, 0, 1, 1, 0, 1, 1, 1, -1, 0, 1, 0};
        glGenVertexArrays(1, &quad_vao_);
        glGenBuffers(1, &quad_vbo_);
        glBindVertexArray(quad_vao_);
        glBindBuffer(GL_ARRAY_BUFFER, quad_vbo_);
        glBufferData(GL_ARRAY_BUFFER, sizeof quad, quad, GL_STATIC_DRAW);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 5 * sizeof(float), nullptr);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, 5 * sizeof(float), reinterpret_cast<void*>(3 * sizeof(float)));
        glEnableVertexAttribArray(1);
        glBindVertexArray(0);
        glGenFramebuffers(1, &capture_fbo_);

        equirect_program_ = link_program(kCaptureVertexShader, kEquirectToCubemapShader, "equirectangular_to_cubemap.fs");
        prefilter_program_ = link_program(kCaptureVertexShader,
                                          std::string("#version 330 core\n") + kSamplingFunctions + kPrefilterShaderBody,
                                          "prefilter.fs");
        brdf_program_ = link_program(kBrdfVertexShader,
                                     std::string("#version 330 core\n") + kSamplingFunctions + kBrdfShaderBody, "brdf.fs");
        background_program_ = link_program(kBackgroundVertexShader, kBackgroundFragmentShader, "background.fs");
    }
    if (irradiance_program_ == 0 || irradiance_program_from_derivatives_ != options_.irradiance_lod_from_derivatives) {
        if (irradiance_program_) glDeleteProgram(irradiance_program_);
        const std::string lookup = options_.irradiance_lod_from_derivatives
                                       ? "texture(environmentMap, sampleVec)"
                                       : "textureLod(environmentMap, sampleVec, 4.0)";  // kIrradianceLod
        irradiance_program_ = link_program(
            kCaptureVertexShader, "#version 330 core\n#define ENVIRONMENT_LOOKUP " + lookup + "\n" + kIrradianceShaderBody,
            "irradiance_convolution.fs");
        irradiance_program_from_derivatives_ = options_.irradiance_lod_from_derivatives;
    }
    check_gl("building the IBL programs");
}

void GlIbl::prepare(const std::string& image_path, const IblOptions& options) {
    if (ready_ && image_path == image_path_ && options == options_) return;
    free_maps();
    image_path_ = image_path;
    options_ = options;
    build_programs();

    // The file is decoded by Tessera's loader (rows bottom-up, as stbi_set_flip_vertically_on_load
    // leaves them); everything after the decode is GL's.
    const environment::EquirectImage image = environment::load_equirect_image(image_path);
    const auto start = std::chrono::steady_clock::now();
    const bool half = options.half_float_storage;
    const GLenum rgb_format = half ? GL_RGB16F : GL_RGB32F;

    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    glDisable(GL_DEPTH_TEST);  // each capture pixel is covered by one cube face: no depth buffer needed
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);

    glGenTextures(1, &hdr_texture_);
    glBindTexture(GL_TEXTURE_2D, hdr_texture_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GLint(rgb_format), image.width, image.height, 0, GL_RGB, GL_FLOAT, image.rgb.data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);

    const glm::mat4 capture_projection = glm::perspective(glm::radians(90.0f), 1.0f, 0.1f, 10.0f);
    const glm::vec3 o(0.0f);
    const glm::mat4 capture_views[6] = {
        glm::lookAt(o, glm::vec3(1, 0, 0), glm::vec3(0, -1, 0)), glm::lookAt(o, glm::vec3(-1, 0, 0), glm::vec3(0, -1, 0)),
        glm::lookAt(o, glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)),  glm::lookAt(o, glm::vec3(0, -1, 0), glm::vec3(0, 0, -1)),
        glm::lookAt(o, glm::vec3(0, 0, 1), glm::vec3(0, -1, 0)), glm::lookAt(o, glm::vec3(0, 0, -1), glm::vec3(0, -1, 0))};
    // Draws the cube six times, each face of `target` (at `level`) a framebuffer.
    const auto capture = [&](GLuint program, GLuint target, int level, int size, const char* what) {
        glUseProgram(program);
        glUniformMatrix4fv(glGetUniformLocation(program, "projection"), 1, GL_FALSE, glm::value_ptr(capture_projection));
        glViewport(0, 0, size, size);
        glBindFramebuffer(GL_FRAMEBUFFER, capture_fbo_);
        glBindVertexArray(cube_vao_);
        for (GLenum i = 0; i < 6; ++i) {
            glUniformMatrix4fv(glGetUniformLocation(program, "view"), 1, GL_FALSE, glm::value_ptr(capture_views[i]));
            glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_CUBE_MAP_POSITIVE_X + i, target, level);
            check_capture_framebuffer(what);
            glClear(GL_COLOR_BUFFER_BIT);
            glDrawArrays(GL_TRIANGLES, 0, 36);
        }
        check_gl(what);
    };

    // The environment cube, then glGenerateMipmap (a 2x2 box filter per face on Mesa).
    env_cubemap_ = make_cube_texture(rgb_format, kEnvironmentSize);
    set_cube_parameters(GL_LINEAR_MIPMAP_LINEAR);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, hdr_texture_);
    glUseProgram(equirect_program_);
    glUniform1i(glGetUniformLocation(equirect_program_, "equirectangularMap"), 0);
    capture(equirect_program_, env_cubemap_, 0, kEnvironmentSize, "equirectangular_to_cubemap");
    glBindTexture(GL_TEXTURE_CUBE_MAP, env_cubemap_);
    glGenerateMipmap(GL_TEXTURE_CUBE_MAP);

    // The irradiance cube.
    irradiance_map_ = make_cube_texture(rgb_format, kIrradianceSize);
    set_cube_parameters(GL_LINEAR);
    glBindTexture(GL_TEXTURE_CUBE_MAP, env_cubemap_);
    glUseProgram(irradiance_program_);
    glUniform1i(glGetUniformLocation(irradiance_program_, "environmentMap"), 0);
    capture(irradiance_program_, irradiance_map_, 0, kIrradianceSize, "irradiance_convolution");

    // The pre-filtered cube: glGenerateMipmap only allocates the chain; levels 0..4 are drawn,
    // at roughness mip / 4. GL_TEXTURE_MAX_LEVEL 4 (not in the chapter) keeps the never-drawn
    // levels 5..7 out of textureLod(..., 4.0) at roughness 1: Tessera stores 5 levels.
    prefilter_map_ = make_cube_texture(rgb_format, kPrefilterSize);
    set_cube_parameters(GL_LINEAR_MIPMAP_LINEAR);
    glGenerateMipmap(GL_TEXTURE_CUBE_MAP);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAX_LEVEL, kPrefilterLevels - 1);
    glBindTexture(GL_TEXTURE_CUBE_MAP, env_cubemap_);
    glUseProgram(prefilter_program_);
    glUniform1i(glGetUniformLocation(prefilter_program_, "environmentMap"), 0);
    for (int mip = 0; mip < kPrefilterLevels; ++mip) {
        glUniform1f(glGetUniformLocation(prefilter_program_, "roughness"), float(mip) / float(kPrefilterLevels - 1));
        capture(prefilter_program_, prefilter_map_, mip, kPrefilterSize >> mip, "prefilter");
    }

    // The BRDF table: one quad over the 512² texture.
    glGenTextures(1, &brdf_lut_);
    glBindTexture(GL_TEXTURE_2D, brdf_lut_);
    glTexImage2D(GL_TEXTURE_2D, 0, half ? GL_RG16F : GL_RG32F, kBrdfSize, kBrdfSize, 0, GL_RG, GL_FLOAT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glBindFramebuffer(GL_FRAMEBUFFER, capture_fbo_);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, brdf_lut_, 0);
    check_capture_framebuffer("brdf");
    glViewport(0, 0, kBrdfSize, kBrdfSize);
    glUseProgram(brdf_program_);
    glClear(GL_COLOR_BUFFER_BIT);
    glBindVertexArray(quad_vao_);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glFinish();
    check_gl("computing the IBL maps");
    precompute_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    ready_ = true;
}

void GlIbl::bind_for_shading(GLuint program, float intensity, float cos_rotation, float sin_rotation) const {
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_CUBE_MAP, irradiance_map_);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_CUBE_MAP, prefilter_map_);
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D, brdf_lut_);
    glActiveTexture(GL_TEXTURE0);
    glUniform1i(glGetUniformLocation(program, "irradianceMap"), 0);
    glUniform1i(glGetUniformLocation(program, "prefilterMap"), 1);
    glUniform1i(glGetUniformLocation(program, "brdfLUT"), 2);
    glUniform1f(glGetUniformLocation(program, "environmentIntensity"), intensity);
    glUniform2f(glGetUniformLocation(program, "environmentRotation"), cos_rotation, sin_rotation);
}

void GlIbl::draw_background(const glm::mat4& view, const glm::mat4& projection, float intensity, float cos_rotation,
                            float sin_rotation) {
    glUseProgram(background_program_);
    glUniformMatrix4fv(glGetUniformLocation(background_program_, "view"), 1, GL_FALSE, glm::value_ptr(view));
    glUniformMatrix4fv(glGetUniformLocation(background_program_, "projection"), 1, GL_FALSE,
                       glm::value_ptr(projection));
    glUniform1i(glGetUniformLocation(background_program_, "environmentMap"), 0);
    glUniform1f(glGetUniformLocation(background_program_, "environmentIntensity"), intensity);
    glUniform2f(glGetUniformLocation(background_program_, "environmentRotation"), cos_rotation, sin_rotation);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_CUBE_MAP, env_cubemap_);
    glDisable(GL_CULL_FACE);
    glDepthFunc(GL_LEQUAL);  // the cube lies at depth 1, the cleared value
    glBindVertexArray(cube_vao_);
    glDrawArrays(GL_TRIANGLES, 0, 36);
    glBindVertexArray(0);
    glDepthFunc(GL_LESS);
}

IblMapsReadback GlIbl::read_maps() const {
    IblMapsReadback maps;
    for (int level = 0; (kEnvironmentSize >> level) >= 1; ++level) maps.environment.push_back(read_cube_level(env_cubemap_, level));
    maps.irradiance = read_cube_level(irradiance_map_, 0);
    for (int level = 0; level < kPrefilterLevels; ++level) maps.prefiltered.push_back(read_cube_level(prefilter_map_, level));
    maps.brdf_size = kBrdfSize;
    maps.brdf_rg.resize(std::size_t(kBrdfSize) * kBrdfSize * 2);
    glBindTexture(GL_TEXTURE_2D, brdf_lut_);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RG, GL_FLOAT, maps.brdf_rg.data());
    maps.precompute_ms = precompute_ms_;
    check_gl("reading the IBL maps back");
    return maps;
}

}  // namespace tessera::gl_reference
