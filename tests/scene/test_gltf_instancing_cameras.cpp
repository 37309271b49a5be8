// glTF geometry and cameras of issue 31, each on a small file built here:
// EXT_mesh_gpu_instancing, orthographic cameras, the first-camera warning,
// points and lines primitives, and quantized morph targets.
#include <cmath>
#include <functional>
#include <string>

#include <doctest/doctest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "scene/gltf_geometry_files.hpp"
#include "scene/gltf/gltf_import.hpp"
#include "scene/gltf_text_import.hpp"

using namespace tessera;

namespace {

GltfContent import_text(const std::string& text, const std::string& name = "test.gltf") {
    return test::import_gltf_text(text, name);
}

std::string error_of(const std::string& text) { return test::gltf_import_error(text); }

bool near(const glm::vec3& a, const glm::vec3& b, float tolerance = 1e-5f) { return glm::length(a - b) <= tolerance; }

glm::vec3 placed(const Object& object, const glm::vec3& point) { return glm::vec3(object.model * glm::vec4(point, 1.0f)); }

}  // namespace

TEST_CASE("EXT_mesh_gpu_instancing: one object per instance, all drawing the one converted mesh") {
    const GltfContent content = import_text(test::instanced_triangle_gltf());
    REQUIRE(content.meshes.size() == 1);
    REQUIRE(content.objects.size() == 3);
    for (const Object& object : content.objects) CHECK(object.mesh == 0);
    // world = node × T × R × S, applied to vertex (1, 0, 0).
    CHECK(near(placed(content.objects[0], {1, 0, 0}), {1, 0, -5}));
    CHECK(near(placed(content.objects[1], {1, 0, 0}), {10, 1, -5}));  // rotated 90° about Z, then moved
    CHECK(near(placed(content.objects[2], {1, 0, 0}), {2, 10, -5}));   // scaled by 2
    CHECK(near(content.bounds.max, {10, 12, -5}));
    CHECK(content.warnings.empty());

    // An instance accessor of the wrong count is refused, naming both.
    const std::string wrong = error_of(test::instanced_triangle_gltf(3, 2, 3));
    CHECK(wrong.find("bad.gltf: nodes[0] EXT_mesh_gpu_instancing ROTATION") == 0);
    CHECK(wrong.find("has 2 elements but TRANSLATION has 3") != std::string::npos);
    CHECK(error_of(test::instanced_triangle_gltf(3, 3, 1)).find("SCALE") != std::string::npos);
}

TEST_CASE("orthographic cameras: glTF's matrix from xmag, ymag, znear, zfar, and the image aspect they give") {
    const std::string text = test::cameras_gltf();
    // Nodes 1 and 2 place cameras 0 and 1; camera 2 is placed by none.
    const GltfContent content = import_text(text);
    REQUIRE(content.camera);
    const Camera& camera = content.camera->camera;
    CHECK(camera.projection == Projection::perspective);  // camera 0, the first placed in node order
    const Scene ortho = make_gltf_scene(content, "test.gltf", "flat");
    CHECK(ortho.camera.projection == Projection::orthographic);
    CHECK(ortho.camera.x_magnification == 4.0f);
    CHECK(ortho.camera.y_magnification == 2.0f);
    CHECK(ortho.width == 2 * ortho.height);  // aspect xmag / ymag
    const glm::mat4 p = projection_matrix(ortho.camera, ortho.width, ortho.height);
    // glTF §3.10.3: diag(1/xmag, 1/ymag, 2/(n − f), 1), z offset (f + n)/(n − f).
    CHECK(p[0][0] == doctest::Approx(0.25));
    CHECK(p[1][1] == doctest::Approx(0.5));
    CHECK(p[2][2] == doctest::Approx(2.0 / (0 - 20)));
    CHECK(p[3][2] == doctest::Approx(20.0 / (0 - 20)));
    CHECK(p[2][3] == 0.0f);
    CHECK(p[3][3] == 1.0f);
    // A point 4 right, 2 up of the camera, 20 in front lands on the image's corner at the far plane.
    const glm::vec4 clip = p * view_matrix(ortho.camera) * glm::vec4(4, 2, 7 - 20, 1);
    CHECK(glm::vec3(clip) / clip.w == glm::vec3(1, 1, 1));
    CHECK(content.warnings.empty());  // cameras[0] is placed

    // Bad xmag and zfar.
    std::string bad = text;
    bad.replace(bad.find("\"xmag\": 4"), 9, "\"xmag\": 0");
    CHECK(error_of(bad).find("cameras[1] 'flat' xmag, ymag are 0") != std::string::npos);
    bad = text;
    bad.replace(bad.find("\"zfar\": 20"), 10, "\"zfar\": -1");
    CHECK(error_of(bad).find("zfar is -1") != std::string::npos);

    // The file's first camera placed by no node: one warning naming it and the one used.
    std::string unplaced = text;
    unplaced.replace(unplaced.find("{\"camera\": 0, "), 14, "{");
    const GltfContent skipped = import_text(unplaced);
    REQUIRE(skipped.warnings.size() == 1);
    CHECK(skipped.warnings[0] == "cameras[0] 'unplaced' is skipped: no node of the scene places it; using cameras[1] 'flat'");
    CHECK(skipped.camera->camera.projection == Projection::orthographic);
}

TEST_CASE("points and lines primitives become point and line meshes, strips and loops line lists") {
    const std::string text = test::points_and_lines_gltf();
    const GltfContent content = import_text(text);
    REQUIRE(content.meshes.size() == 4);
    CHECK(content.skipped_primitives == 0);
    CHECK(content.meshes[0].topology == Topology::points);
    CHECK(content.meshes[0].indices == std::vector<std::uint32_t>{0, 1, 2, 3});
    CHECK(content.meshes[0].normals.empty());  // unlit in glTF; lit facing the camera here
    CHECK(content.meshes[1].topology == Topology::lines);
    CHECK(content.meshes[1].indices == std::vector<std::uint32_t>{0, 1, 2, 3});
    CHECK(content.meshes[2].indices == std::vector<std::uint32_t>{0, 1, 1, 2, 2, 3, 3, 0});  // LINE_LOOP
    CHECK(content.meshes[3].indices == std::vector<std::uint32_t>{0, 1, 1, 2, 2, 3});        // LINE_STRIP
    const Scene scene = make_gltf_scene(content, "test.gltf");  // validates
    CHECK(scene.objects.size() == 4);

    // LINES with an odd vertex count: skipped, counted.
    std::string odd = text;
    odd.replace(odd.find("\"count\": 4"), 10, "\"count\": 3");
    const GltfContent skipped = import_text(odd);
    CHECK(skipped.skipped_primitives == 1);  // LINES of 3 vertices; the strip and loop of 3 are drawn
    CHECK(skipped.meshes.size() == 3);
}

TEST_CASE("KHR_mesh_quantization morph targets: plain SHORT POSITION deltas in quantized units, as gltfpack writes") {
    // A triangle stored as plain shorts (positions in units of 1/100, dequantized by the
    // node's scale 0.01), one morph target moving vertex 2 by +50 units in Z.
    const std::string strided = test::quantized_morph_gltf();
    const GltfContent content = import_text(strided);
    REQUIRE(content.meshes.size() == 1);
    CHECK(near(content.meshes[0].positions[2], {0, 100, 50}));  // rest pose at weight 1, in quantized units
    CHECK(near(placed(content.objects[0], content.meshes[0].positions[2]), {0, 1, 0.5f}));
    // Without KHR_mesh_quantization plain shorts are refused.
    std::string plain = strided;
    plain.replace(plain.find("\"extensionsUsed\": [\"KHR_mesh_quantization\"],"), 44, "");
    plain.replace(plain.find("\"extensionsRequired\": [\"KHR_mesh_quantization\"],"), 48, "");
    CHECK(error_of(plain).find("bad.gltf:") == 0);
}
