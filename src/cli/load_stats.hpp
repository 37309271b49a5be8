// `tessera render --stats`: where a scene's wall time went before and after
// the frame (loading, decoding and mip-mapping its images, writing outputs).
#pragma once

#include <chrono>
#include <cstdint>

namespace tessera::cli {

// The process-wide load counters (gltf_import_times(), texture::build_times())
// at one moment, so one scene's share is a difference.
struct LoadCounters {
    std::int64_t file_read_ns = 0, parse_ns = 0, convert_ns = 0, images_ns = 0;
    std::int64_t decode_ns = 0, upload_ns = 0, mips_ns = 0;
    std::int64_t textures = 0, texture_bytes = 0;
};
LoadCounters read_load_counters();

// Prints a scene's load split (before → after is this scene's part; load_ms: the wall
// time of load_scene_file, all of it).
void print_load_stats(const LoadCounters& before, const LoadCounters& after, double load_ms);

// Prints the wall time a frame's outputs took to encode and write, and the peak RSS so far.
void print_write_stats(double encode_ms);

inline double milliseconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace tessera::cli
