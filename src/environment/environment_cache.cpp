#include "environment/environment_cache.hpp"

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <random>
#include <string>
#include <system_error>
#include <vector>

#include <unistd.h>

namespace tessera::environment {

std::uint64_t fnv1a(const void* data, std::size_t size, std::uint64_t hash) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * 0x100000001b3ull;
    return hash;
}

namespace {

// Every setting the maps depend on: a change here makes new keys.
constexpr char kSettings[] =
    "tessera-ibl-v1 cube=512 irradiance=32 lod=4 delta=0.025 prefilter=128x5 samples=1024 brdf=512 float-rgb seamless-border";
constexpr char kMagic[8] = {'T', 'S', 'R', 'I', 'B', 'L', '0', '1'};

std::mutex g_mutex;
std::map<std::uint64_t, std::shared_ptr<const EnvironmentMaps>> g_maps;  // by key
bool g_disk_enabled = true;
AcquireStats g_last;

using Clock = std::chrono::steady_clock;

std::vector<char> read_bytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return {};
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    if (size <= 0) return {};
    std::vector<char> bytes(static_cast<std::size_t>(size));
    in.seekg(0);
    in.read(bytes.data(), size);
    if (!in) return {};
    return bytes;
}

// An entry: magic, key, payload size, payload, FNV-1a of the payload.
bool write_entry(const std::filesystem::path& path, std::uint64_t key, const std::vector<char>& payload) {
    std::error_code error;
    std::filesystem::create_directories(path.parent_path(), error);
    std::random_device random;
    const std::filesystem::path temporary =
        path.string() + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(random());
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out) return false;
        const std::uint64_t size = payload.size(), checksum = fnv1a(payload.data(), payload.size());
        out.write(kMagic, sizeof kMagic);
        out.write(reinterpret_cast<const char*>(&key), sizeof key);
        out.write(reinterpret_cast<const char*>(&size), sizeof size);
        out.write(payload.data(), std::streamsize(payload.size()));
        out.write(reinterpret_cast<const char*>(&checksum), sizeof checksum);
        if (!out.flush()) {
            out.close();
            std::filesystem::remove(temporary, error);
            return false;
        }
    }
    std::filesystem::rename(temporary, path, error);
    if (error) std::filesystem::remove(temporary, error);
    return !error;
}

// The payload of a whole entry for `key`, or empty.
std::vector<char> read_entry(const std::filesystem::path& path, std::uint64_t key) {
    const std::vector<char> bytes = read_bytes(path);
    constexpr std::size_t header = sizeof kMagic + 16, trailer = 8;
    if (bytes.size() < header + trailer || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) return {};
    std::uint64_t stored_key, size, checksum;
    std::memcpy(&stored_key, bytes.data() + 8, 8);
    std::memcpy(&size, bytes.data() + 16, 8);
    if (stored_key != key || size != bytes.size() - header - trailer) return {};
    std::memcpy(&checksum, bytes.data() + header + size, 8);
    if (checksum != fnv1a(bytes.data() + header, size)) return {};
    return {bytes.begin() + std::ptrdiff_t(header), bytes.begin() + std::ptrdiff_t(header + size)};
}

template <class T>
void append(std::vector<char>& out, const std::vector<T>& values) {
    const char* p = reinterpret_cast<const char*>(values.data());
    out.insert(out.end(), p, p + values.size() * sizeof(T));
}

template <class T>
bool take(const std::vector<char>& in, std::size_t& at, std::vector<T>& values) {
    const std::size_t bytes = values.size() * sizeof(T);
    if (at + bytes > in.size()) return false;
    std::memcpy(values.data(), in.data() + at, bytes);
    at += bytes;
    return true;
}

std::shared_ptr<const BrdfLut> load_or_compute_brdf() {
    const std::uint64_t key = fnv1a(kSettings, sizeof kSettings, fnv1a("brdf", 4));
    const std::filesystem::path path = disk_cache_directory() / "brdf_lut.bin";
    auto lut = std::make_shared<BrdfLut>(kBrdfLutSize);
    if (disk_cache_enabled()) {
        const std::vector<char> payload = read_entry(path, key);
        std::size_t at = 0;
        if (!payload.empty() && take(payload, at, lut->data()) && at == payload.size()) return lut;
    }
    *lut = integrate_brdf(kBrdfLutSize);
    if (disk_cache_enabled()) {
        std::vector<char> payload;
        append(payload, lut->data());
        write_entry(path, key, payload);
    }
    return lut;
}

}  // namespace

std::shared_ptr<const BrdfLut> brdf_lut() {
    static const std::shared_ptr<const BrdfLut> lut = load_or_compute_brdf();
    return lut;
}

void set_disk_cache_enabled(bool enabled) {
    std::lock_guard lock(g_mutex);
    g_disk_enabled = enabled;
}

bool disk_cache_enabled() {
    const char* off = std::getenv("TESSERA_NO_ENVIRONMENT_CACHE");
    if (off && *off && std::string(off) != "0") return false;
    return g_disk_enabled;
}

std::filesystem::path disk_cache_directory() {
    if (const char* dir = std::getenv("TESSERA_CACHE_DIR"); dir && *dir) return dir;
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::filesystem::path(xdg) / "tessera";
    if (const char* home = std::getenv("HOME"); home && *home) return std::filesystem::path(home) / ".cache" / "tessera";
    return std::filesystem::temp_directory_path() / "tessera-cache";
}

void clear_memory_cache() {
    std::lock_guard lock(g_mutex);
    g_maps.clear();
}

AcquireStats last_acquire_stats() {
    std::lock_guard lock(g_mutex);
    return g_last;
}

std::shared_ptr<const EnvironmentMaps> acquire_environment(const std::filesystem::path& path) {
    const auto start = Clock::now();
    const std::string source = path.string();
    check_equirect_path(path);
    const std::vector<char> bytes = read_bytes(path);
    if (bytes.empty()) throw EnvironmentError(source + ": cannot read the environment image (empty or unreadable)");
    const std::uint64_t key = fnv1a(kSettings, sizeof kSettings, fnv1a(bytes.data(), bytes.size()));
    const auto finish = [&](CacheSource how, std::shared_ptr<const EnvironmentMaps> maps) {
        std::lock_guard lock(g_mutex);
        g_maps.emplace(key, maps);
        g_last = {how, std::chrono::duration<double, std::milli>(Clock::now() - start).count()};
        return maps;
    };
    {
        std::lock_guard lock(g_mutex);
        if (const auto found = g_maps.find(key); found != g_maps.end()) {
            g_last = {CacheSource::memory, std::chrono::duration<double, std::milli>(Clock::now() - start).count()};
            return found->second;
        }
    }
    char name[64];
    std::snprintf(name, sizeof name, "environment_%016llx.bin", static_cast<unsigned long long>(key));
    const std::filesystem::path entry = disk_cache_directory() / name;
    auto maps = std::make_shared<EnvironmentMaps>();
    maps->background = CubeMap(kEnvironmentCubeSize, 1);
    maps->irradiance = CubeMap(kIrradianceSize, 1);
    maps->prefiltered = CubeMap(kPrefilterSize, kPrefilterLevels);
    if (disk_cache_enabled()) {
        const std::vector<char> payload = read_entry(entry, key);
        std::size_t at = 0;
        if (!payload.empty() && take(payload, at, maps->background.data()) && take(payload, at, maps->irradiance.data()) &&
            take(payload, at, maps->prefiltered.data()) && at == payload.size()) {
            maps->brdf = brdf_lut();
            return finish(CacheSource::disk, std::move(maps));
        }
    }
    // Decoded here, not before: a cache hit never needs the image's pixels.
    const EquirectImage image = load_equirect_image(path);
    *maps = precompute_environment(image, brdf_lut());
    if (disk_cache_enabled()) {
        std::vector<char> payload;
        append(payload, maps->background.data());
        append(payload, maps->irradiance.data());
        append(payload, maps->prefiltered.data());
        write_entry(entry, key, payload);
    }
    return finish(CacheSource::computed, std::move(maps));
}

}  // namespace tessera::environment
