// Loading environment images and caching their maps (src/environment/
// equirect_image.cpp, environment_cache.cpp): bad files are refused with the
// file's name, a second acquisition comes from memory, a new process's from
// disk, and a damaged cache entry is ignored and computed again.
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#include <doctest/doctest.h>

#include "environment/environment_cache.hpp"
#include "cli_runner.hpp"
#include "test_paths.hpp"

namespace fs = std::filesystem;
using namespace tessera::environment;

namespace {

fs::path shipped() { return tessera::test::source_dir() / "scenes" / "environments" / "studio_256.exr"; }

void write_file(const fs::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

std::string load_error(const fs::path& path) {
    try {
        load_equirect_image(path);
    } catch (const EnvironmentError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("environment image: the shipped studio image loads as 256x128 linear RGB, bottom row first") {
    const EquirectImage image = load_equirect_image(shipped());
    CHECK(image.width == 256);
    CHECK(image.height == 128);
    // The studio has a white floor and a black ceiling: the floor (the image's
    // bottom rows, stored first) outshines the ceiling (stored last) many times.
    double ceiling = 0, floor = 0;
    for (int x = 0; x < image.width; ++x) ceiling += image.rgb[std::size_t(126) * 256 + x].g, floor += image.rgb[std::size_t(1) * 256 + x].g;
    CHECK(floor > 20.0 * ceiling);
}

TEST_CASE("environment image: missing, truncated, non-HDR and mis-sized files are refused, naming the file") {
    const fs::path dir = tessera::test::output_dir("environment_bad");
    const std::string exr = tessera::test::read_file(shipped());
    write_file(dir / "truncated.exr", exr.substr(0, 300));
    write_file(dir / "text.hdr", "this is not an image\n");
    write_file(dir / "wide.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 1000000\n" + std::string(64, '\x80'));
    write_file(dir / "empty.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 0 +X 0\n");
    write_file(dir / "picture.png", exr);
    for (const char* name : {"missing.exr", "truncated.exr", "text.hdr", "wide.hdr", "empty.hdr", "picture.png"}) {
        const std::string error = load_error(dir / name);
        INFO(name << ": " << error);
        CHECK(error.find((dir / name).string()) == 0);
        CHECK(error.find('\n') == std::string::npos);
    }
    CHECK(load_error(dir / "wide.hdr").find("1000000x1") != std::string::npos);
    CHECK(load_error(dir / "picture.png").find(".hdr or OpenEXR") != std::string::npos);
}

TEST_CASE("environment cache: memory, then disk, and a damaged entry is computed again") {
    const fs::path dir = tessera::test::output_dir("environment_cache");
    for (const auto& entry : fs::directory_iterator(dir)) fs::remove(entry.path());
    setenv("TESSERA_CACHE_DIR", dir.c_str(), 1);
    unsetenv("TESSERA_NO_ENVIRONMENT_CACHE");
    clear_memory_cache();
    const auto first = acquire_environment(shipped());
    CHECK(last_acquire_stats().source == CacheSource::computed);
    CHECK(first->prefiltered.levels() == kPrefilterLevels);
    CHECK(acquire_environment(shipped()) == first);
    CHECK(last_acquire_stats().source == CacheSource::memory);

    fs::path entry;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().filename().string().starts_with("environment_")) entry = e.path();
    REQUIRE(!entry.empty());
    CHECK(entry.extension() == ".bin");  // no temporary file left behind
    clear_memory_cache();
    const auto from_disk = acquire_environment(shipped());
    CHECK(last_acquire_stats().source == CacheSource::disk);
    CHECK(std::memcmp(from_disk->prefiltered.data().data(), first->prefiltered.data().data(),
                      first->prefiltered.data().size() * sizeof(glm::vec3)) == 0);
    CHECK(std::memcmp(from_disk->background.data().data(), first->background.data().data(),
                      first->background.data().size() * sizeof(glm::vec3)) == 0);

    // One flipped byte in the middle: the checksum refuses the entry.
    std::string bytes = tessera::test::read_file(entry);
    bytes[bytes.size() / 2] = char(bytes[bytes.size() / 2] ^ 0x40);
    write_file(entry, bytes);
    clear_memory_cache();
    const auto recomputed = acquire_environment(shipped());
    CHECK(last_acquire_stats().source == CacheSource::computed);
    CHECK(std::memcmp(recomputed->irradiance.data().data(), first->irradiance.data().data(),
                      first->irradiance.data().size() * sizeof(glm::vec3)) == 0);
    // Turned off by the environment variable (the CLI's --no-environment-cache sets the same switch).
    CHECK(disk_cache_enabled());
    setenv("TESSERA_NO_ENVIRONMENT_CACHE", "1", 1);
    CHECK(!disk_cache_enabled());
    unsetenv("TESSERA_NO_ENVIRONMENT_CACHE");
    unsetenv("TESSERA_CACHE_DIR");
}
