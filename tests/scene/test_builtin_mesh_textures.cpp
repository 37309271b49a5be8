// Textures on the built-in plane and cube (src/scene/builtin_meshes.cpp) read
// as glTF's would: upright and not mirrored, seen from above (the plane, the
// cube's top) or from outside each face. The test texture has four quadrants
// of different colours, so a flip or a mirror moves a colour to another
// corner; it is shown through the emissive map of a black, unlit material, so
// each pixel is the texel's colour tonemapped. uv_scale repeats it.
#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "tessera/image_io.hpp"
#include "tessera/renderer.hpp"
#include "tessera/scene.hpp"
#include "test_paths.hpp"

namespace fs = std::filesystem;

namespace {

enum class Colour { red, green, blue, white, other };

const char* colour_name(Colour c) {
    switch (c) {
        case Colour::red: return "red";
        case Colour::green: return "green";
        case Colour::blue: return "blue";
        case Colour::white: return "white";
        default: return "other";
    }
}

// The texture: 8x8, as stored (row 0 at the top): top-left red, top-right green,
// bottom-left blue, bottom-right white; one quadrant alone has no mirror image.
fs::path write_quadrant_texture(const fs::path& dir) {
    constexpr int kSize = 8;
    tessera::RenderedImage image;
    image.width = image.height = kSize;
    image.display.resize(std::size_t(kSize) * kSize * 3);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const bool right = x >= kSize / 2, bottom = y >= kSize / 2;
            const std::array<std::uint8_t, 3> rgb = !bottom ? (right ? std::array<std::uint8_t, 3>{0, 255, 0}
                                                                     : std::array<std::uint8_t, 3>{255, 0, 0})
                                                            : (right ? std::array<std::uint8_t, 3>{255, 255, 255}
                                                                     : std::array<std::uint8_t, 3>{0, 0, 255});
            for (int c = 0; c < 3; ++c) image.display[(std::size_t(y) * kSize + x) * 3 + c] = rgb[c];
        }
    const fs::path path = dir / "quadrants.png";
    tessera::write_image(image, path);
    return path;
}

// One object seen from `eye` towards the origin with `up` up the screen: 64x64 pixels.
tessera::RenderedImage render(const fs::path& dir, const std::string& mesh, const std::string& eye,
                              const std::string& up, const std::string& uv_scale = "") {
    const fs::path scene = dir / "scene.toml";
    std::ofstream(scene) << "[output]\nwidth = 64\nheight = 64\nclear_color = [0, 0, 0]\n"
                         << "[camera]\nposition = " << eye << "\ntarget = [0, 0, 0]\nup = " << up << "\n"
                         << "[materials.shown]\nalbedo = [0, 0, 0]\nemissive = [1, 1, 1]\n"
                         << "emissive_map = \"quadrants.png\"\nwrap = \"" << (uv_scale.empty() ? "clamp_to_edge" : "repeat")
                         << "\"\n[[objects]]\nmesh = \"" << mesh << "\"\nmaterial = \"shown\"\n"
                         << (uv_scale.empty() ? "" : "uv_scale = " + uv_scale + "\n");
    tessera::RenderSettings settings;
    settings.threads = 1;
    tessera::Renderer renderer(settings);
    return renderer.render(tessera::load_scene_file(scene));
}

Colour colour_at(const tessera::RenderedImage& image, int x, int y) {
    const std::uint8_t* p = &image.display[(std::size_t(y) * image.width + x) * 3];
    const auto high = [](std::uint8_t v) { return v > 100; };
    const auto low = [](std::uint8_t v) { return v < 20; };
    if (high(p[0]) && low(p[1]) && low(p[2])) return Colour::red;
    if (low(p[0]) && high(p[1]) && low(p[2])) return Colour::green;
    if (low(p[0]) && low(p[1]) && high(p[2])) return Colour::blue;
    if (high(p[0]) && high(p[1]) && high(p[2])) return Colour::white;
    return Colour::other;
}

// A face 2 units wide, 3 units away at fov 45 degrees: its quadrants' centres
// fall at pixels 19 and 45 of 64 (0.5 / (3 tan 22.5°) of the half-width).
void check_upright(const tessera::RenderedImage& image) {
    CHECK(colour_name(colour_at(image, 19, 19)) == std::string("red"));    // top-left
    CHECK(colour_name(colour_at(image, 45, 19)) == std::string("green"));  // top-right
    CHECK(colour_name(colour_at(image, 19, 45)) == std::string("blue"));   // bottom-left
    CHECK(colour_name(colour_at(image, 45, 45)) == std::string("white"));  // bottom-right
}

}  // namespace

TEST_CASE("a texture reads upright on the built-in plane seen from above and on each cube face seen from outside") {
    const fs::path dir = tessera::test::output_dir("builtin_mesh_textures");
    write_quadrant_texture(dir);

    SUBCASE("the plane, from above, with -Z (away from a viewer in front) up the screen") {
        check_upright(render(dir, "plane", "[0, 3, 0]", "[0, 0, -1]"));
    }
    // Each face 3 units from the eye (the cube's faces are at ±1).
    struct Face {
        const char* name;
        const char* eye;
        const char* up;
    };
    for (const Face& face : {Face{"+Z (front)", "[0, 0, 4]", "[0, 1, 0]"}, Face{"-Z (back)", "[0, 0, -4]", "[0, 1, 0]"},
                             Face{"+X (right)", "[4, 0, 0]", "[0, 1, 0]"}, Face{"-X (left)", "[-4, 0, 0]", "[0, 1, 0]"},
                             // The top with the back edge up the screen, the bottom with the front edge.
                             Face{"+Y (top)", "[0, 4, 0]", "[0, 0, -1]"}, Face{"-Y (bottom)", "[0, -4, 0]", "[0, 0, 1]"}}) {
        CAPTURE(face.name);
        check_upright(render(dir, "cube", face.eye, face.up));
    }
}

TEST_CASE("uv_scale repeats a texture across a built-in mesh") {
    const fs::path dir = tessera::test::output_dir("builtin_mesh_uv_scale");
    write_quadrant_texture(dir);
    // Pixels 13, 26, 38 and 51 look at x (and z) = -0.75, -0.25, 0.25 and 0.75 on the plane.
    const std::array<int, 4> at{13, 26, 38, 51};

    SUBCASE("uv_scale = 2: two copies across and two down") {
        const tessera::RenderedImage image = render(dir, "plane", "[0, 3, 0]", "[0, 0, -1]", "2");
        for (int row = 0; row < 4; ++row)
            for (int column = 0; column < 4; ++column) {
                CAPTURE(row);
                CAPTURE(column);
                const bool right = column % 2 == 1, bottom = row % 2 == 1;
                const Colour expected = !bottom ? (right ? Colour::green : Colour::red)
                                                : (right ? Colour::white : Colour::blue);
                CHECK(colour_name(colour_at(image, at[column], at[row])) == std::string(colour_name(expected)));
            }
    }
    SUBCASE("uv_scale = [2, 1]: two copies across, one down") {
        const tessera::RenderedImage image = render(dir, "plane", "[0, 3, 0]", "[0, 0, -1]", "[2, 1]");
        for (int row = 0; row < 4; ++row)
            for (int column = 0; column < 4; ++column) {
                CAPTURE(row);
                CAPTURE(column);
                const bool right = column % 2 == 1, bottom = row >= 2;
                const Colour expected = !bottom ? (right ? Colour::green : Colour::red)
                                                : (right ? Colour::white : Colour::blue);
                CHECK(colour_name(colour_at(image, at[column], at[row])) == std::string(colour_name(expected)));
            }
    }
    SUBCASE("objects with and without uv_scale share no mesh; objects with the same one do") {
        const fs::path scene = dir / "shared.toml";
        std::ofstream(scene) << "[camera]\nposition = [0, 0, 5]\ntarget = [0, 0, 0]\n"
                             << "[[objects]]\nmesh = \"cube\"\n[[objects]]\nmesh = \"cube\"\nuv_scale = [3, 2]\n"
                             << "[[objects]]\nmesh = \"cube\"\nuv_scale = [3, 2]\n";
        const tessera::Scene loaded = tessera::load_scene_file(scene);
        REQUIRE(loaded.meshes.size() == 2);
        CHECK(loaded.objects[1].mesh == loaded.objects[2].mesh);
        CHECK(loaded.objects[0].mesh != loaded.objects[1].mesh);
        const tessera::Mesh& plain = loaded.meshes[loaded.objects[0].mesh];
        const tessera::Mesh& scaled = loaded.meshes[loaded.objects[1].mesh];
        REQUIRE(plain.uvs.size() == scaled.uvs.size());
        for (std::size_t i = 0; i < plain.uvs.size(); ++i) CHECK(scaled.uvs[i] == plain.uvs[i] * glm::vec2(3, 2));
    }
}
