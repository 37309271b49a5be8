// Determinism at scale: every scene in scenes/ renders bit-identically with
// 1, 2, 3, 7 and 16 threads (more than this machine has cores) and on every run.
#include <algorithm>
#include <filesystem>
#include <vector>

#include <doctest/doctest.h>

#include "tessera/renderer.hpp"
#include "test_paths.hpp"

using namespace tessera;

namespace {

void check_thread_counts(const std::vector<std::filesystem::path>& scenes) {
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

}  // namespace

TEST_CASE("every bundled scene is bit-identical for 1, 2, 3, 7 and 16 threads and across runs") {
    const std::vector<std::filesystem::path> scenes = test::scene_files();
    REQUIRE(scenes.size() >= 2);
    check_thread_counts(scenes);
}

// scenes/gltf/ too, with the sample models (textured, normal-mapped, glTF lights); Skipped without them.
TEST_CASE("every sample-model scene (scenes/gltf) is bit-identical for 1, 2, 3, 7 and 16 threads and across runs") {
    if (test::skip_without_assets()) return;
    const std::vector<std::filesystem::path> scenes = test::gltf_scene_files();
    REQUIRE(!scenes.empty());
    check_thread_counts(scenes);
}
