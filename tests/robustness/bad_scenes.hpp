// The table of bad scene files shared by the parser test (parse_scene in
// process) and the command-line test (the tessera binary on a file): each row
// is a scene text and what its error message must contain. "@" in `expected`
// stands for the file name, so rows can pin the line and column ("@:3:9:").
#pragma once

#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "scene/gltf_animation_files.hpp"
#include "scene/gltf_compressed_files.hpp"
#include "scene/gltf_geometry_files.hpp"
#include "scene/gltf_test_files.hpp"

namespace tessera::test {

struct BadScene {
    const char* name;  // also the file stem in the CLI test
    std::string_view text;
    std::vector<std::string_view> expected;  // substrings of the error message
};

// A camera that passes validation, on lines 1-3.
#define TESSERA_CAMERA "[camera]\nposition = [0, 0, 5]\ntarget = [0, 0, 0]\n"

inline const std::vector<BadScene>& bad_scenes() {
    static const std::vector<BadScene> rows = {
        // Malformed TOML: toml++'s description with file:line:column.
        {"unclosed_table_header", "[camera\nposition = [0, 0, 5]\n", {"@:1:"}},
        {"unclosed_array", TESSERA_CAMERA "up = [0, 1, 0\n[output]\n", {"@:5:1:", "expected comma or closing ']'"}},
        {"missing_value", TESSERA_CAMERA "fov_y =\n", {"@:4:"}},
        {"duplicate_key", TESSERA_CAMERA "target = [1, 0, 0]\n", {"@:4:"}},
        {"bare_word_value", TESSERA_CAMERA "fov_y = wide\n", {"@:4:"}},
        // Orthographic cameras.
        {"camera_unknown_projection", TESSERA_CAMERA "projection = \"fisheye\"\n",
         {"@:4:", "unsupported camera projection 'fisheye' for 'camera.projection'"}},
        {"camera_xmag_with_perspective", TESSERA_CAMERA "xmag = 2.0\n",
         {"@:4:", "'camera.xmag' applies to projection = \"orthographic\" only"}},
        {"camera_orthographic_ymag_zero", TESSERA_CAMERA "projection = \"orthographic\"\nymag = 0.0\n",
         {"@:5:", "expected 'camera.ymag' to be a finite number > 0, got 0"}},
        {"camera_orthographic_fov", TESSERA_CAMERA "projection = \"orthographic\"\nfov_y = 30.0\n",
         {"@:5:", "'camera.fov_y' does not apply to an orthographic camera"}},
        {"binary_garbage", std::string_view("\x00\xff\xfe[[\x01", 6), {"@:1:"}},
        {"invalid_utf8_string", TESSERA_CAMERA "[materials.a]\nalbedo = \"\xc3\x28\"\n", {"@:5:"}},
        // [environment]: its file (missing, not an image, not HDR) and values.
        {"environment_missing_file", TESSERA_CAMERA "[environment]\nfile = \"no/such/sky.hdr\"\n",
         {"@:5:8:", "cannot load the environment for 'environment.file'", "no/such/sky.hdr", "no such file"}},
        {"environment_not_hdr", TESSERA_CAMERA "[environment]\nfile = \"sky.png\"\n",
         {"@:5:8:", "expected a Radiance .hdr or OpenEXR .exr environment image"}},
        {"environment_nan_intensity", TESSERA_CAMERA "[environment]\nfile = \"sky.hdr\"\nintensity = nan\n",
         {"@:6:13:", "environment.intensity"}},
        {"environment_negative_intensity", TESSERA_CAMERA "[environment]\nfile = \"sky.hdr\"\nintensity = -1\n",
         {"@:6:13:", "expected 'environment.intensity' to be >= 0"}},
        {"environment_no_file", TESSERA_CAMERA "[environment]\nintensity = 1\n", {"environment", "file"}},
        {"environment_unknown_key", TESSERA_CAMERA "[environment]\nfile = \"sky.hdr\"\nblur = 2\n", {"@:6:", "blur"}},
        // Textures.
        {"missing_texture", TESSERA_CAMERA "[materials.a]\nalbedo_map = \"no/such/albedo.png\"\n",
         {"@:5:14:", "cannot load the texture for 'materials.a.albedo_map'", "no/such/albedo.png"}},
        {"unknown_albedo_encoding", TESSERA_CAMERA "[materials.a]\nalbedo_map_encoding = \"gamma3\"\n",
         {"@:5:", "expected 'gamma2.2', 'srgb' or 'linear' for 'materials.a.albedo_map_encoding'"}},
        {"unknown_wrap", TESSERA_CAMERA "[materials.a]\nwrap = \"mirror\"\n",
         {"@:5:8:", "expected 'repeat', 'clamp_to_edge' or 'mirrored_repeat' for 'materials.a.wrap'"}},
        {"unknown_wrap_t", TESSERA_CAMERA "[materials.a]\nwrap_t = \"mirror\"\n",
         {"@:5:10:", "expected 'repeat', 'clamp_to_edge' or 'mirrored_repeat' for 'materials.a.wrap_t'"}},
        {"unknown_min_filter", TESSERA_CAMERA "[materials.a]\nmin_filter = \"trilinear\"\n",
         {"@:5:14:", "'nearest_mipmap_linear' or 'linear_mipmap_linear' for 'materials.a.min_filter'"}},
        {"mag_filter_mipmapped", TESSERA_CAMERA "[materials.a]\nmag_filter = \"linear_mipmap_linear\"\n",
         {"@:5:14:", "expected 'nearest' or 'linear' for 'materials.a.mag_filter'"}},
        {"unlit_not_boolean", TESSERA_CAMERA "[materials.a]\nunlit = 1\n", {"@:5:9:", "materials.a.unlit"}},
        {"double_sided_not_boolean", TESSERA_CAMERA "[materials.a]\ndouble_sided = \"no\"\n",
         {"@:5:16:", "materials.a.double_sided"}},
        {"alpha_mode_unknown", TESSERA_CAMERA "[materials.a]\nalpha_mode = \"add\"\n",
         {"@:5:14:", "expected 'opaque', 'mask' or 'blend' for 'materials.a.alpha_mode'"}},
        {"alpha_nan", TESSERA_CAMERA "[materials.a]\nalpha_mode = \"blend\"\nalpha = nan\n",
         {"@:6:", "materials.a.alpha"}},
        {"alpha_above_one", TESSERA_CAMERA "[materials.a]\nalpha_mode = \"blend\"\nalpha = 1.5\n",
         {"@:6:", "materials.a.alpha"}},
        {"alpha_cutoff_negative", TESSERA_CAMERA "[materials.a]\nalpha_cutoff = -0.5\n",
         {"@:5:", "materials.a.alpha_cutoff"}},
        // Wrong value types.
        {"msaa_is_2", TESSERA_CAMERA "[output]\nmsaa = 2\n", {"@:5:8:", "expected 'output.msaa' to be 1 or 4, got 2"}},
        {"msaa_is_float", TESSERA_CAMERA "[output]\nmsaa = 4.0\n", {"@:5:8:", "expected an integer for 'output.msaa', got"}},
        {"width_is_string", TESSERA_CAMERA "[output]\nwidth = \"big\"\n",
         {"@:5:9:", "expected an integer for 'output.width', got string"}},
        {"width_is_float", TESSERA_CAMERA "[output]\nwidth = 640.0\n",
         {"@:5:9:", "expected an integer for 'output.width', got floating-point"}},
        {"position_is_string", "[camera]\nposition = \"here\"\ntarget = [0, 0, 0]\n",
         {"@:2:12:", "expected an array of 3 numbers for 'camera.position', got string"}},
        {"position_has_two_elements", "[camera]\nposition = [0, 5]\ntarget = [0, 0, 0]\n",
         {"@:2:", "expected an array of 3 numbers for 'camera.position', got 2 elements"}},
        {"fov_is_boolean", TESSERA_CAMERA "fov_y = true\n", {"@:4:9:", "expected a number for 'camera.fov_y', got boolean"}},
        {"camera_is_number", "camera = 5\n", {"@:1:", "expected a table for 'camera', got integer"}},
        {"objects_is_table", TESSERA_CAMERA "[objects]\nmesh = \"sphere\"\n",
         {"expected an array of tables for 'objects', got table"}},
        {"mesh_is_number", TESSERA_CAMERA "[[objects]]\nmesh = 1\n",
         {"@:5:8:", "expected a string for 'objects[0].mesh', got integer"}},
        {"material_is_number", TESSERA_CAMERA "[[objects]]\nmesh = \"cube\"\nmaterial = 3\n",
         {"@:6:", "expected a material name or an inline material table for 'objects[0].material'"}},
        {"scale_is_string", TESSERA_CAMERA "[[objects]]\nmesh = \"cube\"\nscale = \"big\"\n",
         {"@:6:", "expected a number or an array of 3 numbers for 'objects[0].scale', got string"}},
        {"light_color_element_is_string", TESSERA_CAMERA "[[lights]]\nposition = [0, 0, 0]\ncolor = [1, \"x\", 1]\n",
         {"@:6:", "expected a number for 'lights[0].color[1]', got string"}},
        // Missing required keys.
        {"no_camera", "[output]\nwidth = 64\n", {"@: missing required table [camera]"}},
        {"empty_file", "", {"@: missing required table [camera]"}},
        {"no_camera_position", "[camera]\ntarget = [0, 0, 0]\n", {"@:1:1:", "missing required key 'camera.position'"}},
        {"no_camera_target", "[camera]\nposition = [0, 0, 5]\n", {"@:1:1:", "missing required key 'camera.target'"}},
        {"light_without_position", TESSERA_CAMERA "[[lights]]\ncolor = [1, 1, 1]\n",
         {"@:4:", "missing required key 'lights[0].position'"}},
        {"light_without_color", TESSERA_CAMERA "[[lights]]\nposition = [1, 1, 1]\n",
         {"@:4:", "missing required key 'lights[0].color'"}},
        {"object_without_mesh", TESSERA_CAMERA "[[objects]]\ntranslate = [0, 0, 0]\n",
         {"@:4:", "missing required key 'objects[0].mesh'"}},
        // Unknown keys are errors: a typo must not pass silently.
        {"unknown_top_level_table", TESSERA_CAMERA "[outptu]\nwidth = 64\n",
         {"@:4:", "unknown key 'outptu' at top level", "valid keys: output, camera"}},
        {"unknown_camera_key", TESSERA_CAMERA "fov = 60\n", {"@:4:1:", "unknown key 'fov' in 'camera'"}},
        {"unknown_output_key", TESSERA_CAMERA "[output]\nwidht = 64\n", {"@:5:1:", "unknown key 'widht' in 'output'"}},
        {"unknown_object_key", TESSERA_CAMERA "[[objects]]\nmesh = \"cube\"\nrotation = [0, 1, 0]\n",
         {"@:6:1:", "unknown key 'rotation' in 'objects[0]'"}},
        {"unknown_material_key", TESSERA_CAMERA "[materials.a]\nroughnes = 0.5\n",
         {"@:5:1:", "unknown key 'roughnes' in 'materials.a'"}},
        {"unknown_light_key", TESSERA_CAMERA "[[lights]]\nposition = [0, 0, 0]\ncolor = [1, 1, 1]\nradius = 2\n",
         {"@:7:1:", "unknown key 'radius' in 'lights[0]'"}},
        // NaN and infinities (TOML spells them nan and inf), and finite doubles that overflow float.
        {"fov_nan", TESSERA_CAMERA "fov_y = nan\n", {"@:4:9:", "expected a finite number for 'camera.fov_y'"}},
        {"position_inf", "[camera]\nposition = [inf, 0, 5]\ntarget = [0, 0, 0]\n",
         {"@:2:", "expected a finite number for 'camera.position[0]'"}},
        {"light_color_minus_inf", TESSERA_CAMERA "[[lights]]\nposition = [0, 0, 0]\ncolor = [1, -inf, 1]\n",
         {"@:6:", "expected a finite number for 'lights[0].color[1]'"}},
        {"translate_overflows_float", TESSERA_CAMERA "[[objects]]\nmesh = \"cube\"\ntranslate = [1e300, 0, 0]\n",
         {"@:6:", "expected a finite number for 'objects[0].translate[0]'"}},
        {"metallic_nan", TESSERA_CAMERA "[materials.a]\nmetallic = -nan\n",
         {"@:5:", "expected a finite number for 'materials.a.metallic'"}},
        // Image sizes: each side 1..16384, and at most 2^27 pixels in all.
        {"width_zero", TESSERA_CAMERA "[output]\nwidth = 0\n", {"@:5:9:", "expected 'output.width' to be in 1..16384, got 0"}},
        {"height_negative", TESSERA_CAMERA "[output]\nheight = -720\n",
         {"@:5:10:", "expected 'output.height' to be in 1..16384, got -720"}},
        {"width_too_large", TESSERA_CAMERA "[output]\nwidth = 16385\n", {"@:5:", "expected 'output.width' to be in 1..16384"}},
        {"width_absurd", TESSERA_CAMERA "[output]\nwidth = 9223372036854775807\n",
         {"@:5:", "expected 'output.width' to be in 1..16384"}},
        {"width_beyond_int64", TESSERA_CAMERA "[output]\nwidth = 99999999999999999999\n", {"@:5:"}},
        {"too_many_pixels", TESSERA_CAMERA "[output]\nwidth = 16384\nheight = 16384\n",
         {"@:6:10:", "output size 16384x16384 is 268435456 pixels; at most 134217728 are allowed"}},
        {"too_many_pixels_height_first", TESSERA_CAMERA "[output]\nheight = 16384\nwidth = 8193\n",
         {"output size 8193x16384 is 134234112 pixels; at most 134217728 are allowed"}},
        // Field of view in (0, 180).
        {"fov_zero", TESSERA_CAMERA "fov_y = 0\n", {"@:4:9:", "expected 'camera.fov_y' to be in (0, 180) degrees, got 0"}},
        {"fov_180", TESSERA_CAMERA "fov_y = 180.0\n", {"@:4:9:", "expected 'camera.fov_y' to be in (0, 180) degrees"}},
        {"fov_negative", TESSERA_CAMERA "fov_y = -45\n", {"expected 'camera.fov_y' to be in (0, 180) degrees"}},
        {"fov_huge", TESSERA_CAMERA "fov_y = 1e30\n", {"expected 'camera.fov_y' to be in (0, 180) degrees"}},
        // Clip planes: 0 < near < far.
        {"near_zero", TESSERA_CAMERA "near = 0\n", {"@:4:8:", "expected 'camera.near' to be > 0, got 0"}},
        {"near_negative", TESSERA_CAMERA "near = -1.0\n", {"@:4:8:", "expected 'camera.near' to be > 0, got -1"}},
        {"near_equals_far", TESSERA_CAMERA "near = 10\nfar = 10\n",
         {"@:5:7:", "expected 'camera.near' < 'camera.far', got near = 10, far = 10"}},
        {"near_beyond_far", TESSERA_CAMERA "near = 10\nfar = 1\n", {"@:5:7:", "expected 'camera.near' < 'camera.far'"}},
        {"far_below_default_near", TESSERA_CAMERA "far = 0.05\n", {"@:4:7:", "expected 'camera.near' < 'camera.far'"}},
        {"far_negative", TESSERA_CAMERA "far = -100\n", {"expected 'camera.near' < 'camera.far'"}},
        // A degenerate camera: no view direction, or up along it.
        {"target_equals_position", "[camera]\nposition = [1, 2, 3]\ntarget = [1, 2, 3]\n",
         {"@:3:10:", "expected 'camera.target' to differ from 'camera.position'"}},
        {"up_parallel_to_view", "[camera]\nposition = [0, 5, 0]\ntarget = [0, 0, 0]\n",
         {"@:1:1:", "expected 'camera.up' to be non-zero and not parallel to the view direction"}},
        {"up_antiparallel_to_view", TESSERA_CAMERA "up = [0, 0, 7]\n",
         {"@:4:6:", "expected 'camera.up' to be non-zero and not parallel to the view direction"}},
        {"up_zero", TESSERA_CAMERA "up = [0, 0, 0]\n", {"@:4:6:", "expected 'camera.up' to be non-zero"}},
        // Values out of their documented ranges.
        {"clear_color_above_one", TESSERA_CAMERA "[output]\nclear_color = [0, 2, 0]\n",
         {"@:5:", "expected 'output.clear_color[1]' to be in [0, 1], got 2"}},
        {"metallic_above_one", TESSERA_CAMERA "[[objects]]\nmesh = \"sphere\"\nmaterial = { metallic = 2 }\n",
         {"@:6:", "expected 'objects[0].material.metallic' to be in [0, 1], got 2"}},
        {"albedo_negative", TESSERA_CAMERA "[materials.a]\nalbedo = [-0.1, 0, 0]\n",
         {"@:5:", "expected 'materials.a.albedo[0]' to be in [0, 1]"}},
        {"light_color_negative", TESSERA_CAMERA "[[lights]]\nposition = [0, 0, 0]\ncolor = [1, 1, -1]\n",
         {"@:6:", "expected 'lights[0].color[2]' to be >= 0"}},
        {"unknown_light_type", TESSERA_CAMERA "[[lights]]\ntype = \"area\"\nposition = [0, 0, 0]\ncolor = [1, 1, 1]\n",
         {"@:5:8:", "unsupported light type 'area'", "supported types: point, directional, spot"}},
        // Light types: directions, cones and ranges.
        {"light_type_is_number", TESSERA_CAMERA "[[lights]]\ntype = 2\nposition = [0, 0, 0]\ncolor = [1, 1, 1]\n",
         {"@:5:8:", "expected a string for 'lights[0].type', got integer"}},
        {"directional_without_direction", TESSERA_CAMERA "[[lights]]\ntype = \"directional\"\ncolor = [1, 1, 1]\n",
         {"@:4:", "missing required key 'lights[0].direction'"}},
        {"spot_direction_zero",
         TESSERA_CAMERA "[[lights]]\ntype = \"spot\"\nposition = [0, 0, 0]\ndirection = [0, 0, 0]\ncolor = [1, 1, 1]\n",
         {"@:7:13:", "expected 'lights[0].direction' to be non-zero"}},
        {"spot_direction_two_elements",
         TESSERA_CAMERA "[[lights]]\ntype = \"spot\"\nposition = [0, 0, 0]\ndirection = [0, 1]\ncolor = [1, 1, 1]\n",
         {"@:7:13:", "expected an array of 3 numbers for 'lights[0].direction', got 2 elements"}},
        {"directional_with_position",
         TESSERA_CAMERA "[[lights]]\ntype = \"directional\"\ndirection = [0, -1, 0]\nposition = [0, 0, 0]\ncolor = [1, 1, 1]\n",
         {"@:7:12:", "'lights[0].position' does not apply to a directional light"}},
        {"point_with_cone", TESSERA_CAMERA "[[lights]]\nposition = [0, 0, 0]\ncolor = [1, 1, 1]\ninner_cone = 5\n",
         {"@:7:14:", "'lights[0].inner_cone' does not apply to a point light"}},
        {"spot_inner_not_below_outer",
         TESSERA_CAMERA "[[lights]]\ntype = \"spot\"\nposition = [0, 0, 0]\ndirection = [0, -1, 0]\ncolor = [1, 1, 1]\n"
                        "inner_cone = 40\nouter_cone = 20\n",
         {"@:9:14:", "expected 'lights[0].inner_cone' < 'lights[0].outer_cone', got inner = 40, outer = 20"}},
        {"spot_outer_above_90",
         TESSERA_CAMERA "[[lights]]\ntype = \"spot\"\nposition = [0, 0, 0]\ndirection = [0, -1, 0]\ncolor = [1, 1, 1]\n"
                        "outer_cone = 120\n",
         {"@:9:14:", "expected 'lights[0].outer_cone' to be in [0, 90] degrees, got 120"}},
        {"spot_cone_nan",
         TESSERA_CAMERA "[[lights]]\ntype = \"spot\"\nposition = [0, 0, 0]\ndirection = [0, -1, 0]\ncolor = [1, 1, 1]\n"
                        "inner_cone = nan\n",
         {"@:9:14:", "expected a finite number for 'lights[0].inner_cone'"}},
        {"light_range_negative", TESSERA_CAMERA "[[lights]]\nposition = [0, 0, 0]\ncolor = [1, 1, 1]\nrange = -1\n",
         {"@:7:9:", "expected 'lights[0].range' to be > 0"}},
        {"light_range_word", TESSERA_CAMERA "[[lights]]\nposition = [0, 0, 0]\ncolor = [1, 1, 1]\nrange = \"automatic\"\n",
         {"@:7:9:", "expected a number > 0 or \"auto\" for 'lights[0].range', got \"automatic\""}},
        {"directional_with_range",
         TESSERA_CAMERA "[[lights]]\ntype = \"directional\"\ndirection = [0, -1, 0]\ncolor = [1, 1, 1]\nrange = 3\n",
         {"@:8:9:", "'lights[0].range' does not apply to a directional light"}},
        {"unknown_mesh", TESSERA_CAMERA "[[objects]]\nmesh = \"teapot\"\n",
         {"@:5:8:", "unknown mesh 'teapot' for 'objects[0].mesh'; built-in meshes: sphere, plane, cube"}},
        {"unknown_material", TESSERA_CAMERA "[[objects]]\nmesh = \"cube\"\nmaterial = \"gold\"\n",
         {"@:6:12:", "unknown material 'gold'", "no materials are defined"}},
        {"scale_zero", TESSERA_CAMERA "[[objects]]\nmesh = \"cube\"\nscale = [1, 0, 1]\n",
         {"@:6:9:", "expected every component of 'objects[0].scale' to be non-zero"}},
        {"scale_nan", TESSERA_CAMERA "[[objects]]\nmesh = \"cube\"\nscale = nan\n",
         {"@:6:9:", "expected a finite number for 'objects[0].scale'"}},
        {"rotate_inf", TESSERA_CAMERA "[[objects]]\nmesh = \"cube\"\nrotate = [0, inf, 0]\n",
         {"@:6:", "expected a finite number for 'objects[0].rotate[1]'"}},
    };
    return rows;
}

#undef TESSERA_CAMERA

// Bad glTF files, made at run time by breaking the test document of
// scene/gltf_test_files.hpp; written to disk as <name><extension> and loaded
// with load_scene_file or the tessera binary. "@" in `expected` is the path.
struct BadGltf {
    std::string name;
    std::string extension;  // ".gltf" or ".glb"
    std::string bytes;
    std::vector<std::string> expected;
};

inline std::vector<BadGltf> bad_gltf_files() {
    const std::vector<std::uint8_t> glb = test_glb();
    const std::string glb_text(glb.begin(), glb.end());
    const std::string good = embedded_test_gltf();
    return {
        {"gltf_truncated_header", ".glb", glb_text.substr(0, 16), {"@: invalid glTF binary (.glb): "}},
        {"gltf_truncated_json", ".glb", glb_text.substr(0, 200), {"@: invalid glTF binary (.glb): Invalid glTF binary."}},
        {"gltf_truncated_bin", ".glb", glb_text.substr(0, glb_text.size() - 40), {"@: invalid glTF binary (.glb): "}},
        {"gltf_empty", ".glb", "", {"@: invalid glTF: "}},
        {"gltf_not_json", ".gltf", "{\"asset\": {\"version\": \"2.0\"}, ", {"@: invalid glTF: "}},
        {"gltf_missing_bin", ".gltf", test_gltf_json("missing_buffer.bin"),
         {"@: invalid glTF: ", "File not found : missing_buffer.bin", "(looked in '"}},
        {"gltf_missing_texture", ".gltf",
         replaced(good, "data:image/png;base64," + std::string(kTestPngBase64), "missing_texture.png"),
         {"@: images[0] ('missing_texture.png'): cannot read image file '", "missing_texture.png'"}},
        {"gltf_corrupt_texture", ".gltf", replaced(good, "iVBORw0KGgo", "iVBORw0KGgX"),
         {"@: images[0]: cannot decode image: "}},
        {"gltf_accessor_out_of_range", ".gltf", replaced(good, "\"count\": 6", "\"count\": 600000"),
         {"@: meshes[0] 'parts' primitives[1] POSITION (accessor 4) is out of range: 600000 elements"}},
        {"gltf_accessor_offset_huge", ".glb",
         [&] {
             const std::vector<std::uint8_t> bytes = make_glb(
                 replaced(test_gltf_json(""), "\"byteOffset\": 104, \"byteLength\": 72", "\"byteOffset\": 18446744073709551600, \"byteLength\": 72"),
                 test_gltf_buffer());
             return std::string(bytes.begin(), bytes.end());
         }(),
         {"@: "}},
        {"gltf_unknown_light_type", ".gltf", replaced(good, "\"type\": \"point\"", "\"type\": \"area\""),
         {"@: KHR_lights_punctual lights[1] has type 'area', expected point, spot or directional"}},
        {"gltf_required_extension", ".gltf",
         replaced(good, R"("extensionsUsed": ["KHR_lights_punctual"])",
                  R"("extensionsUsed": ["KHR_lights_punctual", "KHR_texture_basisu"], )"
                  R"("extensionsRequired": ["KHR_texture_basisu"])"),
         {"@: the file requires the extension 'KHR_texture_basisu', which is not supported"}},
        {"gltf_alpha_cutoff_negative", ".gltf",
         replaced(good, R"("alphaMode": "BLEND",)", R"("alphaMode": "MASK", "alphaCutoff": -1,)"),
         {"@: materials[0] 'painted' alphaCutoff is -1.000000, expected a finite number >= 0"}},
        {"gltf_alpha_cutoff_overflows_float", ".gltf",
         replaced(good, R"("alphaMode": "BLEND",)", R"("alphaMode": "MASK", "alphaCutoff": 1e300,)"),
         {"@: materials[0] 'painted' alphaCutoff is ", "expected a finite number >= 0"}},
        {"gltf_texture_transform_rotation_not_number", ".gltf",
         replaced(good, R"("baseColorTexture": {"index": 0})",
                  R"("baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"rotation": [1]}}})"),
         {"@: materials[0] 'painted' baseColorTexture KHR_texture_transform rotation is not a finite number"}},
        {"gltf_texcoord_set_absurd", ".gltf",
         replaced(good, R"("baseColorTexture": {"index": 0})", R"("baseColorTexture": {"index": 0, "texCoord": 4000000})"),
         {"@: materials[0] 'painted' baseColorTexture uses TEXCOORD_4000000; expected a set from 0 to 9"}},
        {"gltf_color_0_vec2", ".gltf",
         replaced(good, R"("TEXCOORD_0": 2})", R"("TEXCOORD_0": 2, "COLOR_0": 2})"),
         {"@: meshes[0] 'parts' primitives[0] COLOR_0 (accessor 2) is VEC2, expected VEC3 or VEC4"}},
        {"gltf_color_0_scalar_indices", ".gltf",
         replaced(good, R"("TEXCOORD_0": 2})", R"("TEXCOORD_0": 2, "COLOR_0": 3})"),
         {"@: meshes[0] 'parts' primitives[0] COLOR_0 (accessor 3) is SCALAR, expected VEC3 or VEC4"}},
        {"gltf_color_0_count", ".gltf",
         replaced(good, R"("TEXCOORD_0": 2})", R"("TEXCOORD_0": 2, "COLOR_0": 4})"),
         {"@: meshes[0] 'parts' primitives[0] COLOR_0 has 6 elements for 3 positions"}},
        // Materials and textures (issue 31): samplers, texture coordinates, WebP, KTX2.
        {"gltf_sampler_wrap_unknown", ".gltf", replaced(good, R"("wrapT": 10497)", R"("wrapT": 12345)"),
         {"@: samplers[0] wrapT is 12345, expected 10497 (REPEAT), 33071 (CLAMP_TO_EDGE) or 33648 (MIRRORED_REPEAT)"}},
        {"gltf_sampler_min_filter_unknown", ".gltf", replaced(good, R"("wrapT": 10497)", R"("wrapT": 10497, "minFilter": 9729000)"),
         {"@: samplers[0] minFilter is 9729000, expected 9728, 9729, 9984, 9985, 9986 or 9987"}},
        {"gltf_sampler_mag_filter_mipmapped", ".gltf", replaced(good, R"("wrapT": 10497)", R"("wrapT": 10497, "magFilter": 9987)"),
         {"@: samplers[0] magFilter is 9987, expected 9728 (NEAREST) or 9729 (LINEAR)"}},
        {"gltf_texcoord_set_missing", ".gltf",
         replaced(good, R"("baseColorTexture": {"index": 0})", R"("baseColorTexture": {"index": 0, "texCoord": 1})"),
         {"@: meshes[0] 'parts' primitives[0]: material 0 has a map with texCoord 1 but the primitive has no TEXCOORD_1"}},
        {"gltf_texture_transform_scale_not_numbers", ".gltf",
         replaced(good, R"("baseColorTexture": {"index": 0})",
                  R"("baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"scale": [1, "x"]}}})"),
         {"@: materials[0] 'painted' baseColorTexture KHR_texture_transform scale is not an array of 2 numbers"}},
        {"gltf_texture_transform_offset_infinite", ".gltf",
         replaced(good, R"("baseColorTexture": {"index": 0})",
                  R"("baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"offset": [1e300, 0]}}})"),
         {"@: materials[0] 'painted' baseColorTexture KHR_texture_transform offset is not finite"}},
        {"gltf_webp_corrupt", ".gltf",
         replaced(replaced(good, "data:image/png;base64," + std::string(kTestPngBase64),
                           "data:application/octet-stream;base64,UklGRhQAAABXRUJQVlA4IAgAAAABAgMEBQYHCA=="),
                  R"("textures": [{"source": 0, "sampler": 0})",
                  R"("textures": [{"extensions": {"EXT_texture_webp": {"source": 0}}, "sampler": 0})"),
         {"@: images[0]: ", "WebP"}},
        {"gltf_webp_source_out_of_range", ".gltf",
         replaced(good, R"("textures": [{"source": 0, "sampler": 0})",
                  R"("textures": [{"extensions": {"EXT_texture_webp": {"source": 7}}, "sampler": 0})"),
         {"@: textures[0] (materials[0] 'painted' baseColorTexture) EXT_texture_webp source is not an image index below 1"}},
        {"gltf_basisu_only", ".gltf",
         replaced(good, R"("textures": [{"source": 0, "sampler": 0})",
                  R"("textures": [{"extensions": {"KHR_texture_basisu": {"source": 0}}, "sampler": 0})"),
         {"@: textures[0] (materials[0] 'painted' baseColorTexture) has only a KHR_texture_basisu (KTX2) image, which is "
          "not supported: convert the image to PNG", "ktx extract"}},
        {"gltf_ktx2_image", ".gltf",
         replaced(good, "data:image/png;base64," + std::string(kTestPngBase64),
                  "data:application/octet-stream;base64,q0tUWCAyMLsNChoKAAAAAAAAAAA="),
         {"@: images[0] is a KTX2 image (KHR_texture_basisu), which is not supported: convert the image to PNG"}},
        {"gltf_alpha_mode_unknown", ".gltf", replaced(good, R"("alphaMode": "BLEND",)", R"("alphaMode": "CLIP",)"),
         {"@: materials[0] 'painted' alphaMode is 'CLIP', expected OPAQUE, MASK or BLEND"}},
        // Quantized, sparse and compressed geometry (gltf_compressed_files.hpp).
        {"gltf_quantized_normal_unsigned", ".gltf",
         replaced(replaced(good, R"("extensionsUsed": ["KHR_lights_punctual"])",
                           R"("extensionsUsed": ["KHR_lights_punctual", "KHR_mesh_quantization"])"),
                  R"({"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"})",
                  R"({"bufferView": 1, "componentType": 5121, "normalized": true, "count": 3, "type": "VEC3"})"),
         {"@: meshes[0] 'parts' primitives[0] NORMAL (accessor 1) has components of UNSIGNED_BYTE, expected FLOAT, BYTE, SHORT"}},
        {"gltf_sparse_index_out_of_range", ".gltf",
         // The strip's u8 indices 0 1 read as one u16: 256.
         replaced(good, R"("min": [0, 0, 0], "max": [1, 1, 0])",
                  R"("min": [0, 0, 0], "max": [1, 1, 0], "sparse": {"count": 1, )"
                  R"("indices": {"bufferView": 5, "componentType": 5123}, "values": {"bufferView": 4}})"),
         {"@: meshes[0] 'parts' primitives[0] POSITION (accessor 0) sparse index 256 at [0] is out of range; the accessor has 3 elements"}},
        {"gltf_sparse_values_past_view", ".gltf",
         replaced(good, R"("min": [0, 0, 0], "max": [1, 1, 0])",
                  R"("min": [0, 0, 0], "max": [1, 1, 0], "sparse": {"count": 2, )"
                  R"("indices": {"bufferView": 5, "componentType": 5121}, "values": {"bufferView": 4, "byteOffset": 64}})"),
         {"@: meshes[0] 'parts' primitives[0] POSITION (accessor 0) sparse values is out of range: 2 values of 12 bytes"}},
        {"gltf_implicit_zeros_huge", ".gltf",
         replaced(good, R"({"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"})",
                  R"({"componentType": 5126, "count": 3000000000, "type": "VEC2"})"),
         {"@: meshes[0] 'parts' primitives[0] TEXCOORD_0 (accessor 2) has no bufferView and 3000000000 elements"}},
        {"gltf_draco_does_not_decode", ".glb",
         [] {
             const GridMesh grid = grid_mesh(2);
             DracoGrid draco = draco_grid(grid);
             for (std::size_t i = 0; i < draco.bytes.size(); ++i) draco.bytes[i] = std::uint8_t(0xA5 ^ i);
             const GltfParts parts = draco_grid_parts(draco, grid.positions.size(), grid.indices.size());
             return as_text(make_glb(parts.json, parts.bin));
         }(),
         {"@: meshes[0] 'grid' primitives[0] KHR_draco_mesh_compression: the Draco data in bufferView 0 (",
          " bytes) does not decode: "}},
        {"gltf_draco_unknown_attribute_id", ".glb",
         [] {
             const GridMesh grid = grid_mesh(2);
             DracoGrid draco = draco_grid(grid);
             draco.normal_id = 9;
             const GltfParts parts = draco_grid_parts(draco, grid.positions.size(), grid.indices.size());
             return as_text(make_glb(parts.json, parts.bin));
         }(),
         {"@: meshes[0] 'grid' primitives[0] KHR_draco_mesh_compression attribute NORMAL: the Draco mesh has no attribute with id 9"}},
        {"gltf_draco_bool_attribute", ".glb",
         [] {
             const GridMesh grid = grid_mesh(2);
             const DracoGrid draco = draco_grid(grid, true);
             const GltfParts parts = draco_grid_parts(draco, grid.positions.size(), grid.indices.size());
             return as_text(make_glb(parts.json, parts.bin));
         }(),
         {"@: meshes[0] 'grid' primitives[0] KHR_draco_mesh_compression attribute TANGENT: the Draco attribute holds "
          "bool values, which no glTF accessor holds"}},
        {"gltf_meshopt_stream_too_short", ".glb",
         [] {
             // The positions' stream (81 elements of 12 bytes) cut to 10 bytes; its real length becomes an unknown key.
             GltfParts parts = meshopt_grid_parts(grid_mesh(8));
             parts.json = replaced(parts.json, R"({"buffer": 0, "byteOffset": 0, "byteLength": )",
                                   R"({"buffer": 0, "byteOffset": 0, "byteLength": 10, "was": )");
             return as_text(make_glb(parts.json, parts.bin));
         }(),
         {"@: bufferView 0 EXT_meshopt_compression is too short: 10 bytes cannot hold 81 elements of 12 bytes"}},
        {"gltf_meshopt_stream_does_not_decode", ".glb",
         [] {
             GltfParts parts = meshopt_grid_parts(grid_mesh(8));
             parts.json = replaced(parts.json, R"({"buffer": 0, "byteOffset": 0, "byteLength": )",
                                   R"({"buffer": 0, "byteOffset": 0, "byteLength": 40, "was": )");
             return as_text(make_glb(parts.json, parts.bin));
         }(),
         {"@: bufferView 0 EXT_meshopt_compression: the ATTRIBUTES data (40 bytes) does not decode to 81 elements of 12 bytes"}},
        {"gltf_meshopt_unknown_mode", ".glb",
         [] {
             GltfParts parts = meshopt_grid_parts(grid_mesh(2));
             parts.json = replaced(parts.json, R"("mode": "TRIANGLES")", R"("mode": "STRIPS")");
             return as_text(make_glb(parts.json, parts.bin));
         }(),
         {"@: bufferView 4 EXT_meshopt_compression mode is 'STRIPS', expected ATTRIBUTES, TRIANGLES or INDICES"}},
        {"gltf_meshopt_fallback_read_plainly", ".glb",
         [] {
             // One more buffer view, over the fallback buffer and not compressed.
             GltfParts parts = meshopt_grid_parts(grid_mesh(2));
             parts.json = replaced(parts.json, "],\n  \"buffers\": [", ", {\"buffer\": 1, \"byteLength\": 8}],\n  \"buffers\": [");
             return as_text(make_glb(parts.json, parts.bin));
         }(),
         {"@: bufferView 5 reads buffer 1, a EXT_meshopt_compression fallback buffer without data, but is not compressed"}},
    };
}

// Bad skins, morph targets and animations (gltf_animation_files.hpp, broken).
inline std::vector<BadGltf> bad_gltf_animation_files() {
    const std::string strip = skinned_strip_gltf(), morph = morph_triangle_gltf(), node = animated_node_gltf();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    return {
        {"gltf_skin_joint_out_of_range", ".gltf", replaced(strip, "\"joints\": [1, 2]", "\"joints\": [1, 9]"),
         {"@: skins[0] 'bones' joint [1] is node 9 but the file has 3 nodes"}},
        {"gltf_skin_vertex_joint_out_of_range", ".gltf", replaced(strip, "\"joints\": [1, 2]", "\"joints\": [1]"),
         {"@: meshes[0] 'strip' primitives[0] JOINTS_0 of vertex 2 names joint 1 but its skin has 1 joints"}},
        {"gltf_skin_weights_without_joints", ".gltf", replaced(strip, "\"JOINTS_0\"", "\"JOINTS_5\""),
         {"@: meshes[0] 'strip' primitives[0] has WEIGHTS_0 without JOINTS_0"}},
        {"gltf_skin_joints_normalized", ".gltf",
         replaced(strip, "\"componentType\": 5121, \"count\": 6", "\"componentType\": 5121, \"normalized\": true, \"count\": 6"),
         {"@: meshes[0] 'strip' primitives[0] JOINTS_0 (accessor 2) is normalized; joint indices must not be"}},
        {"gltf_skin_unknown", ".gltf", replaced(strip, "\"skin\": 0", "\"skin\": 4"),
         {"@: nodes[0] 'strip' uses skin 4 but the file has 1 skins"}},
        {"gltf_morph_weights_count", ".gltf", replaced(morph, "\"weights\": [0.5, 0]", "\"weights\": [0.5]"),
         {"@: meshes[0] 'triangle' has 1 weights for 2 morph targets"}},
        {"gltf_sampler_count_mismatch", ".gltf", replaced(node, "\"interpolation\": \"STEP\"", "\"interpolation\": \"CUBICSPLINE\""),
         {"@: animations[1] 'step' samplers[0] has 3 key times but 3 output elements; expected 9 (3 per key)"}},
        {"gltf_sampler_times_not_increasing", ".gltf", animated_node_gltf({0, 1, 1}),
         {"@: animations[1] 'step' samplers[0] input times are not strictly increasing: [2] = 1 after 1"}},
        {"gltf_sampler_time_negative", ".gltf", animated_node_gltf({-1, 1, 2}),
         {"@: animations[1] 'step' samplers[0] input time [0] is -1, expected a finite number >= 0"}},
        {"gltf_sampler_time_nan", ".gltf", animated_node_gltf({0, nan, 2}),
         {"@: animations[1] 'step' samplers[0] input time [1] is nan, expected a finite number >= 0"}},
        {"gltf_sampler_value_nan", ".gltf", animated_node_gltf({0, 1, 2}, {0, 0, 0, nan, 0, 0, 5, 0, 0}),
         {"@: animations[1] 'step' samplers[0] output value [3] is not finite"}},
        {"gltf_sampler_interpolation_unknown", ".gltf", replaced(node, "\"interpolation\": \"STEP\"", "\"interpolation\": \"SMOOTH\""),
         {"@: animations[1] 'step' samplers[0] has interpolation 'SMOOTH', expected LINEAR, STEP or CUBICSPLINE"}},
        {"gltf_channel_weights_without_morph", ".gltf", replaced(node, "\"path\": \"scale\"", "\"path\": \"weights\""),
         {"@: animations[0] 'linear' channels[1] animates the morph weights of nodes[0] 'mover', which has no mesh with morph targets"}},
        {"gltf_channel_twice", ".gltf", replaced(node, "\"path\": \"scale\"", "\"path\": \"translation\""),
         {"@: animations[0] 'linear' channels[1] animates nodes[0] 'mover' translation again"}},
        {"gltf_channel_node_out_of_range", ".gltf", replaced(node, "\"node\": 0, \"path\": \"scale\"", "\"node\": 7, \"path\": \"scale\""),
         {"@: animations[0] 'linear' channels[1] targets node 7 but the file has 2 nodes"}},
        {"gltf_channel_path_unknown", ".gltf", replaced(node, "\"path\": \"scale\"", "\"path\": \"color\""),
         {"@: animations[0] 'linear' channels[1] has target path 'color', expected translation, rotation, scale or weights"}},
    };
}

// Bad instancing, cameras, points and lines, quantized morph targets, KHR meshopt (gltf_geometry_files.hpp, broken).
inline std::vector<BadGltf> bad_gltf_geometry_files() {
    const std::string cameras = cameras_gltf(), lines = points_and_lines_gltf();
    return {
        {"gltf_instancing_count_mismatch", ".gltf", instanced_triangle_gltf(3, 2, 3),
         {"@: nodes[0] EXT_mesh_gpu_instancing ROTATION (accessor 2) has 2 elements but TRANSLATION has 3; every "
          "instancing attribute has one element per instance"}},
        {"gltf_instancing_no_attributes", ".gltf",
         replaced(instanced_triangle_gltf(), "\"attributes\":", "\"attribute\":"),
         {"@: nodes[0] EXT_mesh_gpu_instancing has no 'attributes' object"}},
        {"gltf_instancing_accessor_out_of_range", ".gltf",
         replaced(instanced_triangle_gltf(), "\"TRANSLATION\": 1", "\"TRANSLATION\": 40"),
         {"@: nodes[0] EXT_mesh_gpu_instancing TRANSLATION"}},
        {"gltf_orthographic_xmag_zero", ".gltf", replaced(cameras, "\"xmag\": 4", "\"xmag\": 0"),
         {"@: cameras[1] 'flat' xmag, ymag are 0"}},
        {"gltf_orthographic_zfar_before_znear", ".gltf", replaced(cameras, "\"zfar\": 20", "\"zfar\": 0"),
         {"@: cameras[1] 'flat' zfar is 0"}},
        {"gltf_quantized_morph_without_extension", ".gltf",
         replaced(replaced(quantized_morph_gltf(), "\"extensionsUsed\": [\"KHR_mesh_quantization\"],", ""),
                  "\"extensionsRequired\": [\"KHR_mesh_quantization\"],", ""),
         {"@: meshes[0] primitives[0] POSITION"}},
        // A codec version 0 stream under a version 1 header: its bytes do not end where the tail begins.
        {"gltf_khr_meshopt_codec_v1_mislabelled", ".glb", as_text(khr_meshopt_grid_glb(grid_mesh(2), 1)),
         {"@: bufferView 0 KHR_meshopt_compression: the ATTRIBUTES data (120 bytes): "}},
        {"gltf_meshopt_offset_past_buffer", ".glb",
         [] {
             GltfParts parts = meshopt_grid_parts(grid_mesh(2));
             parts.json = replaced(parts.json, R"({"buffer": 0, "byteOffset": 0,)", R"({"buffer": 0, "byteOffset": 99999999,)");
             return as_text(make_glb(parts.json, parts.bin));
         }(),
         {"@: bufferView 0 EXT_meshopt_compression spans bytes 99999999 + "}},
    };
}

// Every bad glTF row: the importer's and those of skins and animations.
inline std::vector<BadGltf> all_bad_gltf_files() {
    std::vector<BadGltf> rows = bad_gltf_files();
    for (BadGltf& row : bad_gltf_animation_files()) rows.push_back(std::move(row));
    for (BadGltf& row : bad_gltf_geometry_files()) rows.push_back(std::move(row));
    return rows;
}

}  // namespace tessera::test
