// The peer's shaders for the scene's objects: the reference GLSL of docs/reference/pbr_lighting.md
// (with the splice points the IBL and shadow chapters fill) and the object-id shader.
// Internal to tools/gl_reference (gl_renderer.cpp).
#pragma once

namespace tessera::gl_reference {

// The reference vertex shader of pbr_lighting.md, verbatim but for the normal: the
// reference's mat3(model) is only right for uniform scale (its own comment says so),
// and Tessera uses the inverse-transpose, so the peer must too or ellipsoids differ.
inline constexpr const char* kVertexShader = R"(#version 330 core
layout (location = 0) in vec3 aPos;
layout (location = 1) in vec2 aTexCoords;
layout (location = 2) in vec3 aNormal;
out vec2 TexCoords; out vec3 WorldPos; out vec3 Normal;
uniform mat4 projection, view, model;
uniform mat3 normalMatrix;  // transpose(inverse(mat3(model))), computed on the CPU as Tessera does
void main() {
    TexCoords = aTexCoords;
    WorldPos  = vec3(model * vec4(aPos, 1.0));
    Normal    = normalMatrix * aNormal;
    gl_Position = projection * view * vec4(WorldPos, 1.0);
}
)";

// The reference fragment shader, verbatim but for the light count: the arrays hold
// LIGHT_ARRAY_SIZE = max(LIGHT_COUNT, 1) entries (GLSL has no empty arrays) and the
// loop runs LIGHT_COUNT times, so a scene without lights gets ambient only. With an
// environment, IBL_DECLARATIONS and IBL_AMBIENT splice in the IBL chapter's pbr.fs (gl_ibl.cpp):
// its ambient term in place of 0.03·albedo·ao. With LIGHT_TYPES (a directional or spot light in
// the scene) the loop's first lines take each light's type as pbr_lighting.md's "Other light
// types" says; with RANGES (a light with Light::range) a light adds nothing past its range, as
// Tessera's light culling cuts it; with SHADOWS, SHADOW_DECLARATIONS splices in the shadow chapters' functions
// (gl_shadows.cpp) and each light's term of Lo is scaled by its 1 − shadow. Without either the
// shader is the reference's, line for line.
inline constexpr const char* kFragmentShaderBody = R"(
in vec2 TexCoords; in vec3 WorldPos; in vec3 Normal;
out vec4 FragColor;
uniform vec3  albedo;  uniform float metallic;  uniform float roughness;  uniform float ao;
uniform vec3  lightPositions[LIGHT_ARRAY_SIZE];  uniform vec3 lightColors[LIGHT_ARRAY_SIZE];  uniform vec3 camPos;
#if RANGES
uniform float lightRanges[LIGHT_ARRAY_SIZE];  // 0: unlimited
#endif
#if LIGHT_TYPES
uniform int lightTypes[LIGHT_ARRAY_SIZE];  // 0 point, 1 directional, 2 spot
uniform vec3 lightDirections[LIGHT_ARRAY_SIZE];  // where the light travels, unit
uniform float lightCosInner[LIGHT_ARRAY_SIZE];  uniform float lightCosOuter[LIGHT_ARRAY_SIZE];
#endif
const float PI = 3.14159265359;
IBL_DECLARATIONS
SHADOW_DECLARATIONS
float DistributionGGX(vec3 N, vec3 H, float roughness) {
    float a = roughness*roughness; float a2 = a*a;
    float NdotH = max(dot(N, H), 0.0); float NdotH2 = NdotH*NdotH;
    float denom = (NdotH2 * (a2 - 1.0) + 1.0);
    return a2 / (PI * denom * denom);
}
float GeometrySchlickGGX(float NdotV, float roughness) {
    float r = (roughness + 1.0); float k = (r*r) / 8.0;
    return NdotV / (NdotV * (1.0 - k) + k);
}
float GeometrySmith(vec3 N, vec3 V, vec3 L, float roughness) {
    return GeometrySchlickGGX(max(dot(N, L), 0.0), roughness) * GeometrySchlickGGX(max(dot(N, V), 0.0), roughness);
}
vec3 fresnelSchlick(float cosTheta, vec3 F0) {
    return F0 + (1.0 - F0) * pow(clamp(1.0 - cosTheta, 0.0, 1.0), 5.0);
}
void main() {
    vec3 N = normalize(Normal);
    vec3 V = normalize(camPos - WorldPos);
    vec3 F0 = mix(vec3(0.04), albedo, metallic);
    vec3 Lo = vec3(0.0);
    for (int i = 0; i < LIGHT_COUNT; ++i) {
#if RANGES
        // Light::range: nothing past it (shade::light_reaches, (dx² + dy²) + dz² <= range²).
        vec3 toLight = lightPositions[i] - WorldPos;
        if (lightRanges[i] > 0.0 &&
            (toLight.x * toLight.x + toLight.y * toLight.y) + toLight.z * toLight.z > lightRanges[i] * lightRanges[i])
            continue;
#endif
#if LIGHT_TYPES
        vec3 L; vec3 radiance;
        if (lightTypes[i] == 1) {  // directional: L = -direction, no attenuation
            L = -lightDirections[i];
            radiance = lightColors[i];
        } else {
            L = normalize(lightPositions[i] - WorldPos);
            float distance = length(lightPositions[i] - WorldPos);
            radiance = lightColors[i] / (distance * distance);
            if (lightTypes[i] == 2)  // spot: the clamp ramp between the cones
                radiance *= clamp((dot(lightDirections[i], -L) - lightCosOuter[i]) / (lightCosInner[i] - lightCosOuter[i]),
                                  0.0, 1.0);
        }
        vec3 H = normalize(V + L);
#else
        vec3 L = normalize(lightPositions[i] - WorldPos);
        vec3 H = normalize(V + L);
        float distance = length(lightPositions[i] - WorldPos);
        vec3 radiance = lightColors[i] / (distance * distance);
#endif
        float NDF = DistributionGGX(N, H, roughness);
        float G   = GeometrySmith(N, V, L, roughness);
        vec3  F   = fresnelSchlick(max(dot(H, V), 0.0), F0);
        vec3 kD = (vec3(1.0) - F) * (1.0 - metallic);
        vec3 specular = NDF * G * F / (4.0 * max(dot(N, V), 0.0) * max(dot(N, L), 0.0) + 0.0001);
        float NdotL = max(dot(N, L), 0.0);
#if SHADOWS
        Lo += lightVisibility(i) * ((kD * albedo / PI + specular) * radiance * NdotL);
#else
        Lo += (kD * albedo / PI + specular) * radiance * NdotL;
#endif
    }
#if ENVIRONMENT
IBL_AMBIENT
#else
    vec3 color = vec3(0.03) * albedo * ao + Lo;
#endif
    color = color / (color + vec3(1.0));
    color = pow(color, vec3(1.0/2.2));
    FragColor = vec4(color, 1.0);
}
)";

// Writes the object id (i + 1) as four bytes; k/255 converts back to unorm8 exactly.
inline constexpr const char* kObjectIdFragmentShader = R"(#version 330 core
out vec4 FragColor;
uniform uint objectId;
void main() {
    uvec4 bytes = uvec4(objectId, objectId >> 8u, objectId >> 16u, objectId >> 24u) & 255u;
    FragColor = vec4(bytes) / 255.0;
}
)";

}  // namespace tessera::gl_reference
