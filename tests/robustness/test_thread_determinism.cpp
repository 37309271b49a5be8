// Determinism at scale: every scene in scenes/ renders bit-identically with
// 1, 2, 3, 7 and 16 threads (more than this machine has cores) and on every run.
#include <algorithm>
#include <filesystem>
#include <vector>

#include <doctest/doctest.h>

#include "tessera/renderer.hpp"
#include "test_paths.hpp"

using namespace tessera;

TEST_CASE("every bundled scene is bit-identical for 1, 2, 3, 7 and 16 threads and across runs") {
    std::vector<std::filesystem::path> scenes = test::scene_files();
    REQUIRE(scenes.size() >= 2);
    // scenes/gltf/ too, where the sample models are (textured, normal-mapped, glTF lights).
    if (std::filesystem::is_directory(test::assets_dir())) {
        const std::vector<std::filesystem::path> models = test::gltf_scene_files();
        scenes.insert(scenes.end(), models.begin(), models.end());
    } else {
        MESSAGE("scenes/gltf skipped: no sample models at " << test::assets_dir().string());
    }
    for (const std::filesystem::path& path : scenes) {
        CAPTURE(path.string());
        const Scene scene = load_scene_file(path);
        Renderer one({.threads = 1});
        const RenderedImage reference = one.render(scene);  // a copy: render() reuses its image
        for (int threads : {1, 2, 3, 7, 16}) {
            CAPTURE(threads);
            Renderer renderer({.threads = threads});
            for (int run = 0; run < 2; ++run) {  // the second frame reuses the first one's memory
                CAPTURE(run);
                const RenderedImage& image = renderer.render(scene);
                CHECK(image.display == reference.display);
                CHECK(image.radiance == reference.radiance);  // bitwise: no NaN in these scenes
            }
        }
    }
}
