// The scene: what is drawn, from where, under which lights. Everything the
// pipeline needs, already validated: the later stages trust these values.
#pragma once

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace tessera {

// Limits on what a scene may ask for, named in one place.
inline constexpr int kMaxImageDimension = 16384;  // pixels, per side
inline constexpr long long kMaxImagePixels = 1LL << 27;  // width × height: 134M pixels, ~2 GB of frame at 15 B/pixel

// The reference shader's material inputs (untextured demo).
struct Material {
    glm::vec3 albedo{0.5f, 0.0f, 0.0f};  // linear RGB reflectance, each in [0, 1]
    float metallic = 0.0f;                // [0, 1]
    float roughness = 0.5f;               // [0, 1]; GGX alpha = roughness²
    float ao = 1.0f;                      // ambient occlusion, [0, 1]
};

// A point light: radiance arriving at distance d is color / d² (the reference's
// inverse-square falloff), so color is in radiance·distance² units.
struct PointLight {
    glm::vec3 position{0.0f};  // world space
    glm::vec3 color{1.0f};     // linear RGB, >= 0
};

// A perspective camera, as glm::perspective and glm::lookAt take it.
struct Camera {
    glm::vec3 position{0.0f, 0.0f, 3.0f};  // world space; also the shader's camPos
    glm::vec3 target{0.0f};                // world space point looked at
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fov_y_degrees = 45.0f;           // vertical field of view, (0, 180)
    float near_plane = 0.1f;               // view-space distances, 0 < near < far
    float far_plane = 100.0f;
};

// An indexed triangle mesh in object space; positions, normals and uvs run in parallel.
struct Mesh {
    std::string name;
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> uvs;
    std::vector<std::uint32_t> indices;  // three per triangle, each < positions.size()
};

// One placed instance of a mesh.
struct Object {
    std::uint32_t mesh = 0;      // index into Scene::meshes
    std::uint32_t material = 0;  // index into Scene::materials
    glm::mat4 model{1.0f};       // object -> world
};

struct Scene {
    std::string source;  // where the scene came from, for messages
    int width = 1280;    // output size in pixels, 1..kMaxImageDimension
    int height = 720;
    glm::vec3 clear_color{0.1f, 0.1f, 0.1f};  // display-referred, as glClearColor
    Camera camera;
    std::vector<PointLight> lights;
    std::vector<Material> materials;
    std::vector<Mesh> meshes;
    std::vector<Object> objects;
};

// A scene file that cannot be used. what() reads "file:line:column: message"
// (or "file: message" where no position applies).
class SceneError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Reads and validates a TOML scene file; throws SceneError.
Scene load_scene_file(const std::filesystem::path& path);
// The same from text in memory; source_name stands for the file in messages.
Scene parse_scene(std::string_view toml_text, std::string_view source_name);

// Built-in meshes.
Mesh make_sphere_mesh();  // the reference's 64×64 UV sphere, radius 1
Mesh make_plane_mesh();   // 2×2 square in the XZ plane at y = 0, normal +Y, uv over [0,1]²
Mesh make_cube_mesh();    // 2×2×2 cube centred on the origin, flat normals, 24 vertices

// The camera's matrices with OpenGL conventions (right-handed view, clip z in [-w, w]).
glm::mat4 view_matrix(const Camera& camera);
glm::mat4 projection_matrix(const Camera& camera, int width, int height);

}  // namespace tessera
