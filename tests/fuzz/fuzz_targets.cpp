#include "fuzz/fuzz_targets.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string_view>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/gltf/gltf_import.hpp"
#include "scene/scene_validation.hpp"
#include "tessera/animation.hpp"
#include "tessera/renderer.hpp"

namespace tessera::fuzz {
namespace {

[[noreturn]] void invariant_failed(const char* what) {
    std::fprintf(stderr, "fuzz invariant failed: %s\n", what);
    std::abort();
}

void check_frame(const RenderedImage& image, const Scene& scene) {
    const std::size_t values = std::size_t(3) * scene.width * scene.height;
    if (image.width != scene.width || image.height != scene.height || image.display.size() != values ||
        image.radiance.size() != values)
        invariant_failed("the image does not have the scene's size");
}

// One renderer per process: its construction (thread arena) costs more than a small frame.
Renderer& renderer() {
    static Renderer instance({.threads = 2, .tile_size = 16});
    return instance;
}

// A scene a loader accepted: it must pass validate_scene too (`refused` says
// which promise broke if not), and render into a frame of its size.
void check_accepted_scene(Scene& scene, const char* refused) {
    try {
        validate_scene(scene);
    } catch (const SceneError& e) {
        std::fprintf(stderr, "%s\n", e.what());
        invariant_failed(refused);
    }
    // Small frames keep the fuzzer fast; the camera's aspect ratio follows.
    scene.width = std::min(scene.width, 32);
    scene.height = std::min(scene.height, 32);
    check_frame(renderer().render(scene), scene);
}

// Reads the fuzz input front to back; past the end it reads zeros.
class ByteReader {
public:
    ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
    std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }
    float raw_float() {
        std::uint8_t bytes[4] = {byte(), byte(), byte(), byte()};
        float value;
        std::memcpy(&value, bytes, sizeof value);
        return value;
    }
    // Mostly ordinary coordinates, often the values that break arithmetic.
    float coordinate() {
        static constexpr float kSpecial[] = {
            std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
            -std::numeric_limits<float>::infinity(), 1e30f, -1e30f, std::numeric_limits<float>::max(),
            -std::numeric_limits<float>::max(), std::numeric_limits<float>::denorm_min(), 0.0f, -0.0f,
            1e-30f, 16384.0f, 1e7f, -1e7f, 0.5f, -1.0f};
        const std::uint8_t selector = byte();
        if (selector >= 0xF0) return kSpecial[selector & 0x0F];
        if (selector >= 0xE0) return raw_float();
        return (float(selector) - 112.0f) / 32.0f + float(int8_t(byte())) / 4096.0f;  // about [-3.5, 3.5]
    }
    glm::vec3 vec3() {
        const float x = coordinate(), y = coordinate();
        return {x, y, coordinate()};
    }

private:
    const std::uint8_t* data_;
    std::size_t size_;
    std::size_t pos_ = 0;
};

}  // namespace

void scene_parser(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    Scene scene;
    try {
        scene = parse_scene(text, "fuzz.toml");
    } catch (const SceneError&) {
        return;  // the expected outcome for most inputs
    }
    check_accepted_scene(scene, "parse_scene accepted a scene that validate_scene refuses");
}

void gltf_loader(const std::uint8_t* data, std::size_t size) {
    Scene scene;
    try {
        const GltfContent content = import_gltf({data, size}, "fuzz.glb", "", {.read_external_files = false});
        scene = make_gltf_scene(content, "fuzz.glb");  // validates
    } catch (const SceneError&) {
        return;
    }
    check_accepted_scene(scene, "make_gltf_scene returned a scene that validate_scene refuses");
    // Skins, morph targets and animations posed at a few times and frames: never a
    // crash; a pose that leaves the valid range is refused by validate_scene.
    try {
        for (const double seconds : {0.0, 0.37, 1e4}) {
            set_scene_time(scene, seconds);
            validate_scene(scene);
        }
        if (play_gltf_animation(scene)) {
            set_scene_frame(scene, scene.animation->frame_count - 1);
            set_scene_frame(scene, scene.animation->frame_count / 2);
        }
    } catch (const SceneError&) {
    }
}

void rasterizer(const std::uint8_t* data, std::size_t size) {
    ByteReader in(data, size);
    Scene scene;
    scene.source = "fuzz";
    scene.width = 64;
    scene.height = 64;
    scene.camera.position = {0.0f, 0.0f, 3.0f};
    scene.lights.push_back({{2.0f, 3.0f, 4.0f}, {50.0f, 50.0f, 50.0f}});
    scene.materials.push_back(Material{});

    Mesh mesh;
    mesh.name = "fuzz";
    const int vertices = 3 + in.byte() % 10;
    for (int v = 0; v < vertices; ++v) {
        mesh.positions.push_back(in.vec3());
        // Mostly a sane normal; sometimes one from the input, NaN included.
        mesh.normals.push_back(in.byte() < 0xC0 ? glm::vec3{0.0f, 0.0f, 1.0f} : in.vec3());
    }
    const int triangle_count = 1 + in.byte() % 8;
    for (int i = 0; i < 3 * triangle_count; ++i) mesh.indices.push_back(in.byte() % vertices);
    scene.meshes.push_back(std::move(mesh));
    // The mesh drawn twice: as given, and through a model matrix from the input
    // (skipped where the matrix would not be finite, which validate_scene refuses).
    scene.objects.push_back(Object{});
    const glm::vec3 translate = in.vec3(), scale = in.vec3();
    const glm::mat4 model = glm::scale(glm::translate(glm::mat4(1.0f), translate), scale);
    bool model_finite = true;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) model_finite = model_finite && std::isfinite(model[c][r]);
    if (model_finite) scene.objects.push_back(Object{0, 0, model});

    validate_scene(scene);  // must hold by construction: indices are in range
    check_frame(renderer().render(scene), scene);
}

}  // namespace tessera::fuzz
