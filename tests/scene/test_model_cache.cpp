// ModelCache: a model file is imported once per process, however many scenes
// (or placements in one scene) use it.
#include <filesystem>
#include <memory>
#include <string>

#include <doctest/doctest.h>

#include "scene/gltf_test_files.hpp"
#include "scene/model_cache.hpp"
#include "test_paths.hpp"

namespace {

namespace fs = std::filesystem;
using namespace tessera;

std::string scene_placing(const std::string& model_file, int copies) {
    std::string text = "[camera]\nposition = [0, 0, 20]\ntarget = [0, 0, 0]\n";
    for (int i = 0; i < copies; ++i) text += "[[models]]\nfile = \"" + model_file + "\"\ntranslate = [" + std::to_string(3 * i) + ", 0, 0]\n";
    return text;
}

}  // namespace

TEST_CASE("model cache: one import per file, the same content after") {
    const fs::path dir = test::output_dir("model_cache");
    fs::create_directories(dir / "models");
    test::write_bytes(dir / "models" / "a.glb", test::test_glb());
    test::write_bytes(dir / "models" / "b.glb", test::test_glb());

    ModelCache cache;
    const std::shared_ptr<const GltfContent> first = cache.load(dir / "models" / "a.glb");
    CHECK(cache.imports() == 1);
    CHECK(first->textures.size() == 2);
    // Another spelling of the same file is the same file.
    CHECK(cache.load(dir / "models" / ".." / "models" / "a.glb") == first);
    CHECK(cache.imports() == 1);
    // A different file with the same bytes is another model.
    const std::shared_ptr<const GltfContent> other = cache.load(dir / "models" / "b.glb");
    CHECK(other != first);
    CHECK(cache.imports() == 2);

    cache.clear();
    const std::shared_ptr<const GltfContent> again = cache.load(dir / "models" / "a.glb");
    CHECK(again != first);
    CHECK(cache.imports() == 3);
}

TEST_CASE("model cache: scenes loaded through one cache share a model's import and textures") {
    const fs::path dir = test::output_dir("model_cache");
    fs::create_directories(dir / "models");
    test::write_bytes(dir / "models" / "shared.glb", test::test_glb());
    test::write_bytes(dir / "scene_a.toml", scene_placing("models/shared.glb", 1));
    test::write_bytes(dir / "scene_b.toml", scene_placing("models/shared.glb", 2));

    ModelCache cache;
    const Scene a = load_scene_file(dir / "scene_a.toml", cache);
    const Scene b = load_scene_file(dir / "scene_b.toml", cache);
    const Scene c = load_scene_file(dir / "models" / "shared.glb", cache);  // a model file as a whole scene
    CHECK(cache.imports() == 1);
    REQUIRE(a.textures.size() == 2);
    REQUIRE(b.textures.size() == 4);  // two placements, each with its texture slots
    REQUIRE(c.textures.size() == 2);
    for (std::size_t t = 0; t < 2; ++t) {
        CHECK(b.textures[t] == a.textures[t]);
        CHECK(b.textures[t + 2] == a.textures[t]);
        CHECK(c.textures[t] == a.textures[t]);
    }
    CHECK(a.objects.size() == 6);
    CHECK(b.objects.size() == 12);

    // Without a cache each load imports anew (nothing outlives the call)...
    const Scene a_alone = load_scene_file(dir / "scene_a.toml");
    CHECK(a_alone.textures[0] != a.textures[0]);
    // ...but one scene placing a model twice still reads it once.
    const Scene b_alone = load_scene_file(dir / "scene_b.toml");
    CHECK(b_alone.textures[2] == b_alone.textures[0]);
    CHECK(b_alone.textures[3] == b_alone.textures[1]);
}

TEST_CASE("model cache: a file that failed to import is tried again") {
    const fs::path dir = test::output_dir("model_cache");
    const fs::path late = dir / "late.glb";
    fs::remove(late);
    ModelCache cache;
    CHECK_THROWS_AS((void)cache.load(late), SceneError);
    CHECK(cache.imports() == 0);
    test::write_bytes(late, test::test_glb());
    CHECK(cache.load(late)->objects.size() == 6);
    CHECK(cache.imports() == 1);
}
