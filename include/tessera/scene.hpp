// The scene: what is drawn, from where, under which lights. Everything the
// pipeline needs, already validated: the later stages trust these values.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace tessera {

// Opaque here (the library's own types, never needed to use a Scene): a texture image with its
// mip chain, and a glTF file's nodes, skins, morph targets and animations.
namespace texture {
class Texture;
}
struct GltfRig;
namespace environment {
struct EnvironmentMaps;  // environment/precompute.hpp: the IBL maps of one equirectangular image
}
struct Animation;  // tessera/animation.hpp: what changes from frame to frame

// Limits on what a scene may ask for, named in one place.
inline constexpr int kMaxImageDimension = 16384;  // pixels, per side
inline constexpr long long kMaxImagePixels = 1LL << 27;  // width × height: 134M pixels, ~2 GB of frame at 15 B/pixel

// How a texture map extends past [0, 1], per axis: GL_REPEAT, GL_CLAMP_TO_EDGE
// or GL_MIRRORED_REPEAT.
enum class TextureWrap { repeat, clamp_to_edge, mirrored_repeat };
// GL's magnification (nearest, linear) and minification (all six) filters.
enum class TextureFilter { nearest, linear, nearest_mipmap_nearest, linear_mipmap_nearest, nearest_mipmap_linear,
                           linear_mipmap_linear };

// A material's use of one texture: which image, how it is sampled (a GL
// sampler: texture/texture.hpp, Sampler), and which texture coordinates it reads.
struct TextureSlot {
    std::int32_t texture = -1;  // index into Scene::textures; -1 = no map
    TextureWrap wrap_s = TextureWrap::repeat;  // along u
    TextureWrap wrap_t = TextureWrap::repeat;  // along v
    TextureFilter mag_filter = TextureFilter::linear;
    TextureFilter min_filter = TextureFilter::linear_mipmap_linear;
    // 0: Mesh::uvs, 1: Mesh::uvs1 (which the mesh must then have). Then, where
    // uv_transformed, uv' = uv_transform·(u, v, 1) (glTF KHR_texture_transform, column-major).
    int uv_set = 0;
    bool uv_transformed = false;
    glm::mat3 uv_transform{1.0f};
    bool present() const { return texture >= 0; }
    // Reads uvs as they are: set 0, untransformed (the material pass's fast path).
    bool plain_uvs() const { return uv_set == 0 && !uv_transformed; }
};

// How a material's albedo map turns into linear albedo.
enum class AlbedoDecode {
    // The texels are linear already (the texture was decoded from sRGB at load,
    // before filtering, as GL does for GL_SRGB8 textures: glTF base colour).
    linear,
    // The reference's textured demo: pow(texture(albedoMap, uv).rgb, 2.2),
    // the power applied after filtering the stored values.
    pow_2_2_after_filter,
};

// Where a normal map's tangent frame comes from when the mesh stores no
// tangents: both derive it from screen-space derivatives of WorldPos and
// TexCoords.
enum class DerivedTangentFrame {
    // The reference's getNormalFromMap (LearnOpenGL): T = normalize(Q1·st2.t − Q2·st1.t),
    // B = −normalize(cross(N, T)).
    learnopengl,
    // glTF's convention: T along +u, B along −v (green up, UV origin at the
    // image's top-left), whatever the handedness of the mesh's UV layout.
    gltf,
};

// What a material's alpha does (glTF alphaMode). The reference shader is opaque.
enum class AlphaMode : std::uint8_t {
    opaque,  // alpha ignored
    mask,    // a fragment whose alpha < alpha_cutoff is discarded before the depth write
    // Drawn after the opaque geometry, objects back to front, each fragment
    // tested against the opaque depth (no depth write) and composited "over" in
    // scene-linear radiance: src·alpha + dst·(1 − alpha) (src/image/blend.hpp).
    blend,
};

// The reference shader's material inputs. Each map multiplies the factor
// it belongs to (glTF's rule): a scene file that gives a map and no factor
// gets factor 1.
struct Material {
    glm::vec3 albedo{0.5f, 0.0f, 0.0f};  // linear RGB reflectance, each in [0, 1]
    float metallic = 0.0f;                // [0, 1]
    float roughness = 0.5f;               // [0, 1]; GGX alpha = roughness²
    float ao = 1.0f;                      // ambient occlusion, [0, 1]
    glm::vec3 emissive{0.0f};             // HDR radiance added to the shaded colour, >= 0

    TextureSlot albedo_map{};     // RGB
    AlbedoDecode albedo_decode = AlbedoDecode::linear;
    TextureSlot metallic_map{};   // channel metallic_channel
    int metallic_channel = 0;   // 0..3 = R, G, B, A (glTF: B)
    TextureSlot roughness_map{};  // channel roughness_channel
    int roughness_channel = 0;  // (glTF: G)
    TextureSlot ao_map{};         // R; ao = 1 + ao_strength·(texel − 1)
    float ao_strength = 1.0f;
    TextureSlot normal_map{};     // tangent-space normals, RGB = xyz·0.5 + 0.5
    float normal_scale = 1.0f;  // scales the map's x and y (glTF normalTexture.scale)
    DerivedTangentFrame derived_tangent_frame = DerivedTangentFrame::learnopengl;
    TextureSlot emissive_map{};   // RGB, multiplies `emissive`

    // false: back faces are culled, glTF's rule (front = counter-clockwise in
    // window space after the object's transform; a model matrix with a
    // negative determinant makes clockwise the front). true draws both sides;
    // a back face is shaded with its normal and tangent frame negated (glTF's
    // rule, for every scene), so it is lit from the side it shows.
    bool double_sided = true;

    // Alpha = alpha_factor × albedo map's alpha (where mapped) × the mesh's colour alpha (where
    // it has Mesh::colors). glTF's baseColorFactor[3], baseColorTexture's alpha and COLOR_0's;
    // AlphaMode::mask and AlphaMode::blend use it.
    AlphaMode alpha_mode = AlphaMode::opaque;
    float alpha_factor = 1.0f;  // [0, 1]
    float alpha_cutoff = 0.5f;  // mask: discarded below this; finite, >= 0 (glTF's default 0.5)

    // KHR_materials_unlit: no lighting; the albedo (× its map × the vertex
    // colour) is the colour shown, as glTF viewers draw it: the fragment's
    // radiance is the one the display encoding turns into that colour
    // (shade::radiance_for_display), so the tone curve leaves it as it is.
    // Metallic, roughness, ao, normal and emissive are not used.
    bool unlit = false;

    bool has_maps() const {
        return albedo_map.present() || metallic_map.present() || roughness_map.present() || ao_map.present() ||
               normal_map.present() || emissive_map.present();
    }
};

enum class LightType { point, directional, spot };

// Shadow map limits (Light::shadow_map_size, shadow_filter_radius).
inline constexpr int kMinShadowMapSize = 16;
inline constexpr int kMaxShadowMapSize = 8192;
inline constexpr int kDefaultShadowMapSize = 1024;  // the chapters' SHADOW_WIDTH
inline constexpr int kMaxShadowFilterRadius = 8;
inline constexpr int kDefaultShadowFilterRadius = 1;
// What a frame's shadow maps may take together (4 bytes per texel, six faces
// for a point light, whose cube also keeps 2 floats per 4×4 texels of
// summaries): the renderer refuses more.
inline constexpr std::uint64_t kMaxShadowMapBytes = std::uint64_t(2) << 30;

// A light (docs/reference/pbr_lighting.md). Point and spot lights fall off with the
// inverse square of distance: radiance arriving at distance d is color / d², so
// color is in radiance·distance² units; a directional light's color is the
// radiance itself, arriving along `direction` everywhere.
struct Light {
    glm::vec3 position{0.0f};              // world space; point and spot
    glm::vec3 color{1.0f};                 // linear RGB, >= 0
    LightType type = LightType::point;
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  // where the light travels, unit length; directional and spot
    // Spot cone half-angles in degrees, 0 <= inner < outer <= 90: full radiance
    // inside `inner`, none outside `outer`, the reference's clamp ramp of cos θ between.
    float inner_cone_degrees = 0.0f;
    float outer_cone_degrees = 45.0f;
    // Distance past which this light adds nothing, a hard cut per visible point
    // (with RenderSettings::light_culling, the default): a promise by the scene
    // that the light adds next to nothing farther away, which lets light
    // culling skip it wherever no point is within range. Points within range
    // get the light in full. 0 = unlimited, never culled. Point and spot only.
    float range = 0.0f;
    // Shadow mapping (docs/scene-format.md, src/shade/shadow_maps.hpp): the
    // light's direct contribution is multiplied by how much of it a depth map
    // rendered from the light sees reach the point. Directional and spot lights
    // take one square map of shadow_map_size² texels, point lights a cube of
    // six; shadow_filter_radius r filters with (2r + 1)² texels (the chapter's
    // PCF is r = 1) or, for point lights, r × the chapter's 20-sample disk (0:
    // a single sample).
    bool shadows = false;
    int shadow_map_size = kDefaultShadowMapSize;        // kMinShadowMapSize..kMaxShadowMapSize
    int shadow_filter_radius = kDefaultShadowFilterRadius;  // 0..kMaxShadowFilterRadius
};

// The irradiance below which a light counts as negligible for range = "auto":
// the range is where the light's brightest channel, color / d², falls to this.
// A larger threshold lets the many culled tails of a scene of many lights add
// up to visible steps; tests/render/test_light_culling.cpp holds
// scenes/many_lights.toml within 0.2% of 8-bit values more than a step off the
// uncut image. Glints of far lights on mirror-like surfaces magnify any
// threshold: those single pixels can differ a lot.
inline constexpr float kAutoRangeIrradiance = 1.0f / 4096.0f;

// range = "auto" for a point or spot light of this colour: sqrt(max(color) / kAutoRangeIrradiance).
// Never 0 (which would mean unlimited): a black light gets the smallest range.
float auto_light_range(const glm::vec3& color);

// How a camera projects: glm::perspective's frustum, or glTF's orthographic box.
enum class Projection : std::uint8_t { perspective, orthographic };

// A camera, as glm::lookAt and glm::perspective (or glTF's orthographic matrix) take it.
struct Camera {
    glm::vec3 position{0.0f, 0.0f, 3.0f};  // world space; also the shader's camPos
    glm::vec3 target{0.0f};                // world space point looked at
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fov_y_degrees = 45.0f;           // vertical field of view, (0, 180)
    float near_plane = 0.1f;               // view-space distances, 0 < near < far
    float far_plane = 100.0f;
    // Orthographic: the view box's half-width and half-height in world units
    // (glTF's xmag, ymag; > 0), mapped to the image's edges whatever its aspect,
    // and fov_y_degrees unused.
    Projection projection = Projection::perspective;
    float x_magnification = 1.0f;
    float y_magnification = 1.0f;
    // A camera given as matrices instead (intrinsics K and an extrinsic, as the
    // Python module's Camera.from_intrinsics makes them): when set, view_matrix()
    // and projection_matrix() return these (`projection` below is then unused), for any image size. position (the
    // shader's camPos), target and up must still describe the same camera.
    bool explicit_matrices = false;
    glm::mat4 explicit_view{1.0f};        // world -> view space, OpenGL's: looking along -Z, +Y up
    glm::mat4 explicit_projection{1.0f};  // view -> clip space, OpenGL's: clip z in [-w, w]
};

// What a mesh's indices draw. Points and lines (glTF modes 0..3; loops and strips
// become line lists at import) are drawn as GL draws them at size and width 1,
// expanded each frame into screen-space quads of triangles (src/geometry/line_expansion.hpp).
enum class Topology : std::uint8_t {
    triangles,  // three indices per triangle
    points,     // one index per point
    lines,      // two indices per segment
};

// An indexed mesh in object space (triangles, or points or lines); positions,
// normals and uvs run in parallel.
struct Mesh {
    std::string name;
    Topology topology = Topology::triangles;
    std::vector<glm::vec3> positions;
    // One per position. Points and lines may have none: glTF draws those unlit,
    // and so does line_expansion.cpp (the material's unlit path).
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> uvs;            // empty, or one per position; (0, 0) = top-left of a texture
    std::vector<glm::vec2> uvs1;           // a second set (TextureSlot::uv_set 1): empty, or one per position
    std::vector<glm::vec4> tangents;       // empty, or one per position: xyz and handedness w = ±1 (glTF TANGENT)
    std::vector<std::uint32_t> indices;  // three per triangle (one per point, two per line), each < positions.size()
    // Added for vertex colours (glTF COLOR_0): empty, or one per position, linear RGBA in
    // [0, 1] (alpha 1 where the file gives RGB). RGB multiplies the material's albedo and
    // its map, alpha its alpha; interpolated perspective-correctly like the uvs.
    std::vector<glm::vec4> colors;
};

// One placed instance of a mesh.
struct Object {
    std::uint32_t mesh = 0;      // index into Scene::meshes
    std::uint32_t material = 0;  // index into Scene::materials
    glm::mat4 model{1.0f};       // object -> world
    // The object_id AOV's value: what a person calls one object, so that its
    // pixels form one mask. The loaders give one id per TOML [[objects]] or
    // [[models]] entry (all of a model's meshes share it), in file order from 1,
    // and, for a glTF file loaded as the scene, one per node that places a mesh
    // (all the mesh's primitives share it), in the scene's node order from 1.
    // 0 = none given: the renderer uses the object's index + 1.
    std::uint32_t id = 0;
};

// A glTF model in the scene that can be posed (it has skins, morph targets or
// animations): its meshes and objects are recomputed from the rig's rest data
// by set_scene_frame and set_scene_time (tessera/animation.hpp).
struct PosedGltfModel {
    std::shared_ptr<const GltfRig> rig;
    std::uint32_t first_mesh = 0;    // its meshes are Scene::meshes[first_mesh + GltfContent mesh index]
    std::uint32_t first_object = 0;  // and its objects Scene::objects[first_object + ...]
    glm::mat4 placement{1.0f};       // world = placement × the file's world space
    // The animation frames play ([[models]].animation, or --frames on a glTF
    // file): index into the rig's animations; -1 = none (the model keeps its pose).
    int animation = -1;
    // At frame f the animation is at start_seconds + speed · f / fps seconds;
    // with loop, wrapped into [0, duration).
    double start_seconds = 0.0;
    double speed = 1.0;
    bool loop = false;
};

// Image-based lighting (docs/reference/ibl_lighting.md): an equirectangular
// HDR image lights every surface through LearnOpenGL's split-sum ambient term,
// in place of the reference's 0.03·albedo·ao, and may be shown behind the scene.
struct EnvironmentLight {
    std::shared_ptr<const environment::EnvironmentMaps> maps;  // null: no environment (the reference look)
    std::string file;               // where the image came from, for messages
    float intensity = 1.0f;         // scales the image's radiance; finite, >= 0
    float rotation_degrees = 0.0f;  // turns the image about +Y (right-handed); finite
    bool background = true;         // shown where no surface is (else the clear colour)
    bool present() const { return maps != nullptr; }
};

struct Scene {
    std::string source;  // where the scene came from, for messages
    int width = 1280;    // output size in pixels, 1..kMaxImageDimension
    int height = 720;
    glm::vec3 clear_color{0.1f, 0.1f, 0.1f};  // display-referred, as glClearColor
    // Samples per pixel: 1, or 4 for 4× MSAA (GL's sample pattern, shading
    // once per pixel and triangle; see src/raster/msaa/msaa.hpp). A property of the
    // output like its size, so it lives here; the CLI's --msaa overrides it.
    int msaa = 1;
    Camera camera;
    std::vector<Light> lights;
    // The lights are default_light_rig's (a glTF file with none of its own):
    // the CLI's default look replaces them.
    bool default_lights = false;
    EnvironmentLight environment;
    // Radiance is scaled by 2^exposure_ev before tonemapping (and in the EXR);
    // 0 leaves every value untouched. Finite.
    float exposure_ev = 0.0f;
    std::vector<Material> materials;
    std::vector<std::shared_ptr<const texture::Texture>> textures;  // what TextureSlot::texture indexes
    std::vector<Mesh> meshes;
    std::vector<Object> objects;
    // A scene file's [animation], or null for a still scene. The values above
    // are those of the current frame (frame 0 as loaded); set_scene_frame
    // (tessera/animation.hpp) moves the scene to another.
    std::shared_ptr<const Animation> animation;
    // glTF models with skins, morph targets or animations (gltf-animation):
    // what set_scene_frame and set_scene_time pose. Empty for other scenes.
    std::vector<PosedGltfModel> posed_models;
};

// A scene file that cannot be used. what() reads "file:line:column: message"
// (or "file: message" where no position applies).
class SceneError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Reads and validates a TOML scene file, or a .gltf/.glb file as a whole scene
// (src/scene/gltf/gltf_import.hpp); throws SceneError. gltf_camera (the CLI's
// --camera NAME|INDEX) picks a glTF file's camera; a TOML file refuses it.
Scene load_scene_file(const std::filesystem::path& path, const std::string& gltf_camera = "");
// The same from text in memory; source_name stands for the file in messages.
Scene parse_scene(std::string_view toml_text, std::string_view source_name);

// Built-in meshes.
Mesh make_sphere_mesh();  // the reference's 64×64 UV sphere, radius 1
Mesh make_plane_mesh();   // 2×2 square in the XZ plane at y = 0, normal +Y, uv over [0,1]²
Mesh make_cube_mesh();    // 2×2×2 cube centred on the origin, flat normals, 24 vertices

// The camera's matrices with OpenGL conventions (right-handed view, clip z in [-w, w]).
// An orthographic camera's projection is glTF's (spec §3.10.3): diag(1/xmag, 1/ymag,
// 2/(near − far)), z offset (far + near)/(near − far), w = 1; width and height unused.
glm::mat4 view_matrix(const Camera& camera);
glm::mat4 projection_matrix(const Camera& camera, int width, int height);

}  // namespace tessera
