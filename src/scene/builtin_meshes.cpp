// The built-in meshes a scene file can name: "sphere", "plane", "cube".
#include <array>
#include <cmath>
#include <cstdint>

#include "tessera/scene.hpp"

namespace tessera {

// The reference demo's UV sphere, computed exactly as its C++ code does (in
// float, with the same operation order), so positions match it bit for bit.
// The reference's triangles (i0, i1, i2) and (i0, i2, i3) are clockwise when
// seen from outside (it draws without face culling); here each has corners 1
// and 2 swapped, counter-clockwise from outside, so that the outside is the
// front face: culled when single-sided, and not a back face whose normal a
// double-sided material flips. Triangle setup orders corners 1 and 2 by the
// sign of the area, so it makes the same records either way: the images are
// the reference's bit for bit. The first row of triangles touching each pole
// is degenerate (two corners at the pole), also as in the reference.
Mesh make_sphere_mesh() {
    constexpr std::uint32_t kSegmentsX = 64;
    constexpr std::uint32_t kSegmentsY = 64;
    constexpr float kPi = 3.14159265359f;  // the reference shader's PI

    Mesh mesh;
    mesh.name = "sphere";
    const std::size_t vertex_count = std::size_t{kSegmentsX + 1} * (kSegmentsY + 1);
    mesh.positions.reserve(vertex_count);
    mesh.normals.reserve(vertex_count);
    mesh.uvs.reserve(vertex_count);
    for (std::uint32_t y = 0; y <= kSegmentsY; ++y) {
        for (std::uint32_t x = 0; x <= kSegmentsX; ++x) {
            const float x_segment = static_cast<float>(x) / static_cast<float>(kSegmentsX);
            const float y_segment = static_cast<float>(y) / static_cast<float>(kSegmentsY);
            const float x_pos = std::cos(x_segment * 2.0f * kPi) * std::sin(y_segment * kPi);
            const float y_pos = std::cos(y_segment * kPi);
            const float z_pos = std::sin(x_segment * 2.0f * kPi) * std::sin(y_segment * kPi);
            mesh.positions.emplace_back(x_pos, y_pos, z_pos);
            mesh.normals.emplace_back(x_pos, y_pos, z_pos);
            mesh.uvs.emplace_back(x_segment, y_segment);
        }
    }

    mesh.indices.reserve(std::size_t{kSegmentsX} * kSegmentsY * 6);
    for (std::uint32_t y = 0; y < kSegmentsY; ++y) {
        for (std::uint32_t x = 0; x < kSegmentsX; ++x) {
            const std::uint32_t i0 = y * (kSegmentsX + 1) + x;
            const std::uint32_t i1 = (y + 1) * (kSegmentsX + 1) + x;
            const std::uint32_t i2 = (y + 1) * (kSegmentsX + 1) + x + 1;
            const std::uint32_t i3 = y * (kSegmentsX + 1) + x + 1;
            mesh.indices.insert(mesh.indices.end(), {i0, i2, i1, i0, i3, i2});
        }
    }
    return mesh;
}

namespace {

// Appends the square face centre ± right ± up with normal n = right × up, as
// two triangles counter-clockwise seen from the side n points to. Texture
// coordinates follow glTF's convention (uv (0, 0) is the image's top-left
// texel as the file stores it, v grows downwards): u runs along `right` and
// v against `up`, so an image reads upright, not mirrored, seen from outside
// with `up` pointing up the screen.
void add_quad(Mesh& mesh, glm::vec3 centre, glm::vec3 right, glm::vec3 up) {
    const glm::vec3 normal = glm::cross(right, up);
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    constexpr std::array<glm::vec2, 4> kCorners{{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}};
    for (const glm::vec2 corner : kCorners) {
        mesh.positions.push_back(centre + corner.x * right + corner.y * up);
        mesh.normals.push_back(normal);
        mesh.uvs.emplace_back((corner.x + 1.0f) * 0.5f, (1.0f - corner.y) * 0.5f);
    }
    mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

}  // namespace

Mesh make_plane_mesh() {
    Mesh mesh;
    mesh.name = "plane";
    // Seen from above with -Z up the screen (a camera in front, looking down):
    // the image's top edge lies along -Z, its left edge along -X. Normal +Y;
    // the same layout as the cube's top face.
    add_quad(mesh, {0, 0, 0}, {1, 0, 0}, {0, 0, -1});
    return mesh;
}

Mesh make_cube_mesh() {
    Mesh mesh;
    mesh.name = "cube";
    // One quad per face, (right, up) as seen from outside, right × up pointing
    // outwards. The four sides are upright (+Y up); the top reads upright
    // with its top edge at the back (-Z), the bottom with its top edge at the
    // front (+Z), as in the usual cross-shaped unfolding around the front face.
    add_quad(mesh, {1, 0, 0}, {0, 0, -1}, {0, 1, 0});   // +X
    add_quad(mesh, {-1, 0, 0}, {0, 0, 1}, {0, 1, 0});   // -X
    add_quad(mesh, {0, 1, 0}, {1, 0, 0}, {0, 0, -1});   // +Y
    add_quad(mesh, {0, -1, 0}, {1, 0, 0}, {0, 0, 1});   // -Y
    add_quad(mesh, {0, 0, 1}, {1, 0, 0}, {0, 1, 0});    // +Z
    add_quad(mesh, {0, 0, -1}, {-1, 0, 0}, {0, 1, 0});  // -Z
    return mesh;
}

}  // namespace tessera
