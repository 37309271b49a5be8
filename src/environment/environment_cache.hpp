// Where a scene's environment maps come from: pre-computed once per process
// (kept in memory for every later frame and scene that uses the same image),
// and kept on disk between processes, keyed by a hash of the image file's
// bytes and of every setting of the pre-computation (precompute.hpp), so an
// edited image or a changed setting never reads a stale entry.
//
// The disk cache is a folder: $TESSERA_CACHE_DIR, else $XDG_CACHE_HOME/tessera,
// else ~/.cache/tessera. Entries are written to a temporary name and renamed;
// an entry that does not read back whole (wrong size, key or checksum) is
// ignored and computed again. TESSERA_NO_ENVIRONMENT_CACHE=1 in the
// environment, or set_disk_cache_enabled(false) (--no-environment-cache), turns
// the disk cache off; the memory cache stays.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>

#include "environment/precompute.hpp"

namespace tessera::environment {

// The maps of the image at `path` (EnvironmentError naming the file when it
// cannot be read). Thread-safe.
std::shared_ptr<const EnvironmentMaps> acquire_environment(const std::filesystem::path& path);

// The BRDF table, the same for every environment: computed (or read from the
// disk cache) on first use.
std::shared_ptr<const BrdfLut> brdf_lut();

void set_disk_cache_enabled(bool enabled);
bool disk_cache_enabled();  // set_disk_cache_enabled and TESSERA_NO_ENVIRONMENT_CACHE
std::filesystem::path disk_cache_directory();
// Drops the memory cache (tests, measurements).
void clear_memory_cache();

// How the last acquire_environment call got its maps, and how long it took.
enum class CacheSource { computed, memory, disk };
struct AcquireStats {
    CacheSource source = CacheSource::computed;
    double milliseconds = 0.0;
};
AcquireStats last_acquire_stats();

// FNV-1a, 64 bits: the cache key's hash.
std::uint64_t fnv1a(const void* data, std::size_t size, std::uint64_t hash = 0xcbf29ce484222325ull);

}  // namespace tessera::environment
