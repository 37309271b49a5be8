// Replays every input the fuzzers ever crashed on (tests/fuzz/regressions/<target>/)
// and the seed corpus through the fuzz targets' bodies, in the normal test suite.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "fuzz/fuzz_targets.hpp"
#include "test_paths.hpp"

namespace {

using Target = void (*)(const std::uint8_t*, std::size_t);

int replay_folder(const std::filesystem::path& dir, Target target) {
    if (!std::filesystem::is_directory(dir)) return 0;
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        if (entry.is_regular_file() && entry.path().filename() != "README.md") files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    for (const std::filesystem::path& file : files) {
        CAPTURE(file.string());
        std::ifstream in(file, std::ios::binary);
        const std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
        CHECK_NOTHROW(target(bytes.data(), bytes.size()));
    }
    return int(files.size());
}

void replay(const char* name, Target target) {
    const std::filesystem::path fuzz = tessera::test::source_dir() / "tests" / "fuzz";
    const int corpus = replay_folder(fuzz / "corpus" / name, target);
    const int regressions = replay_folder(fuzz / "regressions" / name, target);
    MESSAGE(std::string(name) << ": replayed " << corpus << " corpus and " << regressions << " regression inputs");
    CHECK(corpus > 0);
}

}  // namespace

TEST_CASE("fuzz regressions: scene parser") { replay("scene_parser", tessera::fuzz::scene_parser); }

TEST_CASE("fuzz regressions: glTF loader") { replay("gltf_loader", tessera::fuzz::gltf_loader); }

TEST_CASE("fuzz regressions: rasterizer") { replay("rasterizer", tessera::fuzz::rasterizer); }
