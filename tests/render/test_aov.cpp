// AOVs from render to file: a plane perpendicular to the view axis at a known
// depth, rendered with every AOV, written to EXR and read back by channel name.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <fstream>
#include <map>
#include <set>
#include <string>

#include <OpenImageIO/imageio.h>
#include <glm/gtc/matrix_transform.hpp>

#include "tessera/image_io.hpp"
#include "tessera/renderer.hpp"
#include "scene/gltf_test_files.hpp"
#include "test_paths.hpp"

using namespace tessera;

namespace {

AovSet every_aov() {
    AovSet set;
    for (Aov aov : kAllAovs) set.insert(aov);
    return set;
}

// The camera looks straight down -Y from 5 units above the plane y = 0.5, so
// every point of the plane is at view depth 5; the plane's 3×2 rectangle is
// off-centre and smaller than the view, leaving background on every side.
constexpr float kPlaneY = 0.5f;
constexpr float kDepth = 5.0f;
const glm::vec3 kPlaneCentre{0.7f, kPlaneY, -0.2f};
constexpr float kHalfX = 1.5f, kHalfZ = 1.0f;
const Material kMaterial{.albedo = {0.2f, 0.4f, 0.6f}, .metallic = 0.25f, .roughness = 0.75f};

Scene plane_scene() {
    Scene scene;
    scene.width = 64;
    scene.height = 48;
    scene.camera.position = {0.3f, kPlaneY + kDepth, -0.2f};
    scene.camera.target = {0.3f, kPlaneY, -0.2f};
    scene.camera.up = {0.0f, 0.0f, -1.0f};
    scene.lights.push_back(Light{.position = {1.0f, 4.0f, 1.0f}, .color = {30.0f, 30.0f, 30.0f}});
    scene.materials.push_back(kMaterial);
    scene.meshes.push_back(make_plane_mesh());  // 2×2 in XZ, normal +Y
    Object plane;
    // Scaling y leaves the flat plane where it is but halves its world normal
    // (the vertex stage does not normalize): the AOV must still be unit length.
    plane.model = glm::scale(glm::translate(glm::mat4(1.0f), kPlaneCentre), glm::vec3(kHalfX, 2.0f, kHalfZ));
    scene.objects.push_back(plane);
    return scene;
}

// An EXR read back whole, as float, with each channel found by name.
struct ExrFile {
    OIIO::ImageSpec spec;
    std::vector<float> pixels;
    std::map<std::string, int> channel;

    float at(int x, int y, const std::string& name) const {
        return pixels[(std::size_t(y) * spec.width + x) * spec.nchannels + channel.at(name)];
    }
};

ExrFile read_exr(const std::filesystem::path& path) {
    auto in = OIIO::ImageInput::open(path.string());
    REQUIRE_MESSAGE(in, OIIO::geterror());
    ExrFile file;
    file.spec = in->spec();
    file.pixels.resize(std::size_t(file.spec.width) * file.spec.height * file.spec.nchannels);
    REQUIRE(in->read_image(0, 0, 0, file.spec.nchannels, OIIO::TypeDesc::FLOAT, file.pixels.data()));
    for (int c = 0; c < file.spec.nchannels; ++c) file.channel[file.spec.channelnames[c]] = c;
    return file;
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

}  // namespace

TEST_CASE("the EXR holds every AOV by its conventional name, with the plane's depth, normal, material and position") {
    const Scene scene = plane_scene();
    Renderer renderer({.threads = 2, .aovs = every_aov()});
    const RenderedImage& image = renderer.render(scene);
    const auto path = test::output_dir("aov") / "plane.exr";
    write_image(image, path);
    const ExrFile file = read_exr(path);

    REQUIRE(file.spec.width == scene.width);
    REQUIRE(file.spec.height == scene.height);
    const std::map<std::string, OIIO::TypeDesc> expected_formats = {
        {"R", OIIO::TypeDesc::HALF},        {"G", OIIO::TypeDesc::HALF},        {"B", OIIO::TypeDesc::HALF},
        {"Z", OIIO::TypeDesc::FLOAT},       {"N.X", OIIO::TypeDesc::FLOAT},     {"N.Y", OIIO::TypeDesc::FLOAT},
        {"N.Z", OIIO::TypeDesc::FLOAT},     {"albedo.R", OIIO::TypeDesc::HALF}, {"albedo.G", OIIO::TypeDesc::HALF},
        {"albedo.B", OIIO::TypeDesc::HALF}, {"roughness", OIIO::TypeDesc::HALF}, {"metallic", OIIO::TypeDesc::HALF},
        {"P.X", OIIO::TypeDesc::FLOAT},     {"P.Y", OIIO::TypeDesc::FLOAT},     {"P.Z", OIIO::TypeDesc::FLOAT},
        {"object_id", OIIO::TypeDesc::UINT}, {"material_id", OIIO::TypeDesc::UINT},
        {"shadow", OIIO::TypeDesc::HALF}};
    REQUIRE(file.channel.size() == expected_formats.size());
    for (const auto& [name, format] : expected_formats) {
        CAPTURE(name);
        REQUIRE(file.channel.count(name) == 1);
        CHECK(file.spec.channelformat(file.channel.at(name)) == format);
    }
    CHECK(file.spec.z_channel == file.channel.at("Z"));

    // Where each pixel centre's ray meets the plane y = kPlaneY.
    const glm::mat4 inverse_view_projection =
        glm::inverse(projection_matrix(scene.camera, scene.width, scene.height) * view_matrix(scene.camera));
    const auto plane_point = [&](int x, int y) {
        const float ndc_x = (x + 0.5f) / scene.width * 2 - 1, ndc_y = 1 - (y + 0.5f) / scene.height * 2;
        const glm::vec4 far_point = inverse_view_projection * glm::vec4(ndc_x, ndc_y, 1, 1);
        const glm::vec3 dir = glm::vec3(far_point) / far_point.w - scene.camera.position;
        return scene.camera.position + (kPlaneY - scene.camera.position.y) / dir.y * dir;
    };
    const float footprint = 2 * kDepth * std::tan(glm::radians(scene.camera.fov_y_degrees) / 2) / scene.height;

    int covered = 0, background = 0;
    for (int y = 0; y < scene.height; ++y) {
        for (int x = 0; x < scene.width; ++x) {
            CAPTURE(x);
            CAPTURE(y);
            const glm::vec3 hit = plane_point(x, y);
            // Signed distance inside the plane's rectangle; pixels within one footprint of its edge are skipped.
            const float inside = std::min(kHalfX - std::abs(hit.x - kPlaneCentre.x), kHalfZ - std::abs(hit.z - kPlaneCentre.z));
            if (inside > footprint) {
                ++covered;
                // View-axis depth, not the distance along the ray (which grows off-centre).
                CHECK(file.at(x, y, "Z") == doctest::Approx(kDepth).epsilon(1e-5));
                CHECK(file.at(x, y, "N.X") == doctest::Approx(0.0f).epsilon(1e-6));
                CHECK(file.at(x, y, "N.Y") == doctest::Approx(1.0f).epsilon(1e-6));
                CHECK(file.at(x, y, "N.Z") == doctest::Approx(0.0f).epsilon(1e-6));
                CHECK(file.at(x, y, "albedo.R") == doctest::Approx(kMaterial.albedo.r).epsilon(1e-3));
                CHECK(file.at(x, y, "albedo.G") == doctest::Approx(kMaterial.albedo.g).epsilon(1e-3));
                CHECK(file.at(x, y, "albedo.B") == doctest::Approx(kMaterial.albedo.b).epsilon(1e-3));
                CHECK(file.at(x, y, "roughness") == doctest::Approx(kMaterial.roughness).epsilon(1e-3));
                CHECK(file.at(x, y, "metallic") == doctest::Approx(kMaterial.metallic).epsilon(1e-3));
                // Vertices snap to sub-pixel positions: the point seen is within a small part of a pixel.
                CHECK(std::abs(file.at(x, y, "P.X") - hit.x) < 0.05f * footprint);
                CHECK(file.at(x, y, "P.Y") == doctest::Approx(kPlaneY).epsilon(1e-5));
                CHECK(std::abs(file.at(x, y, "P.Z") - hit.z) < 0.05f * footprint);
                // Read as float, OpenImageIO scales a uint channel into [0, 1]: the ids' values are
                // checked as uint in "the EXR stores the ids as uint channels, exactly".
                CHECK(file.at(x, y, "object_id") > 0.0f);
                CHECK(file.at(x, y, "material_id") > 0.0f);
                CHECK(file.at(x, y, "shadow") == 1.0f);  // no light casts shadows
            } else if (inside < -footprint) {
                CHECK(file.at(x, y, "shadow") == 1.0f);
                ++background;
                CHECK(file.at(x, y, "Z") == std::numeric_limits<float>::infinity());
                for (const char* name : {"N.X", "N.Y", "N.Z", "albedo.R", "albedo.G", "albedo.B", "roughness",
                                         "metallic", "P.X", "P.Y", "P.Z", "object_id", "material_id"})
                    CHECK(file.at(x, y, name) == 0.0f);
            }
            // The radiance is still R, G, B beside the AOVs.
            const std::size_t i = 3 * (std::size_t(y) * scene.width + x);
            CHECK(file.at(x, y, "R") == doctest::Approx(image.radiance[i]).epsilon(1e-3));
            CHECK(file.at(x, y, "B") == doctest::Approx(image.radiance[i + 2]).epsilon(1e-3));
        }
    }
    CHECK(covered > 600);  // the 3×2 plane over a 5.5×4.1 view: about a quarter of the pixels
    CHECK(background > 600);

    // The pixel at the image centre sees the point the camera looks at.
    const int cx = scene.width / 2, cy = scene.height / 2;
    CHECK(std::abs(file.at(cx, cy, "P.X") - scene.camera.target.x) < footprint);
    CHECK(std::abs(file.at(cx, cy, "P.Y") - scene.camera.target.y) < 1e-5f);
    CHECK(std::abs(file.at(cx, cy, "P.Z") - scene.camera.target.z) < footprint);
}

TEST_CASE("only the AOVs asked for are kept and written, and the other images do not change") {
    const Scene scene = plane_scene();
    Renderer plain({.threads = 2});
    const RenderedImage without = plain.render(scene);
    CHECK(without.aov.empty());
    CHECK(without.aov.depth.capacity() == 0);  // nothing allocated for a render without AOVs
    CHECK(without.aov.position.capacity() == 0);

    AovSet depth_and_albedo;
    parse_aov_list("depth,albedo,depth", depth_and_albedo);
    Renderer with({.threads = 2, .aovs = depth_and_albedo});
    const RenderedImage& image = with.render(scene);
    CHECK(image.aov.depth.size() == std::size_t(scene.width) * scene.height);
    CHECK(image.aov.albedo.size() == 3 * std::size_t(scene.width) * scene.height);
    CHECK(image.aov.normal.empty());
    CHECK(image.aov.roughness.empty());
    CHECK(image.display == without.display);
    CHECK(same_bits(image.radiance, without.radiance));

    const auto path = test::output_dir("aov") / "depth_albedo.exr";
    write_image(image, path);
    const ExrFile file = read_exr(path);
    CHECK(file.channel.size() == 7);
    for (const char* name : {"R", "G", "B", "Z", "albedo.R", "albedo.G", "albedo.B"}) CHECK(file.channel.count(name) == 1);

    // Steady state: the next frame writes into the same planes.
    const float* depth_before = image.aov.depth.data();
    const float* albedo_before = image.aov.albedo.data();
    with.render(scene);
    CHECK(with.render(scene).aov.depth.data() == depth_before);
    CHECK(with.render(scene).aov.albedo.data() == albedo_before);
}

TEST_CASE("AOV planes are bit-identical for any thread count and tile size") {
    const Scene scene = load_scene_file(test::scene_path("spheres.toml"));
    Renderer one({.threads = 1, .aovs = every_aov()});
    const RenderedImage reference = one.render(scene);
    REQUIRE_FALSE(reference.aov.empty());
    for (const auto& [threads, tile_size] : {std::pair{2, 32}, std::pair{5, 16}, std::pair{3, 64}}) {
        CAPTURE(threads);
        CAPTURE(tile_size);
        Renderer renderer({.threads = threads, .tile_size = tile_size, .aovs = every_aov()});
        const AovPlanes& aov = renderer.render(scene).aov;
        CHECK(same_bits(aov.depth, reference.aov.depth));
        CHECK(same_bits(aov.normal, reference.aov.normal));
        CHECK(same_bits(aov.albedo, reference.aov.albedo));
        CHECK(same_bits(aov.roughness, reference.aov.roughness));
        CHECK(same_bits(aov.metallic, reference.aov.metallic));
        CHECK(same_bits(aov.position, reference.aov.position));
        CHECK(aov.object_id == reference.aov.object_id);
        CHECK(aov.material_id == reference.aov.material_id);
    }
}

TEST_CASE("AOV lists name each AOV, anything else is refused with the list of names") {
    AovSet set;
    parse_aov_list("position", set);
    CHECK(set.contains(Aov::position));
    CHECK_FALSE(set.contains(Aov::depth));
    for (Aov aov : kAllAovs) parse_aov_list(aov_name(aov), set);
    CHECK(set == every_aov());
    CHECK_THROWS_WITH_AS(parse_aov_list("depth,colour", set), doctest::Contains("unknown AOV 'colour'"),
                         std::invalid_argument);
    CHECK_THROWS_WITH_AS(parse_aov_list("depth,,normal", set), doctest::Contains("unknown AOV ''"), std::invalid_argument);
    CHECK_THROWS_WITH_AS(parse_aov_list("Depth", set), doctest::Contains("depth, normal, albedo, roughness, metallic, position, object_id, material_id, shadow"),
                         std::invalid_argument);
}

namespace {

// Three planes side by side across the view (left, middle, right thirds, with
// gaps of background between), the middle one given no id.
Scene three_planes(int msaa = 1) {
    Scene scene = plane_scene();
    scene.msaa = msaa;
    scene.objects.clear();
    scene.materials.push_back(Material{.albedo = {0.9f, 0.1f, 0.1f}});
    const float xs[] = {-1.2f, 0.3f, 1.8f};
    const std::uint32_t ids[] = {7, 0, 40000000};  // past float's exact integers: the EXR's channel must be uint
    const std::uint32_t materials[] = {1, 0, 1};
    for (int k = 0; k < 3; ++k) {
        Object plane;
        plane.model = glm::scale(glm::translate(glm::mat4(1.0f), {xs[k], kPlaneY, -0.2f}), glm::vec3(0.6f, 1.0f, 1.0f));
        plane.material = materials[k];
        plane.id = ids[k];
        scene.objects.push_back(plane);
    }
    return scene;
}

AovSet ids_only() {
    AovSet set;
    set.insert(Aov::object_id);
    set.insert(Aov::material_id);
    return set;
}

}  // namespace

TEST_CASE("object_id and material_id say which object and material each pixel shows, 0 for the background") {
    for (const int msaa : {1, 4}) {
        CAPTURE(msaa);
        const Scene scene = three_planes(msaa);
        Renderer renderer({.threads = 2, .tile_size = 16, .aovs = ids_only()});
        const RenderedImage& image = renderer.render(scene);
        REQUIRE(image.aov.object_id.size() == std::size_t(scene.width) * scene.height);
        CHECK(image.aov.depth.empty());
        // Along the middle row: background, plane 7, background, plane 2 (index 1 + 1), background, plane 40000000.
        const int y = scene.height / 2;
        std::vector<std::uint32_t> runs;
        for (int x = 0; x < scene.width; ++x) {
            const std::size_t i = std::size_t(y) * scene.width + x;
            const std::uint32_t object = image.aov.object_id[i], material = image.aov.material_id[i];
            CHECK((object == 0) == (material == 0));
            if (object == 7 || object == 40000000) CHECK(material == 2);
            if (object == 2) CHECK(material == 1);
            if (runs.empty() || runs.back() != object) runs.push_back(object);
        }
        CHECK(runs == std::vector<std::uint32_t>{0, 7, 0, 2, 0, 40000000, 0});
        // The top and bottom rows see past the planes.
        CHECK(image.aov.object_id[0] == 0);
        CHECK(image.aov.material_id.back() == 0);

        // Bit-identical for other thread counts and tile sizes.
        Renderer other({.threads = 3, .tile_size = 64, .aovs = ids_only()});
        CHECK(other.render(scene).aov.object_id == image.aov.object_id);
        CHECK(other.render(scene).aov.material_id == image.aov.material_id);
    }
}

TEST_CASE("the EXR stores the ids as uint channels, exactly") {
    const Scene scene = three_planes();
    Renderer renderer({.threads = 2, .aovs = ids_only()});
    const RenderedImage& image = renderer.render(scene);
    const auto path = test::output_dir("aov") / "ids.exr";
    write_image(image, path);
    auto in = OIIO::ImageInput::open(path.string());
    REQUIRE_MESSAGE(in, OIIO::geterror());
    const OIIO::ImageSpec spec = in->spec();
    REQUIRE(spec.nchannels == 5);  // R G B material_id object_id
    std::map<std::string, int> channel;
    for (int c = 0; c < spec.nchannels; ++c) channel[spec.channelnames[c]] = c;
    REQUIRE(channel.count("object_id") == 1);
    REQUIRE(channel.count("material_id") == 1);
    CHECK(spec.channelformat(channel["object_id"]) == OIIO::TypeDesc::UINT);
    std::vector<std::uint32_t> object_id(image.aov.object_id.size()), material_id(object_id.size());
    REQUIRE(in->read_image(0, 0, channel["object_id"], channel["object_id"] + 1, OIIO::TypeDesc::UINT32, object_id.data()));
    REQUIRE(in->read_image(0, 0, channel["material_id"], channel["material_id"] + 1, OIIO::TypeDesc::UINT32,
                           material_id.data()));
    CHECK(object_id == image.aov.object_id);
    CHECK(material_id == image.aov.material_id);
    CHECK(std::count(object_id.begin(), object_id.end(), 40000000u) > 50);
}

TEST_CASE("object ids: one per TOML object or model entry, one per glTF node that places a mesh") {
    const auto dir = test::output_dir("aov");
    std::ofstream(dir / "parts.gltf") << test::embedded_test_gltf();
    // The glTF as the scene: nodes "child" and "second" place mesh "parts" (several primitives each).
    const Scene gltf = load_scene_file(dir / "parts.gltf");
    std::vector<std::uint32_t> ids;
    for (const Object& object : gltf.objects) ids.push_back(object.id);
    REQUIRE(ids.size() >= 4);
    CHECK(std::count(ids.begin(), ids.end(), 1u) == std::ptrdiff_t(ids.size() / 2));
    CHECK(std::count(ids.begin(), ids.end(), 2u) == std::ptrdiff_t(ids.size() / 2));
    CHECK(std::is_sorted(ids.begin(), ids.end()));

    // In a TOML file: [[objects]] first, in order, then each [[models]] entry as one object.
    std::ofstream(dir / "entries.toml") << R"([camera]
position = [0, 0, 10]
target = [0, 0, 0]
[[objects]]
mesh = "sphere"
[[models]]
file = "parts.gltf"
[[objects]]
mesh = "cube"
[[models]]
file = "parts.gltf"
translate = [3, 0, 0]
)";
    const Scene toml = load_scene_file(dir / "entries.toml");
    REQUIRE(toml.objects.size() == 2 + 2 * gltf.objects.size());
    CHECK(toml.objects[0].id == 1);
    CHECK(toml.objects[1].id == 2);
    std::set<std::uint32_t> model_ids[2];
    for (std::size_t o = 2; o < toml.objects.size(); ++o)
        model_ids[(o - 2) / gltf.objects.size()].insert(toml.objects[o].id);
    CHECK(model_ids[0] == std::set<std::uint32_t>{3});
    CHECK(model_ids[1] == std::set<std::uint32_t>{4});
}
