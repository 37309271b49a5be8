#include "scene/scene_validation.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <string>

namespace tessera {
namespace {

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool in_unit_interval(float x) { return x >= 0.0f && x <= 1.0f; }  // false for NaN

template <typename... Parts>
[[noreturn]] void fail(const Scene& scene, const Parts&... parts) {
    std::ostringstream message;
    message << (scene.source.empty() ? std::string("scene") : scene.source) << ": ";
    (message << ... << parts);
    throw SceneError(message.str());
}

std::string mesh_label(const Scene& scene, std::size_t m) {
    const std::string& name = scene.meshes[m].name;
    return "mesh " + (name.empty() ? std::string() : "'" + name + "' ") + "(meshes[" + std::to_string(m) + "])";
}

void validate_size(const Scene& scene) {
    if (scene.width < 1 || scene.width > kMaxImageDimension || scene.height < 1 ||
        scene.height > kMaxImageDimension) {
        fail(scene, "image size ", scene.width, "x", scene.height, " is outside 1..", kMaxImageDimension,
             " pixels per side");
    }
    const long long pixels = static_cast<long long>(scene.width) * scene.height;
    if (pixels > kMaxImagePixels) {
        fail(scene, "image size ", scene.width, "x", scene.height, " is ", pixels, " pixels; at most ",
             kMaxImagePixels, " are allowed");
    }
    if (scene.msaa != 1 && scene.msaa != 4) fail(scene, "msaa is ", scene.msaa, "; expected 1 or 4 samples per pixel");
}

void validate_camera(const Scene& scene) {
    const Camera& c = scene.camera;
    if (!finite(c.position) || !finite(c.target) || !finite(c.up)) {
        fail(scene, "camera position, target and up must be finite");
    }
    if (!(c.fov_y_degrees > 0.0f && c.fov_y_degrees < 180.0f)) {
        fail(scene, "camera fov_y must be in (0, 180) degrees, got ", c.fov_y_degrees);
    }
    const bool orthographic = c.projection == Projection::orthographic;
    if (orthographic && !(c.x_magnification > 0.0f && c.y_magnification > 0.0f && std::isfinite(c.x_magnification) &&
                          std::isfinite(c.y_magnification)))
        fail(scene, "orthographic camera xmag and ymag must be finite and > 0, got ", c.x_magnification, ", ",
             c.y_magnification);
    // An orthographic box may start at the eye (glTF allows znear = 0); a frustum may not.
    if (!((orthographic ? c.near_plane >= 0.0f : c.near_plane > 0.0f) && c.near_plane < c.far_plane &&
          std::isfinite(c.far_plane))) {
        fail(scene, "camera planes must satisfy ", orthographic ? "0 <= near < far" : "0 < near < far",
             ", got near = ", c.near_plane, ", far = ", c.far_plane);
    }
    // The same tolerances as the scene file reader.
    const glm::vec3 forward = c.target - c.position;
    const float scale = std::max({1.0f, glm::length(c.position), glm::length(c.target)});
    if (!(glm::length(forward) > 1e-6f * scale)) fail(scene, "camera target must differ from its position");
    const float up_length = glm::length(c.up);
    const float sine =
        up_length > 0.0f ? glm::length(glm::cross(glm::normalize(forward), c.up / up_length)) : 0.0f;
    if (!(sine > 1e-5f)) fail(scene, "camera up must be non-zero and not parallel to the view direction");
}

void validate_lights_and_materials(const Scene& scene) {
    const glm::vec3 cc = scene.clear_color;
    if (!(in_unit_interval(cc.x) && in_unit_interval(cc.y) && in_unit_interval(cc.z))) {
        fail(scene, "clear colour components must be in [0, 1]");
    }
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& light = scene.lights[i];
        if (!finite(light.position) || !finite(light.color) || light.color.x < 0.0f || light.color.y < 0.0f ||
            light.color.z < 0.0f) {
            fail(scene, "lights[", i, "] must have a finite position and a finite colour >= 0");
        }
        if (light.type != LightType::point &&
            !(finite(light.direction) && std::abs(glm::length(light.direction) - 1.0f) < 1e-3f)) {
            fail(scene, "lights[", i, "] needs a finite direction of unit length");
        }
        if (light.type == LightType::spot &&
            !(light.inner_cone_degrees >= 0.0f && light.inner_cone_degrees < light.outer_cone_degrees &&
              light.outer_cone_degrees <= 90.0f)) {
            fail(scene, "lights[", i, "]: spot cone angles need 0 <= inner < outer <= 90 degrees");
        }
        if (!(light.range >= 0.0f) || !std::isfinite(light.range)) {
            fail(scene, "lights[", i, "]: range must be finite and >= 0 (0 = unlimited)");
        }
        if (light.shadow_map_size < kMinShadowMapSize || light.shadow_map_size > kMaxShadowMapSize) {
            fail(scene, "lights[", i, "]: shadow_map_size must be in ", kMinShadowMapSize, "..", kMaxShadowMapSize,
                 " texels, not ", light.shadow_map_size);
        }
        if (light.shadow_filter_radius < 0 || light.shadow_filter_radius > kMaxShadowFilterRadius) {
            fail(scene, "lights[", i, "]: shadow_filter_radius must be in 0..", kMaxShadowFilterRadius, ", not ",
                 light.shadow_filter_radius);
        }
    }
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        const Material& m = scene.materials[i];
        if (!(in_unit_interval(m.albedo.x) && in_unit_interval(m.albedo.y) && in_unit_interval(m.albedo.z) &&
              in_unit_interval(m.metallic) && in_unit_interval(m.roughness) && in_unit_interval(m.ao))) {
            fail(scene, "materials[", i, "]: albedo, metallic, roughness and ao must be in [0, 1]");
        }
        if (!finite(m.emissive) || m.emissive.x < 0.0f || m.emissive.y < 0.0f || m.emissive.z < 0.0f ||
            !std::isfinite(m.ao_strength) || !std::isfinite(m.normal_scale)) {
            fail(scene, "materials[", i, "]: emissive must be finite and >= 0, ao strength and normal scale finite");
        }
        for (const TextureSlot* slot : {&m.albedo_map, &m.metallic_map, &m.roughness_map, &m.ao_map, &m.normal_map,
                                        &m.emissive_map}) {
            if (slot->texture >= std::int64_t(scene.textures.size()) ||
                (slot->present() && !scene.textures[std::size_t(slot->texture)])) {
                fail(scene, "materials[", i, "] uses texture ", slot->texture, " but the scene has ",
                     scene.textures.size(), " textures");
            }
        }
        if (!in_unit_interval(m.alpha_factor) || !(m.alpha_cutoff >= 0.0f && std::isfinite(m.alpha_cutoff))) {
            fail(scene, "materials[", i, "]: alpha must be in [0, 1] and the alpha cutoff finite and >= 0");
        }
        if (m.metallic_channel < 0 || m.metallic_channel > 3 || m.roughness_channel < 0 || m.roughness_channel > 3) {
            fail(scene, "materials[", i, "]: texture channels are 0..3 (R, G, B, A)");
        }
    }
}

void validate_meshes(const Scene& scene) {
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        const std::size_t vertices = mesh.positions.size();
        const bool points_or_lines = mesh.topology != Topology::triangles;
        if (mesh.normals.size() != vertices && !(points_or_lines && mesh.normals.empty())) {
            fail(scene, mesh_label(scene, m), " has ", mesh.normals.size(), " normals for ", vertices,
                 " positions");
        }
        if (!mesh.uvs1.empty() && mesh.uvs1.size() != vertices)
            fail(scene, mesh_label(scene, m), " has ", mesh.uvs1.size(), " second-set uvs for ", vertices, " positions");
        if (!mesh.uvs.empty() && mesh.uvs.size() != vertices) {
            fail(scene, mesh_label(scene, m), " has ", mesh.uvs.size(), " uvs for ", vertices, " positions");
        }
        if (!mesh.tangents.empty() && mesh.tangents.size() != vertices) {
            fail(scene, mesh_label(scene, m), " has ", mesh.tangents.size(), " tangents for ", vertices, " positions");
        }
        if (!mesh.colors.empty() && mesh.colors.size() != vertices) {
            fail(scene, mesh_label(scene, m), " has ", mesh.colors.size(), " colours for ", vertices, " positions");
        }
        for (std::size_t v = 0; v < mesh.colors.size(); ++v) {
            const glm::vec4& c = mesh.colors[v];
            if (!(in_unit_interval(c.r) && in_unit_interval(c.g) && in_unit_interval(c.b) && in_unit_interval(c.a)))
                fail(scene, mesh_label(scene, m), " colour ", v, " is outside [0, 1]");
        }
        if (mesh.topology == Topology::triangles && mesh.indices.size() % 3 != 0) {
            fail(scene, mesh_label(scene, m), " has ", mesh.indices.size(),
                 " indices, not a multiple of 3 (three per triangle)");
        }
        if (mesh.topology == Topology::lines && mesh.indices.size() % 2 != 0) {
            fail(scene, mesh_label(scene, m), " has ", mesh.indices.size(),
                 " indices, not a multiple of 2 (two per line)");
        }
        for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
            if (mesh.indices[i] >= vertices) {
                const std::size_t per = mesh.topology == Topology::triangles ? 3 : mesh.topology == Topology::lines ? 2 : 1;
                const char* what = mesh.topology == Topology::triangles ? "triangle" : mesh.topology == Topology::lines ? "line" : "point";
                fail(scene, mesh_label(scene, m), ": index ", mesh.indices[i], " at indices[", i, "] (", what, " ",
                     i / per, ") is out of range; the mesh has ", vertices, " vertices");
            }
        }
    }
}

void validate_objects(const Scene& scene) {
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        const Object& object = scene.objects[o];
        if (object.mesh >= scene.meshes.size()) {
            fail(scene, "objects[", o, "] uses mesh ", object.mesh, " but the scene has ", scene.meshes.size(),
                 " meshes");
        }
        if (object.material >= scene.materials.size()) {
            fail(scene, "objects[", o, "] uses material ", object.material, " but the scene has ",
                 scene.materials.size(), " materials");
        }
        for (int c = 0; c < 4; ++c) {
            for (int r = 0; r < 4; ++r) {
                if (!std::isfinite(object.model[c][r])) fail(scene, "objects[", o, "] has a non-finite model matrix");
            }
        }
        // A map on the second uv set needs a mesh that has one (TextureSlot::uv_set).
        const Material& m = scene.materials[object.material];
        for (const TextureSlot* slot : {&m.albedo_map, &m.metallic_map, &m.roughness_map, &m.ao_map, &m.normal_map,
                                        &m.emissive_map}) {
            if (!slot->present() || slot->uv_set == 0) continue;
            if (slot->uv_set != 1 || scene.meshes[object.mesh].uvs1.empty())
                fail(scene, "objects[", o, "]: its material reads uv set ", slot->uv_set,
                     ", which its mesh does not have (sets: 0, and 1 where the mesh has a second set)");
        }
    }
}

}  // namespace

void validate_environment(const Scene& scene) {
    const EnvironmentLight& e = scene.environment;
    if (!(std::isfinite(e.intensity) && e.intensity >= 0.0f))
        fail(scene, "environment intensity must be finite and >= 0");
    if (!std::isfinite(e.rotation_degrees)) fail(scene, "environment rotation must be finite");
    if (!std::isfinite(scene.exposure_ev) || std::fabs(scene.exposure_ev) > 64.0f)
        fail(scene, "exposure must be a finite number of stops in [-64, 64]");
}

void validate_scene(const Scene& scene) {
    validate_size(scene);
    validate_environment(scene);
    validate_camera(scene);
    validate_lights_and_materials(scene);
    validate_meshes(scene);
    validate_objects(scene);
}

}  // namespace tessera
