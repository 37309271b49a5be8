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
// 02: the word-wise checksum (01's entries are ignored and computed again).
constexpr char kMagic[8] = {'T', 'S', 'R', 'I', 'B', 'L', '0', '2'};

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

// A part of an entry's payload: the bytes of one array, read into or written from in place.
struct Part {
    void* data;
    std::size_t bytes;
};
template <class T>
Part part(std::vector<T>& values) {
    return {values.data(), values.size() * sizeof(T)};
}

// The payload's checksum: FNV-1a's step over 64-bit words in four
// independent lanes (each step a bijection of the lane, so any changed word
// changes its lane), then FNV-1a of the lanes and the tail bytes. FNV-1a byte
// by byte took longer than reading the 21 MB entry.
std::uint64_t checksum(const std::vector<Part>& parts) {
    std::uint64_t hash = 0xcbf29ce484222325ull;
    for (const Part& p : parts) {
        const auto* bytes = static_cast<const unsigned char*>(p.data);
        std::uint64_t lane[4] = {hash, hash ^ 1, hash ^ 2, hash ^ 3};
        std::size_t i = 0;
        for (; i + 32 <= p.bytes; i += 32)
            for (int k = 0; k < 4; ++k) {
                std::uint64_t word;
                std::memcpy(&word, bytes + i + 8 * k, 8);
                lane[k] = (lane[k] ^ word) * 0x100000001b3ull;
            }
        hash = fnv1a(bytes + i, p.bytes - i, fnv1a(lane, sizeof lane, hash));
    }
    return hash;
}

std::uint64_t payload_size(const std::vector<Part>& parts) {
    std::uint64_t size = 0;
    for (const Part& p : parts) size += p.bytes;
    return size;
}

// An entry: magic, key, payload size, the parts, their checksum.
bool write_entry(const std::filesystem::path& path, std::uint64_t key, const std::vector<Part>& parts) {
    std::error_code error;
    std::filesystem::create_directories(path.parent_path(), error);
    std::random_device random;
    const std::filesystem::path temporary =
        path.string() + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(random());
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out) return false;
        const std::uint64_t size = payload_size(parts), sum = checksum(parts);
        out.write(kMagic, sizeof kMagic);
        out.write(reinterpret_cast<const char*>(&key), sizeof key);
        out.write(reinterpret_cast<const char*>(&size), sizeof size);
        for (const Part& p : parts) out.write(static_cast<const char*>(p.data), std::streamsize(p.bytes));
        out.write(reinterpret_cast<const char*>(&sum), sizeof sum);
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

// Reads a whole entry for `key` straight into the parts (no copy of the
// payload is held): false, the parts' contents undefined, if the file is
// missing, of another key or size, or damaged.
bool read_entry(const std::filesystem::path& path, std::uint64_t key, const std::vector<Part>& parts) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    char magic[sizeof kMagic];
    std::uint64_t stored_key = 0, size = 0, sum = 0;
    in.read(magic, sizeof magic);
    in.read(reinterpret_cast<char*>(&stored_key), sizeof stored_key);
    in.read(reinterpret_cast<char*>(&size), sizeof size);
    if (!in || std::memcmp(magic, kMagic, sizeof kMagic) != 0 || stored_key != key || size != payload_size(parts))
        return false;
    for (const Part& p : parts) in.read(static_cast<char*>(p.data), std::streamsize(p.bytes));
    in.read(reinterpret_cast<char*>(&sum), sizeof sum);
    if (!in || in.peek() != std::char_traits<char>::eof()) return false;
    return sum == checksum(parts);
}

std::shared_ptr<const BrdfLut> load_or_compute_brdf() {
    const std::uint64_t key = fnv1a(kSettings, sizeof kSettings, fnv1a("brdf", 4));
    const std::filesystem::path path = disk_cache_directory() / "brdf_lut.bin";
    auto lut = std::make_shared<BrdfLut>(kBrdfLutSize);
    if (disk_cache_enabled() && read_entry(path, key, {part(lut->data())})) return lut;
    *lut = integrate_brdf(kBrdfLutSize);
    if (disk_cache_enabled()) write_entry(path, key, {part(lut->data())});
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
    const auto parts = [&] {
        return std::vector<Part>{part(maps->background.data()), part(maps->irradiance.data()),
                                 part(maps->prefiltered.data())};
    };
    if (disk_cache_enabled() && read_entry(entry, key, parts())) {
        maps->brdf = brdf_lut();
        return finish(CacheSource::disk, std::move(maps));
    }
    // Decoded here, not before: a cache hit never needs the image's pixels.
    const EquirectImage image = load_equirect_image(path);
    *maps = precompute_environment(image, brdf_lut());
    if (disk_cache_enabled()) write_entry(entry, key, parts());
    return finish(CacheSource::computed, std::move(maps));
}

}  // namespace tessera::environment
