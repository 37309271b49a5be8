// Every bad scene in bad_scenes.hpp is refused by parse_scene with a SceneError
// naming the file (and, for most, the line and column) and saying what is wrong.
// Scenes at the edge of validity load.
#include <string>

#include <doctest/doctest.h>

#include "robustness/bad_scenes.hpp"
#include "tessera/scene.hpp"
#include "test_paths.hpp"

namespace {

std::string with_file_name(std::string_view expected, const std::string& file) {
    std::string text(expected);
    for (std::size_t at = text.find('@'); at != std::string::npos; at = text.find('@', at + file.size()))
        text.replace(at, 1, file);
    return text;
}

}  // namespace

TEST_CASE("bad scene files are refused with the file, the position and what is wrong") {
    for (const tessera::test::BadScene& row : tessera::test::bad_scenes()) {
        const std::string row_name = row.name;
        CAPTURE(row_name);
        const std::string file = std::string(row.name) + ".toml";
        std::string message;
        try {
            tessera::parse_scene(row.text, file);
            FAIL_CHECK("accepted");
            continue;
        } catch (const tessera::SceneError& error) {
            message = error.what();
        }
        CHECK_MESSAGE(message.rfind(file + ":", 0) == 0, message);
        for (std::string_view part : row.expected) {
            const std::string wanted = with_file_name(part, file);
            CHECK_MESSAGE(message.find(wanted) != std::string::npos, "'" << wanted << "' not in: " << message);
        }
    }
}

TEST_CASE("scenes at the edge of validity load") {
    const std::string camera = "[camera]\nposition = [0, 0, 5]\ntarget = [0, 0, 0]\n";
    SUBCASE("no lights and no objects") {
        const tessera::Scene scene = tessera::parse_scene(camera, "empty.toml");
        CHECK(scene.lights.empty());
        CHECK(scene.objects.empty());
    }
    SUBCASE("the largest allowed sizes: one side at the limit, the pixel count at the limit") {
        const tessera::Scene wide = tessera::parse_scene(camera + "[output]\nwidth = 16384\nheight = 8192\n", "w.toml");
        CHECK(static_cast<long long>(wide.width) * wide.height == tessera::kMaxImagePixels);
        const tessera::Scene thin = tessera::parse_scene(camera + "[output]\nwidth = 16384\nheight = 1\n", "t.toml");
        CHECK(thin.width == tessera::kMaxImageDimension);
    }
    SUBCASE("a field of view just inside (0, 180) and a tiny near plane") {
        CHECK_NOTHROW(tessera::parse_scene(camera + "fov_y = 179.9\nnear = 1e-6\nfar = 1e30\n", "f.toml"));
        CHECK_NOTHROW(tessera::parse_scene(camera + "fov_y = 0.001\n", "f.toml"));
    }
    SUBCASE("up nearly, but not exactly, along the view direction") {
        CHECK_NOTHROW(tessera::parse_scene(camera + "up = [0.001, 0, 1]\n", "u.toml"));
    }
}

TEST_CASE("bad glTF files are refused with the file and what is wrong, never a crash") {
    const std::filesystem::path dir = tessera::test::output_dir("bad_gltf_files");
    for (const tessera::test::BadGltf& row : tessera::test::all_bad_gltf_files()) {
        CAPTURE(row.name);
        const std::filesystem::path file = dir / (row.name + row.extension);
        tessera::test::write_bytes(file, row.bytes);
        std::string message;
        try {
            tessera::load_scene_file(file);
            FAIL_CHECK("accepted");
            continue;
        } catch (const tessera::SceneError& error) {
            message = error.what();
        }
        CHECK_MESSAGE(message.rfind(file.string() + ":", 0) == 0, message);
        for (const std::string& part : row.expected) {
            const std::string wanted = with_file_name(part, file.string());
            CHECK_MESSAGE(message.find(wanted) != std::string::npos, "'" << wanted << "' not in: " << message);
        }
    }
}
