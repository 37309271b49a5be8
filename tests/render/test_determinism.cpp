#include <doctest/doctest.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tessera/image_io.hpp"
#include "render/isa_agreement.hpp"
#include "simd/isa.hpp"
#include "tessera/renderer.hpp"
#include "test_paths.hpp"

using namespace tessera;

TEST_CASE("the spheres scene renders bit-identically with 1, 2 and 8 threads and on every run") {
    const Scene scene = load_scene_file(test::scene_path("spheres.toml"));
    Renderer one({.threads = 1});
    const RenderedImage reference = one.render(scene);  // a copy: render() reuses its image
    CHECK(one.render(scene).display == reference.display);  // a second frame from reused memory
    for (int threads : {2, 8}) {
        CAPTURE(threads);
        Renderer renderer({.threads = threads});
        const RenderedImage& image = renderer.render(scene);
        CHECK(image.display == reference.display);
        CHECK(image.radiance == reference.radiance);
    }
}

TEST_CASE("the tile size changes the schedule, not the picture") {
    const Scene scene = load_scene_file(test::scene_path("spheres.toml"));
    Renderer small({.threads = 2, .tile_size = 16});
    const RenderedImage reference = small.render(scene);
    Renderer large({.threads = 2, .tile_size = 64});
    CHECK(large.render(scene).radiance == reference.radiance);
}

// Every scene, with the SIMD kernels: where a tile's runs of materials meet
// moves with the tile size, and textured runs once depended on it (the
// normal-map kernel wrote past its run into the next one). The narrowest and
// the widest ISA (a sanitizer build renders slowly; the scalar path works
// fragment by fragment and has its own tests).
namespace {

void check_tile_sizes(const std::vector<std::filesystem::path>& files) {
    REQUIRE(!files.empty());
    std::vector<simd::Isa> isas = {simd::Isa::sse4};
    if (simd::best_supported_isa() != simd::Isa::sse4) isas.push_back(simd::best_supported_isa());
    for (const auto& file : files) {
        const Scene scene = load_scene_file(file);
        for (const simd::Isa isa : isas) {
            if (!simd::isa_supported(isa)) continue;
            const std::string name(simd::isa_name(isa));
            CAPTURE(file.string());
            CAPTURE(name);
            Renderer small({.threads = 2, .tile_size = 16, .isa = name});
            const RenderedImage reference = small.render(scene);
            Renderer large({.threads = 2, .tile_size = 128, .isa = name});
            CHECK(large.render(scene).radiance == reference.radiance);
        }
    }
}

}  // namespace

TEST_CASE("the tile size changes no scene's picture, with SIMD kernels") {
    check_tile_sizes(test::scene_files(test::source_dir() / "scenes"));
}

// The same for scenes/gltf/ with the sample models; Skipped without them.
TEST_CASE("the tile size changes no sample-model scene's picture (scenes/gltf), with SIMD kernels") {
    if (test::skip_without_assets()) return;
    check_tile_sizes(test::gltf_scene_files());
}

TEST_CASE("every shading ISA renders the spheres scene within 1/255 of the scalar reference path") {
    const Scene scene = load_scene_file(test::scene_path("spheres.toml"));
    Renderer scalar({.isa = "scalar"});
    const RenderedImage reference = scalar.render(scene);
    test::check_every_isa_within(scene, reference, 1);
}

TEST_CASE("renderer settings are validated") {
    CHECK_THROWS_AS(Renderer({.tile_size = 48}), std::invalid_argument);
    CHECK_THROWS_AS(Renderer({.tile_size = 4}), std::invalid_argument);
    CHECK_THROWS_AS(Renderer({.threads = -1}), std::invalid_argument);
    CHECK_THROWS_WITH_AS(Renderer({.isa = "neon"}), doctest::Contains("unknown ISA"), std::invalid_argument);
}

TEST_CASE("dropping the HDR radiance image leaves the display image as it was, and EXR output is refused") {
    const Scene scene = load_scene_file(test::scene_path("shapes.toml"));
    Renderer with({.threads = 2});
    const RenderedImage reference = with.render(scene);
    Renderer without({.threads = 2, .keep_radiance = false});
    const RenderedImage& image = without.render(scene);
    CHECK(image.radiance.empty());
    CHECK(image.display == reference.display);
    CHECK_THROWS_WITH_AS(write_image(image, test::output_dir("no_radiance") / "out.exr"),
                         doctest::Contains("no HDR radiance"), ImageError);
}
