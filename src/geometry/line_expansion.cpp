#include "geometry/line_expansion.hpp"

#include <cmath>
#include <cstdint>

#include "geometry/vertex_stage.hpp"

namespace tessera::geometry {
namespace {

// One end of a point or line: its clip position and what the surface carries.
struct End {
    glm::vec4 clip;
    glm::vec3 normal;  // world space, unit
    glm::vec2 uv{0.0f};
    glm::vec4 color{1.0f};
};

End lerp(const End& a, const End& b, float t) {
    return {a.clip + t * (b.clip - a.clip), glm::normalize(a.normal + t * (b.normal - a.normal)), a.uv + t * (b.uv - a.uv),
            a.color + t * (b.color - a.color)};
}

class Expander {
public:
    Expander(const Mesh& mesh, const glm::mat4& model, const Camera& camera, int width, int height)
        : mesh_(mesh), model_(model), normal_matrix_(geometry::normal_matrix(model)), camera_(camera),
          view_projection_(projection_matrix(camera, width, height) * view_matrix(camera)),
          world_from_clip_(glm::inverse(glm::dmat4(view_projection_))),
          pixel_to_ndc_(2.0f / float(width), 2.0f / float(height)) {
        out_.name = mesh.name;
        out_.topology = Topology::triangles;
    }

    Mesh run() {
        if (mesh_.topology == Topology::points) {
            for (const std::uint32_t v : mesh_.indices) point(end(v));
        } else {
            for (std::size_t i = 0; i + 1 < mesh_.indices.size(); i += 2) line(end(mesh_.indices[i]), end(mesh_.indices[i + 1]));
        }
        if (!mesh_.uvs.empty() && !out_.positions.empty()) out_.uvs = std::move(uvs_);
        if (!mesh_.colors.empty() && !out_.positions.empty()) out_.colors = std::move(colors_);
        return std::move(out_);
    }

private:
    End end(std::uint32_t v) const {
        End e;
        const glm::vec3 world = glm::vec3(model_ * glm::vec4(mesh_.positions[v], 1.0f));
        e.clip = view_projection_ * glm::vec4(world, 1.0f);
        glm::vec3 n;
        if (mesh_.normals.size() == mesh_.positions.size()) n = normal_matrix_ * mesh_.normals[v];
        else n = camera_.projection == Projection::orthographic ? camera_.position - camera_.target : camera_.position - world;
        const float length = glm::length(n);
        e.normal = length > 0.0f && std::isfinite(length) ? n / length : glm::vec3(0.0f, 0.0f, 1.0f);
        if (!mesh_.uvs.empty()) e.uv = mesh_.uvs[v];
        if (!mesh_.colors.empty()) e.color = mesh_.colors[v];
        return e;
    }

    // A corner `offset` pixels from `e` in the window, at e's depth, in world space.
    void corner(const End& e, const glm::vec2& offset) {
        const glm::vec4 clip = e.clip + glm::vec4(offset * pixel_to_ndc_ * e.clip.w, 0.0f, 0.0f);
        const glm::dvec4 world = world_from_clip_ * glm::dvec4(clip);
        out_.positions.push_back(glm::vec3(world / world.w));
        out_.normals.push_back(e.normal);
        uvs_.push_back(e.uv);
        colors_.push_back(e.color);
    }

    void quad(const End& a, const End& b, const glm::vec2& across, bool point) {
        const auto first = std::uint32_t(out_.positions.size());
        if (point) {
            corner(a, {-0.5f, -0.5f}), corner(a, {0.5f, -0.5f}), corner(a, {0.5f, 0.5f}), corner(a, {-0.5f, 0.5f});
        } else {
            corner(a, -across), corner(a, across), corner(b, across), corner(b, -across);
        }
        out_.indices.insert(out_.indices.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
    }

    static bool inside(const glm::vec4& c) {
        return c.w > 0.0f && std::abs(c.x) <= c.w && std::abs(c.y) <= c.w && std::abs(c.z) <= c.w;
    }

    void point(const End& e) {
        if (inside(e.clip)) quad(e, e, {}, true);
    }

    void line(End a, End b) {
        // Clip to near (z + w >= 0) and far (w - z >= 0): window positions need w > 0.
        float t0 = 0.0f, t1 = 1.0f;
        for (const float side : {1.0f, -1.0f}) {
            const float da = a.clip.w + side * a.clip.z, db = b.clip.w + side * b.clip.z;
            if (da < 0.0f && db < 0.0f) return;
            if (da < 0.0f) t0 = std::max(t0, da / (da - db));
            if (db < 0.0f) t1 = std::min(t1, da / (da - db));
        }
        if (!(t0 < t1)) return;
        const End ca = t0 > 0.0f ? lerp(a, b, t0) : a, cb = t1 < 1.0f ? lerp(a, b, t1) : b;
        if (!(ca.clip.w > 0.0f && cb.clip.w > 0.0f)) return;
        const glm::vec2 pa = glm::vec2(ca.clip) / ca.clip.w / pixel_to_ndc_, pb = glm::vec2(cb.clip) / cb.clip.w / pixel_to_ndc_;
        const glm::vec2 d = pb - pa;
        if (!(d.x != 0.0f || d.y != 0.0f)) return;  // zero length: no fragments
        glm::vec2 across = std::abs(d.x) >= std::abs(d.y) ? glm::vec2(0.0f, 0.5f) : glm::vec2(0.5f, 0.0f);
        // Wound counter-clockwise in the window (front-facing), so that the fragment stage never
        // takes the quad's halves for back faces and flips their normals (double-sided shading).
        if (across.x * d.y - across.y * d.x < 0.0f) across = -across;
        quad(ca, cb, across, false);
    }

    const Mesh& mesh_;
    glm::mat4 model_;
    glm::mat3 normal_matrix_;
    const Camera& camera_;
    glm::mat4 view_projection_;
    glm::dmat4 world_from_clip_;
    glm::vec2 pixel_to_ndc_;  // NDC units per pixel
    Mesh out_;
    std::vector<glm::vec2> uvs_;
    std::vector<glm::vec4> colors_;
};

}  // namespace

bool has_points_or_lines(const Scene& scene) {
    for (const Object& object : scene.objects)
        if (object.mesh < scene.meshes.size() && scene.meshes[object.mesh].topology != Topology::triangles) return true;
    return false;
}

Mesh expand_to_triangles(const Mesh& mesh, const glm::mat4& model, const Camera& camera, int width, int height) {
    return Expander(mesh, model, camera, width, height).run();
}

void expand_points_and_lines(const Scene& scene, Scene& drawn) {
    drawn = scene;
    for (Object& object : drawn.objects) {
        const Mesh& mesh = scene.meshes[object.mesh];
        if (mesh.topology == Topology::triangles) continue;
        drawn.meshes.push_back(expand_to_triangles(mesh, object.model, scene.camera, scene.width, scene.height));
        Material material = scene.materials[object.material];
        material.double_sided = true;
        // glTF: points and lines without normals SHOULD be drawn unlit (base colour as shown).
        if (mesh.normals.empty()) material.unlit = true;
        drawn.materials.push_back(material);
        object = Object{std::uint32_t(drawn.meshes.size() - 1), std::uint32_t(drawn.materials.size() - 1), glm::mat4(1.0f),
                        object.id};  // the object_id AOV stays the scene's
    }
}

}  // namespace tessera::geometry
