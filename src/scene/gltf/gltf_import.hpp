// glTF 2.0 import: a .gltf (JSON with external or data-URI buffers and images)
// or a .glb file becomes meshes, materials, textures, placed objects, lights and
// a camera, ready to append to a Scene. Parsing is tinygltf's; every accessor,
// buffer view and index is checked here before it is read, so a bad file ends in
// a SceneError "file: what is wrong (which accessor, mesh, image...)", never a crash.
//
// What is read, and how:
// - The default scene (`scene`), else scene 0, else every root node. World
//   transform = parent × (matrix, or T·R·S). Each node with a mesh places one
//   Object per primitive; a mesh used by several nodes is converted once.
//   EXT_mesh_gpu_instancing: one more Object per instance (world × T·R·S of
//   its TRANSLATION, ROTATION, SCALE), all drawing the one converted mesh.
// - Primitives: TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN (turned into triangle
//   lists); POINTS, and LINES, LINE_STRIP, LINE_LOOP (turned into line lists),
//   as Mesh::topology says (LINES with an odd vertex count are skipped and
//   counted in GltfContent::skipped_primitives). Indexed (u8, u16, u32) or not.
//   POSITION (required), NORMAL and TANGENT as float, TEXCOORD_n (the set the
//   material's maps read) as float or normalized u8/u16, COLOR_0 (VEC3/VEC4,
//   float or normalized u8/u16, into Mesh::colors: it multiplies the base
//   colour and its alpha; floats clamped to [0, 1], NaN refused); with
//   KHR_mesh_quantization in extensionsUsed also the extension's types
//   (positions and uvs: 8/16-bit integers, normalized or not; normals and
//   tangents: normalized i8/i16). Without NORMAL the primitive gets
//   flat normals, as glTF requires (its vertices are split per triangle).
//   Accessors (gltf_accessors.hpp): sparse ones get their substitutions, ones
//   without a buffer view are zeros (at most kMaxImplicitElements elements).
//   Compressed geometry is decoded right after parsing (gltf_compression.hpp):
//   EXT_ and KHR_meshopt_compression buffer views (every mode and filter, both
//   attribute codec versions; fallback buffers are never read) and
//   KHR_draco_mesh_compression primitives.
// - Skins, morph targets and animations: gltf_animation.hpp (GltfContent::rig).
//   A node with a skin or a morphed mesh gets its own copy of the mesh, posed on
//   the CPU at the rest pose (the nodes' own TRS and weights); skinned objects'
//   model matrix is the identity (the spec ignores a skinned mesh's node).
// - Materials (pbrMetallicRoughness): baseColorFactor.rgb × baseColorTexture
//   (sRGB); metallic/roughnessFactor × metallicRoughnessTexture (B and G of one
//   linear texture); occlusionTexture (R, strength); normalTexture (scale);
//   emissiveFactor × emissiveTexture (sRGB), × KHR_materials_emissive_strength.
//   doubleSided false (the default) culls back faces (Material::double_sided);
//   true draws them with the normal and tangent frame flipped (lit from their side).
//   alphaMode MASK: alpha = baseColorFactor[3] × baseColorTexture's alpha × COLOR_0's
//   alpha; a fragment below alphaCutoff is discarded (Material::alpha_mode). BLEND:
//   that alpha composites the primitive over what lies behind it, drawn after the
//   opaque ones, back to front (AlphaMode::blend, src/image/blend.hpp). OPAQUE
//   ignores alpha; it is straight (colour never multiplied by it).
//   KHR_materials_unlit: the base colour is shown as is (Material::unlit). Material
//   extensions that change shading beyond the reference (transmission, volume,
//   clearcoat, sheen, specular, ior, iridescence, anisotropy) are ignored with one
//   warning each. A primitive without a material gets glTF's default (white,
//   metallic 1, roughness 1).
// - Textures: one Texture per (image, colour space), only for images materials
//   use, decoded in parallel (Texture::decode: PNG, JPEG, WebP, AVIF, straight to
//   RGBA8, sRGB maps kept encoded); EXT_texture_webp's and EXT_texture_avif's
//   source wins over the texture's own. KHR_texture_basisu (KTX2) alone is
//   refused, saying how to convert it. Each map reads TEXCOORD_<texCoord>, transformed
//   by its KHR_texture_transform (offset, rotation, scale, texCoord): baked into
//   the uvs when all of a material's maps agree, else per map when sampling
//   (a second set in Mesh::uvs1; gltf_materials.hpp: MaterialUvs). A map on a set
//   the primitive lacks is refused; a primitive with no TEXCOORD_n reads uv 0.
//   Samplers: wrapS and wrapT (REPEAT, CLAMP_TO_EDGE, MIRRORED_REPEAT), magFilter
//   and minFilter as GL defines them (default LINEAR, LINEAR_MIPMAP_LINEAR); other
//   values are refused. glTF's UV origin (top-left) is Texture's: no flip.
// - Cameras: the first perspective camera met in the node walk (depth first,
//   in node order), or the one --camera NAME|INDEX selects. It looks down its node's -Z with +Y up; yfov, znear, zfar
//   (absent = infinite: a far plane past the model's bounds is chosen) and
//   aspectRatio (kept in GltfCamera; 0 when absent). Orthographic cameras keep
//   xmag, ymag, znear, zfar (glTF's matrix, projection_matrix) and ask for the
//   aspect xmag / ymag. A first camera no node places is skipped with a warning.
// - KHR_lights_punctual: point, spot and directional lights on nodes. Light::color
//   = color × intensity, used as is: glTF's candela (point, spot) is taken as
//   our radiance·distance² and lux (directional) as radiance, with no 4π or 683
//   factors. Spot cone angles: radians to degrees; direction = the node's -Z.
//   range -> Light::range (absent = 0 = unlimited).
// - Extensions (gltf_extensions.hpp): a file requiring one not supported is
//   refused, naming it; one only used is ignored with a warning.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/framing.hpp"
#include "tessera/scene.hpp"

namespace tessera {

struct GltfCamera {
    Camera camera;             // world space
    float aspect_ratio = 0.0f;  // width / height the file asks for; 0 = not given
};

// One entry of the file's `cameras` array, where the node walk first placed it.
struct PlacedGltfCamera {
    std::string name;                // the camera's name, or else its node's
    std::string type;                // "perspective" or "orthographic"
    std::optional<GltfCamera> view;  // where a node placed it; else none
};

// What one glTF file holds, in its own index space: Object::mesh and ::material
// and TextureSlot::texture index the vectors here.
struct GltfContent {
    std::vector<Mesh> meshes;
    std::vector<Material> materials;
    std::vector<std::shared_ptr<const texture::Texture>> textures;
    std::vector<Object> objects;  // model = the node's world transform
    std::vector<Light> lights;    // world space
    std::optional<GltfCamera> camera;     // the first perspective camera met in the node walk
    std::vector<PlacedGltfCamera> cameras;  // one per entry of the file's `cameras`, in its order
    Bounds bounds;                // world box of every object
    int skipped_primitives = 0;   // primitives not drawn: LINES with an odd vertex count
    // One line each, without the file name: what was ignored (extensions the
    // file uses that are not supported). import_gltf_file prints them.
    std::vector<std::string> warnings;
    // Skins, morph targets and animations (gltf_animation.hpp), with meshes and
    // objects above at the rest pose; null when nothing in the file can move.
    std::shared_ptr<const GltfRig> rig;
};

bool external_uris_allowed();

struct GltfReadOptions {
    // Whether external buffers and images (URIs naming files) are read, relative
    // to base_dir. Off for the fuzzer, which must not read the machine's files.
    bool read_external_files = true;
    // Whether a URI may name a file outside the model's folder: an absolute
    // path, a ../ traversal (also percent-encoded), or a symbolic link leading
    // out. Refused by default, so a model file cannot make us read (and draw)
    // the machine's other files; data: URIs are always allowed, other schemes
    // (file://, http://) never. Default: external_uris_allowed().
    bool allow_external_uris = external_uris_allowed();
};

// The process's default for GltfReadOptions::allow_external_uris: false until
// the CLI's --allow-external-uris sets it.
bool external_uris_allowed();
void set_external_uris_allowed(bool allowed);

// Reads a .gltf or .glb file (told apart by the "glTF" magic, not the name),
// printing each warning to stderr as "tessera: warning: FILE: ...".
GltfContent import_gltf_file(const std::filesystem::path& path, const GltfReadOptions& options = {});

// Wall time of glTF imports in this process, for `tessera render --stats`
// (texture::build_times() splits the image stage by thread time).
struct GltfImportTimes {
    std::atomic<std::int64_t> file_read_ns{0};  // the .gltf/.glb file (import_gltf_file)
    std::atomic<std::int64_t> parse_ns{0};      // tinygltf (which also reads external buffers and image files), and decoding Draco/meshopt geometry
    std::atomic<std::int64_t> convert_ns{0};    // the node walk: meshes, materials, lights
    std::atomic<std::int64_t> images_ns{0};     // decoding and mip-mapping the images, all threads
};
GltfImportTimes& gltf_import_times();
// The same from bytes in memory; `source` names the file in messages, and
// external files resolve against base_dir.
GltfContent import_gltf(std::span<const std::uint8_t> bytes, const std::string& source,
                        const std::filesystem::path& base_dir, const GltfReadOptions& options = {});

// True for a path ending in .gltf or .glb (any case).
bool is_gltf_path(const std::filesystem::path& path);

// Appends the content's meshes, materials, textures and objects to `scene`,
// with `placement` applied before each object's own transform (world =
// placement × node world). Its lights too when with_lights, moved the same way.
// The camera is not used. Indices are shifted to the scene's.
void append_gltf_content(Scene& scene, const GltfContent& content, const glm::mat4& placement, bool with_lights);

// A scene showing one glTF file on its own: 1280 pixels wide; the file's camera
// (height = round(1280 / aspectRatio) when it gives one, else 720) or
// framing_camera; the file's lights or default_light_rig. Validated.
// camera_selector (the CLI's --camera): empty for the first perspective camera,
// else an index into the file's cameras or a camera's name (a node's name for
// an unnamed camera); a selector naming no camera placed in the
// scene is a SceneError listing the cameras there are.
Scene make_gltf_scene(const GltfContent& content, const std::string& source, const std::string& camera_selector = "");

}  // namespace tessera
